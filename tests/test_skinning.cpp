// Skins and morph targets (scene/deformation.h, the vertex stage, posing in
// scene/animation.h) against an independent evaluation: the shared skinned
// and morphed models' accessors read here straight from tinygltf's buffers
// (sparse and normalized elements decoded here too), their animations
// sampled, the node tree composed from the file's TRS, and each vertex
// morphed and skinned by glTF 2.0 §3.7.2.2 and §3.7.3 — all in double
// precision, none of it through the engine's posing. The engine's side is
// what the renderer's vertex stage outputs for the posed instance. Also: the
// loader's one-line errors for bad skin and morph data, and whole frames of
// the posed models against the reference tracer.
#include <gtest/gtest.h>

#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "api/renderer.h"
#include "core/error.h"
#include "core/parallel.h"
#include "gltf_reference.h"
#include "lab/image/image_difference.h"
#include "lab/reference/reference_tracer.h"
#include "lab/scene/builtin_scenes.h"
#include "render_helpers.h"
#include "scene/animation.h"
#include "scene/gltf_loader.h"
#include "vertex/vertex_stage.h"

namespace quadra {
namespace {

namespace fs = std::filesystem;

// One component of type `type` at `bytes`, as a double (normalized per glTF 2.0 §3.11).
double component(const unsigned char* bytes, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, bytes, 4);
      return double(f);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? bytes[0] / 255.0 : bytes[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, bytes, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, bytes, 4);
      return double(v);
    }
  }
  ADD_FAILURE() << "component type " << type << " not read by the reference";
  return 0.0;
}

// Every element of accessor `index` (dense part, then sparse substitutions).
std::vector<DVec> readElements(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = model.accessors.at(std::size_t(index));
  const int n = tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type));
  const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
  std::vector<DVec> out(accessor.count, DVec(std::size_t(n), 0.0));
  if (accessor.bufferView >= 0) {
    const tinygltf::BufferView& view = model.bufferViews.at(std::size_t(accessor.bufferView));
    const unsigned char* base = model.buffers.at(std::size_t(view.buffer)).data.data() +
                                view.byteOffset + accessor.byteOffset;
    const std::size_t stride = view.byteStride ? view.byteStride : std::size_t(size * n);
    for (std::size_t i = 0; i < accessor.count; ++i)
      for (int c = 0; c < n; ++c)
        out[i][std::size_t(c)] = component(base + i * stride + std::size_t(c * size),
                                           accessor.componentType, accessor.normalized);
  }
  if (accessor.sparse.isSparse) {
    const auto& sparse = accessor.sparse;
    const auto& indexView = model.bufferViews.at(std::size_t(sparse.indices.bufferView));
    const auto& valueView = model.bufferViews.at(std::size_t(sparse.values.bufferView));
    const unsigned char* indices = model.buffers.at(std::size_t(indexView.buffer)).data.data() +
                                   indexView.byteOffset + sparse.indices.byteOffset;
    const unsigned char* values = model.buffers.at(std::size_t(valueView.buffer)).data.data() +
                                  valueView.byteOffset + sparse.values.byteOffset;
    const int indexSize =
        tinygltf::GetComponentSizeInBytes(std::uint32_t(sparse.indices.componentType));
    for (int k = 0; k < sparse.count; ++k) {
      const auto target =
          std::size_t(component(indices + k * indexSize, sparse.indices.componentType, false));
      for (int c = 0; c < n; ++c)
        out.at(target)[std::size_t(c)] = component(values + std::size_t((k * n + c) * size),
                                                   accessor.componentType, accessor.normalized);
    }
  }
  return out;
}

DVec transformPoint(const DMat& m, const DVec& p) {
  DVec r(3);
  for (int row = 0; row < 3; ++row)
    r[std::size_t(row)] = m[std::size_t(row)] * p[0] + m[std::size_t(4 + row)] * p[1] +
                          m[std::size_t(8 + row)] * p[2] + m[std::size_t(12 + row)];
  return r;
}

// Spherical interpolation by the angle's cosine (the engine uses chord
// lengths), the shorter way round.
DVec slerp(DVec a, DVec b, double u) {
  // Exporters round keys off the unit sphere (SimpleSkin's 0.707).
  for (DVec* q : {&a, &b}) {
    const double length =
        std::sqrt((*q)[0] * (*q)[0] + (*q)[1] * (*q)[1] + (*q)[2] * (*q)[2] + (*q)[3] * (*q)[3]);
    for (double& c : *q) c /= length;
  }
  double dot = 0.0;
  for (int c = 0; c < 4; ++c) dot += a[std::size_t(c)] * b[std::size_t(c)];
  if (dot < 0.0) {
    for (double& c : b) c = -c;
    dot = -dot;
  }
  const double theta = std::acos(std::min(1.0, dot));
  DVec r(4);
  for (int c = 0; c < 4; ++c) {
    r[std::size_t(c)] = theta < 1e-12
                            ? a[std::size_t(c)] + u * (b[std::size_t(c)] - a[std::size_t(c)])
                            : (std::sin((1 - u) * theta) * a[std::size_t(c)] +
                               std::sin(u * theta) * b[std::size_t(c)]) /
                                  std::sin(theta);
  }
  return r;
}

