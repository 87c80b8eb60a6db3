// The tile kernels, compiled once per ISA (tile_kernel_isa.cpp.in) and reached
// through one table chosen at start-up: rasterize one triangle into one tile.
#pragma once

#include "setup/triangle_record.h"
#include "simd/isa.h"
#include "tile/tile_buffers.h"
#include "vertex/draw.h"

namespace quadra {

struct TileKernels {
  Isa isa;
  int lanes;  // SIMD width in pixels (4 per quad)
  // Coverage, depth test, perspective-correct attributes, LOD, texture
  // sample, blend, for the part of the triangle inside the tile.
  void (*rasterize)(const TriangleRecord& triangle, const Plane* planes, const ShadeState& shade,
                    TileBuffers& tile);
};

// The table for an ISA; the caller has checked isaSupported(isa).
const TileKernels& tileKernels(Isa isa);

const TileKernels& tileKernelsScalar();
const TileKernels& tileKernelsSse2();
const TileKernels& tileKernelsAvx2();
const TileKernels& tileKernelsAvx512();

}  // namespace quadra
