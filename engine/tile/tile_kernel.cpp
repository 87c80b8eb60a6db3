// The single dispatch point from Isa to kernel tables.
#include "tile/tile_kernel.h"

#include <iterator>

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

TileKernelSelection selectTileKernels(Isa isa) {
  TileKernelSelection selection;
  selection.wide = selection.narrow = &tileKernels(isa);
  if (isa == Isa::Avx512) {
    // A 16-lane group is 8x2 pixels; a triangle under 4 pixels wide leaves at
    // least half of it empty, while the AVX2 group (4x2) fits it.
    selection.narrow = &tileKernels(Isa::Avx2);
    selection.narrowBelow = 4;
  }
  for (int i = 0; i < int(std::size(selection.quadSamples)); ++i) {
    const int samples = 1 << i;
    for (const TileKernels* kernels : {selection.wide, selection.narrow})
      if (selection.quadSamples[i] == nullptr &&
          TileKernelSelection::quadSampleRegisters(kernels->isa, kernels->lanes, samples) > 0)
        selection.quadSamples[i] = kernels;
  }
  return selection;
}

}  // namespace quadra
