// The single dispatch point from Isa to kernel table.
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

}  // namespace quadra
