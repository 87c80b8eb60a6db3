// The shading stage run over arrays, one lane group at a time, on a chosen
// ISA path: what the tests (bit identity across paths, accuracy) and the
// benchmark call. The tile kernels call shade_lanes.h directly.
#pragma once

#include <cstddef>

#include "shading/lighting.h"
#include "simd/isa.h"

namespace quadra {

// One surface point, world space (shade_lanes.h SurfaceLanes, per lane).
struct SurfaceRecord {
  float position[3] = {0.0f, 0.0f, 0.0f};
  float normal[3] = {0.0f, 0.0f, 1.0f};
  float view[3] = {0.0f, 0.0f, 1.0f};
  float baseColor[3] = {1.0f, 1.0f, 1.0f};
  float metallic = 1.0f, roughness = 1.0f, occlusion = 1.0f;
  float dielectricF0[3] = {0.04f, 0.04f, 0.04f};
  float dielectricF90 = 1.0f;
  float emission[3] = {0.0f, 0.0f, 0.0f};
};

// A footprint of the background: direction (any length) and solid angle.
struct BackgroundRay {
  float direction[3] = {0.0f, 0.0f, -1.0f};
  float solidAngle = 0.0f;
};

using ShadeBatchKernel = void (*)(const LightingView& view, const SurfaceRecord* surfaces,
                                  std::size_t count, float* rgb);
using BackgroundBatchKernel = void (*)(const LightingView& view, const BackgroundRay* rays,
                                       std::size_t count, float* rgb);

ShadeBatchKernel shadeBatchKernel(Isa isa);
BackgroundBatchKernel backgroundBatchKernel(Isa isa);

// Per ISA (shade_kernel_<isa>.cpp).
ShadeBatchKernel shadeKernelScalar();
ShadeBatchKernel shadeKernelSse2();
ShadeBatchKernel shadeKernelAvx2();
ShadeBatchKernel shadeKernelAvx512();
BackgroundBatchKernel backgroundKernelScalar();
BackgroundBatchKernel backgroundKernelSse2();
BackgroundBatchKernel backgroundKernelAvx2();
BackgroundBatchKernel backgroundKernelAvx512();

}  // namespace quadra
