// The one spelling of a parameterized test's instance name: GoogleTest takes
// only letters, digits and underscores, and scene and file names have more.
#pragma once

#include <cctype>
#include <string>

namespace quadra {

inline std::string asTestName(std::string text) {
  for (char& c : text)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return text;
}

}  // namespace quadra
