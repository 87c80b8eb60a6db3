// Animation evaluation: key lookup, the three glTF interpolations, the node
// tree composed parents first into world transforms, and skinned and morphed
// instances posed from it.
#include "scene/animation.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace quadra {

namespace {

// Element `part` of key `key`: CUBICSPLINE keys hold in-tangent (0), value
// (1) and out-tangent (2); the other interpolations only the value.
glm::dvec4 element(const AnimationSampler& sampler, std::size_t key, int part) {
  const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
  const std::size_t n = std::size_t(sampler.components);
  const std::size_t offset = key * n * (cubic ? 3 : 1) + (cubic ? std::size_t(part) * n : 0);
  glm::dvec4 v(0.0);
  for (std::size_t c = 0; c < n; ++c) v[int(c)] = double(sampler.values[offset + c]);
  return v;
}

glm::dvec4 keyValue(const AnimationSampler& sampler, std::size_t key) {
  return element(sampler, key, 1);
}

// A zero quaternion (a file's, or a spline's through zero) means no rotation.
glm::dvec4 normalizedQuat(const glm::dvec4& q) {
  const double length = glm::length(q);
  return length > 0.0 && std::isfinite(length) ? q / length : glm::dvec4(0.0, 0.0, 0.0, 1.0);
}

// Spherical interpolation along the shorter arc between unit quaternions.
// The angle comes from atan2 of the chord lengths, which keeps its precision
// for nearly equal keys where acos of the dot product would not.
glm::dvec4 slerp(glm::dvec4 a, glm::dvec4 b, double u) {
  a = normalizedQuat(a);
  b = normalizedQuat(b);
  if (glm::dot(a, b) < 0.0) b = -b;  // q and -q are one rotation; take the short way
  const double theta = 2.0 * std::atan2(glm::length(a - b), glm::length(a + b));
  const double s = std::sin(theta);
  if (s < 1e-12) return normalizedQuat(a + u * (b - a));  // equal keys: any blend is exact
  return normalizedQuat(a * (std::sin((1.0 - u) * theta) / s) + b * (std::sin(u * theta) / s));
}

// The key after `seconds`: the interval [t0, t1) holding the time ends at
// the first key after it, so t1 > t0 even where keys share a time.
std::size_t keyAfter(const std::vector<float>& times, double seconds) {
  QUADRA_CHECK(!times.empty());
  return std::size_t(std::upper_bound(times.begin(), times.end(), seconds,
                                      [](double t, float key) { return t < double(key); }) -
                     times.begin());
}

// Hermite basis (glTF 2.0 Appendix C) for the interval's u; tangents are per
// second, so they are scaled by the interval to be per unit of u.
template <typename Value>
Value hermite(const Value& p0, const Value& m0, const Value& p1, const Value& m1, double u,
              double interval) {
  const double u2 = u * u, u3 = u2 * u;
  return (2.0 * u3 - 3.0 * u2 + 1.0) * p0 + (u3 - 2.0 * u2 + u) * (interval * m0) +
         (-2.0 * u3 + 3.0 * u2) * p1 + (u3 - u2) * (interval * m1);
}

}  // namespace

glm::dvec4 sampleAnimation(const AnimationSampler& sampler, bool rotation, double seconds) {
  const std::vector<float>& times = sampler.times;
  const auto after = times.begin() + std::ptrdiff_t(keyAfter(times, seconds));
  glm::dvec4 value;
  if (after == times.begin()) {
    value = keyValue(sampler, 0);
  } else if (after == times.end()) {
    value = keyValue(sampler, times.size() - 1);
  } else {
    const std::size_t k1 = std::size_t(after - times.begin()), k0 = k1 - 1;
    const double t0 = times[k0], t1 = times[k1];
    const double interval = t1 - t0;
    const double u = (seconds - t0) / interval;
    switch (sampler.interpolation) {
      case Interpolation::Step:
        value = keyValue(sampler, k0);
        break;
      case Interpolation::Linear:
        value = rotation ? slerp(keyValue(sampler, k0), keyValue(sampler, k1), u)
                         : glm::mix(keyValue(sampler, k0), keyValue(sampler, k1), u);
        break;
      case Interpolation::CubicSpline:
        value = hermite(keyValue(sampler, k0), element(sampler, k0, 2), keyValue(sampler, k1),
                        element(sampler, k1, 0), u, interval);
        break;
    }
  }
  return rotation ? normalizedQuat(value) : value;
}

