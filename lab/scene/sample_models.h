// What a sample model's glTF file asks of quadra before it is loaded: the
// tests and `quadra report frames` leave out the models quadra must refuse.
#pragma once

#include <filesystem>
#include <string>

namespace quadra {

// The first extension the .gltf file lists in extensionsRequired that quadra
// does not implement (scene/gltf_loader.h implementsGltfExtension), or "" when
// there is none or the file is not readable JSON (the loader then says why).
// Read from the JSON directly, not through the loader.
std::string lackedRequiredGltfExtension(const std::filesystem::path& gltf);

}  // namespace quadra
