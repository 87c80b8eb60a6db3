// Surface AOVs (README "AOVs"): a finished tile's visibility (each sample's
// winning triangle, TileBuffers::visible) → the frame's normal, position,
// uv, motion and id planes. Per pixel, the triangle holding the pixel's
// nearest sample (the one whose depth Z reports; the lowest sample on a
// tie), evaluated where the ray through the pixel centre meets that
// triangle's plane, in double from the mesh's own vertices: no attribute
// is interpolated for it by the pipeline, so a render without AOVs does
// none of this work.
#pragma once

#include <cstdint>
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
  glm::dmat4 modelView{1.0};             // object → view space
  glm::dmat4 world{1.0};                 // object → world space
  glm::dmat3 normalToWorld{1.0};         // the inverse transpose of world's 3x3
  glm::dmat4 previousObjectToClip{1.0};  // object → the previous pose's clip space
  std::uint32_t node = kNoId;            // id.node
  std::uint32_t material = kNoId;        // id.material
};

// What every tile's AOV pass shares.
struct AovFrame {
  AovSet aovs = 0;
  int width = 0, height = 0;
  glm::dmat4 clipToView{1.0};    // the inverse projection
  bool hasPreviousPose = false;  // else motion is 0
  std::vector<AovDraw> draws;    // indexed like the frame's draws
};

// The AOVs of the tile's pixels into `out`. samplePlanes: the tile's sample
// planes after its visibility pass; visible: the triangles their ids index,
// with their mesh triangles in `sources`.
void writeSurfaceAovs(const AovFrame& aov, const TileBuffers* samplePlanes, int samples,
                      bool depthGreater, const std::vector<TileTriangle>& visible,
                      const std::vector<std::uint32_t>& sources, Frame& out);

}  // namespace quadra