void sampleWeights(const AnimationSampler& sampler, double seconds, std::vector<float>& weights) {
  const std::vector<float>& times = sampler.times;
  const std::size_t n = std::size_t(sampler.components);
  const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
  // Component c of key k's part (as element() above).
  const auto at = [&](std::size_t key, std::size_t part, std::size_t c) {
    return double(sampler.values[key * n * (cubic ? 3 : 1) + (cubic ? part * n : 0) + c]);
  };
  const std::size_t k1 = keyAfter(times, seconds);
  weights.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    double value = 0.0;
    if (k1 == 0 || k1 == times.size()) {
      value = at(k1 == 0 ? 0 : times.size() - 1, 1, c);
    } else {
      const std::size_t k0 = k1 - 1;
      const double interval = double(times[k1]) - double(times[k0]);
      const double u = (seconds - double(times[k0])) / interval;
      switch (sampler.interpolation) {
        case Interpolation::Step:
          value = at(k0, 1, c);
          break;
        case Interpolation::Linear:
          value = glm::mix(at(k0, 1, c), at(k1, 1, c), u);
          break;
        case Interpolation::CubicSpline:
          value = hermite(at(k0, 1, c), at(k0, 2, c), at(k1, 1, c), at(k1, 0, c), u, interval);
          break;
      }
    }
    weights[c] = float(value);
  }
}

void poseNodes(const Scene& scene, int animation, double seconds, NodePose& pose) {
  const std::size_t count = scene.nodes.size();
  // The TRS of each node some channel drives, starting from its rest values.
  struct Driven {
    bool driven = false;
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
  };
  std::vector<Driven> driven(count);
  pose.weights.resize(count);
  for (std::size_t i = 0; i < count; ++i) pose.weights[i] = scene.nodes[i].weights;
  if (animation >= 0) {
    const Animation& a = scene.animations.at(std::size_t(animation));
    for (const AnimationChannel& channel : a.channels) {
      const Node& node = scene.nodes.at(std::size_t(channel.node));
      if (channel.property == AnimatedProperty::Weights) {
        // Weights leave the transform alone (and its loaded bits with it).
        sampleWeights(a.samplers.at(std::size_t(channel.sampler)), seconds,
                      pose.weights[std::size_t(channel.node)]);
        continue;
      }
      Driven& d = driven[std::size_t(channel.node)];
      if (!d.driven) d = {true, node.translation, node.rotation, node.scale};
      const bool rotation = channel.property == AnimatedProperty::Rotation;
      const glm::dvec4 v =
          sampleAnimation(a.samplers.at(std::size_t(channel.sampler)), rotation, seconds);
      switch (channel.property) {
        case AnimatedProperty::Translation:
          d.translation = glm::vec3(v);
          break;
        case AnimatedProperty::Rotation:
          d.rotation = glm::quat(float(v.w), float(v.x), float(v.y), float(v.z));
          break;
        case AnimatedProperty::Scale:
          d.scale = glm::vec3(v);
          break;
        case AnimatedProperty::Weights:
          break;  // handled above
      }
    }
  }
  std::vector<glm::mat4>& worlds = pose.worlds;
  worlds.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const Node& node = scene.nodes[i];
    glm::mat4 local = node.local;
    if (driven[i].driven) {
      // T * R * S, composed as the loader composes a node's rest transform.
      local = glm::translate(glm::mat4(1.0f), driven[i].translation);
      local *= glm::mat4_cast(driven[i].rotation);
      local = glm::scale(local, driven[i].scale);
    }
    // Roots multiply the identity too, as the loader's walk does, so that a
    // rest pose keeps the loaded bits (identity * m is m except where m has
    // an infinity, and then the loader's product is what was drawn).
    QUADRA_CHECK(node.parent < int(i));
    const glm::mat4 parent = node.parent < 0 ? glm::mat4(1.0f) : worlds[std::size_t(node.parent)];
    worlds[i] = parent * local;
  }
}

void placeOnNodes(Scene& scene, const NodePose& pose) {
  const std::vector<glm::mat4>& worlds = pose.worlds;
  for (Instance& instance : scene.instances) {
    if (instance.node < 0) continue;
    const std::vector<float>& weights = pose.weights.at(std::size_t(instance.node));
    if (!weights.empty()) instance.morphWeights = weights;
    if (instance.skin < 0) {
      instance.world = worlds.at(std::size_t(instance.node));
      continue;
    }
    // glTF 2.0 §3.7.3: the joints place the vertices; the skinned mesh's own
    // node transform does not apply.
    const Skin& skin = scene.skins.at(std::size_t(instance.skin));
    instance.world = glm::mat4(1.0f);
    instance.jointMatrices.resize(skin.joints.size());
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      instance.jointMatrices[j] =
          worlds.at(std::size_t(skin.joints[j])) * skin.inverseBindMatrices[j];
    }
  }
  for (Camera& camera : scene.cameras) {
    if (camera.node >= 0) camera.world = cameraWorldOf(worlds.at(std::size_t(camera.node)));
  }
  for (Light& light : scene.lights) {
    if (light.node >= 0) light.world = cameraWorldOf(worlds.at(std::size_t(light.node)));
  }
}

double animationDuration(const Animation& animation) {
  double duration = 0.0;
  for (const AnimationSampler& sampler : animation.samplers) {
    if (!sampler.times.empty()) duration = std::max(duration, double(sampler.times.back()));
  }
  return duration;
}

}  // namespace quadra
