// Vertex stage: a draw's mesh → clip-space positions plus exactly the
// attributes the draw's material reads, one flat float array.
#pragma once

#include <vector>

#include "vertex/draw.h"

namespace quadra {

class Executor;

// Vertex i occupies data[i*stride .. i*stride+stride): x, y, z, w (clip space),
// then the attributes at the offsets of geometry.attributes (plus 4).
struct TransformedVertices {
  std::vector<float> data;
  int stride = 4;
  const float* vertex(std::uint32_t i) const { return &data[std::size_t(i) * std::size_t(stride)]; }
};

void transformVertices(const DrawGeometry& geometry, const Executor& executor,
                       TransformedVertices& out);

}  // namespace quadra
