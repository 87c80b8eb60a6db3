// loadGltf: reads the file, validates a GLB container before tinygltf sees it,
// lets tinygltf parse the JSON (and fetch buffers and images, only inside the
// sandbox of core/file_sandbox.h), then walks the chosen scene's node tree
// into instances and cameras, with the skins and morph weights they use.
// Primitives, accessors and materials are
// converted by the other gltf_*.cpp files; every reference and range is
// checked there, because tinygltf has had overflows in both.
#include "scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <new>
#include <set>
#include <span>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/file_bytes.h"
#include "core/file_sandbox.h"
#include "core/parallel.h"
#include "scene/animation.h"
#include "scene/gltf_internal.h"

namespace quadra {

namespace {

using gltf::ModelRef;

constexpr std::uint32_t kGlbMagic = 0x46546C67;     // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;    // "JSON"
constexpr std::uint32_t kChunkBinary = 0x004E4942;  // "BIN\0"

std::string firstLine(const std::string& text) {
  std::size_t begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  std::size_t end = text.find_first_of("\r\n", begin);
  std::string line = text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.pop_back();
  return line;
}

// Names and URIs from the file end up in messages; keep each message one line.
std::string oneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

std::uint32_t readU32(const std::vector<std::uint8_t>& bytes, std::uint64_t offset) {
  return std::uint32_t(bytes[offset]) | std::uint32_t(bytes[offset + 1]) << 8 |
         std::uint32_t(bytes[offset + 2]) << 16 | std::uint32_t(bytes[offset + 3]) << 24;
}

bool isGlb(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  if (bytes.size() >= 4 && readU32(bytes, 0) == kGlbMagic) return true;
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".glb";
}

// GLB container (glTF 2.0 §4.4): 12-byte header, a JSON chunk, an optional BIN
// chunk, each 4-byte aligned, all inside the file and the declared length.
void checkGlbLayout(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const std::uint64_t size = bytes.size();
  if (size < 12) {
    throw makeError(path, "truncated GLB header (" + std::to_string(size) + " of 12 bytes)");
  }
  if (readU32(bytes, 0) != kGlbMagic) throw makeError(path, "not a GLB file (bad magic)");
  const std::uint32_t version = readU32(bytes, 4);
  if (version != 2) {
    throw makeError(path, "GLB version " + std::to_string(version) + " is not supported (needs 2)");
  }
  const std::uint32_t length = readU32(bytes, 8);
  if (length != size) {
    throw makeError(path, "GLB header says " + std::to_string(length) + " bytes but the file has " +
                              std::to_string(size));
  }
  std::uint64_t offset = 12;
  for (int chunk = 0; offset < size; ++chunk) {
    const std::string name = "GLB chunk " + std::to_string(chunk);
    if (size - offset < 8) throw makeError(path, name + " header is truncated");
    const std::uint64_t chunkLength = readU32(bytes, offset);
    const std::uint32_t chunkType = readU32(bytes, offset + 4);
    if (chunkLength > size - offset - 8) {
      throw makeError(path, name + " (" + std::to_string(chunkLength) +
                                " bytes) runs past the end of the file");
    }
    if (chunkLength % 4 != 0) {
      throw makeError(path,
                      name + " length " + std::to_string(chunkLength) + " is not a multiple of 4");
    }
    if (chunk == 0 && (chunkType != kChunkJson || chunkLength == 0)) {
      throw makeError(path, "GLB does not start with a JSON chunk");
    }
    if (chunk == 1 && chunkType != kChunkBinary) {
      throw makeError(path, "GLB chunk 1 is not a BIN chunk");
    }
    offset += 8 + chunkLength;
  }
  if (offset == 12) throw makeError(path, "GLB has no JSON chunk");
}

// ---- external files ----------------------------------------------------------

// tinygltf's file callbacks, confined to the sandbox. For a URI it asks for
// JoinPath(baseDir, decoded URI), then for "./" + the URI (the working
// directory, which glTF never means); only the first is answered, so the
// reference is what follows baseDir. Nothing is opened that resolve() did not
// approve, and the first refusal is kept for the error: tinygltf itself only
// warns about an image it could not read.
struct SandboxedFiles {
  const FileSandbox& sandbox;
  std::string prefix;    // baseDir as tinygltf joins it, ending in '/'
  MemoryBudget& budget;  // each file is charged before it is read
  std::set<std::string> approved;
  std::string refusal;     // "URI '<reference>' <why>"
  std::string overBudget;  // the budget's error for a file too big to read
};

// Charges the budget for reading the file at `path` whole, by its size on
// disk, before it is read (a size that cannot be read is the reader's error).
void chargeFileRead(MemoryBudget& budget, const std::string& path, const std::string& what) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec) budget.charge(what + " (" + std::to_string(size) + " bytes)", size);
}

