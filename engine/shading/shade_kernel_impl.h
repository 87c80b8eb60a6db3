// The shading batch kernels (shade_batch.h) compiled once per ISA: loads a
// lane group of surface records, runs shade_lanes.h, writes RGB. Included
// only by the generated shade_kernel_<isa>.cpp.
#pragma once

#include <algorithm>

#include "shading/shade_batch.h"
#include "shading/shade_lanes.h"
#include "simd/kernel_isa.h"

namespace quadra {
namespace QUADRA_KERNEL_NAMESPACE {
namespace {

using L = simd::Lanes<QUADRA_KERNEL_ARCH>;
using F = L::F;
constexpr int W = L::kWidth;

// Lane k of the result: field `offset` (in floats) of record first + k; a
// short tail repeats the last record.
template <class Record>
F gatherField(const Record* records, std::size_t first, std::size_t count, std::size_t offset) {
  alignas(64) float v[W];
  for (int k = 0; k < W; ++k) {
    const Record& r = records[std::min(first + k, count - 1)];
    v[k] = reinterpret_cast<const float*>(&r)[offset];
  }
  return F::load_aligned(v);
}

void storeRgb(const RgbLanes<L>& c, std::size_t first, std::size_t count, float* rgb) {
  alignas(64) float ch[3][W];
  c.r.store_aligned(ch[0]);
  c.g.store_aligned(ch[1]);
  c.b.store_aligned(ch[2]);
  const std::size_t n = std::min<std::size_t>(W, count - first);
  for (std::size_t k = 0; k < n; ++k)
    for (int j = 0; j < 3; ++j) rgb[(first + k) * 3 + j] = ch[j][k];
}

void shadeBatch(const LightingView& view, const SurfaceRecord* surfaces, std::size_t count,
                float* rgb) {
  constexpr std::size_t kFloats = sizeof(SurfaceRecord) / sizeof(float);
  static_assert(kFloats == 22, "SurfaceRecord is 22 floats");
  for (std::size_t first = 0; first < count; first += W) {
    F field[kFloats];
    for (std::size_t f = 0; f < kFloats; ++f) field[f] = gatherField(surfaces, first, count, f);
    SurfaceLanes<L> s;
    s.position = {field[0], field[1], field[2]};
    s.normal = {field[3], field[4], field[5]};
    s.view = {field[6], field[7], field[8]};
    s.baseColor = {field[9], field[10], field[11]};
    s.metallic = field[12], s.roughness = field[13], s.occlusion = field[14];
    s.dielectricF0 = {field[15], field[16], field[17]};
    s.dielectricF90 = field[18];
    s.emission = {field[19], field[20], field[21]};
    storeRgb(surfaceRadiance<L>(view, s), first, count, rgb);
  }
}

void backgroundBatch(const LightingView& view, const BackgroundRay* rays, std::size_t count,
                     float* rgb) {
  for (std::size_t first = 0; first < count; first += W) {
    const Vec3Lanes<L> d{gatherField(rays, first, count, 0), gatherField(rays, first, count, 1),
                         gatherField(rays, first, count, 2)};
    storeRgb(backgroundRadiance<L>(view, d, gatherField(rays, first, count, 3)), first, count, rgb);
  }
}

}  // namespace
}  // namespace QUADRA_KERNEL_NAMESPACE

ShadeBatchKernel QUADRA_KERNEL_ENTRY(shadeKernel)() {
  return &QUADRA_KERNEL_NAMESPACE::shadeBatch;
}
BackgroundBatchKernel QUADRA_KERNEL_ENTRY(backgroundKernel)() {
  return &QUADRA_KERNEL_NAMESPACE::backgroundBatch;
}

}  // namespace quadra
