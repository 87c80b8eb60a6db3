// quadra::api::Error, the one exception every public quadra function throws
// for bad input or a failed load or render: its what() is one line naming the
// thing at fault and the problem, e.g. "mesh: index 7 (entry 5) is out of
// range for 4 vertices". The facade turns the engine's own errors into it, so
// an embedder catches one class for loading, building and rendering alike.
#pragma once

#include <stdexcept>
#include <string>

#include "quadra/export.h"

namespace quadra::api {

class QUADRA_API Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace quadra::api
