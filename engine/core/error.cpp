// Where failed internal checks end: print and abort (a bug, never user input).
#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace quadra::detail {

void checkFailed(const char* file, int line, const std::string& what) {
  std::fprintf(stderr, "quadra: internal check failed at %s:%d: %s\n", file, line, what.c_str());
  std::abort();
}

}  // namespace quadra::detail