std::string expandSandboxed(const std::string& joined, void* user) {
  auto& files = *static_cast<SandboxedFiles*>(user);
  if (joined.compare(0, files.prefix.size(), files.prefix) != 0) return "";
  const std::string reference = joined.substr(files.prefix.size());
  const FileSandbox::Resolved resolved = files.sandbox.resolve(reference);
  if (!resolved.refusal.empty()) {
    if (files.refusal.empty()) files.refusal = "URI '" + reference + "' " + resolved.refusal;
    return "";
  }
  files.approved.insert(resolved.path.string());
  return resolved.path.string();
}

bool existsSandboxed(const std::string& path, void* user) {
  const auto& files = *static_cast<SandboxedFiles*>(user);
  std::error_code ec;
  return files.approved.count(path) != 0 && std::filesystem::is_regular_file(path, ec);
}

bool readSandboxed(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* user) {
  auto& files = *static_cast<SandboxedFiles*>(user);
  try {
    if (files.approved.count(path) == 0) throw makeError(path, "outside the sandbox");
    try {
      chargeFileRead(files.budget, path, "file '" + path + "'");
    } catch (const Error& e) {
      if (files.overBudget.empty()) files.overBudget = e.what();
      throw;
    }
    *out = readCanonicalFile(path);
    return true;
  } catch (const Error& e) {
    if (err) *err += e.what();
    return false;
  }
}

bool writeRefused(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the loader writes no files";
  return false;
}

// What parsing a JSON text may allocate, bounded from its structure before
// it is parsed: a few bytes of JSON can become a big structure ("{}," is an
// empty material, 2144 bytes as tinygltf holds it, plus the JSON document's
// own node). Scanned outside strings: each '{' counts as the largest tinygltf
// object and its document node, each '[', ',' or ':' as one value (a
// tinygltf::Value, 152 bytes, and its node), and the text once (strings are
// copied out of it).
std::uint64_t jsonParseBytes(const std::uint8_t* text, std::size_t size) {
  constexpr std::uint64_t kObjectBytes = 2560, kValueBytes = 256;
  std::uint64_t objects = 0, values = 0;
  bool inString = false, escaped = false;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = char(text[i]);
    if (inString) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        inString = false;
      continue;
    }
    if (c == '"') inString = true;
    if (c == '{') ++objects;
    if (c == '[' || c == ',' || c == ':') ++values;
  }
  return size + objects * kObjectBytes + values * kValueBytes;
}

// The JSON text of a .gltf file or of a GLB's JSON chunk (which follows
// the 12-byte header and the chunk's own 8), the GLB's layout checked first.
std::span<const std::uint8_t> jsonText(const std::string& path,
                                       const std::vector<std::uint8_t>& bytes) {
  if (!isGlb(path, bytes)) return bytes;
  checkGlbLayout(path, bytes);
  return std::span(bytes).subspan(20, readU32(bytes, 12));
}

}  // namespace

std::uint64_t parsedJsonBytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const std::span<const std::uint8_t> text = jsonText(path, bytes);
  return jsonParseBytes(text.data(), text.size());
}

namespace {

tinygltf::Model parseModel(const std::string& path, const std::vector<std::uint8_t>& bytes,
                           const LoadOptions& options, MemoryBudget& budget,
                           gltf::ImageStash& stash) {
  budget.charge(
      "the parsed JSON (" + std::to_string(jsonText(path, bytes).size()) + " bytes of text)",
      parsedJsonBytes(path, bytes));
  const bool binary = isGlb(path, bytes);
  const FileSandbox sandbox(std::filesystem::path(path).parent_path(), options.allowedPaths);
  const std::string baseDir = sandbox.home().string();
  SandboxedFiles files{sandbox, baseDir.back() == '/' ? baseDir : baseDir + "/", budget, {}, {},
                       {}};
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&gltf::stashImageBytes, &stash);
  parser.SetFsCallbacks(
      {&existsSandboxed, &expandSandboxed, &readSandboxed, &writeRefused, &files});
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try {
    ok = binary ? parser.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                              unsigned(bytes.size()), baseDir)
                : parser.LoadASCIIFromString(&model, &err, &warn,
                                             reinterpret_cast<const char*>(bytes.data()),
                                             unsigned(bytes.size()), baseDir);
  } catch (const std::exception& e) {
    throw makeError(path, "invalid glTF (" + firstLine(e.what()) + ")");
  }
  if (!files.refusal.empty()) throw makeError(path, files.refusal);
  if (!files.overBudget.empty()) throw Error(files.overBudget);
  if (!ok) {
    const std::string problem = firstLine(err);
    throw makeError(path, problem.empty() ? "invalid glTF" : problem);
  }
  return model;
}