// A sampler's value at t, `n` components per key; LINEAR and STEP (the
// models checked here use no other interpolation).
DVec sample(const tinygltf::Model& model, const tinygltf::AnimationSampler& sampler, bool rotation,
            std::size_t n, double t) {
  EXPECT_TRUE(sampler.interpolation == "LINEAR" || sampler.interpolation == "STEP")
      << sampler.interpolation;
  const std::vector<DVec> times = readElements(model, sampler.input);
  const std::vector<DVec> flat = readElements(model, sampler.output);
  DVec values;
  for (const DVec& e : flat) values.insert(values.end(), e.begin(), e.end());
  EXPECT_EQ(values.size(), times.size() * n);
  const auto key = [&](std::size_t k) {
    return DVec(values.begin() + std::ptrdiff_t(k * n), values.begin() + std::ptrdiff_t(k * n + n));
  };
  if (t <= times.front()[0]) return key(0);
  if (t >= times.back()[0]) return key(times.size() - 1);
  std::size_t k = 0;
  while (times[k + 1][0] <= t) ++k;
  if (sampler.interpolation == "STEP") return key(k);
  const double u = (t - times[k][0]) / (times[k + 1][0] - times[k][0]);
  if (rotation) return slerp(key(k), key(k + 1), u);
  DVec r(n);
  const DVec a = key(k), b = key(k + 1);
  for (std::size_t c = 0; c < n; ++c) r[c] = a[c] * (1 - u) + b[c] * u;
  return r;
}

// The file's node tree at time t of animation 0: every node's world matrix
// and morph weights (the node's, else its mesh's, else zeros).
struct ReferencePose {
  std::vector<DMat> worlds;
  std::vector<DVec> weights;
};

ReferencePose referencePose(const tinygltf::Model& model, double t) {
  const std::size_t count = model.nodes.size();
  std::vector<DVec> translation(count, DVec{0, 0, 0}), rotation(count, DVec{0, 0, 0, 1}),
      scale(count, DVec{1, 1, 1});
  ReferencePose pose;
  pose.weights.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const tinygltf::Node& node = model.nodes[i];
    if (!node.translation.empty()) translation[i] = node.translation;
    if (!node.rotation.empty()) rotation[i] = node.rotation;
    if (!node.scale.empty()) scale[i] = node.scale;
    if (!node.weights.empty()) {
      pose.weights[i] = node.weights;
    } else if (node.mesh >= 0) {
      const tinygltf::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
      pose.weights[i] =
          !mesh.weights.empty() ? mesh.weights : DVec(mesh.primitives.at(0).targets.size(), 0.0);
    }
  }
  for (const tinygltf::AnimationChannel& channel : model.animations.at(0).channels) {
    const auto node = std::size_t(channel.target_node);
    const auto& sampler = model.animations[0].samplers.at(std::size_t(channel.sampler));
    const std::string& path = channel.target_path;
    if (path == "translation") translation[node] = sample(model, sampler, false, 3, t);
    if (path == "rotation") rotation[node] = sample(model, sampler, true, 4, t);
    if (path == "scale") scale[node] = sample(model, sampler, false, 3, t);
    if (path == "weights")
      pose.weights[node] = sample(model, sampler, false, pose.weights[node].size(), t);
  }
  pose.worlds.assign(count, identity());
  std::vector<int> parent(count, -1);
  for (std::size_t i = 0; i < count; ++i)
    for (int child : model.nodes[i].children) parent[std::size_t(child)] = int(i);
  // Composed by recursion up the parents (no order assumed).
  std::vector<char> done(count, 0);
  std::function<void(std::size_t)> compose = [&](std::size_t i) {
    if (done[i]) return;
    const tinygltf::Node& node = model.nodes[i];
    DMat local;
    if (node.matrix.size() == 16) {
      std::copy(node.matrix.begin(), node.matrix.end(), local.begin());
    } else {
      local = composeTrs(translation[i], rotation[i], scale[i]);
    }
    if (parent[i] >= 0) {
      compose(std::size_t(parent[i]));
      pose.worlds[i] = multiply(pose.worlds[std::size_t(parent[i])], local);
    } else {
      pose.worlds[i] = local;
    }
    done[i] = 1;
  };
  for (std::size_t i = 0; i < count; ++i) compose(i);
  return pose;
}

