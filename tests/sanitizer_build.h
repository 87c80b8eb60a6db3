// Whether this test binary is built with ASan or TSan, for the tests that
// measure memory (under a sanitizer, resident memory and big allocations
// measure the sanitizer). GCC says so with __SANITIZE_ADDRESS__ and
// __SANITIZE_THREAD__; clang 14, which builds the ASan suite, only through
// __has_feature.
#pragma once

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define QUADRA_SANITIZED_BUILD 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define QUADRA_SANITIZED_BUILD 1
#endif
#endif

namespace quadra {

#if defined(QUADRA_SANITIZED_BUILD)
constexpr bool kSanitizedBuild = true;
#else
constexpr bool kSanitizedBuild = false;
#endif

}  // namespace quadra