// A required extension quadra does not implement would draw the scene wrong:
// an error. An optional one leaves a valid fallback (glTF 2.0 §3.12): a note.
void checkExtensions(const ModelRef& ref, std::vector<std::string>& notes) {
  for (const std::string& extension : ref.model.extensionsRequired) {
    if (!implementsGltfExtension(extension))
      throw ref.fail("unsupported required extension " + extension);
  }
  for (const std::string& extension : ref.model.extensionsUsed) {
    if (!implementsGltfExtension(extension))
      notes.push_back(ref.note("optional extension " + extension + " is not supported; ignored"));
  }
}

// ---- node tree ----------------------------------------------------------------

// The node's rest transform, and its TRS parts for an animation to replace.
Node readNode(const ModelRef& ref, int index) {
  const tinygltf::Node& source = ref.model.nodes[std::size_t(index)];
  const std::string what = "node " + std::to_string(index);
  Node node;
  if (!source.matrix.empty()) {
    if (source.matrix.size() != 16) throw ref.fail(what + " matrix does not have 16 numbers");
    for (int i = 0; i < 16; ++i)
      glm::value_ptr(node.local)[i] = float(source.matrix[std::size_t(i)]);
    node.hasMatrix = true;  // both glTF and glm store columns first
    return node;
  }
  if (!source.translation.empty() && source.translation.size() != 3) {
    throw ref.fail(what + " translation does not have 3 numbers");
  }
  if (!source.rotation.empty() && source.rotation.size() != 4) {
    throw ref.fail(what + " rotation does not have 4 numbers");
  }
  if (!source.scale.empty() && source.scale.size() != 3) {
    throw ref.fail(what + " scale does not have 3 numbers");
  }
  // Only the parts the file gives are applied, so a static scene's matrices
  // keep the bits they had before nodes were kept for animation.
  glm::mat4 m(1.0f);
  if (!source.translation.empty()) {
    node.translation = glm::vec3(float(source.translation[0]), float(source.translation[1]),
                                 float(source.translation[2]));
    m = glm::translate(m, node.translation);
  }
  if (!source.rotation.empty()) {
    // glTF stores x, y, z, w; glm's constructor takes w first.
    glm::quat q(float(source.rotation[3]), float(source.rotation[0]), float(source.rotation[1]),
                float(source.rotation[2]));
    const float length = glm::length(q);
    if (length > 0.0f && std::isfinite(length)) q /= length;  // exporters round
    node.rotation = q;
    m *= glm::mat4_cast(q);
  }
  if (!source.scale.empty()) {
    node.scale = glm::vec3(float(source.scale[0]), float(source.scale[1]), float(source.scale[2]));
    m = glm::scale(m, node.scale);
  }
  node.local = m;
  return node;
}

struct PlacedNode {
  int node;    // glTF node index
  int parent;  // index of the parent's PlacedNode in the walk's order; -1: a root
  Node local;  // its rest transform
  glm::mat4 world;
};

// Pre-order walk from the roots; a node reached twice means a cycle or a node
// with two parents, both forbidden by glTF 2.0 §3.5.2.
std::vector<PlacedNode> walkNodes(const ModelRef& ref, const std::vector<int>& roots) {
  const std::size_t nodeCount = ref.model.nodes.size();
  std::vector<char> visited(nodeCount, 0);
  // Stack entries: the node to visit, its parent's position in `order` and
  // the parent's world transform.
  struct Pending {
    int node, parent;
    glm::mat4 parentWorld;
  };
  std::vector<Pending> stack;
  std::vector<PlacedNode> order;
  for (auto root = roots.rbegin(); root != roots.rend(); ++root) {
    stack.push_back({*root, -1, glm::mat4(1.0f)});
  }
  while (!stack.empty()) {
    const Pending next = stack.back();
    stack.pop_back();
    if (next.node < 0 || std::size_t(next.node) >= nodeCount) {
      throw ref.fail("node " + std::to_string(next.node) + " does not exist (the file has " +
                     std::to_string(nodeCount) + ")");
    }
    if (visited[std::size_t(next.node)]) {
      throw ref.fail("node " + std::to_string(next.node) +
                     " is reached twice (a cycle or a node with two parents)");
    }
    visited[std::size_t(next.node)] = 1;
    const Node local = readNode(ref, next.node);
    const glm::mat4 world = next.parentWorld * local.local;
    order.push_back({next.node, next.parent, local, world});
    const int placed = int(order.size()) - 1;
    const std::vector<int>& children = ref.model.nodes[std::size_t(next.node)].children;
    for (auto child = children.rbegin(); child != children.rend(); ++child) {
      stack.push_back({*child, placed, world});
    }
  }
  return order;
}

