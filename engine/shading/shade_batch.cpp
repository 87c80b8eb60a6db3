// The shading batch kernels' dispatch by ISA.
#include "shading/shade_batch.h"

namespace quadra {

ShadeBatchKernel shadeBatchKernel(Isa isa) {
  switch (isa) {
    case Isa::Avx512:
      return shadeKernelAvx512();
    case Isa::Avx2:
      return shadeKernelAvx2();
    case Isa::Sse2:
      return shadeKernelSse2();
    case Isa::Scalar:
      break;
  }
  return shadeKernelScalar();
}

BackgroundBatchKernel backgroundBatchKernel(Isa isa) {
  switch (isa) {
    case Isa::Avx512:
      return backgroundKernelAvx512();
    case Isa::Avx2:
      return backgroundKernelAvx2();
    case Isa::Sse2:
      return backgroundKernelSse2();
    case Isa::Scalar:
      break;
  }
  return backgroundKernelScalar();
}

}  // namespace quadra