// World positions of primitive `primitive` of node `node`'s mesh.
std::vector<DVec> referencePositions(const tinygltf::Model& model, const ReferencePose& pose,
                                     int node, int primitive) {
  const tinygltf::Node& source = model.nodes.at(std::size_t(node));
  const tinygltf::Primitive& p =
      model.meshes.at(std::size_t(source.mesh)).primitives.at(std::size_t(primitive));
  std::vector<DVec> positions = readElements(model, p.attributes.at("POSITION"));
  const DVec& weights = pose.weights[std::size_t(node)];
  for (std::size_t target = 0; target < p.targets.size(); ++target) {
    const std::vector<DVec> delta = readElements(model, p.targets[target].at("POSITION"));
    for (std::size_t v = 0; v < positions.size(); ++v)
      for (int c = 0; c < 3; ++c)
        positions[v][std::size_t(c)] += weights.at(target) * delta[v][std::size_t(c)];
  }
  if (source.skin < 0) {
    for (DVec& position : positions)
      position = transformPoint(pose.worlds[std::size_t(node)], position);
    return positions;
  }
  // §3.7.3: sum over influences of weight * world(joint) * inverseBind(joint) * v;
  // the skinned node's own transform does not apply.
  const tinygltf::Skin& skin = model.skins.at(std::size_t(source.skin));
  std::vector<DMat> jointMatrices;
  const std::vector<DVec> inverseBind =
      skin.inverseBindMatrices >= 0
          ? readElements(model, skin.inverseBindMatrices)
          : std::vector<DVec>(skin.joints.size(), DVec(identity().begin(), identity().end()));
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    DMat bind;
    std::copy(inverseBind[j].begin(), inverseBind[j].end(), bind.begin());
    jointMatrices.push_back(multiply(pose.worlds[std::size_t(skin.joints[j])], bind));
  }
  std::vector<DVec> skinned(positions.size(), DVec(3, 0.0));
  for (int set = 0; set < 2; ++set) {
    const std::string suffix = std::to_string(set);
    if (!p.attributes.count("JOINTS_" + suffix)) continue;
    const std::vector<DVec> joints = readElements(model, p.attributes.at("JOINTS_" + suffix));
    const std::vector<DVec> jointWeights =
        readElements(model, p.attributes.at("WEIGHTS_" + suffix));
    for (std::size_t v = 0; v < positions.size(); ++v) {
      for (int k = 0; k < 4; ++k) {
        const double w = jointWeights[v][std::size_t(k)];
        const DVec moved =
            transformPoint(jointMatrices.at(std::size_t(joints[v][std::size_t(k)])), positions[v]);
        for (int c = 0; c < 3; ++c) skinned[v][std::size_t(c)] += w * moved[std::size_t(c)];
      }
    }
  }
  return skinned;
}

// Unit world normals of the primitive: NORMAL plus the weighted target
// deltas, then through the inverse transpose of the node's world matrix, or
// of a skinned vertex's blended joint matrix (glm's inverse in double).
std::vector<glm::dvec3> referenceNormals(const tinygltf::Model& model, const ReferencePose& pose,
                                         int node, int primitive) {
  const tinygltf::Node& source = model.nodes.at(std::size_t(node));
  const tinygltf::Primitive& p =
      model.meshes.at(std::size_t(source.mesh)).primitives.at(std::size_t(primitive));
  std::vector<DVec> normals = readElements(model, p.attributes.at("NORMAL"));
  const DVec& weights = pose.weights[std::size_t(node)];
  for (std::size_t target = 0; target < p.targets.size(); ++target) {
    if (!p.targets[target].count("NORMAL")) continue;
    const std::vector<DVec> delta = readElements(model, p.targets[target].at("NORMAL"));
    for (std::size_t v = 0; v < normals.size(); ++v)
      for (int c = 0; c < 3; ++c)
        normals[v][std::size_t(c)] += weights.at(target) * delta[v][std::size_t(c)];
  }
  const auto toGlm = [](const DMat& m) {
    glm::dmat3 r;
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) r[col][row] = m[std::size_t(col * 4 + row)];
    return r;
  };
  std::vector<DMat> blended(normals.size(), pose.worlds[std::size_t(node)]);
  if (source.skin >= 0) {
    const tinygltf::Skin& skin = model.skins.at(std::size_t(source.skin));
    const std::vector<DVec> inverseBind = readElements(model, skin.inverseBindMatrices);
    const std::vector<DVec> joints = readElements(model, p.attributes.at("JOINTS_0"));
    const std::vector<DVec> jointWeights = readElements(model, p.attributes.at("WEIGHTS_0"));
    for (std::size_t v = 0; v < normals.size(); ++v) {
      blended[v] = DMat{};
      for (int k = 0; k < 4; ++k) {
        const auto j = std::size_t(joints[v][std::size_t(k)]);
        DMat bind;
        std::copy(inverseBind[j].begin(), inverseBind[j].end(), bind.begin());
        const DMat joint = multiply(pose.worlds[std::size_t(skin.joints[j])], bind);
        for (std::size_t e = 0; e < 16; ++e)
          blended[v][e] += jointWeights[v][std::size_t(k)] * joint[e];
      }
    }
  }
  std::vector<glm::dvec3> out;
  for (std::size_t v = 0; v < normals.size(); ++v) {
    const glm::dvec3 n = glm::transpose(glm::inverse(toGlm(blended[v]))) *
                         glm::dvec3(normals[v][0], normals[v][1], normals[v][2]);
    out.push_back(glm::normalize(n));
  }
  return out;
}

