// lackedRequiredGltfExtension: the glTF file's extensionsRequired against what
// the loader implements.
#include "lab/scene/sample_models.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "scene/gltf_loader.h"

namespace quadra {

std::string lackedRequiredGltfExtension(const std::filesystem::path& gltf) {
  std::ifstream in(gltf);
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  if (json.is_discarded() || !json.contains("extensionsRequired")) return "";
  for (const nlohmann::json& name : json["extensionsRequired"])
    if (name.is_string() && !implementsGltfExtension(name.get<std::string>())) return name;
  return "";
}

}  // namespace quadra