std::vector<int> sceneRoots(const ModelRef& ref, const LoadOptions& options,
                            std::vector<std::string>& notes) {
  const auto& scenes = ref.model.scenes;
  int index = options.sceneIndex >= 0 ? options.sceneIndex : ref.model.defaultScene;
  if (scenes.empty() && index < 0) {
    // A file without scenes is a library of nodes; draw its root nodes.
    notes.push_back(ref.note("no scene defined; drawing every root node"));
    std::vector<char> isChild(ref.model.nodes.size(), 0);
    for (const tinygltf::Node& node : ref.model.nodes) {
      for (int child : node.children) {
        if (child >= 0 && std::size_t(child) < isChild.size()) isChild[std::size_t(child)] = 1;
      }
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < isChild.size(); ++i) {
      if (!isChild[i]) roots.push_back(int(i));
    }
    return roots;
  }
  if (index < 0) index = 0;
  if (std::size_t(index) >= scenes.size()) {
    throw ref.fail("scene " + std::to_string(index) + " does not exist (the file has " +
                   std::to_string(scenes.size()) + ")");
  }
  return scenes[std::size_t(index)].nodes;
}

// ---- cameras --------------------------------------------------------------------

bool positiveFinite(double v) {
  return std::isfinite(v) && v > 0.0;
}

Camera makeCamera(const ModelRef& ref, int index, const glm::mat4& world, int sceneNode) {
  if (index < 0 || std::size_t(index) >= ref.model.cameras.size()) {
    throw ref.fail("camera " + std::to_string(index) + " does not exist");
  }
  const tinygltf::Camera& source = ref.model.cameras[std::size_t(index)];
  const std::string what = "camera " + std::to_string(index);
  Camera camera;
  camera.world = cameraWorldOf(world);
  camera.node = sceneNode;
  if (source.type == "perspective") {
    const tinygltf::PerspectiveCamera& p = source.perspective;
    const bool farOk = p.zfar == 0.0 || (std::isfinite(p.zfar) && p.zfar > p.znear);
    if (!positiveFinite(p.yfov) || !positiveFinite(p.znear) || !farOk) {
      throw ref.fail(what + " needs yfov > 0, znear > 0 and zfar > znear (or no zfar)");
    }
    camera.type = Camera::Type::Perspective;
    camera.yfov = float(p.yfov);
    camera.znear = float(p.znear);
    camera.zfar = float(p.zfar);
  } else if (source.type == "orthographic") {
    const tinygltf::OrthographicCamera& o = source.orthographic;
    const bool magOk =
        std::isfinite(o.xmag) && std::isfinite(o.ymag) && o.xmag != 0.0 && o.ymag != 0.0;
    const bool depthOk =
        std::isfinite(o.znear) && o.znear >= 0.0 && std::isfinite(o.zfar) && o.zfar > o.znear;
    if (!magOk || !depthOk) {
      throw ref.fail(what + " needs non-zero xmag and ymag and zfar > znear >= 0");
    }
    camera.type = Camera::Type::Orthographic;
    camera.xmag = float(o.xmag);
    camera.ymag = float(o.ymag);
    camera.znear = float(o.znear);
    camera.zfar = float(o.zfar);
  } else {
    throw ref.fail(what + " has unknown type '" + source.type + "'");
  }
  return camera;
}

// ---- lights (KHR_lights_punctual) -------------------------------------------------

// The file's lights, checked as the extension's specification bounds them:
// intensity finite and >= 0, range > 0 where given (tinygltf reads an absent
// range as 0, the extension's "unlimited"), 0 <= inner < outer <= pi/2.
std::vector<Light> readLights(const ModelRef& ref) {
  std::vector<Light> lights;
  for (std::size_t i = 0; i < ref.model.lights.size(); ++i) {
    const tinygltf::Light& source = ref.model.lights[i];
    const std::string what =
        "light " + std::to_string(i) + (source.name.empty() ? "" : " ('" + source.name + "')");
    Light light;
    if (source.type == "directional")
      light.type = Light::Type::Directional;
    else if (source.type == "point")
      light.type = Light::Type::Point;
    else if (source.type == "spot")
      light.type = Light::Type::Spot;
    else
      throw ref.fail(what + " has unknown type '" + source.type + "'");
    if (!source.color.empty()) {
      if (source.color.size() != 3) throw ref.fail(what + " color does not have 3 numbers");
      for (int c = 0; c < 3; ++c) {
        const double value = source.color[std::size_t(c)];
        if (!(value >= 0.0 && value <= double(FLT_MAX)))
          throw ref.fail(what + " color " + std::to_string(value) + " is not finite and >= 0");
        light.color[c] = float(value);
      }
    }
    if (!(source.intensity >= 0.0 && source.intensity <= double(FLT_MAX)))
      throw ref.fail(what + " intensity " + std::to_string(source.intensity) +
                     " is not finite and >= 0");
    light.intensity = float(source.intensity);
    if (!(source.range >= 0.0 && source.range <= double(FLT_MAX)))
      throw ref.fail(what + " range " + std::to_string(source.range) + " is not finite and > 0");
    light.range = float(source.range);
    if (light.type == Light::Type::Spot) {
      const double inner = source.spot.innerConeAngle, outer = source.spot.outerConeAngle;
      if (!(inner >= 0.0 && inner < outer && outer <= 1.5707963267948966))
        throw ref.fail(what + " spot cone (inner " + std::to_string(inner) + ", outer " +
                       std::to_string(outer) + ") does not satisfy 0 <= inner < outer <= pi/2");
      light.innerConeAngle = float(inner);
      light.outerConeAngle = float(outer);
    }
    lights.push_back(light);
  }
  return lights;
}

