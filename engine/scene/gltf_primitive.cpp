// One glTF mesh primitive → one Mesh: attributes decoded through the checked
// accessor reader, indices validated against the vertex count, and strips and
// fans expanded to triangle lists with the winding glTF 2.0 §3.7.2.1 defines;
// skin influences (JOINTS_n, WEIGHTS_n) and morph targets read and checked;
// TANGENT read, or MikkTSpace tangents generated (scene/tangent_space.h),
// where the material has a normal map.
#include <tiny_gltf.h>

#include <cstring>
#include <limits>
#include <optional>

#include "scene/gltf_internal.h"
#include "scene/tangent_space.h"

namespace quadra::gltf {

namespace {

const char* modeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "POINTS";
    case TINYGLTF_MODE_LINE:
      return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
      return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
      return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES:
      return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN:
      return "TRIANGLE_FAN";
    default:
      return nullptr;
  }
}

const char* typeName(int components) {
  static const char* const names[] = {"?", "SCALAR", "VEC2", "VEC3", "VEC4"};
  return components == 16 ? "MAT4" : names[components];
}

// glm vectors are tightly packed floats, so the decoded array is their storage.
template <typename Vec>
std::vector<Vec> toVectors(const std::vector<float>& flat) {
  static_assert(sizeof(Vec) == sizeof(float) * Vec::length());
  std::vector<Vec> out(flat.size() / Vec::length());
  if (!out.empty()) std::memcpy(out.data(), flat.data(), out.size() * sizeof(Vec));
  return out;
}

// The primitive's context: where it is (for messages) and its attributes.
struct PrimitiveReader {
  const ModelRef& ref;
  const tinygltf::Primitive& primitive;
  std::string where;  // "mesh M primitive P"

  std::optional<int> attribute(const char* name) const {
    const auto it = primitive.attributes.find(name);
    if (it == primitive.attributes.end()) return std::nullopt;
    return it->second;
  }

  // Decodes attribute `name` with one of the allowed element sizes.
  std::vector<float> read(const char* name, int accessor, int minComponents, int maxComponents,
                          std::uint64_t vertexCount, int* components = nullptr) const {
    const AccessorView view = viewAccessor(ref, accessor, where + " " + name);
    if (view.components < minComponents || view.components > maxComponents) {
      throw ref.fail(
          where + ": " + name + " accessor " + std::to_string(accessor) + " is " +
          typeName(view.components) + " (needs " + typeName(minComponents) +
          (minComponents == maxComponents ? "" : std::string(" or ") + typeName(maxComponents)) +
          ")");
    }
    if (vertexCount != 0 && view.count != vertexCount) {
      throw ref.fail(where + ": " + name + " has " + std::to_string(view.count) +
                     " elements but POSITION has " + std::to_string(vertexCount));
    }
    if (components) *components = view.components;
    return decodeFloats(ref, view);
  }

  // Every attribute, read or not, must reference a real accessor of the
  // primitive's vertex count (glTF 2.0 §3.7.2.1).
  void checkAttributeCounts(std::uint64_t vertexCount) const {
    const auto& accessors = ref.model.accessors;
    for (const auto& [name, index] : primitive.attributes) {
      if (index < 0 || std::size_t(index) >= accessors.size()) {
        throw ref.fail(where + ": attribute " + name + " refers to accessor " +
                       std::to_string(index) + ", which does not exist");
      }
      if (accessors[std::size_t(index)].count != vertexCount) {
        throw ref.fail(where + ": attribute " + name + " has " +
                       std::to_string(accessors[std::size_t(index)].count) +
                       " elements but POSITION has " + std::to_string(vertexCount));
      }
    }
  }

