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

// The kernels a frame runs: `wide` for most triangles, and for triangles
// narrower than `narrowBelow` pixels the next narrower SIMD path, which such a
// triangle fills better. Every path writes the same bits (the precision
// contract), so mixing them changes speed only. Measured on the dense mesh
// (2M triangles, 1080p, 2 threads): AVX-512 alone 117 ms, AVX2 alone 109 ms.
struct TileKernelSelection {
  const TileKernels* wide = nullptr;
  const TileKernels* narrow = nullptr;
  int narrowBelow = 0;
  const TileKernels& forWidth(int pixels) const { return pixels < narrowBelow ? *narrow : *wide; }
};
TileKernelSelection selectTileKernels(Isa isa);

const TileKernels& tileKernelsScalar();
const TileKernels& tileKernelsSse2();
const TileKernels& tileKernelsAvx2();
const TileKernels& tileKernelsAvx512();

}  // namespace quadra
