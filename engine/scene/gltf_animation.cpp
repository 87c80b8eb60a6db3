// glTF animations → Scene::animations: each sampler's key times and values
// read through the checked accessor reader, their shapes checked against the
// interpolation and the property a channel drives, channels pointed at the
// scene's nodes (weights channels to nodes with morph targets). Evaluating them at a time is
// scene/animation.h's job.
#include <tiny_gltf.h>

#include <cmath>

#include "scene/gltf_internal.h"

namespace quadra::gltf {

namespace {

std::string samplerName(int animation, int sampler) {
  return "animation " + std::to_string(animation) + " sampler " + std::to_string(sampler);
}

Interpolation interpolationOf(const ModelRef& ref, const std::string& text,
                              const std::string& who) {
  if (text == "LINEAR" || text.empty()) return Interpolation::Linear;
  if (text == "STEP") return Interpolation::Step;
  if (text == "CUBICSPLINE") return Interpolation::CubicSpline;
  throw ref.fail(who + " has unknown interpolation '" + text + "'");
}

// Key times: SCALAR floats (glTF 2.0 §5.5), finite and never decreasing.
std::vector<float> readTimes(const ModelRef& ref, int accessor, const std::string& who) {
  const AccessorView view = viewAccessor(ref, accessor, who + " input");
  if (view.components != 1 || view.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    throw ref.fail("accessor " + std::to_string(accessor) + " (" + who +
                   " input) must be SCALAR of FLOAT");
  }
  std::vector<float> times = decodeFloats(ref, view);
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k]) || (k > 0 && times[k] < times[k - 1])) {
      throw ref.fail("accessor " + std::to_string(accessor) + " (" + who + " input) key " +
                     std::to_string(k) + " time is not finite and non-decreasing");
    }
  }
  return times;
}

// outputComponents: the output accessor's element size (1 for morph weights,
// whose count per key only the channel's node tells).
AnimationSampler readSampler(const ModelRef& ref, const tinygltf::AnimationSampler& source,
                             const std::string& who, int& outputComponents) {
  AnimationSampler sampler;
  sampler.interpolation = interpolationOf(ref, source.interpolation, who);
  ref.charge(who + " decoded",
             decodedAccessorBytes(ref, source.input) + decodedAccessorBytes(ref, source.output));
  sampler.times = readTimes(ref, source.input, who);
  const AccessorView output = viewAccessor(ref, source.output, who + " output");
  outputComponents = output.components;
  // Translation and scale are VEC3, rotations VEC4, morph weights SCALAR
  // (float or normalized integers, which decodeFloats maps to [0, 1] or
  // [-1, 1]); no channel takes another type, so such samplers keep no values.
  if (output.components != 1 && output.components != 3 && output.components != 4) return sampler;
  const std::uint64_t perKey = sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
  if (output.components == 1) {
    // The weights per key: checked against the node a channel drives.
    sampler.components = 0;
    sampler.values = decodeFloats(ref, output);
    return sampler;
  }
  sampler.components = output.components;
  if (output.count != sampler.times.size() * perKey) {
    throw ref.fail("accessor " + std::to_string(source.output) + " (" + who + " output) has " +
                   std::to_string(output.count) + " elements for " +
                   std::to_string(sampler.times.size()) + " keys (needs " +
                   std::to_string(sampler.times.size() * perKey) + ")");
  }
  sampler.values = decodeFloats(ref, output);
  return sampler;
}