  std::vector<std::uint32_t> readIndices(std::uint64_t vertexCount) const {
    if (primitive.indices == -1) {
      std::vector<std::uint32_t> sequential(vertexCount);
      for (std::uint64_t i = 0; i < vertexCount; ++i) sequential[i] = std::uint32_t(i);
      return sequential;
    }
    const AccessorView view = viewAccessor(ref, primitive.indices, where + " indices");
    std::vector<std::uint32_t> indices = decodeUnsigned(ref, view);
    for (std::size_t i = 0; i < indices.size(); ++i) {
      if (indices[i] >= vertexCount) {
        throw ref.fail(where + ": index " + std::to_string(indices[i]) + " (at position " +
                       std::to_string(i) + ") is out of range (" + std::to_string(vertexCount) +
                       " vertices)");
      }
    }
    return indices;
  }
};

// glTF 2.0 §3.7.2.1: strip triangle i is (v_i, v_{i+1+i%2}, v_{i+2-i%2}), which
// flips every odd triangle so that all of them wind like the first.
std::vector<std::uint32_t> expandStrip(const std::vector<std::uint32_t>& strip) {
  std::vector<std::uint32_t> list;
  if (strip.size() < 3) return list;
  list.reserve((strip.size() - 2) * 3);
  for (std::size_t i = 0; i + 2 < strip.size(); ++i) {
    const std::size_t odd = i % 2;
    list.insert(list.end(), {strip[i], strip[i + 1 + odd], strip[i + 2 - odd]});
  }
  return list;
}

// glTF 2.0 §3.7.2.1: fan triangle i is (v_{i+1}, v_{i+2}, v_0).
std::vector<std::uint32_t> expandFan(const std::vector<std::uint32_t>& fan) {
  std::vector<std::uint32_t> list;
  if (fan.size() < 3) return list;
  list.reserve((fan.size() - 2) * 3);
  for (std::size_t i = 0; i + 2 < fan.size(); ++i) {
    list.insert(list.end(), {fan[i + 1], fan[i + 2], fan[0]});
  }
  return list;
}

std::vector<std::uint32_t> toTriangleList(const PrimitiveReader& reader, int mode,
                                          std::vector<std::uint32_t> indices,
                                          std::vector<std::string>& notes) {
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) return expandStrip(indices);
  if (mode == TINYGLTF_MODE_TRIANGLE_FAN) return expandFan(indices);
  if (indices.size() % 3 != 0) {
    notes.push_back(reader.ref.note(reader.where + ": " + std::to_string(indices.size()) +
                                    " indices are not whole triangles; the last " +
                                    std::to_string(indices.size() % 3) + " dropped"));
    indices.resize(indices.size() - indices.size() % 3);
  }
  return indices;
}

void readVertexAttributes(const PrimitiveReader& reader, const PrimitiveNeeds& needs,
                          std::uint64_t vertexCount, Mesh& out, std::vector<std::string>& notes) {
  if (const auto normal = reader.attribute("NORMAL")) {
    out.normals = toVectors<glm::vec3>(reader.read("NORMAL", *normal, 3, 3, vertexCount));
  }
  if (const auto color = reader.attribute("COLOR_0")) {
    int components = 0;
    std::vector<float> flat = reader.read("COLOR_0", *color, 3, 4, vertexCount, &components);
    if (components == 3) {
      out.colors.resize(vertexCount);
      for (std::uint64_t i = 0; i < vertexCount; ++i) {
        out.colors[i] = glm::vec4(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2], 1.0f);
      }
    } else {
      out.colors = toVectors<glm::vec4>(flat);
    }
  }
  for (int set = 0; set < 2; ++set) {
    if (!needs.texcoordSets[set]) continue;  // no texture of the material reads it
    const std::string name = "TEXCOORD_" + std::to_string(set);
    if (const auto texcoord = reader.attribute(name.c_str())) {
      out.texcoords[set] =
          toVectors<glm::vec2>(reader.read(name.c_str(), *texcoord, 2, 2, vertexCount));
    } else {
      // The renderer may rely on a textured material finding its coordinates.
      notes.push_back(reader.ref.note(reader.where + ": its material reads " + name +
                                      ", which it does not have; using (0, 0)"));
      out.texcoords[set].assign(vertexCount, glm::vec2(0.0f));
    }
  }
  if (needs.normalMapSet < 0) return;  // tangents serve normal maps only
  if (const auto tangent = reader.attribute("TANGENT")) {
    // VEC4: xyz the tangent, w the bitangent's sign (float, or normalized
    // byte or short under KHR_mesh_quantization, which the reader decodes).
    out.tangents = toVectors<glm::vec4>(reader.read("TANGENT", *tangent, 4, 4, vertexCount));
  }
}

