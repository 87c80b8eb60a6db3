// Surface AOVs (docs/cli.md "AOVs"): a finished tile's visibility (each sample's
// winning triangle, TileBuffers::visible) → the frame's normal, position,
// uv, motion and id planes. Per pixel, the triangle holding the pixel's
// nearest sample (the one whose depth Z reports; the lowest sample on a
// tie), evaluated where the ray through the pixel centre meets that
// triangle's plane, in double from the mesh's own vertices: no attribute
// is interpolated for it by the pipeline, so a render without AOVs does
// none of this work. The barycentrics of that point are the triangle's
// clip-space (x, y, w) matrix, inverted once per triangle and tile, applied
// to the pixel centre's (x, y, 1) in NDC (homogeneous rasterization: exact
// for any w, so clipped triangles need nothing apart).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "io/frame.h"
#include "scene/scene.h"
#include "tile/tile_buffers.h"
#include "tile/tile_kernel.h"

namespace quadra {

// Per draw of the frame, what its pixels' AOVs are computed from.
struct AovDraw {
  const Mesh* mesh = nullptr;
  glm::dmat4 objectToClip{1.0};          // projection x view x world
  glm::dmat4 world{1.0};                 // object → world space
  glm::dmat3 normalToWorld{1.0};         // the inverse transpose of world's 3x3
  glm::dmat4 previousObjectToClip{1.0};  // object → the previous pose's clip space
  std::uint32_t node = kNoId;            // id.node
  std::uint32_t material = kNoId;        // id.material
  // A skinned or morphed instance's weights and joint matrices (as the
  // draw's geometry has them): its vertices are read deformed, as the vertex
  // stage drew them; and those of the previous pose, for motion (the same
  // spans when the previous pose did not say).
  std::span<const float> morphWeights;
  std::span<const glm::mat4> jointMatrices;
  std::span<const float> previousMorphWeights;
  std::span<const glm::mat4> previousJointMatrices;
};

// What every tile's AOV pass shares.
struct AovFrame {
  AovSet aovs = 0;
  int width = 0, height = 0;
  bool hasPreviousPose = false;  // else motion is 0
  // 2^-exposure: an unlit draw's base colour carries the exposure
  // (api/renderer.cpp), which its albedo AOV takes back out exactly.
  float albedoScale = 1.0f;
  std::vector<AovDraw> draws;  // indexed like the frame's draws
};

// One visible triangle's vertices, as the AOVs read them.
struct AovTriangle {
  bool ready = false;             // filled for this tile
  bool flat = false;              // its plane holds the eye: every pixel takes the centroid
  glm::dmat3 clipToWeights{1.0};  // inverse of the columns (x, y, w) of its corners
  glm::dvec3 world[3], normal[3];
  glm::dvec2 uv[3];
  glm::dvec4 previousClip[3];
  std::uint32_t primitive = 0, node = kNoId, material = kNoId;
};

// The tile triangle holding pixel p's nearest sample (the one whose depth Z
// reports; the lowest sample on a tie), or kNoTriangle: the surface every
// AOV reports.
std::uint32_t nearestSampleTriangle(const TileBuffers* samplePlanes, int samples, bool depthGreater,
                                    int p);

// The AOVs of the tile's pixels into `out`. samplePlanes: the tile's sample
// planes after its visibility pass; visible: the triangles their ids index,
// with their mesh triangles in `sources`; `triangles` is working memory.
void writeSurfaceAovs(const AovFrame& aov, const TileBuffers* samplePlanes, int samples,
                      bool depthGreater, const std::vector<TileTriangle>& visible,
                      const std::vector<std::uint32_t>& sources,
                      std::vector<AovTriangle>& triangles, Frame& out);

}  // namespace quadra
