// Where failed internal checks end: a std::logic_error naming the check, not
// an abort, so that an application embedding the library survives quadra's
// bug (the public API reports it as the call's error, the CLI as its one
// line and exit 1).
#include "core/error.h"

namespace quadra::detail {

void checkFailed(const char* file, int line, const std::string& what) {
  throw std::logic_error("internal check failed at " + std::string(file) + ":" +
                         std::to_string(line) + ": " + what);
}

}  // namespace quadra::detail
