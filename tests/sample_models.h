// The shared sample models (../shared/assets, beside the checkout) as the
// tests see them: every model's .gltf file, and which of them quadra must
// refuse because the file requires an extension quadra does not implement.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/gltf_loader.h"

namespace quadra {

// Every <model>/glTF/*.gltf under QUADRA_ASSETS_DIR, sorted; empty where the
// folder is absent.
inline std::vector<std::filesystem::path> allSampleModels() {
  namespace fs = std::filesystem;
  std::vector<fs::path> models;
  std::error_code ec;
  if (!fs::is_directory(QUADRA_ASSETS_DIR, ec)) return models;
  for (const fs::directory_entry& entry : fs::directory_iterator(QUADRA_ASSETS_DIR, ec)) {
    const fs::path folder = entry.path() / "glTF";
    if (!fs::is_directory(folder, ec)) continue;
    for (const fs::directory_entry& file : fs::directory_iterator(folder, ec))
      if (file.path().extension() == ".gltf") models.push_back(file.path());
  }
  std::sort(models.begin(), models.end());
  return models;
}

// The extensions the file lists in extensionsRequired that quadra lacks,
// read from its JSON independently of the loader.
inline std::vector<std::string> unimplementedRequiredExtensions(const std::filesystem::path& gltf) {
  std::ifstream in(gltf);
  const nlohmann::json json = nlohmann::json::parse(in);
  std::vector<std::string> lacking;
  if (const auto found = json.find("extensionsRequired"); found != json.end())
    for (const auto& name : *found)
      if (!implementsGltfExtension(name.get<std::string>())) lacking.push_back(name);
  return lacking;
}

// The models quadra loads: all but those requiring what it lacks.
inline std::vector<std::filesystem::path> loadableSampleModels() {
  std::vector<std::filesystem::path> models = allSampleModels();
  std::erase_if(models, [](const std::filesystem::path& model) {
    return !unimplementedRequiredExtensions(model).empty();
  });
  return models;
}

}  // namespace quadra
