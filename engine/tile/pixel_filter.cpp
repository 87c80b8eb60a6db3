// The wide pixel filter's two passes (pixel_filter.h). Tiles stay
// independent: a tile never reads another's samples, only the weighted sums it
// left in its ring, so the first pass runs inside the tile task with the
// samples still in cache, and only 528 pixels of sums a tile outlive it
// (instead of every sample of the frame).
//
// Summation order, fixed by the data alone: an output pixel's sum is its own
// tile's sum, then its neighbours' ring sums in tile order. Within a tile, the
// pixels whose samples all agree are summed first, 25 taps in row order with
// the pixel weight (one read instead of N), then each pixel whose samples
// differ adds its samples' weighted sum, pixels in the tile's storage order.
// Which pixels differ is a property of each pixel's samples (their colours
// and coverage, or with shading per pixel, whether several triangles hold
// them), not of the thread, so the frame is bit-identical for every thread
// count and ISA path (this file is
// compiled once, without ISA flags); a pixel whose footprint straddles a tile
// border differs from one that does not only by the grouping of its sum
// (float rounding, ~1e-7 relative).
#include "tile/pixel_filter.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>

#include "core/error.h"

namespace quadra {

namespace {

constexpr int kRadius = kPixelFilterRadius;
constexpr int kTaps = kPixelFilterTaps;
// The sources: the tile's pixels, zero-padded so that every output pixel
// of the grown tile reads 5x5 of them without a bounds test.
constexpr int kSourcePad = 2 * kRadius;
constexpr int kSourceStride = kTileSize + 2 * kSourcePad;
constexpr int kSourcePlane = kSourceStride * kSourceStride;
// The sums: the tile grown by the radius on every side.
constexpr int kSumsStride = kTileSize + 2 * kRadius;
constexpr int kSumsPlane = kSumsStride * kSumsStride;

// Whether a depth-writing triangle holds the sample: its depth moved off
// the clear value (a triangle exactly at the clear depth fails the depth test).
float covered(float depth, float clearDepth) {
  return depth != clearDepth ? 1.0f : 0.0f;
}

// A sample's value in channel c: colour, or coverage as the fifth.
float sampleValue(const TileBuffers& plane, int channel, int pixel, float clearDepth) {
  return channel < 4 ? plane.color[channel][pixel] : covered(plane.depth[pixel], clearDepth);
}

bool samplesDiffer(const TileBuffers* planes, int samples, int channels, int pixel,
                   float clearDepth) {
  for (int k = 1; k < samples; ++k)
    for (int c = 0; c < channels; ++c)
      if (sampleValue(planes[k], c, pixel, clearDepth) !=
          sampleValue(planes[0], c, pixel, clearDepth))
        return true;
  return false;
}

// Window position of a tile's top-left pixel, and its pixels inside the image.
struct TileRect {
  int x = 0, y = 0, width = 0, height = 0;
};

TileRect tileRect(int tileIndex, int tilesX, const Frame& out) {
  TileRect r;
  r.x = (tileIndex % tilesX) * kTileSize;
  r.y = (tileIndex / tilesX) * kTileSize;
  r.width = std::min(kTileSize, out.width - r.x);
  r.height = std::min(kTileSize, out.height - r.y);
  return r;
}

// Whether the footprint of position p (one axis) within the image [0, size)
// lies in [begin, begin + extent): then the tile alone finishes the pixel.
bool footprintWithin(int p, int size, int begin, int extent) {
  return std::max(p - kRadius, 0) >= begin && std::min(p + kRadius, size - 1) < begin + extent;
}

// Where the ring keeps a pixel (lx, ly) outside the tile and at most the
// radius from it, local to the tile: the two rows above (corners included),
// the two below, then the two columns left and right of the tile's rows.
int ringIndex(int lx, int ly) {
  constexpr int rowBand = kRadius * kSumsStride;
  if (ly < 0) return (ly + kRadius) * kSumsStride + lx + kRadius;
  if (ly >= kTileSize) return rowBand + (ly - kTileSize) * kSumsStride + lx + kRadius;
  if (lx < 0) return 2 * rowBand + ly * kRadius + lx + kRadius;
  return 2 * rowBand + kTileSize * kRadius + ly * kRadius + lx - kTileSize;
}
static_assert(2 * kRadius * kSumsStride + 2 * kTileSize * kRadius == kBorderRingPixels);

// The tile's sources, row-major and zero-padded; the pixels whose samples
// differ are left at zero in them and listed in scratch.mixed. Visited in
// storage order, which reads each plane's cache lines once.
void gatherSources(const TileRect& rect, const PixelFilterFrame& filter, const TileBuffers* planes,
                   const std::uint32_t* sampleDiffers, PixelFilterScratch& scratch) {
  const int channels = filter.channels(), samples = filter.weights.samples;
  scratch.source.assign(std::size_t(channels) * kSourcePlane, 0.0f);
  scratch.mixed.clear();
  for (int pixel = 0; pixel < TileBuffers::kPixels; ++pixel) {
    const int x = TileBuffers::xAt(pixel), y = TileBuffers::yAt(pixel);
    if (x >= rect.width || y >= rect.height) continue;
    const bool mixed = samples > 1 && (sampleDiffers ? sampleDiffers[pixel] != 0
                                                     : samplesDiffer(planes, samples, channels,
                                                                     pixel, filter.clearDepth));
    if (mixed) {
      scratch.mixed.push_back(std::uint16_t(pixel));
      continue;
    }
    float* const at =
        &scratch.source[std::size_t((y + kSourcePad) * kSourceStride + x + kSourcePad)];
    for (int c = 0; c < channels; ++c)
      at[std::size_t(c) * kSourcePlane] = sampleValue(planes[0], c, pixel, filter.clearDepth);
  }
}

// Four floats as one SSE2 register (the baseline every x86-64 has), with
// element-wise arithmetic: each lane adds in the order the code states.
using Float4 = float __attribute__((vector_size(16)));

Float4 loadFloat4(const float* from) {
  Float4 v;
  std::memcpy(&v, from, sizeof v);
  return v;
}

// The pixels whose samples agree, as a 5x5 convolution over the grown tile,
// four outputs of a row at a time: their sums stay in a register over the 25
// taps (a tap at a time over the whole row loaded and stored the row 25
// times), each output's additions in tap order.
void sumAgreeingPixels(const PixelFilterWeights& weights, int channels,
                       PixelFilterScratch& scratch) {
  constexpr int kRun = 4;
  static_assert(kSumsStride % kRun == 0);
  scratch.sums.resize(std::size_t(channels) * kSumsPlane);
  for (int c = 0; c < channels; ++c) {
    const float* const plane = &scratch.source[std::size_t(c) * kSourcePlane];
    for (int oy = 0; oy < kSumsStride; ++oy) {
      float* const row = &scratch.sums[std::size_t(c) * kSumsPlane + std::size_t(oy) * kSumsStride];
      for (int ox = 0; ox < kSumsStride; ox += kRun) {
        Float4 sum = {0.0f, 0.0f, 0.0f, 0.0f};
        for (int dy = 0; dy < kTaps; ++dy) {
          const float* const source = plane + (oy + dy) * kSourceStride + ox;
          for (int dx = 0; dx < kTaps; ++dx) sum += weights.pixel[dy][dx] * loadFloat4(source + dx);
        }
        std::memcpy(row + ox, &sum, sizeof sum);
      }
    }
  }
}

// Each pixel whose samples differ: every sample weighted by its own position.
// Its 25 outputs' sums are built side by side (sample by sample, so each
// output still adds its samples in order) and the loop over them vectorizes.
void addMixedPixels(const PixelFilterFrame& filter, const TileBuffers* planes,
                    PixelFilterScratch& scratch) {
  constexpr int kOutputs = kTaps * kTaps;
  const PixelFilterWeights& weights = filter.weights;
  const int channels = filter.channels();
  for (const std::uint16_t pixel : scratch.mixed) {
    float sums[5][kOutputs] = {};
    for (int k = 0; k < weights.samples; ++k) {
      const float* const weight = &weights.sample[k][0][0];
      for (int c = 0; c < channels; ++c) {
        const float value = sampleValue(planes[k], c, pixel, filter.clearDepth);
        for (int t = 0; t < kOutputs; ++t) sums[c][t] += weight[t] * value;
      }
    }
    const int x = TileBuffers::xAt(pixel), y = TileBuffers::yAt(pixel);
    for (int dy = 0; dy < kTaps; ++dy)
      for (int dx = 0; dx < kTaps; ++dx) {
        // The output pixel that sees this one (dx - 2, dy - 2) away, in the grown tile.
        const std::size_t at =
            std::size_t(y - dy + 2 * kRadius) * kSumsStride + std::size_t(x - dx + 2 * kRadius);
        for (int c = 0; c < channels; ++c)
          scratch.sums[std::size_t(c) * kSumsPlane + at] += sums[c][dy * kTaps + dx];
      }
  }
}

float* tileRing(const PixelFilterFrame& filter, int tileIndex) {
  return filter.borderRings + std::size_t(tileIndex) * kBorderRingPixels * filter.channels();
}

bool pixelFinishedByTile(const TileRect& rect, int x, int y, const Frame& out) {
  return footprintWithin(x, out.width, rect.x, rect.width) &&
         footprintWithin(y, out.height, rect.y, rect.height);
}

}  // namespace

double blackmanHarris(double x) {
  constexpr double kPi = 3.14159265358979323846;
  constexpr double a0 = 0.35875, a1 = 0.48829, a2 = 0.14128, a3 = 0.01168;
  if (std::abs(x) >= kRadius) return 0.0;
  const double t = kPi * x / kRadius;  // the window centred on 0: 1 there
  return a0 + a1 * std::cos(t) + a2 * std::cos(2.0 * t) + a3 * std::cos(3.0 * t);
}

PixelFilterWeights PixelFilterWeights::blackmanHarris(const SamplePattern& pattern) {
  PixelFilterWeights w;
  w.samples = pattern.count;
  for (int k = 0; k < pattern.count; ++k) {
    const double ox = double(pattern.offsets[k].x) / kSampleUnitsPerPixel;
    const double oy = double(pattern.offsets[k].y) / kSampleUnitsPerPixel;
    for (int dy = 0; dy < kTaps; ++dy)
      for (int dx = 0; dx < kTaps; ++dx)
        w.sample[k][dy][dx] = float(quadra::blackmanHarris(dx - kRadius + ox) *
                                    quadra::blackmanHarris(dy - kRadius + oy));
  }
  for (int dy = 0; dy < kTaps; ++dy)
    for (int dx = 0; dx < kTaps; ++dx) {
      double sum = 0.0;
      for (int k = 0; k < pattern.count; ++k) sum += w.sample[k][dy][dx];
      w.pixel[dy][dx] = float(sum);
      w.interiorSum += w.pixel[dy][dx];
    }
  return w;
}

float PixelFilterWeights::weightSum(int x, int y, int width, int height) const {
  if (x >= kRadius && x < width - kRadius && y >= kRadius && y < height - kRadius)
    return float(interiorSum);
  double sum = 0.0;
  for (int dy = 0; dy < kTaps; ++dy)
    for (int dx = 0; dx < kTaps; ++dx) {
      const int sx = x + dx - kRadius, sy = y + dy - kRadius;
      if (sx >= 0 && sx < width && sy >= 0 && sy < height) sum += pixel[dy][dx];
    }
  return float(sum);
}

void filterTileSamples(int tileIndex, const PixelFilterFrame& filter, TileBuffers* planes,
                       const std::uint32_t* sampleDiffers, PixelFilterScratch& scratch,
                       Frame& out) {
  const TileRect rect = tileRect(tileIndex, filter.tilesX, out);
  const int channels = filter.channels();
  gatherSources(rect, filter, planes, sampleDiffers, scratch);
  sumAgreeingPixels(filter.weights, channels, scratch);
  addMixedPixels(filter, planes, scratch);
  // The sums out: finished, partial, or to the ring.
  float* const ring = tileRing(filter, tileIndex);
  for (int ly = -kRadius; ly < rect.height + kRadius; ++ly) {
    const int y = rect.y + ly;
    if (y < 0 || y >= out.height) continue;
    for (int lx = -kRadius; lx < rect.width + kRadius; ++lx) {
      const int x = rect.x + lx;
      if (x < 0 || x >= out.width) continue;
      const std::size_t at = std::size_t(ly + kRadius) * kSumsStride + std::size_t(lx + kRadius);
      const float* const sum = &scratch.sums[at];
      if (lx < 0 || lx >= rect.width || ly < 0 || ly >= rect.height) {
        float* const to = ring + std::size_t(ringIndex(lx, ly)) * channels;
        for (int c = 0; c < channels; ++c) to[c] = sum[std::size_t(c) * kSumsPlane];
        continue;
      }
      // x / 1 is x: a partial sum goes out as it is.
      const float weights = pixelFinishedByTile(rect, x, y, out)
                                ? filter.weights.weightSum(x, y, out.width, out.height)
                                : 1.0f;
      const int pixel = TileBuffers::index(lx, ly);
      for (int c = 0; c < 4; ++c)
        planes[0].color[c][pixel] = sum[std::size_t(c) * kSumsPlane] / weights;
      if (filter.coverage)
        out.coverage[std::size_t(y) * std::size_t(out.width) + std::size_t(x)] =
            sum[std::size_t(4) * kSumsPlane] / weights;
    }
  }
}

void finishTileBorders(int tileIndex, const PixelFilterFrame& filter, Frame& out) {
  const TileRect rect = tileRect(tileIndex, filter.tilesX, out);
  const int channels = filter.channels();
  const int tileX = tileIndex % filter.tilesX, tileY = tileIndex / filter.tilesX;
  for (int ly = 0; ly < rect.height; ++ly) {
    // Only pixels within the radius of the tile's sides can need a neighbour.
    const bool rowNearSide = ly < kRadius || ly >= rect.height - kRadius;
    for (int lx = 0; lx < rect.width; ++lx) {
      if (!rowNearSide && lx == kRadius) lx = std::max(kRadius, rect.width - kRadius);
      const int x = rect.x + lx, y = rect.y + ly;
      if (pixelFinishedByTile(rect, x, y, out)) continue;
      const std::size_t pixel = std::size_t(y) * std::size_t(out.width) + std::size_t(x);
      float value[5];
      float* const rgba = out.colorPixels() + pixel * 4;
      for (int c = 0; c < 4; ++c) value[c] = rgba[c];
      if (filter.coverage) value[4] = out.coverage[pixel];
      for (int ny = std::max(tileY - 1, 0); ny <= std::min(tileY + 1, filter.tilesY - 1); ++ny)
        for (int nx = std::max(tileX - 1, 0); nx <= std::min(tileX + 1, filter.tilesX - 1); ++nx) {
          const int nlx = x - nx * kTileSize, nly = y - ny * kTileSize;
          const bool inNeighbour = nlx >= 0 && nlx < kTileSize && nly >= 0 && nly < kTileSize;
          if (inNeighbour || nlx < -kRadius || nlx >= kTileSize + kRadius || nly < -kRadius ||
              nly >= kTileSize + kRadius)
            continue;  // this tile itself, or too far for the neighbour to reach
          const float* const from = tileRing(filter, ny * filter.tilesX + nx) +
                                    std::size_t(ringIndex(nlx, nly)) * channels;
          for (int c = 0; c < channels; ++c) value[c] += from[c];
        }
      const float sum = filter.weights.weightSum(x, y, out.width, out.height);
      for (int c = 0; c < 4; ++c) rgba[c] = value[c] / sum;
      if (filter.coverage) out.coverage[pixel] = value[4] / sum;
    }
  }
}

void boxCoverage(const TileBuffers* planes, int samples, float clearDepth, Frame& out) {
  const TileBuffers& tile = planes[0];
  const float weight = 1.0f / float(samples);  // a power of two: exact
  for (int y = 0; y < tile.height; ++y)
    for (int x = 0; x < tile.width; ++x) {
      const int pixel = TileBuffers::index(x, y);
      float count = 0.0f;
      for (int k = 0; k < samples; ++k) count += covered(planes[k].depth[pixel], clearDepth);
      out.coverage[std::size_t(tile.originY + y) * std::size_t(out.width) +
                   std::size_t(tile.originX + x)] = count * weight;
    }
}

}  // namespace quadra