// What the vertex stage outputs for the instance with an identity
// projection: its world positions (w = 1, as the model-view is affine).
std::vector<glm::dvec3> enginePositions(const Scene& scene, const Instance& instance) {
  DrawGeometry geometry;
  geometry.mesh = &scene.meshes.at(std::size_t(instance.mesh));
  geometry.modelView = instance.world;
  geometry.projection = glm::mat4(1.0f);
  geometry.morphWeights = instance.morphWeights;
  geometry.jointMatrices = instance.jointMatrices;
  const Executor executor(1);
  TransformedVertices out;
  transformVertices(geometry, Viewport{64, 64}, executor, out);
  std::vector<glm::dvec3> positions;
  for (std::size_t i = 0; i < geometry.mesh->positions.size(); ++i) {
    const float* v = out.vertex(std::uint32_t(i));
    EXPECT_EQ(v[3], 1.0f);
    positions.emplace_back(v[0], v[1], v[2]);
  }
  return positions;
}

double animationEnd(const tinygltf::Model& model) {
  double end = 0.0;
  for (const auto& sampler : model.animations.at(0).samplers)
    end = std::max(end, readElements(model, sampler.input).back()[0]);
  return end;
}

// The largest distance between the engine's posed vertices and the
// reference's, over instances and the chosen times, relative to the size of
// the posed model (its largest coordinate).
void expectPosedPositionsMatch(const std::string& model, double tolerance) {
  const std::string path = assetPath(model);
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
  const tinygltf::Model file = parseReference(path);
  Scene scene = loadGltf(path);
  ASSERT_FALSE(scene.animations.empty());
  const double end = animationEnd(file);
  NodePose pose;
  std::size_t checked = 0;
  for (const double t : {0.0, 0.137 * end, 0.5 * end, 0.71 * end, end, end + 1.0}) {
    poseNodes(scene, 0, t, pose);
    placeOnNodes(scene, pose);
    const ReferencePose reference = referencePose(file, t);
    // Instances of a node follow its primitives in order.
    int lastNode = -1, primitive = 0;
    for (const Instance& instance : scene.instances) {
      const int node = scene.nodes.at(std::size_t(instance.node)).fileIndex;
      primitive = node == lastNode ? primitive + 1 : 0;
      lastNode = node;
      const std::vector<DVec> want = referencePositions(file, reference, node, primitive);
      const std::vector<glm::dvec3> got = enginePositions(scene, instance);
      ASSERT_EQ(got.size(), want.size());
      double extent = 0.0, worst = 0.0;
      for (const DVec& p : want)
        for (double c : p) extent = std::max(extent, std::fabs(c));
      for (std::size_t v = 0; v < want.size(); ++v) {
        const glm::dvec3 w(want[v][0], want[v][1], want[v][2]);
        worst = std::max(worst, glm::length(got[v] - w));
      }
      EXPECT_LE(worst, tolerance * extent) << model << " t=" << t << " node " << node;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0u);
}

// Tolerance: the engine poses in float (ulp 6e-8 relative). A vertex goes
// through its joint's chain of ancestors (up to ~10 matrix products), the
// inverse bind matrix, the blend of up to 4 joint matrices (or a few weighted
// morph deltas) and one transform, each rounding a quantity of the model's
// size. Measured worst, over these models and times: 2.6e-7 of the extent
// (CesiumMan, AnimatedMorphCube), about 4 ulps. 2e-6 (~33 ulps) leaves room
// for other compilers' orderings; a wrong joint, weight, matrix order or
// interpolation moves vertices by a good part of the extent.
constexpr double kPoseTolerance = 2e-6;

// Normals as the lit shading reads them from the vertex stage (view space
// with an identity view: world space), against the reference's, as
// directions: within 2e-6 (float rounding of unit vectors through a few
// matrix products, as for positions; measured worst 3.1e-7, CesiumMan; a
// missing inverse transpose or a skipped skin turns them by far more).
TEST(Skinning, NormalsFollowTheSkinsAndMorphs) {
  int models = 0;
  for (const char* model : {"RiggedSimple", "RiggedFigure", "CesiumMan", "AnimatedMorphCube"}) {
    const std::string path = assetPath(model);
    if (!fs::exists(path)) continue;
    ++models;
    const tinygltf::Model file = parseReference(path);
    Scene scene = loadGltf(path);
    NodePose pose;
    const double t = 0.37 * animationEnd(file);
    poseNodes(scene, 0, t, pose);
    placeOnNodes(scene, pose);
    const ReferencePose reference = referencePose(file, t);
    for (const Instance& instance : scene.instances) {
      const int node = scene.nodes.at(std::size_t(instance.node)).fileIndex;
      const std::vector<glm::dvec3> want = referenceNormals(file, reference, node, 0);
      DrawGeometry geometry;
      geometry.mesh = &scene.meshes.at(std::size_t(instance.mesh));
      geometry.modelView = instance.world;
      geometry.projection = glm::mat4(1.0f);
      geometry.morphWeights = instance.morphWeights;
      geometry.jointMatrices = instance.jointMatrices;
      geometry.attributes.normal = 0;
      geometry.attributes.count = 3;
      const Executor executor(1);
      TransformedVertices out;
      transformVertices(geometry, Viewport{64, 64}, executor, out);
      double worst = 0.0;
      for (std::size_t v = 0; v < want.size(); ++v) {
        const float* n = out.vertex(std::uint32_t(v)) + 4;
        const glm::dvec3 got = glm::normalize(glm::dvec3(n[0], n[1], n[2]));
        worst = std::max(worst, glm::length(got - want[v]));
      }
      EXPECT_LE(worst, 2e-6) << model << " t=" << t;
    }
  }
  if (models == 0) GTEST_SKIP() << "no skinned or morphed models with normals";
}

TEST(Skinning, SimpleSkinMatchesADoublePrecisionEvaluation) {
  expectPosedPositionsMatch("SimpleSkin", kPoseTolerance);
}
TEST(Skinning, RiggedSimpleMatchesADoublePrecisionEvaluation) {
  expectPosedPositionsMatch("RiggedSimple", kPoseTolerance);
}
TEST(Skinning, RiggedFigureMatchesADoublePrecisionEvaluation) {
  expectPosedPositionsMatch("RiggedFigure", kPoseTolerance);
}
TEST(Skinning, CesiumManMatchesADoublePrecisionEvaluation) {
  expectPosedPositionsMatch("CesiumMan", kPoseTolerance);
}
TEST(Morphing, SimpleMorphMatchesADoublePrecisionEvaluation) {
  expectPosedPositionsMatch("SimpleMorph", kPoseTolerance);
}
TEST(Morphing, AnimatedMorphCubeMatchesADoublePrecisionEvaluation) {
  expectPosedPositionsMatch("AnimatedMorphCube", kPoseTolerance);
}

// A weights sampler is evaluated as a translation's, componentwise: the
// same values (rounded to float) for every interpolation, inside and
// outside the keys.
TEST(Morphing, WeightsFollowTheSamplerInterpolations) {
  for (const Interpolation interpolation :
       {Interpolation::Step, Interpolation::Linear, Interpolation::CubicSpline}) {
    AnimationSampler sampler;
    sampler.interpolation = interpolation;
    sampler.components = 3;
    sampler.times = {0.5f, 1.0f, 2.5f};
    const int perKey = interpolation == Interpolation::CubicSpline ? 3 : 1;
    for (int k = 0; k < 3 * 3 * perKey; ++k) sampler.values.push_back(float(k % 7) * 0.37f - 1.0f);
    std::vector<float> weights;
    for (const double t : {0.0, 0.5, 0.7, 1.0, 1.3, 2.49, 2.5, 3.0}) {
      sampleWeights(sampler, t, weights);
      const glm::dvec4 want = sampleAnimation(sampler, false, t);
      ASSERT_EQ(weights.size(), 3u);
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(weights[std::size_t(c)], float(want[c])) << int(interpolation) << " t=" << t;
    }
  }
}

// ---- frames against the reference tracer -------------------------------------------

// The posed scene with every instance's vertices replaced by the
// reference's posed world positions (rounded once to float) and nothing left
// to deform: what the reference tracer draws for the animated frame.
Scene bakedReference(const Scene& posed, const tinygltf::Model& file, double t) {
  const ReferencePose reference = referencePose(file, t);
  Scene baked = posed;
  baked.meshes.clear();
  int lastNode = -1, primitive = 0;
  for (Instance& instance : baked.instances) {
    const int node = baked.nodes.at(std::size_t(instance.node)).fileIndex;
    primitive = node == lastNode ? primitive + 1 : 0;
    lastNode = node;
    Mesh mesh = posed.meshes.at(std::size_t(instance.mesh));
    const std::vector<DVec> positions = referencePositions(file, reference, node, primitive);
    for (std::size_t v = 0; v < positions.size(); ++v)
      mesh.positions[v] = glm::vec3(glm::dvec3(positions[v][0], positions[v][1], positions[v][2]));
    mesh.targets.clear();
    mesh.joints[0].clear();
    mesh.joints[1].clear();
    instance = Instance{int(baked.meshes.size()), glm::mat4(1.0f), instance.node};
    baked.meshes.push_back(std::move(mesh));
  }
  return baked;
}

Image drawnFrame(const Scene& scene, const Camera& camera) {
  RenderSettings settings;
  settings.width = 160;
  settings.height = 120;
  settings.samples = 16;  // edges as the reference's box filter sees them
  return frameImage(renderOnce(scene, camera, settings));
}

// Animated models at their first frame and 30% into the animation: the frame drawn
// from the posed scene against the reference tracer's frame of the
// reference's posed geometry, seen by the same camera (the posed scene's:
// the file's, or one framing its posed bounds). The same frame drawn with
// the skins and morphs ignored (the mesh as stored, at its node) must fall
// below the threshold at the later time, so the threshold tells a deformed frame
// from one that is not. 30 dB: CesiumMan's mipmapped texture against the
// reference's level-0 bilinear gives 33 dB; the undeformed frames 10-21 dB.
TEST(Skinning, AnimatedFramesMatchTheReferenceTracer) {
  int models = 0;
  for (const char* model : {"SimpleSkin", "RiggedSimple", "RiggedFigure", "CesiumMan",
                            "SimpleMorph", "AnimatedMorphCube"}) {
    const std::string path = assetPath(model);
    if (!fs::exists(path)) continue;
    ++models;
    const tinygltf::Model file = parseReference(path);
    Scene scene = loadGltf(path);
    NodePose pose;
    // 0.3: SimpleSkin's bend is back to straight half way through.
    for (const double t : {0.0, 0.3 * animationEnd(file)}) {
      poseNodes(scene, 0, t, pose);
      placeOnNodes(scene, pose);
      const Camera camera = firstCameraOrDefault(scene);
      const Scene baked = bakedReference(scene, file, t);
      const Image reference = ref::ReferenceTracer(baked, camera, 160, 120).render(6);
      const double psnr = imageDifference(drawnFrame(scene, camera), reference).psnr;
      Scene rigid = scene;
      for (Instance& instance : rigid.instances) {
        instance.world = pose.worlds.at(std::size_t(instance.node));
        instance.jointMatrices.clear();
        instance.morphWeights.clear();
      }
      const double rigidPsnr = imageDifference(drawnFrame(rigid, camera), reference).psnr;
      std::printf("[ %s t=%.3f ] PSNR %.2f dB against the reference (%.2f dB undeformed)\n", model,
                  t, psnr, rigidPsnr);
      EXPECT_GT(psnr, 30.0) << model << " t=" << t;
      // At t = 0 some models rest undeformed (SimpleMorph's weights start at 0).
      if (t > 0.0) {
        EXPECT_LT(rigidPsnr, 30.0) << model << " t=" << t;
      }
    }
  }
  if (models == 0) GTEST_SKIP() << "no animated models under " << QUADRA_ASSETS_DIR;
}

// The position AOV of a posed skinned or morphed model lies on the posed
// surface: at each pixel centre where the engine and the reference tracer
// see the same triangle, its view depth is the tracer's hit distance (the
// AOV reads the deformed vertices as the vertex stage drew them).
TEST(Skinning, PositionAovLiesOnThePosedSurface) {
  int models = 0;
  for (const char* model : {"CesiumMan", "SimpleMorph"}) {
    const std::string path = assetPath(model);
    if (!fs::exists(path)) continue;
    ++models;
    const tinygltf::Model file = parseReference(path);
    Scene scene = loadGltf(path);
    NodePose pose;
    poseNodes(scene, 0, 0.3 * animationEnd(file), pose);
    placeOnNodes(scene, pose);
    const Camera camera = firstCameraOrDefault(scene);
    RenderSettings settings;
    settings.width = 160;
    settings.height = 120;
    settings.aovs = AovSet(Aov::Position) | AovSet(Aov::Ids);
    const Frame frame = renderOnce(scene, camera, settings);
    const ref::ReferenceTracer tracer(scene, camera, settings.width, settings.height);
    const glm::dmat4 view(viewMatrix(camera));
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    const double size = glm::length(glm::dvec3(hi - lo));
    int compared = 0;
    for (int y = 0; y < settings.height; ++y)
      for (int x = 0; x < settings.width; ++x) {
        const std::size_t p = std::size_t(y) * std::size_t(settings.width) + std::size_t(x);
        const std::optional<ref::TracerHit> hit = tracer.nearestHit({x + 0.5, y + 0.5});
        if (!hit || frame.primitiveId[p] != std::uint32_t(hit->triangle)) continue;
        const glm::dvec3 position(frame.position[3 * p], frame.position[3 * p + 1],
                                  frame.position[3 * p + 2]);
        const glm::dvec4 inView = view * glm::dvec4(position, 1.0);
        EXPECT_NEAR(-inView.z, hit->viewDistance, 1e-5 * size) << model << " " << x << "," << y;
        ++compared;
      }
    EXPECT_GT(compared, 100) << model;
  }
  if (models == 0) GTEST_SKIP() << "no skinned or morphed models";
}

// The motion AOV follows skins and morphs: a frame posed at t with the
// previous pose (t - 1/24) given to the renderer as a sequence gives it, the
// camera fixed. Expected, per pixel: the engine's P (checked on the posed
// surface above) as barycentrics of its triangle (id.primitive) among the
// reference's posed vertices at t, the same barycentrics of the reference's
// vertices at t - 1/24, projected: the pixel centre minus that is the motion.
// The reference poses in double from the accessors; none of it is the
// engine's posing or deformation. Tolerance: P and the deformed vertices
// are float (about 1e-6 of the model's size, 1e-4 px here); 2e-3 px.
TEST(Skinning, MotionAovFollowsJointsAndMorphWeights) {
  int models = 0;
  for (const char* model : {"CesiumMan", "AnimatedMorphCube"}) {
    const std::string path = assetPath(model);
    if (!fs::exists(path)) continue;
    ++models;
    const tinygltf::Model file = parseReference(path);
    Scene scene = loadGltf(path);
    const Camera camera = firstCameraOrDefault(scene);  // the rest pose's framing, kept
    const double t = 0.4 * animationEnd(file), before = t - 1.0 / 24.0;
    NodePose pose;
    poseNodes(scene, 0, before, pose);
    placeOnNodes(scene, pose);
    PreviousPose previous;
    previous.camera = camera;
    for (const Instance& instance : scene.instances) {
      previous.instanceWorlds.push_back(instance.world);
      previous.instanceJoints.push_back(instance.jointMatrices);
      previous.instanceMorphWeights.push_back(instance.morphWeights);
    }
    poseNodes(scene, 0, t, pose);
    placeOnNodes(scene, pose);
    RenderSettings settings;
    settings.width = 160;
    settings.height = 120;
    settings.aovs = AovSet(Aov::Position) | AovSet(Aov::Ids) | AovSet(Aov::Motion);
    settings.previousPose = &previous;
    const Frame frame = renderOnce(scene, camera, settings);

    const ReferencePose now = referencePose(file, t), then = referencePose(file, before);
    const glm::dmat4 viewToClip =
        glm::dmat4(projectionMatrix(camera, double(settings.width) / settings.height,
                                    DepthMode::Standard)) *
        glm::dmat4(viewMatrix(camera));
    int checked = 0, moving = 0;
    double worst = 0.0;
    for (int y = 0; y < settings.height; ++y)
      for (int x = 0; x < settings.width; ++x) {
        const std::size_t p = std::size_t(y) * std::size_t(settings.width) + std::size_t(x);
        if (frame.nodeId[p] == kNoId) continue;
        const int node = int(frame.nodeId[p]);
        ASSERT_GE(file.nodes.at(std::size_t(node)).mesh, 0) << model;
        ASSERT_EQ(file.meshes[std::size_t(file.nodes[std::size_t(node)].mesh)].primitives.size(),
                  1u);
        const std::vector<DVec> at = referencePositions(file, now, node, 0);
        const std::vector<DVec> was = referencePositions(file, then, node, 0);
        const std::vector<DVec> indices = readElements(
            file,
            file.meshes[std::size_t(file.nodes[std::size_t(node)].mesh)].primitives[0].indices);
        glm::dvec3 corner[3], corner0[3];
        for (int k = 0; k < 3; ++k) {
          const auto v =
              std::size_t(indices.at(3 * std::size_t(frame.primitiveId[p]) + std::size_t(k))[0]);
          corner[k] = {at[v][0], at[v][1], at[v][2]};
          corner0[k] = {was[v][0], was[v][1], was[v][2]};
        }
        // P = c0 + b1 (c1 - c0) + b2 (c2 - c0), least squares in 3D.
        const glm::dvec3 e1 = corner[1] - corner[0], e2 = corner[2] - corner[0];
        const glm::dvec3 d(frame.position[3 * p] - corner[0].x,
                           frame.position[3 * p + 1] - corner[0].y,
                           frame.position[3 * p + 2] - corner[0].z);
        const double a11 = glm::dot(e1, e1), a12 = glm::dot(e1, e2), a22 = glm::dot(e2, e2);
        const double det = a11 * a22 - a12 * a12;
        if (!(det > 1e-12 * a11 * a22)) continue;  // a sliver: barycentrics ill-conditioned
        const double b1 = (a22 * glm::dot(d, e1) - a12 * glm::dot(d, e2)) / det;
        const double b2 = (a11 * glm::dot(d, e2) - a12 * glm::dot(d, e1)) / det;
        const glm::dvec3 old =
            corner0[0] + b1 * (corner0[1] - corner0[0]) + b2 * (corner0[2] - corner0[0]);
        const glm::dvec4 clip = viewToClip * glm::dvec4(old, 1.0);
        const double previousX = (clip.x / clip.w + 1.0) * 0.5 * settings.width;
        const double previousY = (1.0 - clip.y / clip.w) * 0.5 * settings.height;
        const double errorX = frame.motion[2 * p] - (x + 0.5 - previousX);
        const double errorY = frame.motion[2 * p + 1] - (y + 0.5 - previousY);
        worst = std::max({worst, std::fabs(errorX), std::fabs(errorY)});
        ASSERT_LT(std::max(std::fabs(errorX), std::fabs(errorY)), 2e-3)
            << model << " pixel " << x << "," << y;
        moving += std::fabs(frame.motion[2 * p]) + std::fabs(frame.motion[2 * p + 1]) > 0.1f;
        ++checked;
      }
    std::printf("%s: motion of %d pixels within %.3g px of the reference (%d moving)\n", model,
                checked, worst, moving);
    EXPECT_GT(checked, 200) << model;
    EXPECT_GT(moving, 100) << model << ": nothing moved between the poses";
  }
  if (models == 0) GTEST_SKIP() << "no skinned or morphed models";
}

// ---- bad input ------------------------------------------------------------------------

struct BadEdit {
  const char* model;
  const char* from;
  const char* to;
  const char* mentions;
};

TEST(Skinning, BadSkinAndMorphDataIsAOneLineErrorNamingTheFile) {
  if (!fs::exists(assetPath("SimpleSkin")) || !fs::exists(assetPath("SimpleMorph")))
    GTEST_SKIP() << "no SimpleSkin or SimpleMorph";
  const BadEdit cases[] = {
      // Vertices name joint 1 of a skin that now has one joint.
      {"SimpleSkin", "\"joints\" : [ 1, 2 ]", "\"joints\" : [ 1 ]", "joint 1"},
      {"SimpleSkin", "\"joints\" : [ 1, 2 ]", "\"joints\" : [ 1, 7 ]", "node 7"},
      {"SimpleSkin", "\"skin\" : 0,", "\"skin\" : 3,", "skin 3"},
      // Inverse bind matrices: two needed, the accessor now a VEC4 one.
      {"SimpleSkin", "\"inverseBindMatrices\" : 4", "\"inverseBindMatrices\" : 3", "MAT4"},
      // WEIGHTS_0 given by the indices accessor (24 elements for 10 vertices).
      {"SimpleSkin", "\"WEIGHTS_0\" : 3", "\"WEIGHTS_0\" : 0", "WEIGHTS_0"},
      {"SimpleSkin", "\"JOINTS_0\" : 2,", "\"JOINTS_0\" : 3,", "JOINTS_0"},
      // Two targets, one default weight.
      {"SimpleMorph", "\"weights\":[\n        0.5,\n        0.5\n      ]",
       "\"weights\":[\n        0.5\n      ]", "weights"},
      // A target's POSITION of the wrong length (the indices' 3 elements are
      // SCALAR; the animation's 2 key times have the wrong count).
      {"SimpleMorph", "\"POSITION\":3", "\"POSITION\":4", "target 1 POSITION"},
      // Target 1's POSITION two elements long for three vertices.
      {"SimpleMorph", "\"byteOffset\":72,\n      \"componentType\":5126,\n      \"count\":3",
       "\"byteOffset\":72,\n      \"componentType\":5126,\n      \"count\":2",
       "target 1 POSITION has 2 elements but POSITION has 3"},
      // Weight keys: 2 keys need 4 values, the times accessor gives 2.
      {"SimpleMorph", "\"output\":5", "\"output\":4", "weights"},
  };
  for (const BadEdit& c : cases) {
    const std::string message = loadErrorWithEdit(c.model, c.from, c.to);
    EXPECT_NE(message.find("edited.gltf"), std::string::npos) << c.model << ": " << message;
    EXPECT_NE(message.find(c.mentions), std::string::npos) << c.model << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace quadra
