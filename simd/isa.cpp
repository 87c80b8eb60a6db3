// CPU detection and the ISA names used on the command line.
#include "simd/isa.h"

#include <cpuid.h>

namespace quadra {
namespace {

// F16C from CPUID leaf 1 (ECX) directly: GCC's __builtin_cpu_supports knows
// "f16c", clang 14's (the fuzz build, scripts/fuzz.sh) rejects it. The AVX2
// check beside it already covers the OS saving the YMM registers.
bool hasF16c() {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  return __get_cpuid(1, &eax, &ebx, &ecx, &edx) && (ecx & bit_F16C) != 0;
}

}  // namespace

const char* isaName(Isa isa) {
  switch (isa) {
    case Isa::Scalar:
      return "scalar";
    case Isa::Sse2:
      return "sse2";
    case Isa::Avx2:
      return "avx2";
    case Isa::Avx512:
      return "avx512";
  }
  return "?";
}

std::optional<Isa> parseIsa(const std::string& name) {
  for (Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512})
    if (name == isaName(isa)) return isa;
  return std::nullopt;
}

bool isaSupported(Isa isa) {
  // __builtin_cpu_supports also checks that the OS saves the wider registers.
  switch (isa) {
    case Isa::Scalar:
      return true;
    case Isa::Sse2:
      return __builtin_cpu_supports("sse2");
    case Isa::Avx2:
      return __builtin_cpu_supports("avx2") && hasF16c();
    case Isa::Avx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") &&
             isaSupported(Isa::Avx2);
  }
  return false;
}

Isa detectBestIsa() {
  for (Isa isa : {Isa::Avx512, Isa::Avx2, Isa::Sse2})
    if (isaSupported(isa)) return isa;
  return Isa::Scalar;
}

}  // namespace quadra
