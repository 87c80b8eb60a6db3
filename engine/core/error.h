// quadra's small error vocabulary: user-facing errors (a file and a problem,
// one line) and always-on internal checks that print both sides.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace quadra {

// A problem with the user's input (a file, an option): the message is one line
// that names the file or option and the problem. Thrown outside hot loops only.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// "<where>: <problem>", the shape every user error takes.
inline Error makeError(const std::string& where, const std::string& problem) {
  return Error(where + ": " + problem);
}

namespace detail {
[[noreturn]] void checkFailed(const char* file, int line, const std::string& what);
}  // namespace detail

}  // namespace quadra

// Always-on invariant check (a bug, never user input): throws std::logic_error.
#define QUADRA_CHECK(cond)                                                 \
  do {                                                                     \
    if (!(cond)) ::quadra::detail::checkFailed(__FILE__, __LINE__, #cond); \
  } while (0)

#define QUADRA_CHECK_OP(a, op, b)                                   \
  do {                                                              \
    const auto& qa_ = (a);                                          \
    const auto& qb_ = (b);                                          \
    if (!(qa_ op qb_)) {                                            \
      std::ostringstream qs_;                                       \
      qs_ << #a " " #op " " #b " (" << qa_ << " vs " << qb_ << ")"; \
      ::quadra::detail::checkFailed(__FILE__, __LINE__, qs_.str()); \
    }                                                               \
  } while (0)
