// The one spelling of a parameterized test's instance name: GoogleTest takes
// only letters, digits and underscores, and scene and file names have more.
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <string>

namespace quadra {

inline std::string asTestName(std::string text) {
  for (char& c : text)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return text;
}

// For INSTANTIATE_TEST_SUITE_P over scene names.
inline std::string sceneTestName(const ::testing::TestParamInfo<std::string>& info) {
  return asTestName(info.param);
}

}  // namespace quadra
