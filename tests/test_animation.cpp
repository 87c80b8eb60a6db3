// Node animation (scene/animation.h) against an independent evaluation: the
// shared animated models' accessors read here straight from tinygltf's
// buffers, each interpolation evaluated in double precision in another form
// than the engine's (slerp as q0 (q0^-1 q1)^u, the cubic spline as a Bezier
// curve by de Casteljau), and the node tree composed from the file's own
// TRS. Also: the shorter arc, clamping outside the keys, the loaded bits of
// the rest pose, and the loader's one-line errors for bad animation data.
#include <gtest/gtest.h>

#include <tiny_gltf.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "gltf_reference.h"
#include "scene/animation.h"
#include "scene/gltf_loader.h"

namespace quadra {
namespace {

namespace fs = std::filesystem;

// ---- the independent evaluation ---------------------------------------------------

// Elements of a FLOAT accessor, each `components` doubles.
std::vector<DVec> readFloats(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = model.accessors.at(std::size_t(index));
  EXPECT_EQ(accessor.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  const tinygltf::BufferView& view = model.bufferViews.at(std::size_t(accessor.bufferView));
  const std::vector<unsigned char>& data = model.buffers.at(std::size_t(view.buffer)).data;
  const int n = tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type));
  const std::size_t stride = view.byteStride ? view.byteStride : std::size_t(4 * n);
  std::vector<DVec> out;
  for (std::size_t i = 0; i < accessor.count; ++i) {
    DVec element;
    for (int c = 0; c < n; ++c) {
      float f;
      std::memcpy(&f, data.data() + view.byteOffset + accessor.byteOffset + i * stride + 4 * c, 4);
      element.push_back(double(f));
    }
    out.push_back(element);
  }
  return out;
}

DVec normalized(DVec q) {
  double length = 0.0;
  for (double c : q) length += c * c;
  length = std::sqrt(length);
  for (double& c : q) c /= length;
  return q;
}

// Hamilton product of x, y, z, w quaternions.
DVec quaternionProduct(const DVec& a, const DVec& b) {
  return {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
          a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
          a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
          a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}

// q0 (q0^-1 q1)^u, the relative rotation taken the short way (w >= 0).
DVec powerSlerp(DVec q0, DVec q1, double u) {
  q0 = normalized(q0);
  q1 = normalized(q1);
  DVec relative = quaternionProduct({-q0[0], -q0[1], -q0[2], q0[3]}, q1);
  if (relative[3] < 0.0)
    for (double& c : relative) c = -c;
  const double half = std::acos(std::min(1.0, relative[3]));
  const double axisLength =
      std::sqrt(relative[0] * relative[0] + relative[1] * relative[1] + relative[2] * relative[2]);
  if (axisLength == 0.0) return q0;
  const double s = std::sin(u * half) / axisLength;
  return normalized(quaternionProduct(
      q0, {relative[0] * s, relative[1] * s, relative[2] * s, std::cos(u * half)}));
}

// One file sampler read back: times and per-key elements (CUBICSPLINE keys
// are three elements: in-tangent, value, out-tangent).
struct ReferenceCurve {
  DVec times;
  std::vector<DVec> elements;
  std::string interpolation;
};

DVec lerp(const DVec& a, const DVec& b, double u) {
  DVec r(a.size());
  for (std::size_t c = 0; c < a.size(); ++c) r[c] = a[c] + u * (b[c] - a[c]);
  return r;
}

DVec referenceValue(const ReferenceCurve& curve, bool rotation, double t) {
  const bool cubic = curve.interpolation == "CUBICSPLINE";
  const auto value = [&](std::size_t k) { return curve.elements[cubic ? 3 * k + 1 : k]; };
  const std::size_t last = curve.times.size() - 1;
  DVec result;
  if (t <= curve.times[0]) {
    result = value(0);
  } else if (t >= curve.times[last]) {
    result = value(last);
  } else {
    std::size_t k = 0;
    while (curve.times[k + 1] <= t) ++k;
    const double dt = curve.times[k + 1] - curve.times[k];
    const double u = (t - curve.times[k]) / dt;
    if (curve.interpolation == "STEP") {
      result = value(k);
    } else if (!cubic) {
      result = rotation ? powerSlerp(value(k), value(k + 1), u) : lerp(value(k), value(k + 1), u);
    } else {
      // The Hermite segment as a Bezier curve: control points p0, p0 + m0/3,
      // p1 - m1/3, p1 with the tangents m scaled by the interval.
      const DVec& p0 = value(k);
      const DVec& p1 = value(k + 1);
      const DVec& out0 = curve.elements[3 * k + 2];
      const DVec& in1 = curve.elements[3 * (k + 1)];
      DVec c1(p0.size()), c2(p0.size());
      for (std::size_t c = 0; c < p0.size(); ++c) {
        c1[c] = p0[c] + out0[c] * dt / 3.0;
        c2[c] = p1[c] - in1[c] * dt / 3.0;
      }
      const DVec a = lerp(p0, c1, u), b = lerp(c1, c2, u), c = lerp(c2, p1, u);
      result = lerp(lerp(a, b, u), lerp(b, c, u), u);
    }
  }
  return rotation ? normalized(result) : result;
}

// The reference pose of a file at time t for animation `animation`: each
// node's world matrix, from the file's TRS with the driven ones replaced.
std::vector<DMat> referenceWorlds(const tinygltf::Model& model,
                                  const std::vector<ReferenceCurve>& curves, int animation,
                                  double t) {
  const std::size_t count = model.nodes.size();
  std::vector<DVec> translation(count, DVec{0, 0, 0}), rotation(count, DVec{0, 0, 0, 1}),
      scale(count, DVec{1, 1, 1});
  for (std::size_t i = 0; i < count; ++i) {
    const tinygltf::Node& node = model.nodes[i];
    if (!node.translation.empty()) translation[i] = node.translation;
    if (!node.rotation.empty()) rotation[i] = normalized(node.rotation);
    if (!node.scale.empty()) scale[i] = node.scale;
  }
  const tinygltf::Animation& a = model.animations.at(std::size_t(animation));
  for (const tinygltf::AnimationChannel& channel : a.channels) {
    const std::size_t node = std::size_t(channel.target_node);
    const ReferenceCurve& curve = curves[std::size_t(channel.sampler)];
    if (channel.target_path == "translation") translation[node] = referenceValue(curve, false, t);
    if (channel.target_path == "rotation") rotation[node] = referenceValue(curve, true, t);
    if (channel.target_path == "scale") scale[node] = referenceValue(curve, false, t);
  }
  std::vector<int> parent(count, -1);
  for (std::size_t i = 0; i < count; ++i)
    for (int child : model.nodes[i].children) parent[std::size_t(child)] = int(i);
  std::vector<DMat> worlds(count);
  std::vector<char> done(count, 0);
  // Parents may come after their children in the file: resolve by recursion.
  std::function<const DMat&(std::size_t)> world = [&](std::size_t i) -> const DMat& {
    if (!done[i]) {
      const tinygltf::Node& node = model.nodes[i];
      DMat local = composeTrs(translation[i], rotation[i], scale[i]);
      if (!node.matrix.empty()) std::copy(node.matrix.begin(), node.matrix.end(), local.begin());
      worlds[i] = parent[i] < 0 ? local : multiply(world(std::size_t(parent[i])), local);
      done[i] = 1;
    }
    return worlds[i];
  };
  for (std::size_t i = 0; i < count; ++i) world(i);
  return worlds;
}

// Every time worth checking on a curve: before, at and after each key, and
// between keys at a quarter, half and three quarters.
DVec timesToCheck(const DVec& keys) {
  DVec times{keys.front() - 0.5, keys.back() + 0.5};
  for (std::size_t k = 0; k < keys.size(); ++k) {
    times.push_back(keys[k]);
    if (k + 1 < keys.size())
      for (double f : {0.25, 0.5, 0.75}) times.push_back(keys[k] + f * (keys[k + 1] - keys[k]));
  }
  return times;
}

// Every channel's values and every node's world transform of every
// animation of `model`, at every time worth checking, against the reference.
void expectMatchesReference(const std::string& model) {
  const std::string path = assetPath(model);
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
  const Scene scene = loadGltf(path);
  const tinygltf::Model file = parseReference(path);
  ASSERT_EQ(scene.animations.size(), file.animations.size());
  std::size_t checked = 0;
  for (std::size_t a = 0; a < file.animations.size(); ++a) {
    const tinygltf::Animation& source = file.animations[a];
    std::vector<ReferenceCurve> curves;
    DVec allTimes;
    for (const tinygltf::AnimationSampler& sampler : source.samplers) {
      ReferenceCurve curve;
      for (const DVec& time : readFloats(file, sampler.input)) curve.times.push_back(time[0]);
      curve.elements = readFloats(file, sampler.output);
      curve.interpolation = sampler.interpolation;
      for (double t : timesToCheck(curve.times)) allTimes.push_back(t);
      curves.push_back(curve);
    }
    // Each sampler through the channels that use it.
    for (const tinygltf::AnimationChannel& channel : source.channels) {
      const bool rotation = channel.target_path == "rotation";
      const ReferenceCurve& curve = curves[std::size_t(channel.sampler)];
      const AnimationSampler& sampler = scene.animations[a].samplers[std::size_t(channel.sampler)];
      for (double t : timesToCheck(curve.times)) {
        const glm::dvec4 got = sampleAnimation(sampler, rotation, t);
        const DVec want = referenceValue(curve, rotation, t);
        for (std::size_t c = 0; c < want.size(); ++c) {
          EXPECT_NEAR(got[int(c)], want[c], 1e-9)
              << model << " animation " << a << " " << channel.target_path << " "
              << curve.interpolation << " t=" << t << " component " << c;
        }
        ++checked;
      }
    }
    // The whole tree, driven nodes and their subtrees.
    NodePose pose;
    for (double t : allTimes) {
      poseNodes(scene, int(a), t, pose);
      const std::vector<glm::mat4>& worlds = pose.worlds;
      const std::vector<DMat> want = referenceWorlds(file, curves, int(a), t);
      ASSERT_EQ(worlds.size(), scene.nodes.size());
      for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        const DMat& w = want[std::size_t(scene.nodes[n].fileIndex)];
        for (int e = 0; e < 16; ++e) {
          const double got = double(glm::value_ptr(worlds[n])[e]);
          EXPECT_NEAR(got, w[std::size_t(e)], 2e-6 * (1.0 + std::fabs(w[std::size_t(e)])))
              << model << " animation " << a << " node " << scene.nodes[n].fileIndex << " t=" << t
              << " element " << e;
        }
      }
    }
  }
  EXPECT_GT(checked, 0u) << model << " has no channel to check";
}

TEST(Animation, AnimatedTriangleMatchesADoublePrecisionEvaluation) {
  expectMatchesReference("AnimatedTriangle");
}

TEST(Animation, BoxAnimatedHierarchyMatchesADoublePrecisionEvaluation) {
  expectMatchesReference("BoxAnimated");
}

TEST(Animation, InterpolationTestStepLinearCubicMatchADoublePrecisionEvaluation) {
  expectMatchesReference("InterpolationTest");
}

// ---- hand-made curves ------------------------------------------------------------------

AnimationSampler curve(Interpolation interpolation, int components, std::vector<float> times,
                       std::vector<float> values) {
  AnimationSampler s;
  s.interpolation = interpolation;
  s.components = components;
  s.times = std::move(times);
  s.values = std::move(values);
  return s;
}

TEST(Animation, SlerpTakesTheShorterArcAndNormalizes) {
  // Key 1 is a 90-degree turn about z written as its negation (and scaled by
  // 2): halfway is 45 degrees, not the long way round through 225.
  const float h = float(std::sqrt(0.5));
  const AnimationSampler s =
      curve(Interpolation::Linear, 4, {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0, -2 * h, -2 * h});
  const glm::dvec4 q = sampleAnimation(s, true, 0.5);
  const double halfAngle = std::acos(std::min(1.0, std::fabs(q.w)));
  EXPECT_NEAR(2.0 * halfAngle, M_PI / 4.0, 1e-7);
  EXPECT_NEAR(glm::length(q), 1.0, 1e-12);
  EXPECT_NEAR(q.x, 0.0, 1e-12);
  EXPECT_NEAR(q.y, 0.0, 1e-12);
  // The same rotation in the same sign as key 0 at the start: no flip.
  const glm::dvec4 start = sampleAnimation(s, true, 0.0);
  EXPECT_NEAR(start.w, 1.0, 1e-12);
}

TEST(Animation, TimesOutsideTheKeysHoldTheEndValues) {
  const AnimationSampler linear = curve(Interpolation::Linear, 3, {1.0f, 2.0f}, {1, 2, 3, 4, 5, 6});
  const AnimationSampler step = curve(Interpolation::Step, 3, {1.0f, 2.0f}, {1, 2, 3, 4, 5, 6});
  // CUBICSPLINE: in-tangent, value, out-tangent per key; large tangents that
  // must not leak past the ends.
  const AnimationSampler cubic = curve(Interpolation::CubicSpline, 3, {1.0f, 2.0f},
                                       {9, 9, 9, 1, 2, 3, 9, 9, 9, 9, 9, 9, 4, 5, 6, 9, 9, 9});
  for (const AnimationSampler* s : {&linear, &step, &cubic}) {
    EXPECT_EQ(sampleAnimation(*s, false, -3.0), glm::dvec4(1, 2, 3, 0));
    EXPECT_EQ(sampleAnimation(*s, false, 1.0), glm::dvec4(1, 2, 3, 0));
    EXPECT_EQ(sampleAnimation(*s, false, 2.0), glm::dvec4(4, 5, 6, 0));
    EXPECT_EQ(sampleAnimation(*s, false, 1e9), glm::dvec4(4, 5, 6, 0));
  }
  EXPECT_EQ(sampleAnimation(step, false, 1.999), glm::dvec4(1, 2, 3, 0));
}

TEST(Animation, CubicSplineTangentsAreScaledByTheKeyInterval) {
  // Keys 2 s apart, both values 0, key 0's out-tangent 1 per second: at the
  // middle the Hermite term (u^3 - 2u^2 + u) * 2 s * 1/s is 0.25.
  const AnimationSampler s = curve(Interpolation::CubicSpline, 3, {0.0f, 2.0f},
                                   {0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  EXPECT_NEAR(sampleAnimation(s, false, 1.0).x, 0.25, 1e-15);
}

TEST(Animation, CamerasAndChildrenFollowTheirNodes) {
  // A root scaled by 2 carries a camera and a child node with an instance;
  // the root moves from z = 0 to z = 10 over one second.
  Scene scene;
  Node root;
  root.scale = glm::vec3(2.0f);
  root.local = glm::scale(glm::mat4(1.0f), root.scale);
  Node child;
  child.parent = 0;
  child.translation = glm::vec3(1.0f, 0.0f, 0.0f);
  child.local = glm::translate(glm::mat4(1.0f), child.translation);
  scene.nodes = {root, child};
  scene.meshes.emplace_back();
  scene.instances.push_back({0, child.local, 1});
  Camera camera;
  camera.node = 0;
  scene.cameras.push_back(camera);
  Animation move;
  move.samplers.push_back(curve(Interpolation::Linear, 3, {0.0f, 1.0f}, {0, 0, 0, 0, 0, 10}));
  move.channels.push_back({0, 0, AnimatedProperty::Translation});
  scene.animations.push_back(move);

  NodePose pose;
  poseNodes(scene, 0, 0.5, pose);
  placeOnNodes(scene, pose);
  // The camera sits at the node's origin, its scale divided out; the child
  // keeps its offset, scaled by its parent.
  EXPECT_EQ(glm::vec3(scene.cameras[0].world[3]), glm::vec3(0.0f, 0.0f, 5.0f));
  for (int axis = 0; axis < 3; ++axis)
    EXPECT_FLOAT_EQ(glm::length(glm::vec3(scene.cameras[0].world[axis])), 1.0f);
  EXPECT_EQ(glm::vec3(scene.instances[0].world[3]), glm::vec3(2.0f, 0.0f, 5.0f));
  EXPECT_EQ(glm::vec3(scene.instances[0].world[0]), glm::vec3(2.0f, 0.0f, 0.0f));
}

// ---- the rest pose and the loader ----------------------------------------------------

TEST(Animation, RestPoseKeepsTheLoadedBits) {
  int models = 0;
  for (const char* model : {"BoxAnimated", "InterpolationTest", "NegativeScaleTest", "Cameras",
                            "CesiumMilkTruck", "OrientationTest"}) {
    const std::string path = assetPath(model);
    if (!fs::exists(path)) continue;
    ++models;
    const Scene loaded = loadGltf(path);
    Scene posed = loaded;
    NodePose pose;
    poseNodes(posed, -1, 0.0, pose);
    placeOnNodes(posed, pose);
    for (std::size_t i = 0; i < loaded.instances.size(); ++i) {
      EXPECT_EQ(
          std::memcmp(&loaded.instances[i].world, &posed.instances[i].world, sizeof(glm::mat4)), 0)
          << model << " instance " << i;
    }
    for (std::size_t i = 0; i < loaded.cameras.size(); ++i) {
      EXPECT_EQ(std::memcmp(&loaded.cameras[i].world, &posed.cameras[i].world, sizeof(glm::mat4)),
                0)
          << model << " camera " << i;
    }
  }
  if (models == 0) GTEST_SKIP() << "no sample models under " << QUADRA_ASSETS_DIR;
}

TEST(Animation, BadAnimationDataIsAOneLineErrorNamingTheFile) {
  if (!fs::exists(assetPath("AnimatedTriangle"))) GTEST_SKIP() << "no AnimatedTriangle";
  struct Case {
    const char* from;
    const char* to;
    const char* mentions;
  };
  const Case cases[] = {
      {"\"output\" : 3", "\"output\" : 7", "accessor 7"},  // no such accessor
      {"\"input\" : 2", "\"input\" : 3", "SCALAR of FLOAT"},
      {"\"count\" : 5,\n      \"type\" : \"VEC4\"", "\"count\" : 4,\n      \"type\" : \"VEC4\"",
       "4 elements for 5 keys"},
      {"\"interpolation\" : \"LINEAR\"", "\"interpolation\" : \"SMOOTH\"", "SMOOTH"},
      {"\"sampler\" : 0,", "\"sampler\" : 3,", "sampler 3"},
      {"\"path\" : \"rotation\"", "\"path\" : \"translation\"", "not VEC3"},
  };
  for (const Case& c : cases) {
    const std::string message = loadErrorWithEdit("AnimatedTriangle", c.from, c.to);
    EXPECT_NE(message.find("edited.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find(c.mentions), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace quadra