// A weights channel's sampler must have SCALAR output with one value per
// morph target of the node's mesh per key (glTF 2.0 §3.11); it then holds
// that many components.
void checkWeightsChannel(const ModelRef& ref, const std::string& who, int fileNode,
                         const Node& node, int outputComponents, AnimationSampler& sampler) {
  const std::uint64_t targets = node.weights.size();
  if (targets == 0) {
    throw ref.fail(who + " drives the weights of node " + std::to_string(fileNode) +
                   ", whose mesh has no morph targets");
  }
  if (outputComponents != 1) {
    throw ref.fail(who + " drives weights with a sampler whose output is not SCALAR");
  }
  const std::uint64_t perKey = sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
  const std::uint64_t needed = sampler.times.size() * perKey * targets;
  if (sampler.values.size() != needed) {
    throw ref.fail(who + " drives " + std::to_string(targets) + " morph weights of node " +
                   std::to_string(fileNode) + " but its sampler output has " +
                   std::to_string(sampler.values.size()) + " elements for " +
                   std::to_string(sampler.times.size()) + " keys (needs " + std::to_string(needed) +
                   ")");
  }
  sampler.components = int(targets);
}

}  // namespace

void readAnimations(const ModelRef& ref, const std::vector<int>& sceneNodeOf, Scene& scene,
                    std::vector<std::string>& notes) {
  const auto& animations = ref.model.animations;
  for (std::size_t a = 0; a < animations.size(); ++a) {
    const tinygltf::Animation& source = animations[a];
    Animation animation;
    animation.name = source.name;
    std::vector<int> outputComponents(source.samplers.size(), 0);
    for (std::size_t s = 0; s < source.samplers.size(); ++s) {
      animation.samplers.push_back(
          readSampler(ref, source.samplers[s], samplerName(int(a), int(s)), outputComponents[s]));
    }
    for (std::size_t c = 0; c < source.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = source.channels[c];
      const std::string who = "animation " + std::to_string(a) + " channel " + std::to_string(c);
      if (channel.sampler < 0 || std::size_t(channel.sampler) >= animation.samplers.size()) {
        throw ref.fail(who + " refers to sampler " + std::to_string(channel.sampler) +
                       ", which does not exist");
      }
      AnimationChannel kept;
      kept.sampler = channel.sampler;
      if (channel.target_path == "translation") {
        kept.property = AnimatedProperty::Translation;
      } else if (channel.target_path == "rotation") {
        kept.property = AnimatedProperty::Rotation;
      } else if (channel.target_path == "scale") {
        kept.property = AnimatedProperty::Scale;
      } else if (channel.target_path == "weights") {
        kept.property = AnimatedProperty::Weights;
      } else {
        notes.push_back(ref.note(who + " path '" + channel.target_path + "' ignored"));
        continue;
      }
      if (channel.target_node == -1) continue;  // no target: an extension's, ignored
      if (channel.target_node < 0 || std::size_t(channel.target_node) >= sceneNodeOf.size()) {
        throw ref.fail(who + " targets node " + std::to_string(channel.target_node) +
                       ", which does not exist");
      }
      kept.node = sceneNodeOf[std::size_t(channel.target_node)];
      if (kept.node < 0) continue;  // not in the scene drawn
      if (kept.property == AnimatedProperty::Weights) {
        checkWeightsChannel(ref, who, channel.target_node, scene.nodes[std::size_t(kept.node)],
                            outputComponents[std::size_t(kept.sampler)],
                            animation.samplers[std::size_t(kept.sampler)]);
        animation.channels.push_back(kept);
        continue;
      }
      const int wanted = kept.property == AnimatedProperty::Rotation ? 4 : 3;
      if (animation.samplers[std::size_t(kept.sampler)].components != wanted ||
          animation.samplers[std::size_t(kept.sampler)].values.empty()) {
        throw ref.fail(who + " drives " + channel.target_path +
                       " with a sampler whose output is not " + (wanted == 4 ? "VEC4" : "VEC3"));
      }
      if (scene.nodes[std::size_t(kept.node)].hasMatrix) {
        // glTF 2.0 §3.11: a node targeted by an animation must not have a matrix.
        notes.push_back(ref.note(who + " targets node " + std::to_string(channel.target_node) +
                                 ", which has a matrix; ignored"));
        continue;
      }
      animation.channels.push_back(kept);
    }
    scene.animations.push_back(std::move(animation));
  }
}

}  // namespace quadra::gltf
