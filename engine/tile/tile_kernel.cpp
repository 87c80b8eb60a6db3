// The single dispatch point from Isa to kernel tables, and the kernels'
// helpers that must round the same on every path.
#include "tile/tile_kernel.h"

#include "simd/double_pairs.h"

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
  // planeInTile(depth.atSample(o)).c, each operation as there, the
  // sample-independent ones once, two samples at a time: the scalar chains
  // were 4-7% of a 4-sample frame (perf, dense-mesh and
  // MetalRoughSpheresNoTextures). Multiplying by 1/16 is dividing by 16.
  using simd::DoublePair;
  const DoublePair dx(depth.dx), dy(depth.dy), c0(depth.c);
  const DoublePair stepX(double(depth.dx) * double(tile.originX - t.minX));
  const DoublePair stepY(double(depth.dy) * double(tile.originY - t.minY));
  const DoublePair toPixels(1.0 / kSampleUnitsPerPixel);
  withSampleCount(pattern.count, [&](auto samples) {
    constexpr int kSamples = decltype(samples)::value;
    double offsetX[kSamples], offsetY[kSamples];
    for (int k = 0; k < kSamples; ++k)
      offsetX[k] = pattern.offsets[k].x, offsetY[k] = pattern.offsets[k].y;
    for (int k = 0; k < kSamples; k += 2) {
      const DoublePair shift =
          (dx * DoublePair::load(offsetX + k) + dy * DoublePair::load(offsetY + k)) * toPixels;
      const DoublePair moved = (c0 + shift).roundedToFloat();  // Plane::atSample's rounding
      ((moved + stepX) + stepY).storeAsFloats(c + k);
    }
  });
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
