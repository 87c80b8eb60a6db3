// Whole files read into memory, for the readers that parse from memory (the
// glTF loader, JPEG images), with their errors as one-line quadra::Errors.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace quadra {

// The largest file read whole: tinygltf takes 32-bit sizes.
constexpr std::uint64_t kMaxFileSize = 0xFFFFFFFFu;

// The file's bytes. Throws Error("<path>: <problem>") for a directory, a file
// that cannot be opened or read, an empty one, or one over kMaxFileSize.
std::vector<std::uint8_t> readWholeFile(const std::string& path);

}  // namespace quadra