// JOINTS_n and WEIGHTS_n for n = 0, 1 (glTF 2.0 §3.7.3.2: VEC4; joints
// unsigned byte or short, weights float or normalized unsigned byte or
// short). A set comes whole, set 1 only after set 0.
void readSkinAttributes(const PrimitiveReader& reader, std::uint64_t vertexCount, Mesh& out) {
  const ModelRef& ref = reader.ref;
  for (int set = 0; set < 2; ++set) {
    const std::string jointsName = "JOINTS_" + std::to_string(set);
    const std::string weightsName = "WEIGHTS_" + std::to_string(set);
    const auto joints = reader.attribute(jointsName.c_str());
    const auto weights = reader.attribute(weightsName.c_str());
    if (!joints && !weights) continue;
    if (!joints || !weights) {
      throw ref.fail(reader.where + ": " + (joints ? jointsName : weightsName) + " without " +
                     (joints ? weightsName : jointsName));
    }
    if (set == 1 && out.joints[0].empty())
      throw ref.fail(reader.where + ": JOINTS_1 without JOINTS_0");
    const AccessorView jointsView = viewAccessor(ref, *joints, reader.where + " " + jointsName);
    if (jointsView.normalized ||
        (jointsView.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         jointsView.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)) {
      throw ref.fail(reader.where + ": " + jointsName +
                     " must be UNSIGNED_BYTE or UNSIGNED_SHORT (not normalized)");
    }
    const AccessorView weightsView = viewAccessor(ref, *weights, reader.where + " " + weightsName);
    if (weightsView.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT &&
        !(weightsView.normalized &&
          (weightsView.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
           weightsView.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))) {
      throw ref.fail(reader.where + ": " + weightsName +
                     " must be FLOAT or normalized UNSIGNED_BYTE or UNSIGNED_SHORT");
    }
    // Unsigned byte and short are exact in float.
    const std::vector<float> jointValues =
        reader.read(jointsName.c_str(), *joints, 4, 4, vertexCount);
    out.joints[set].resize(vertexCount);
    for (std::uint64_t i = 0; i < vertexCount; ++i) {
      for (int k = 0; k < 4; ++k)
        out.joints[set][i][k] = std::uint16_t(jointValues[i * 4 + std::uint64_t(k)]);
    }
    out.weights[set] =
        toVectors<glm::vec4>(reader.read(weightsName.c_str(), *weights, 4, 4, vertexCount));
  }
}

