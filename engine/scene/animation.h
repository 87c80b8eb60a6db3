// Scene + animation + time → the scene's node transforms and morph weights
// at that time, and the scene's instances (their joint matrices and weights
// too) and cameras moved onto them. Pure functions of their inputs: a frame
// of a sequence poses the scene, then renders it as a still.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace quadra {

// The value of `sampler` at `seconds` (glTF 2.0 §3.11 and Appendix C), as
// x, y, z (w unused) or a quaternion x, y, z, w. Before the first key and
// after the last the end key's value holds. STEP holds the key at or before
// the time; LINEAR interpolates componentwise, or for a rotation along the
// shortest great arc (slerp, the second key negated when the two lie more
// than 90 degrees apart); CUBICSPLINE is the cubic Hermite spline of the
// key values with each key's tangents scaled by the interval's length.
// Rotations come back normalized. Evaluated in double precision.
glm::dvec4 sampleAnimation(const AnimationSampler& sampler, bool rotation, double seconds);
// The same for a sampler of sampler.components morph weights (componentwise,
// as translations are), rounded to float into `weights`.
void sampleWeights(const AnimationSampler& sampler, double seconds, std::vector<float>& weights);

// Every Scene::nodes entry's world transform and morph weights.
struct NodePose {
  std::vector<glm::mat4> worlds;
  std::vector<std::vector<float>> weights;  // empty for nodes without morph targets
};

// The pose `seconds` into scene.animations[animation] (-1: the rest pose, as
// loaded). A node no channel drives keeps its loaded local transform and
// weights, so the rest pose has the bits the loader placed the instances with.
void poseNodes(const Scene& scene, int animation, double seconds, NodePose& pose);

// Moves every instance, camera and light that hangs from a node to that node's
// transform in `pose` (from poseNodes on the same scene); a skinned instance
// gets its joint matrices instead, and a morphed one its node's weights.
void placeOnNodes(Scene& scene, const NodePose& pose);

// The last key time over the animation's samplers (0 for none).
double animationDuration(const Animation& animation);

}  // namespace quadra
