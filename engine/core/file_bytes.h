// Whole files read into memory, for the readers that parse from memory (the
// glTF loader, JPEG images), with their errors as one-line quadra::Errors.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace quadra {

// The largest file read whole: tinygltf takes 32-bit sizes.
constexpr std::uint64_t kMaxFileSize = 0xFFFFFFFFu;

// The file's bytes. Throws Error("<path>: <problem>") for a directory or
// anything else that is not a regular file (a FIFO is not waited on), a file
// that cannot be opened or read, an empty one, or one over kMaxFileSize.
std::vector<std::uint8_t> readWholeFile(const std::string& path);

// As readWholeFile, for a canonical path (absolute, no symbolic link on the
// way) that a check such as the scene sandbox's approved: the file opened
// must still be the one at that path, so a link swapped into it between the
// check and the read (a race an uploader with write access could try) is an
// Error naming where it now leads, never followed.
std::vector<std::uint8_t> readCanonicalFile(const std::string& path);

}  // namespace quadra
