// The shared sample models (../shared/assets, beside the checkout) as the
// tests see them: every model's .gltf file, and those quadra loads (not those
// whose file requires an extension quadra does not implement).
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "lab/scene/sample_models.h"

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

// The models quadra loads: all but those requiring what it lacks.
inline std::vector<std::filesystem::path> loadableSampleModels() {
  std::vector<std::filesystem::path> models = allSampleModels();
  std::erase_if(models, [](const std::filesystem::path& model) {
    return !lackedRequiredGltfExtension(model).empty();
  });
  return models;
}

}  // namespace quadra