// The light node `index` carries (node.extensions.KHR_lights_punctual.light),
// -1 when none.
int nodeLight(const ModelRef& ref, int index, std::size_t lightCount) {
  const tinygltf::Node& node = ref.model.nodes[std::size_t(index)];
  const auto found = node.extensions.find("KHR_lights_punctual");
  if (found == node.extensions.end()) return -1;
  const std::string what = "node " + std::to_string(index) + " KHR_lights_punctual";
  const tinygltf::Value& extension = found->second;
  if (!extension.IsObject() || !extension.Has("light") || !extension.Get("light").IsInt())
    throw ref.fail(what + " has no integer light");
  const int light = extension.Get("light").GetNumberAsInt();
  if (light < 0 || std::size_t(light) >= lightCount)
    throw ref.fail(what + " refers to light " + std::to_string(light) +
                   ", which does not exist (the file has " + std::to_string(lightCount) + ")");
  return light;
}

// ---- meshes ---------------------------------------------------------------------

// One (glTF mesh, primitive) pair, decoded once however many nodes draw it.
struct PrimitiveJob {
  int mesh = 0;
  int primitive = 0;
  gltf::PrimitiveNeeds needs;
  int material = -1;  // scene material
  Mesh result;
  bool drawn = false;
  std::vector<std::string> notes;
  std::string error;
};

void decodePrimitives(const ModelRef& ref, std::vector<PrimitiveJob>& jobs) {
  const Executor serial(1);
  const Executor& executor = ref.executor ? *ref.executor : serial;
  executor.parallelFor(jobs.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      PrimitiveJob& job = jobs[i];
      try {
        job.drawn = gltf::buildMesh(ref, job.mesh, job.primitive, job.needs, job.result, job.notes);
      } catch (const Error& e) {
        job.error = e.what();
      } catch (const std::exception& e) {  // bad_alloc and the like
        job.error = ref.fail("mesh " + std::to_string(job.mesh) + ": " + e.what()).what();
      }
    }
  });
}

// ---- skins and morph weights ---------------------------------------------------

// Skin `index` with its joints mapped to Scene::nodes (each must be in the
// scene drawn) and its inverse bind matrices (MAT4 floats, at least one per
// joint; the identity when the skin gives none).
Skin readSkin(const ModelRef& ref, int index, const std::vector<int>& sceneNodeOf) {
  const tinygltf::Skin& source = ref.model.skins[std::size_t(index)];
  const std::string what = "skin " + std::to_string(index);
  if (source.joints.empty()) throw ref.fail(what + " has no joints");
  Skin skin;
  for (std::size_t k = 0; k < source.joints.size(); ++k) {
    const int node = source.joints[k];
    const std::string joint =
        what + " joint " + std::to_string(k) + " is node " + std::to_string(node);
    if (node < 0 || std::size_t(node) >= sceneNodeOf.size())
      throw ref.fail(joint + ", which does not exist");
    if (sceneNodeOf[std::size_t(node)] < 0)
      throw ref.fail(joint + ", which is not in the scene drawn");
    skin.joints.push_back(sceneNodeOf[std::size_t(node)]);
  }
  if (source.inverseBindMatrices == -1) {
    skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));
    return skin;
  }
  const gltf::AccessorView view =
      gltf::viewAccessor(ref, source.inverseBindMatrices, what + " inverseBindMatrices");
  const std::string accessor = "accessor " + std::to_string(source.inverseBindMatrices) + " (" +
                               what + " inverseBindMatrices)";
  if (view.components != 16 || view.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    throw ref.fail(accessor + " must be MAT4 of FLOAT");
  if (view.count < skin.joints.size()) {
    throw ref.fail(accessor + " has " + std::to_string(view.count) + " matrices for " +
                   std::to_string(skin.joints.size()) + " joints");
  }
  const std::vector<float> values = gltf::decodeFloats(ref, view);
  skin.inverseBindMatrices.resize(skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    // glTF and glm both store columns first.
    std::memcpy(glm::value_ptr(skin.inverseBindMatrices[j]), &values[j * 16], sizeof(glm::mat4));
  }
  return skin;
}

