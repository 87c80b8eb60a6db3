// glTF 2.0 (.gltf and .glb) → Scene, through tinygltf, with every length,
// offset, index and size checked before it is trusted.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/memory_budget.h"
#include "core/parallel.h"
#include "scene/scene.h"

namespace quadra {

struct LoadOptions {
  int sceneIndex = -1;  // -1: the file's default scene (or scene 0)
  // Folders besides the file's own that its buffer and image URIs may read
  // (--allow-path); each must exist. The rules: docs/cli.md, "Scene sandbox".
  std::vector<std::string> allowedPaths = {};
  // The bytes the load may allocate for what the file controls (the files
  // read, decoded buffers, meshes and images), each charged before it is
  // allocated (--max-memory). The rules: docs/cli.md, "Memory budget".
  std::uint64_t maxMemory = kDefaultMaxMemory;
  // Where meshes and images are decoded in parallel: the embedder's arena
  // (which must outlive the call), else a private one of `threads` threads
  // (<= 0: all cores). The scene is the same bits either way.
  int threads = 0;
  TaskArena* arena = nullptr;
};

// Throws Error("<path>: <problem>") for anything malformed or unsupported that
// cannot be ignored, and for a URI that reads outside the sandbox
// ("<path>: URI '<uri>' <why>", the URI percent-decoded). Things it can
// ignore (points, lines) go to notes, one line each. Going over
// options.maxMemory is an Error naming the file, what was to be allocated and
// how much, thrown before that allocation.
Scene loadGltf(const std::string& path, const LoadOptions& options = {},
               std::vector<std::string>* notes = nullptr);

// What loadGltf charges for parsing the JSON of the file at `path` (its
// bytes given) before it parses it: bounded from the text's structure
// (docs/cli.md, "Memory budget"). Throws Error for a malformed GLB container.
std::uint64_t parsedJsonBytes(const std::string& path, const std::vector<std::uint8_t>& bytes);

// Whether quadra implements the glTF extension `name`: a file that requires
// one it does not is refused (docs/gltf.md), one that only uses it loads.
bool implementsGltfExtension(const std::string& name);

}  // namespace quadra
