// The single dispatch point from Isa to kernel tables.
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