// The rest morph weights of node `index` drawing glTF mesh `meshIndex`: one
// per morph target, which every primitive of the mesh must have the same
// number of (glTF 2.0 §3.7.2.2); the node's weights, else the mesh's, else zeros.
std::vector<float> restWeights(const ModelRef& ref, int index, int meshIndex) {
  const tinygltf::Node& node = ref.model.nodes[std::size_t(index)];
  const tinygltf::Mesh& mesh = ref.model.meshes[std::size_t(meshIndex)];
  const std::string what = "mesh " + std::to_string(meshIndex);
  const std::size_t targets = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
  for (std::size_t p = 1; p < mesh.primitives.size(); ++p) {
    if (mesh.primitives[p].targets.size() != targets) {
      throw ref.fail(what + " primitive " + std::to_string(p) + " has " +
                     std::to_string(mesh.primitives[p].targets.size()) +
                     " morph targets but primitive 0 has " + std::to_string(targets));
    }
  }
  const auto check = [&](const std::vector<double>& weights, const std::string& who) {
    if (!weights.empty() && weights.size() != targets) {
      throw ref.fail(who + " has " + std::to_string(weights.size()) + " morph weights but " + what +
                     " has " + std::to_string(targets) + " morph targets");
    }
  };
  check(node.weights, "node " + std::to_string(index));
  check(mesh.weights, what);
  const std::vector<double>& given = !node.weights.empty() ? node.weights : mesh.weights;
  std::vector<float> weights(targets, 0.0f);
  for (std::size_t t = 0; t < given.size(); ++t) weights[t] = float(given[t]);
  return weights;
}

// The largest JOINTS_n value of a mesh, -1 when it has no influences.
int largestJoint(const Mesh& mesh) {
  int largest = -1;
  for (const auto& set : mesh.joints) {
    for (const glm::u16vec4& joints : set) {
      for (int k = 0; k < 4; ++k) largest = std::max(largest, int(joints[k]));
    }
  }
  return largest;
}

class SceneBuilder {
 public:
  SceneBuilder(const ModelRef& ref, gltf::MaterialTable& materials, Scene& scene)
      : ref_(ref), materials_(materials), scene_(scene), lights_(readLights(ref)) {}

  // Nodes come in walk order, parents first, as Scene::nodes keeps them.
  void addNode(const PlacedNode& placed) {
    const int sceneNode = int(scene_.nodes.size());
    Node kept = placed.local;
    kept.parent = placed.parent;
    kept.fileIndex = placed.node;
    const tinygltf::Node& node = ref_.model.nodes[std::size_t(placed.node)];
    const std::string what = "node " + std::to_string(placed.node);
    if (node.skin < -1 || node.skin >= int(ref_.model.skins.size())) {
      throw ref_.fail(what + " refers to skin " + std::to_string(node.skin) +
                      ", which does not exist");
    }
    if (node.mesh >= 0 && std::size_t(node.mesh) < ref_.model.meshes.size()) {
      kept.weights = restWeights(ref_, placed.node, node.mesh);
    } else if (!node.weights.empty()) {
      throw ref_.fail(what + " has morph weights but no mesh");
    }
    scene_.nodes.push_back(kept);
    if (node.camera != -1)
      scene_.cameras.push_back(makeCamera(ref_, node.camera, placed.world, sceneNode));
    if (const int light = nodeLight(ref_, placed.node, lights_.size()); light >= 0) {
      Light placedLight = lights_[std::size_t(light)];
      placedLight.world = cameraWorldOf(placed.world);  // rigid, as a camera's
      placedLight.node = sceneNode;
      scene_.lights.push_back(placedLight);
    }
    if (node.mesh == -1) return;
    if (node.mesh < 0 || std::size_t(node.mesh) >= ref_.model.meshes.size()) {
      throw ref_.fail("node " + std::to_string(placed.node) + " refers to mesh " +
                      std::to_string(node.mesh) + ", which does not exist");
    }
    const std::size_t primitiveCount = ref_.model.meshes[std::size_t(node.mesh)].primitives.size();
    for (std::size_t p = 0; p < primitiveCount; ++p) {
      placements_.push_back({jobFor(node.mesh, int(p)), placed.world, sceneNode, node.skin});
    }
  }