// glTF 2.0 §3.7.2.2: each target's deltas for the attributes the mesh keeps
// (POSITION, NORMAL, the TEXCOORD_n its material reads, COLOR_0), each of
// the vertex count. A target may not move an attribute the primitive lacks.
// TANGENT deltas (VEC3) are read where TANGENT is; other sets are not drawn,
// so their deltas are not read.
void readMorphTargets(const PrimitiveReader& reader, const PrimitiveNeeds& needs,
                      std::uint64_t vertexCount, Mesh& out) {
  const ModelRef& ref = reader.ref;
  const auto& targets = reader.primitive.targets;
  out.targets.resize(targets.size());
  for (std::size_t t = 0; t < targets.size(); ++t) {
    MorphTarget& target = out.targets[t];
    const std::string prefix = "target " + std::to_string(t) + " ";
    for (const auto& entry : targets[t]) {
      // Named, not a structured binding: clang before 16 cannot capture one
      // in a lambda (the fuzz build is clang's).
      const std::string& name = entry.first;
      const int accessor = entry.second;
      const std::string what = prefix + name;
      const auto deltas = [&](int components) {
        return reader.read(what.c_str(), accessor, components, components, vertexCount);
      };
      const auto needBase = [&](bool present) {
        if (!present)
          throw ref.fail(reader.where + ": " + what + " moves an attribute the primitive lacks");
      };
      if (name == "POSITION") {
        target.positions = toVectors<glm::vec3>(deltas(3));
      } else if (name == "NORMAL") {
        needBase(!out.normals.empty());
        target.normals = toVectors<glm::vec3>(deltas(3));
      } else if (name == "COLOR_0") {
        needBase(!out.colors.empty());
        int components = 0;
        const std::vector<float> flat =
            reader.read(what.c_str(), accessor, 3, 4, vertexCount, &components);
        if (components == 3) {
          target.colors.resize(vertexCount);
          for (std::uint64_t i = 0; i < vertexCount; ++i)
            target.colors[i] = glm::vec4(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2], 0.0f);
        } else {
          target.colors = toVectors<glm::vec4>(flat);
        }
      } else if (name == "TEXCOORD_0" && needs.texcoordSets[0]) {
        target.texcoords[0] = toVectors<glm::vec2>(deltas(2));
      } else if (name == "TEXCOORD_1" && needs.texcoordSets[1]) {
        target.texcoords[1] = toVectors<glm::vec2>(deltas(2));
      } else if (name == "TANGENT" && !out.tangents.empty()) {
        target.tangents = toVectors<glm::vec3>(deltas(3));
      } else {
        // Checked like any attribute, even where not drawn.
        viewAccessor(ref, accessor, reader.where + " " + what);
      }
    }
  }
}

}  // namespace

bool buildMesh(const ModelRef& ref, int meshIndex, int primitiveIndex, const PrimitiveNeeds& needs,
               Mesh& out, std::vector<std::string>& notes) {
  const tinygltf::Primitive& primitive =
      ref.model.meshes[std::size_t(meshIndex)].primitives[std::size_t(primitiveIndex)];
  const PrimitiveReader reader{
      ref, primitive,
      "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitiveIndex)};

  const int mode = primitive.mode == -1 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (!modeName(mode)) throw ref.fail(reader.where + ": unknown mode " + std::to_string(mode));
  if (mode < TINYGLTF_MODE_TRIANGLES) {
    notes.push_back(ref.note(reader.where + ": mode " + modeName(mode) +
                             " skipped (points and lines are not rasterized)"));
    return false;
  }
  const auto position = reader.attribute("POSITION");
  if (!position) {
    notes.push_back(ref.note(reader.where + ": no POSITION attribute; skipped"));
    return false;
  }
  out.positions = toVectors<glm::vec3>(reader.read("POSITION", *position, 3, 3, 0));
  const std::uint64_t vertexCount = out.positions.size();
  if (vertexCount > std::numeric_limits<std::uint32_t>::max()) {
    throw ref.fail(reader.where + ": " + std::to_string(vertexCount) +
                   " vertices do not fit 32-bit indices");
  }
  reader.checkAttributeCounts(vertexCount);
  if (primitive.indices < -1) {
    throw ref.fail(reader.where + ": indices refer to accessor " +
                   std::to_string(primitive.indices));
  }
  out.indices = toTriangleList(reader, mode, reader.readIndices(vertexCount), notes);
  if (out.indices.empty()) {
    notes.push_back(ref.note(reader.where + ": no complete triangle; skipped"));
    return false;
  }
  readVertexAttributes(reader, needs, vertexCount, out, notes);
  readSkinAttributes(reader, vertexCount, out);
  readMorphTargets(reader, needs, vertexCount, out);
  // glTF 2.0 §3.7.2.1: without TANGENT a client should compute MikkTSpace
  // tangents from the positions, normals and the normal map's coordinates.
  if (needs.normalMapSet >= 0 && out.tangents.empty()) generateTangents(out, needs.normalMapSet);
  return true;
}

}  // namespace quadra::gltf
