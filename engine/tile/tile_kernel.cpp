// The single dispatch point from Isa to kernel tables, and the kernels'
// helpers that must round the same on every path.
#include "tile/tile_kernel.h"

namespace quadra {

const TileKernels& tileKernels(Isa isa) {
  switch (isa) {
    case Isa::Avx512:
      return tileKernelsAvx512();
    case Isa::Avx2:
      return tileKernelsAvx2();
    case Isa::Sse2:
      return tileKernelsSse2();
    case Isa::Scalar:
      break;
  }
  return tileKernelsScalar();
}

void sampleDepthsInTile(const Plane& depth, const SamplePattern& pattern, const TriangleRecord& t,
                        const TileBuffers& tile, float* c) {
  // A copy: c might alias depth for the compiler, which reloaded depth.c
  // after each store (perf annotate), a chain through every sample.
  const Plane plane = depth;
  for (int k = 0; k < pattern.count; ++k)
    c[k] = planeInTile(plane.atSample(pattern.offsets[k]), t, tile).c;
}

TileKernelSelection selectTileKernels(Isa isa) {
  TileKernelSelection selection;
  selection.wide = selection.narrow = &tileKernels(isa);
  if (isa == Isa::Avx512) {
    // A 16-lane group is 8x2 pixels; a triangle under 4 pixels wide leaves at
    // least half of it empty, while the AVX2 group (4x2) fits it.
    selection.narrow = &tileKernels(Isa::Avx2);
    selection.narrowBelow = 4;
  }
  return selection;
}

}  // namespace quadra