  // Decodes every primitive some node draws, then places the drawn ones,
  // reading the skins they use (sceneNodeOf: glTF node → Scene::nodes, -1
  // outside the scene drawn).
  void finish(const std::vector<int>& sceneNodeOf, std::vector<std::string>& notes) {
    for (const PrimitiveJob& job : jobs_) chargeDecode(job);
    decodePrimitives(ref_, jobs_);
    std::vector<int> sceneMesh(jobs_.size(), -1);
    for (std::size_t i = 0; i < jobs_.size(); ++i) {
      PrimitiveJob& job = jobs_[i];
      if (!job.error.empty()) throw Error(job.error);
      notes.insert(notes.end(), job.notes.begin(), job.notes.end());
      if (!job.drawn) continue;
      job.result.material = job.material;
      sceneMesh[i] = int(scene_.meshes.size());
      scene_.meshes.push_back(std::move(job.result));
    }
    std::map<int, int> skinOf;  // glTF skin → Scene::skins
    for (const Placement& placement : placements_) {
      const int mesh = sceneMesh[std::size_t(placement.job)];
      if (mesh < 0) continue;
      Instance instance{mesh, placement.world, placement.node};
      if (placement.fileSkin >= 0) {
        auto [known, added] = skinOf.try_emplace(placement.fileSkin, int(scene_.skins.size()));
        if (added) scene_.skins.push_back(readSkin(ref_, placement.fileSkin, sceneNodeOf));
        instance.skin = known->second;
        checkInfluences(placement, scene_.meshes[std::size_t(mesh)],
                        scene_.skins[std::size_t(instance.skin)]);
      }
      scene_.instances.push_back(std::move(instance));
    }
  }

 private:
  // The budget is charged here, in job order, before the parallel decode: as
  // if every accessor the primitive lists were decoded to 32-bit values (an
  // upper bound on what buildMesh keeps), strips and fans expanded to lists.
  void chargeDecode(const PrimitiveJob& job) const {
    const auto& source =
        ref_.model.meshes[std::size_t(job.mesh)].primitives[std::size_t(job.primitive)];
    std::uint64_t bytes = 0;
    for (const auto& attribute : source.attributes)
      bytes += gltf::decodedAccessorBytes(ref_, attribute.second);
    // Morph targets are expanded to one delta a vertex, sparse or not.
    for (const auto& target : source.targets)
      for (const auto& attribute : target)
        bytes += gltf::decodedAccessorBytes(ref_, attribute.second);
    const auto position = source.attributes.find("POSITION");
    const std::uint64_t indices =
        source.indices != -1 ? gltf::decodedAccessorBytes(ref_, source.indices)
        : position != source.attributes.end()
            ? gltf::decodedAccessorBytes(ref_, position->second) / 3  // one index a VEC3
            : 0;
    const bool expands =
        source.mode == TINYGLTF_MODE_TRIANGLE_STRIP || source.mode == TINYGLTF_MODE_TRIANGLE_FAN;
    bytes += indices * (expands ? 4 : 1);
    // MikkTSpace where a normal-mapped primitive has no TANGENT: its working
    // arrays (welding table, triangles, edges) and, at worst, a copy of a
    // vertex per corner, bounded per corner; the tangents themselves.
    constexpr std::uint64_t kTangentBytesPerCorner = 256;
    if (job.needs.normalMapSet >= 0 && source.attributes.count("TANGENT") == 0) {
      const std::uint64_t corners = indices / 4 * (expands ? 3 : 1);
      const std::uint64_t vertices = position != source.attributes.end()
                                         ? gltf::decodedAccessorBytes(ref_, position->second) / 12
                                         : 0;
      bytes += corners * kTangentBytesPerCorner + vertices * 16;
    }
    ref_.charge("mesh " + std::to_string(job.mesh) + " primitive " + std::to_string(job.primitive) +
                    " decoded",
                bytes);
  }

  int jobFor(int mesh, int primitive) {
    const auto key = std::make_pair(mesh, primitive);
    if (const auto known = jobOf_.find(key); known != jobOf_.end()) return known->second;
    PrimitiveJob job;
    job.mesh = mesh;
    job.primitive = primitive;
    const auto& source = ref_.model.meshes[std::size_t(mesh)].primitives[std::size_t(primitive)];
    job.material = materials_.sceneMaterial(source.material);
    job.needs = materials_.needsOf(job.material);
    jobs_.push_back(std::move(job));
    jobOf_[key] = int(jobs_.size()) - 1;
    return int(jobs_.size()) - 1;
  }

  struct Placement {
    int job;
    glm::mat4 world;
    int node;      // scene node
    int fileSkin;  // the node's glTF skin, -1 for none
  };

