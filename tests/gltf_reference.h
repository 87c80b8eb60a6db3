// What the tests that evaluate glTF data on their own share: the shared
// sample models' paths, and a model parsed by tinygltf with its images left
// undecoded (those tests read accessors, never pixels); the loader's error
// for a model with its JSON edited; and 4x4 matrices in double.
#pragma once

#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/gltf_loader.h"

namespace quadra {

using DVec = std::vector<double>;
using DMat = std::array<double, 16>;  // column-major, as glTF

inline DMat identity() {
  return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
}

inline DMat multiply(const DMat& a, const DMat& b) {
  DMat r{};
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < 4; ++k)
        r[std::size_t(col * 4 + row)] += a[std::size_t(k * 4 + row)] * b[std::size_t(col * 4 + k)];
  return r;
}

// T * R * S from a translation, an x, y, z, w quaternion and a scale.
inline DMat composeTrs(const DVec& t, const DVec& q, const DVec& s) {
  const double length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const double x = q[0] / length, y = q[1] / length, z = q[2] / length, w = q[3] / length;
  const double rotation[9] = {
      1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
      2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
      2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
  DMat m = identity();
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row)
      m[std::size_t(col * 4 + row)] = rotation[col * 3 + row] * s[std::size_t(col)];
  for (int row = 0; row < 3; ++row) m[std::size_t(12 + row)] = t[std::size_t(row)];
  return m;
}

inline std::string assetPath(const std::string& model) {
  return std::string(QUADRA_ASSETS_DIR) + "/" + model + "/glTF/" + model + ".gltf";
}

inline bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                      const unsigned char*, int, void*) {
  return true;
}

inline tinygltf::Model parseReference(const std::string& path) {
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&skipImage, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  EXPECT_TRUE(parser.LoadASCIIFromFile(&model, &err, &warn, path)) << err;
  return model;
}

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `model` copied to a scratch folder with `from` replaced by `to` in its
// JSON; the loader's error for it ("" when it loads).
inline std::string loadErrorWithEdit(const std::string& model, const std::string& from,
                                     const std::string& to) {
  const std::filesystem::path source = std::filesystem::path(assetPath(model)).parent_path();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("quadra_gltf_edit_" + std::to_string(getpid()) + "_" + model);
  std::filesystem::create_directories(dir);
  for (const auto& entry : std::filesystem::directory_iterator(source))
    if (entry.path().extension() == ".bin")
      std::filesystem::copy_file(entry.path(), dir / entry.path().filename(),
                                 std::filesystem::copy_options::overwrite_existing);
  std::string json = readText(source / (model + ".gltf"));
  const std::size_t at = json.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) json.replace(at, from.size(), to);
  const std::filesystem::path path = dir / "edited.gltf";
  std::ofstream(path) << json;
  std::string error;
  try {
    loadGltf(path.string());
  } catch (const Error& e) {
    error = e.what();
  }
  std::error_code ignored;
  std::filesystem::remove_all(dir, ignored);
  return error;
}

}  // namespace quadra
