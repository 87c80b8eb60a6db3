// What the tests that evaluate glTF data on their own share: the shared
// sample models' paths, and a model parsed by tinygltf with its images left
// undecoded (those tests read accessors, never pixels); and the loader's
// error for a model with its JSON edited.
#pragma once

#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.h"
#include "scene/gltf_loader.h"

namespace quadra {

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
  try {
    loadGltf(path.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace quadra