  // A skinned primitive needs influences, each naming one of the skin's joints.
  void checkInfluences(const Placement& placement, const Mesh& mesh, const Skin& skin) const {
    const PrimitiveJob& job = jobs_[std::size_t(placement.job)];
    const std::string where =
        "node " + std::to_string(scene_.nodes[std::size_t(placement.node)].fileIndex) + " (skin " +
        std::to_string(placement.fileSkin) + ") draws mesh " + std::to_string(job.mesh) +
        " primitive " + std::to_string(job.primitive);
    if (mesh.joints[0].empty()) throw ref_.fail(where + ", which has no JOINTS_0 and WEIGHTS_0");
    const int largest = largestJoint(mesh);
    if (std::size_t(largest) >= skin.joints.size()) {
      throw ref_.fail(where + ", whose vertices use joint " + std::to_string(largest) +
                      " of a skin with " + std::to_string(skin.joints.size()) + " joints");
    }
  }

  const ModelRef& ref_;
  gltf::MaterialTable& materials_;
  Scene& scene_;
  std::vector<PrimitiveJob> jobs_;
  std::map<std::pair<int, int>, int> jobOf_;
  std::vector<Placement> placements_;
  std::vector<Light> lights_;  // the file's, checked; nodes place copies
};

// What tinygltf made from the file before quadra saw the model: decoded
// data-URI and GLB buffers and the stashed image bytes. tinygltf allocates
// them itself, so they are counted after the fact; each is bounded by the
// bytes of the files charged before they were read (a data URI decodes to
// 3/4 of its text).
void chargeParsed(const ModelRef& ref, const gltf::ImageStash& stash) {
  for (std::size_t i = 0; i < ref.model.buffers.size(); ++i)
    ref.charge("buffer " + std::to_string(i), ref.model.buffers[i].data.size());
  for (const auto& [image, bytes] : stash.encoded)
    ref.charge("image " + std::to_string(image) + " (encoded)", bytes.size());
}

// Skinned and morphed instances at the rest pose: joint matrices from the
// joints' loaded transforms, the nodes' rest weights. The other instances
// keep the placement the node walk gave them.
void poseDeformedInstances(Scene& scene) {
  const bool deformed =
      !scene.skins.empty() || std::any_of(scene.nodes.begin(), scene.nodes.end(),
                                          [](const Node& node) { return !node.weights.empty(); });
  if (!deformed) return;
  NodePose pose;
  poseNodes(scene, -1, 0.0, pose);
  placeOnNodes(scene, pose);
}

Scene convertModel(const std::string& path, const tinygltf::Model& model,
                   const gltf::ImageStash& stash, const LoadOptions& options, MemoryBudget& budget,
                   std::vector<std::string>& notes) {
  const Executor executor = options.arena ? Executor(*options.arena) : Executor(options.threads);
  const ModelRef ref{model, path, &budget, &executor};
  chargeParsed(ref, stash);
  checkExtensions(ref, notes);
  Scene scene;
  scene.name = path;
  gltf::MaterialTable materials(ref, stash, notes);
  SceneBuilder builder(ref, materials, scene);
  const std::vector<PlacedNode> placed = walkNodes(ref, sceneRoots(ref, options, notes));
  for (const PlacedNode& node : placed) builder.addNode(node);
  std::vector<int> sceneNodeOf(model.nodes.size(), -1);
  for (std::size_t i = 0; i < placed.size(); ++i) sceneNodeOf[std::size_t(placed[i].node)] = int(i);
  builder.finish(sceneNodeOf, notes);
  gltf::readAnimations(ref, sceneNodeOf, scene, notes);
  poseDeformedInstances(scene);
  materials.finish(scene);
  return scene;
}

}  // namespace

Scene loadGltf(const std::string& path, const LoadOptions& options,
               std::vector<std::string>* notes) {
  std::vector<std::string> collected;
  try {
    MemoryBudget budget(options.maxMemory, path);
    chargeFileRead(budget, path, "the file");
    const std::vector<std::uint8_t> bytes = readWholeFile(path);
    gltf::ImageStash stash;
    const tinygltf::Model model = parseModel(path, bytes, options, budget, stash);
    Scene scene = convertModel(path, model, stash, options, budget, collected);
    if (notes) {
      for (const std::string& note : collected) notes->push_back(oneLine(note));
    }
    return scene;
  } catch (const Error& e) {
    throw Error(oneLine(e.what()));
  } catch (const std::bad_alloc&) {
    throw makeError(path, "out of memory while loading");
  } catch (const std::exception& e) {
    throw makeError(path, firstLine(e.what()));
  }
}

// Integer attribute types are read generically, so quantized meshes load;
// every textureInfo's transform is read; the material extensions and lights
// are loaded into the fields the lit shading reads (../shared/LIGHTING.md).
bool implementsGltfExtension(const std::string& name) {
  return name == "KHR_mesh_quantization" || name == "KHR_texture_transform" ||
         name == "KHR_materials_emissive_strength" || name == "KHR_materials_ior" ||
         name == "KHR_materials_specular" || name == "KHR_materials_unlit" ||
         name == "KHR_lights_punctual";
}

}  // namespace quadra
