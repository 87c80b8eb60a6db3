// Tile stage scheduling and the per-tile loop: the visibility pass over the
// two-pass draws' triangles, the shading pass over their visible pixels draw
// by draw, then the forward draws (their blended fragments kept per sample and
// composited in depth order after them), then the tile's resolve. The
// per-pixel work is in the ISA kernels (tile_kernel_impl.h).
//
// Samples: a multisampled tile is one TileBuffers plane per sample, plane s
// holding every pixel's sample s. The kernels see each plane as a frame of
// its own, rendered with the triangle moved by minus sample s's offset
// (atSample): coverage and depth per sample, exact on the fixed-point grid;
// small triangles' visibility walks all the planes at once
// (TileKernels::visibilityAtSamples, the same bits). The shading pass then
// shades each pixel's visible triangles once (or, shading per sample, each
// plane), and the resolve averages the planes.
#include "tile/tile_stage.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "core/error.h"
#include "core/parallel.h"
#include "core/stage_clock.h"
#include "simd/sample_ids.h"
#include "tile/blended_fragments.h"
#include "tile/tile_resolve.h"

namespace quadra {

namespace {

struct MixedPixelTables;

constexpr std::uint32_t kNoCoverageDraw = 0xFFFFFFFFu;

// One worker's working memory, reused from tile to tile and frame to frame
// (TileWorkspace).
struct TileScratch {
  explicit TileScratch(int samples) : planes(new TileBuffers[std::size_t(samples)]) {
    // At their bound from the start, so they never grow past it by doubling
    // (tileMemoryBytes); pages never written take no memory. Kept from
    // frame to frame (TileWorkspace), a list that grew by reallocating left
    // its old block resident and touched a new one: a step in resident
    // memory each time a worker first took a larger tile.
    const std::size_t triangles = std::size_t(maxVisibleTriangles(samples)) + 1;
    const std::size_t slots = std::size_t(samples) * TileBuffers::kPixels;
    const std::size_t pixels = TileBuffers::kPixels + 3;
    visibleTriangles.reserve(triangles);
    shadePlanes.reserve(triangles * kShadePlaneStride + 1);
    for (auto* list : {&renumbered, &runOf, &oneColourDraw, &runGroups, &runPixels, &runJobs,
                       &groupCursor, &pixelCursor})
      list->reserve(triangles);
    for (auto* list : {&groupRun, &sampleDiffers, &pixelFirstJob, &mixedPlaneZeroIds})
      list->reserve(pixels);
    for (auto* list : {&groupList, &pixelList, &mixedPixels}) list->reserve(pixels);
    jobs.reserve(slots);
    sortedJobs.reserve(slots);
    sortedAt.reserve(slots);
    jobColor.reserve(3 * slots);
    sampleSlot.reserve(slots);
  }
  // One per sample (tile_stage.cpp's opening comment). Not value-initialized:
  // every tile clears what it reads.
  std::unique_ptr<TileBuffers[]> planes;
  // Indexed by TileBuffers::visible: each triangle that won a sample of the
  // visibility pass, in submission order, at most maxVisibleTriangles.
  std::vector<TileTriangle> visibleTriangles;
  std::vector<std::uint32_t> renumbered;      // dropOverwrittenTriangles' map
  std::vector<std::uint32_t> visibleSources;  // with AOVs: their mesh triangles
  std::vector<AovTriangle> aovTriangles;      // with AOVs: writeSurfaceAovs' memory
  std::vector<TileTriangle> forward;          // forward-path triangles, in order
  // kShadePlaneStride per visible triangle, and one more float: the
  // kernels load each plane (3 floats) 4 floats at a time.
  std::vector<float> shadePlanes;
  std::vector<std::uint32_t> runOf;     // per visible triangle: its draw's run
  std::vector<std::uint32_t> groupRun;  // per lane group: its run, if all its pixels have one
  // Per run: where its whole groups and its other pixels start in the lists.
  std::vector<std::uint32_t> runGroups, runPixels, groupCursor, pixelCursor;
  std::vector<std::uint16_t> groupList, pixelList;
  // Multisampled shading: per mixed pixel, plane 0's id while the pixel is
  // taken out of that plane (collectPixelJobs).
  std::vector<std::uint32_t> mixedPlaneZeroIds;
  // The pixels whose samples differ (in colour, once shaded), in tile order.
  // With allMixed, every pixel may, and each plane holds its sample's
  // colour; without, only plane 0 holds the colour of the others, and with
  // the box filter the mixed pixels' too (shadePixels resolved them).
  std::vector<std::uint32_t> sampleDiffers;
  std::vector<std::uint16_t> mixedPixels;
  bool allMixed = false;
  // Per visible triangle id + 1 (so that kNoTriangle wraps to 0): its draw
  // where that draw shades one colour, else kNoTriangle (wholePixelsOfOneColour).
  std::vector<std::uint32_t> oneColourDraw;
  std::vector<ShadeJob> jobs, sortedJobs;
  std::vector<float> jobColor;
  std::vector<std::uint32_t> runJobs;
  // Per mixed pixel its first job, and per sample of it the job holding the
  // sample, counted from there (kClearSlot: none), so that the jobs' colours
  // go to the samples without a loop per job; with several runs, each job's
  // place in sortedJobs (where its colour is).
  std::vector<std::uint32_t> pixelFirstJob;
  std::vector<std::uint8_t> sampleSlot;
  std::vector<std::uint32_t> sortedAt;
  BlendedFragments blended;  // the forward "over" draws' fragments, per sample
  // With alpha to coverage, one masked draw's state per sample plane
  // (shadeAtSample), for the draw coverageDraw.
  std::vector<ShadeState> coverageShades;
  std::uint32_t coverageDraw = kNoCoverageDraw;
  // A wide pixel filter's frame (renderTiles) and working memory
  // (tile/pixel_filter.h); null with the box filter.
  const PixelFilterFrame* pixelFilter = nullptr;
  PixelFilterScratch filter;
  // Shading per pixel with several samples: the frame's (collectPixelJobs).
  const MixedPixelTables* mixedTables = nullptr;
};

// How far ahead the visibility pass and the shading planes' rebase fetch
// triangle records and planes.
constexpr std::uint32_t kRecordLookahead = 8, kPlaneLookahead = 4;

// Both ends of a run of bytes that may straddle two cache lines.
void prefetch(const void* begin, std::size_t bytes) {
  __builtin_prefetch(begin);
  __builtin_prefetch(static_cast<const char*>(begin) + bytes - 1);
}

// color: also the colour planes (a multisampled tile shaded per pixel fills
// its other planes' colours itself, when anything reads them).
void clearTile(TileBuffers& tile, const glm::vec4& clearColor, float clearDepth, bool color) {
  std::fill(std::begin(tile.depth), std::end(tile.depth), clearDepth);
  std::fill(std::begin(tile.visible), std::end(tile.visible), kNoTriangle);
  std::fill(std::begin(tile.blockDepthMin), std::end(tile.blockDepthMin), clearDepth);
  std::fill(std::begin(tile.blockDepthMax), std::end(tile.blockDepthMax), clearDepth);
  if (!color) return;
  for (int c = 0; c < 4; ++c)
    std::fill(std::begin(tile.color[c]), std::end(tile.color[c]), clearColor[c]);
}

// Whether the tile's two-pass triangles are better shaded forward: when there
// is only one, nothing can be drawn over, and the visibility pass's ids and
// the shading pass's bookkeeping cost more than they save (checker-plane,
// 1080p, 2 threads: 7.5 ms forward against 12.5 ms two-pass before the
// shading pass shaded whole lane groups in place, and still ~10% after).
bool forwardWins(int tileIndex, const std::vector<Draw>& draws,
                 const std::vector<FrontEndChunk>& chunks) {
  int twoPass = 0;
  for (const FrontEndChunk& chunk : chunks) {
    const std::uint32_t begin = chunk.bins.tileStart[tileIndex];
    const std::uint32_t end = chunk.bins.tileStart[tileIndex + 1];
    for (std::uint32_t i = begin; i < end; ++i)
      if (draws[chunk.setup.triangles[chunk.bins.triangleIndex[i]].draw].shade.twoPass &&
          ++twoPass > 1)
        return false;
  }
  return true;
}

// A draw's state at sample plane k. With alpha to coverage, a masked draw's
// cutoff at plane k of N is (k + 0.5) / N, so where alpha is even over a
// pixel round(alpha * N) of its samples pass (D3D's sample order already
// spreads consecutive samples over the pixel).
const ShadeState& shadeAtSample(const TileFrame& frame, TileScratch& s, std::uint32_t draw, int k) {
  const ShadeState& shade = frame.draws[draw].shade;
  if (!shade.alphaToCoverage || frame.samples.count == 1) return shade;
  if (s.coverageDraw != draw) {
    s.coverageDraw = draw;
    s.coverageShades.assign(std::size_t(frame.samples.count), shade);
    for (int j = 0; j < frame.samples.count; ++j)
      s.coverageShades[std::size_t(j)].alphaCutoff =
          (float(j) + 0.5f) / float(frame.samples.count);  // exact: N is a power of two
  }
  return s.coverageShades[std::size_t(k)];
}

// A masked draw's triangle's visibility at every sample, each plane with the
// triangle and its planes moved to its sample and the draw's cutoff there;
// whether it won any. Out of line: masked draws are few, and the
// multisampled visibility loop keeps only their call.
[[gnu::noinline]] bool maskedVisibilityAtSamples(const TileTriangle& entry, const ShadeState& shade,
                                                 std::uint32_t id, const TileFrame& frame,
                                                 TileScratch& s) {
  const TriangleRecord& t = *entry.triangle;
  const TileKernels& kernel = frame.kernels.forWidth(t.maxX - t.minX + 1);
  const int planeCount = 2 + shade.attributes.count;
  Plane moved[2 + kMaxShadedAttributes];
  bool won = false;
  for (int k = 0; k < frame.samples.count; ++k) {
    const SampleOffset o = frame.samples.offsets[k];
    for (int j = 0; j < planeCount; ++j) moved[j] = entry.planes[j].atSample(o);
    won |= kernel.visibility(atSample(t, o), moved, shadeAtSample(frame, s, entry.draw, k), id,
                             s.planes[k]);
  }
  return won;
}

// Keeps only the visible triangles some sample still holds, renumbered in
// submission order: triangles drawn back to front each win a sample, and
// without this a tile's list (and the shading planes rebased for each entry)
// would grow with the scene instead of with the tile's samples. The order,
// hence the runs and every bit shaded, is unchanged.
void dropOverwrittenTriangles(int samples, TileScratch& s) {
  s.renumbered.assign(s.visibleTriangles.size(), kNoTriangle);
  for (int k = 0; k < samples; ++k)
    for (int p = 0; p < TileBuffers::kPixels; ++p)
      if (const std::uint32_t id = s.planes[k].visible[p]; id != kNoTriangle) s.renumbered[id] = 0;
  std::uint32_t kept = 0;
  for (std::size_t i = 0; i < s.visibleTriangles.size(); ++i) {
    if (s.renumbered[i] == kNoTriangle) continue;
    s.renumbered[i] = kept;
    s.visibleTriangles[kept] = s.visibleTriangles[i];
    if (!s.visibleSources.empty()) s.visibleSources[kept] = s.visibleSources[i];
    ++kept;
  }
  s.visibleTriangles.resize(kept);
  if (!s.visibleSources.empty()) s.visibleSources.resize(kept);
  for (int k = 0; k < samples; ++k)
    for (int p = 0; p < TileBuffers::kPixels; ++p)
      if (std::uint32_t& id = s.planes[k].visible[p]; id != kNoTriangle) id = s.renumbered[id];
}

// Visibility pass: every two-pass triangle binned to the tile, in submission
// order; the forward ones are kept for after the shading pass (the renderer
// puts every two-pass draw before them). A tile where forward shading wins
// (forwardWins) sends every triangle forward: the same bits either way.
// Compiled apart for one sample and several, so that neither loop tests the
// other's kernel choice per triangle.
template <bool kMultisampled>
void visibilityPass(int tileIndex, const TileFrame& frame, TileScratch& s) {
  const std::vector<Draw>& draws = frame.draws;
  const std::vector<FrontEndChunk>& chunks = frame.chunks;
  const TileKernelSelection& kernels = frame.kernels;
  TileBuffers& firstPlane = s.planes[0];
  const int samples = kMultisampled ? frame.samples.count : 1;
  // Several samples: the two passes shade each pixel's triangles once where
  // forward shading would shade every sample.
  const bool allForward =
      samples == 1 && frame.aov == nullptr && forwardWins(tileIndex, draws, chunks);
  const std::size_t maxVisible = std::size_t(maxVisibleTriangles(samples));
  for (const FrontEndChunk& chunk : chunks) {
    const std::uint32_t begin = chunk.bins.tileStart[tileIndex];
    const std::uint32_t end = chunk.bins.tileStart[tileIndex + 1];
    const std::uint32_t* index = chunk.bins.triangleIndex.data();
    const TriangleRecord* records = chunk.setup.triangles.data();
    for (std::uint32_t i = begin; i < end; ++i) {
      // A tile's triangles are scattered over the chunk's records: fetch the
      // records a few triangles ahead and their planes a few less (measured:
      // the record loads were half of this loop's time on dense meshes).
      // A record is one cache line; a triangle's planes (z, 1/w, attributes)
      // may span two.
      if (i + kRecordLookahead < end) __builtin_prefetch(&records[index[i + kRecordLookahead]]);
      if (i + kPlaneLookahead < end)
        prefetch(&chunk.setup.planes[records[index[i + kPlaneLookahead]].firstPlane],
                 4 * sizeof(Plane));
      const TriangleRecord& t = records[index[i]];
      const TileTriangle entry{&t, &chunk.setup.planes[t.firstPlane], t.draw};
      const ShadeState& shade = draws[t.draw].shade;
      if (!shade.twoPass || allForward) {
        s.forward.push_back(entry);
        continue;
      }
      QUADRA_CHECK(s.forward.empty());  // two-pass draws come first
      if (s.visibleTriangles.size() == maxVisible) dropOverwrittenTriangles(samples, s);
      const auto id = std::uint32_t(s.visibleTriangles.size());
      const int pixelsWide = t.maxX - t.minX + 1;
      bool won;
      if constexpr (!kMultisampled)
        won = kernels.forWidth(pixelsWide).visibility(t, entry.planes, shade, id, firstPlane);
      else
        won = shade.alphaMode != AlphaMode::Mask
                  ? kernels.forSamples(pixelsWide, t.maxY - t.minY + 1, samples)
                        .visibilityAtSamples(t, entry.planes, shade, id, frame.samples,
                                             s.planes.get())
                  : maskedVisibilityAtSamples(entry, shade, id, frame, s);
      if (!won) continue;
      s.visibleTriangles.push_back(entry);
      if (frame.aov) s.visibleSources.push_back(chunk.setup.sourceTriangles[index[i]]);
    }
  }
}

// How the draws of a tile's visible triangles shade: whether every one
// shades one colour (Draw::shadesOneColour: no shading plane is read) or
// some does, and whether the triangles are all of one draw (they are in
// submission order, a draw's consecutive).
struct TileDrawShading {
  bool allOneColour = false;
  bool anyOneColour = false;
  bool oneDraw = false;
};

TileDrawShading tileDrawShading(const std::vector<Draw>& draws, const TileScratch& s) {
  TileDrawShading out;
  if (s.visibleTriangles.empty()) return out;
  out.oneDraw = s.visibleTriangles.front().draw == s.visibleTriangles.back().draw;
  out.allOneColour = true;
  std::uint32_t last = kNoTriangle;
  for (const TileTriangle& v : s.visibleTriangles) {
    if (v.draw == last) continue;
    last = v.draw;
    const bool oneColour = draws[v.draw].shade.shadesOneColour();
    out.allOneColour &= oneColour;
    out.anyOneColour |= oneColour;
    if (out.oneDraw || (out.anyOneColour && !out.allOneColour)) break;  // decided
  }
  return out;
}

// Every visible triangle's 1/w and attribute planes, rebased to the tile,
// with each pixel's sample at `offset` standing in for its centre, where its
// draw's colour reads them (the kernels gather no plane of a draw that
// shades one colour). None where every draw shades one colour
// (TileDrawShading::allOneColour): the loop would skip each triangle, at a
// lookup each (~1.5% of a MetalRoughSpheresNoTextures frame; perf), and
// sizing the table zero-filled it (~0.4% at 4 samples; callgrind).
void rebaseShadePlanes(const std::vector<Draw>& draws, const TileBuffers& tile, SampleOffset offset,
                       bool allOneColour, TileScratch& s) {
  if (allOneColour) return;
  s.shadePlanes.resize(s.visibleTriangles.size() * kShadePlaneStride + 1);
  const bool moved = offset.x != 0 || offset.y != 0;  // else the same bits, cheaper
  const std::size_t triangles = s.visibleTriangles.size();
  for (std::size_t i = 0; i < triangles; ++i) {
    // The records and planes are out of the caches again after the
    // visibility pass over a multisampled tile: fetched ahead as there
    // (MetalRoughSpheresNoTextures at 4 samples: the record loads were half
    // of this loop's time).
    if (i + kRecordLookahead < triangles) {
      const TileTriangle& ahead = s.visibleTriangles[i + kRecordLookahead];
      if (!draws[ahead.draw].shade.shadesOneColour()) __builtin_prefetch(ahead.triangle);
    }
    if (i + kPlaneLookahead < triangles) {
      const TileTriangle& ahead = s.visibleTriangles[i + kPlaneLookahead];
      const ShadeState& shade = draws[ahead.draw].shade;
      if (!shade.shadesOneColour())
        prefetch(ahead.planes + 1, (1 + std::size_t(shade.attributes.count)) * sizeof(Plane));
    }
    const TileTriangle& v = s.visibleTriangles[i];
    const ShadeState& shade = draws[v.draw].shade;
    if (shade.shadesOneColour()) continue;  // its colour reads no plane
    const int planeCount = 1 + shade.attributes.count;
    float* out = &s.shadePlanes[i * kShadePlaneStride];
    for (int j = 0; j < planeCount; ++j) {
      const Plane q = planeInTile(moved ? v.planes[1 + j].atSample(offset) : v.planes[1 + j],
                                  *v.triangle, tile);
      out[3 * j] = q.dx, out[3 * j + 1] = q.dy, out[3 * j + 2] = q.c;
    }
  }
}

// Each visible triangle's run: its draw's place among the tile's draws
// (triangles are in submission order, so a draw's are consecutive). Returns
// the number of runs.
std::uint32_t assignRuns(TileScratch& s) {
  const std::size_t triangles = s.visibleTriangles.size();
  s.runOf.resize(triangles);
  std::uint32_t runs = 0;
  for (std::size_t i = 0; i < triangles; ++i) {
    if (i > 0 && s.visibleTriangles[i].draw != s.visibleTriangles[i - 1].draw) ++runs;
    s.runOf[i] = runs;
  }
  return runs + 1;
}

// Shading pass over one plane whose ids are `visible` (the plane's own, or
// fewer): per draw a run of its whole lane groups, shaded in place, and of
// its other visible pixels, packed into lanes. The planes are rebased already.
void shadePlane(const std::vector<Draw>& draws, const TileKernels& kernels,
                const std::uint32_t* visible, TileBuffers& tile, TileScratch& s) {
  const std::size_t triangles = s.visibleTriangles.size();
  // One draw: the kernel finds its groups itself, at two compares per group.
  if (visible == tile.visible &&
      s.visibleTriangles.front().draw == s.visibleTriangles.back().draw &&
      triangles < kMaxScannedTriangles) {
    ShadeRun run;
    run.scanTile = true;
    run.endTriangle = std::uint32_t(triangles);
    run.planes = s.shadePlanes.data();
    kernels.shade(draws[s.visibleTriangles.front().draw].shade, run, tile);
    return;
  }
  const std::uint32_t runs = assignRuns(s);

  // Each lane group: the run all its pixels belong to, or kMixed.
  constexpr std::uint32_t kMixed = 0xFFFFFFFFu;
  const int lanes = kernels.lanes;
  const int groups = TileBuffers::kPixels / lanes;
  s.groupRun.resize(std::size_t(groups));
  s.runGroups.assign(runs + 1, 0);
  s.runPixels.assign(runs + 1, 0);
  for (int g = 0; g < groups; ++g) {
    const std::uint32_t* ids = visible + g * lanes;
    bool oneTriangle = true;  // the common case, decided without looking runs up
    for (int k = 1; k < lanes; ++k) oneTriangle = oneTriangle && ids[k] == ids[0];
    std::uint32_t run = ids[0] == kNoTriangle ? kMixed : s.runOf[ids[0]];
    for (int k = 1; k < lanes && run != kMixed && !oneTriangle; ++k)
      if (ids[k] == kNoTriangle || s.runOf[ids[k]] != run) run = kMixed;
    s.groupRun[std::size_t(g)] = run;
    if (run != kMixed) {
      ++s.runGroups[run + 1];
      continue;
    }
    for (int k = 0; k < lanes; ++k)
      if (ids[k] != kNoTriangle) ++s.runPixels[s.runOf[ids[k]] + 1];
  }
  for (std::uint32_t r = 0; r < runs; ++r) {
    s.runGroups[r + 1] += s.runGroups[r];
    s.runPixels[r + 1] += s.runPixels[r];
  }
  s.groupList.resize(s.runGroups[runs]);
  s.pixelList.resize(s.runPixels[runs]);
  s.groupCursor.assign(s.runGroups.begin(), s.runGroups.end() - 1);
  s.pixelCursor.assign(s.runPixels.begin(), s.runPixels.end() - 1);
  for (int g = 0; g < groups; ++g) {
    const std::uint32_t run = s.groupRun[std::size_t(g)];
    if (run != kMixed) {
      s.groupList[s.groupCursor[run]++] = std::uint16_t(g * lanes);
      continue;
    }
    for (int k = 0; k < lanes; ++k) {
      const std::uint32_t id = visible[g * lanes + k];
      if (id != kNoTriangle)
        s.pixelList[s.pixelCursor[s.runOf[id]]++] = std::uint16_t(g * lanes + k);
    }
  }

  std::uint32_t firstTriangle = 0;  // of the current run
  for (std::uint32_t r = 0; r < runs; ++r) {
    while (s.runOf[firstTriangle] != r) ++firstTriangle;
    ShadeRun run;
    run.groups = s.groupList.data() + s.runGroups[r];
    run.groupCount = int(s.runGroups[r + 1] - s.runGroups[r]);
    run.pixels = s.pixelList.data() + s.runPixels[r];
    run.pixelCount = int(s.runPixels[r + 1] - s.runPixels[r]);
    run.planes = s.shadePlanes.data();
    if (run.groupCount + run.pixelCount == 0) continue;
    kernels.shade(draws[s.visibleTriangles[firstTriangle].draw].shade, run, tile);
  }
}

// s.jobs by run (draw) into s.sortedJobs, in pixel order within each, and
// each run's first job at s.runJobs[run]: the kernels take one draw at a
// time. One draw (a dense mesh's tiles): they are in order already. Returns
// the number of runs.
std::uint32_t sortJobsByRun(TileScratch& s) {
  const std::uint32_t runs = assignRuns(s);
  s.runJobs.assign(runs + 1, 0);
  if (runs == 1) {
    s.runJobs[1] = std::uint32_t(s.jobs.size());
    s.sortedJobs.swap(s.jobs);
    return runs;
  }
  for (const ShadeJob& job : s.jobs) ++s.runJobs[s.runOf[job.triangle] + 1];
  for (std::uint32_t r = 0; r < runs; ++r) s.runJobs[r + 1] += s.runJobs[r];
  s.sortedJobs.resize(s.jobs.size());
  s.sortedAt.resize(s.jobs.size());
  s.groupCursor.assign(s.runJobs.begin(), s.runJobs.end() - 1);
  for (std::size_t j = 0; j < s.jobs.size(); ++j) {
    const std::uint32_t at = s.groupCursor[s.runOf[s.jobs[j].triangle]]++;
    s.sortedJobs[at] = s.jobs[j];
    s.sortedAt[j] = at;
  }
  return runs;
}

// A mixed pixel's sample that no triangle holds (TileScratch::sampleSlot).
constexpr std::uint8_t kClearSlot = 0xFF;

// Up to this many samples, a mixed pixel's jobs come from a table indexed by
// which of its samples hold the same triangle and which none (pixelJobsKey);
// at 8, that is 36 bits.
constexpr int kMaxTabledSamples = 4;

// A mixed pixel's jobs, as they follow from which of its samples share a
// triangle: job j is shaded at (dx[j], dy[j]) pixels from the pixel's centre,
// with sample firstSample[j]'s triangle; slot[k] is sample k's job
// (kClearSlot: none). Past `count` the entries are the table's zeros or an
// earlier pixel's: collectPixelJobs writes them and does not keep them.
template <int kCapacity>
struct PixelJobs {
  float dx[kCapacity] = {}, dy[kCapacity] = {};
  std::uint8_t firstSample[kCapacity] = {};
  std::uint8_t slot[kCapacity] = {};
  std::uint32_t count = 0;
};

// Per set of samples (bit k: sample k), the mean of their offsets in pixels,
// the sum scaled once (the same bits computed anywhere).
void meanSampleOffset(const SamplePattern& pattern, std::uint32_t set, float& x, float& y) {
  int sumX = 0, sumY = 0, held = 0;
  for (int k = 0; k < pattern.count; ++k) {
    const int in = int(set >> k) & 1;
    sumX += in * pattern.offsets[k].x, sumY += in * pattern.offsets[k].y;
    held += in;
  }
  const float scale = 1.0f / float(held * kSampleUnitsPerPixel);
  x = float(sumX) * scale, y = float(sumY) * scale;
}

// What one frame's mixed pixels look up, built once per frame (renderTiles).
struct MixedPixelTables {
  // Up to 8 samples, per set of samples: meanSampleOffset (2^16 sets at 16).
  std::vector<float> meanX, meanY;
  // Up to kMaxTabledSamples, per pixelJobsKey: the pixel's jobs.
  std::vector<PixelJobs<kMaxTabledSamples>> jobs;
};

// A pixel's jobs from its samples' sharing: same[k], the samples holding
// sample k's triangle (k included); clear, the samples holding none. Each
// triangle's job opens at its first sample, in sample order.
template <int kSamples, int kCapacity>
void pixelJobs(const std::uint32_t* same, std::uint32_t clear, const SamplePattern& pattern,
               const MixedPixelTables& tables, PixelJobs<kCapacity>& out) {
  out.count = 0;
  for (int k = 0; k < kSamples; ++k) {
    const bool isClear = (clear >> k & 1u) != 0;
    const int first = __builtin_ctz(same[k]);  // of sample k's triangle
    out.slot[k] = isClear ? kClearSlot : first == k ? std::uint8_t(out.count) : out.slot[first];
    if (isClear || first != k) continue;
    if (tables.meanX.empty())
      meanSampleOffset(pattern, same[k], out.dx[out.count], out.dy[out.count]);
    else
      out.dx[out.count] = tables.meanX[same[k]], out.dy[out.count] = tables.meanY[same[k]];
    out.firstSample[out.count++] = std::uint8_t(k);
  }
}

// The pairs of samples pixelJobsKey's bits compare, in bit order: at 4
// samples simd::fourIdsSharing's.
template <int kSamples>
constexpr auto samplePairs() {
  static_assert(kSamples == 2 || kSamples == 4);
  if constexpr (kSamples == 2)
    return std::array<std::array<int, 2>, 1>{{{0, 1}}};
  else
    return std::array<std::array<int, 2>, 6>{{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}, {1, 3}}};
}

// The table index of a pixel whose samples hold `ids` (up to
// kMaxTabledSamples): a bit per pair of samples (samplePairs), set where
// they hold the same triangle, then a bit per sample, set where it holds
// none.
template <int kSamples>
std::uint32_t pixelJobsKey(const std::uint32_t* ids) {
  if constexpr (kSamples == 4) {
    return simd::fourIdsSharing(ids[0], ids[1], ids[2], ids[3], kNoTriangle);
  } else {
    constexpr auto kPairs = samplePairs<kSamples>();
    std::uint32_t key = 0;
    int bit = 0;
    for (const auto& [j, k] : kPairs) key |= std::uint32_t(ids[j] == ids[k]) << bit++;
    for (int k = 0; k < kSamples; ++k) key |= std::uint32_t(ids[k] == kNoTriangle) << bit++;
    return key;
  }
}

template <int kSamples>
void buildPixelJobsTable(const SamplePattern& pattern, MixedPixelTables& tables) {
  constexpr auto kPairs = samplePairs<kSamples>();
  tables.jobs.resize(std::size_t(1) << (kPairs.size() + kSamples));
  for (std::uint32_t key = 0; key < tables.jobs.size(); ++key) {
    std::uint32_t same[kSamples];
    for (int k = 0; k < kSamples; ++k) same[k] = 1u << k;
    int bit = 0;
    for (const auto& [j, k] : kPairs)
      if (key >> bit++ & 1u) same[j] |= 1u << k, same[k] |= 1u << j;
    // Keys no pixel has (sharing that is not transitive) get some entry.
    pixelJobs<kSamples>(same, key >> kPairs.size(), pattern, tables, tables.jobs[key]);
  }
}

// What mixedPixelTables holds at `samples` samples.
std::uint64_t mixedPixelTablesBytes(int samples) {
  const std::uint64_t sets = samples <= 8 ? std::uint64_t(1) << samples : 0;
  const int keyBits = samples * (samples - 1) / 2 + samples;  // samplePairs and one a sample
  const std::uint64_t keys =
      samples > 1 && samples <= kMaxTabledSamples ? std::uint64_t(1) << keyBits : 0;
  return sets * 2 * sizeof(float) + keys * sizeof(PixelJobs<kMaxTabledSamples>);
}

MixedPixelTables mixedPixelTables(const SamplePattern& pattern) {
  MixedPixelTables tables;
  if (pattern.count <= 8) {
    tables.meanX.resize(std::size_t(1) << pattern.count);
    tables.meanY.resize(tables.meanX.size());
    for (std::uint32_t set = 1; set < tables.meanX.size(); ++set)
      meanSampleOffset(pattern, set, tables.meanX[set], tables.meanY[set]);
  }
  if (pattern.count == 2) buildPixelJobsTable<2>(pattern, tables);
  if (pattern.count == 4) buildPixelJobsTable<4>(pattern, tables);
  return tables;
}

// shadePixels' jobs: each triangle of a pixel whose samples differ, at the
// mean of its samples' positions there, and which job holds each sample;
// those pixels leave plane 0's ids. Per sample count, so the loops over a
// pixel's samples unroll. Without a branch on the number of triangles a
// pixel holds (2 to kSamples, at random on a dense mesh): kSamples jobs are
// written a pixel and `count` kept. Up to 4 samples the jobs are one table
// lookup (dense-mesh, 4 samples, 1 thread, perf: shadePixels' own time
// about a sixth less than computing them per pixel; 46% of its pixels are
// mixed, 2.6 jobs each).
template <int kSamples>
void collectPixelJobs(const TileFrame& frame, TileScratch& s) {
  TileBuffers* const planes = s.planes.get();
  // Room for kSamples jobs a pixel; the pages are warm from the last tile,
  // and the vector only zero-fills past the last tile's jobs.
  s.jobs.resize(s.mixedPixels.size() * kSamples);
  s.pixelFirstJob.resize(s.mixedPixels.size());
  s.sampleSlot.resize(s.mixedPixels.size() * kSamples);
  s.mixedPlaneZeroIds.resize(s.mixedPixels.size());
  ShadeJob* const jobs = s.jobs.data();
  std::uint32_t jobCount = 0;
  std::uint32_t ids[kSamples];
  PixelJobs<kSamples> computed;  // past kMaxTabledSamples
  const auto write = [&](std::size_t i, std::uint16_t p, const auto& pixel) {
    const float x = float(TileBuffers::xAt(p)), y = float(TileBuffers::yAt(p));
    s.pixelFirstJob[i] = jobCount;
    std::copy_n(pixel.slot, kSamples, s.sampleSlot.data() + i * kSamples);
    for (int j = 0; j < kSamples; ++j)
      jobs[jobCount + j] = {x + pixel.dx[j], y + pixel.dy[j], ids[pixel.firstSample[j]], p};
    jobCount += pixel.count;
  };
  for (std::size_t i = 0; i < s.mixedPixels.size(); ++i) {
    const std::uint16_t p = s.mixedPixels[i];
    for (int k = 0; k < kSamples; ++k) ids[k] = planes[k].visible[p];
    s.mixedPlaneZeroIds[i] = ids[0];
    planes[0].visible[p] = kNoTriangle;
    if constexpr (kSamples <= kMaxTabledSamples) {
      write(i, p, s.mixedTables->jobs[pixelJobsKey<kSamples>(ids)]);
    } else {
      std::uint32_t same[kSamples], clear = 0;
      for (int k = 0; k < kSamples; ++k) {
        same[k] = 0;
        for (int j = 0; j < kSamples; ++j) same[k] |= std::uint32_t(ids[j] == ids[k]) << j;
        clear |= std::uint32_t(ids[k] == kNoTriangle) << k;
      }
      pixelJobs<kSamples>(same, clear, frame.samples, *s.mixedTables, computed);
      write(i, p, computed);
    }
  }
  s.jobs.resize(jobCount);
}

// Where each pixel's samples' ids differ from sample 0's (s.sampleDiffers:
// the bits of their differences) and the pixels where any does
// (s.mixedPixels, in tile order): the differences written once, every
// plane's ids read in one vectorized pass (where a pass a plane read and
// wrote them kSamples - 1 times), then the list without a branch per pixel
// (half of a dense mesh's pixels differ, at random, and the mispredictions
// were most of the list's time; perf).
// kCoverageOnly: only whether each sample holds a triangle is compared, for a
// tile whose triangles are all of one draw that shades one colour (those
// pixels' samples are that colour or the clear colour: the pixels
// wholePixelsOfOneColour would leave mixed, found without looking a
// sample's draw up; MetalRoughSpheresNoTextures at 4 samples, where most
// tiles hold one sphere).
template <int kSamples, bool kCoverageOnly>
void findMixedPixels(TileScratch& s) {
  const TileBuffers* const planes = s.planes.get();
  s.sampleDiffers.resize(TileBuffers::kPixels);
  std::uint32_t* const differs = s.sampleDiffers.data();
  for (int p = 0; p < TileBuffers::kPixels; ++p) {
    std::uint32_t differ = 0;
    for (int k = 1; k < kSamples; ++k) {
      if constexpr (kCoverageOnly)
        differ |= std::uint32_t(planes[k].visible[p] == kNoTriangle) ^
                  std::uint32_t(planes[0].visible[p] == kNoTriangle);
      else
        differ |= planes[k].visible[p] ^ planes[0].visible[p];
    }
    differs[p] = differ;
  }
  s.mixedPixels.resize(TileBuffers::kPixels + 3);
  std::size_t mixed = 0;
  for (int p = 0; p < TileBuffers::kPixels; p += 4)
    mixed = simd::appendNonZeroIndices(differs + p, std::uint16_t(p), s.mixedPixels.data(), mixed);
  s.mixedPixels.resize(mixed);
}

// Takes out of the mixed pixels those whose samples the triangles of one
// draw hold, every one, where that draw shades one colour (unlit, untextured
// materials: Draw::shadesOneColour): shaded once in plane 0 like a pixel one
// triangle holds instead of once per triangle. The same bits: the jobs'
// colours would all be the draw's, and their mean (pairwise sums of equal
// values, a power-of-two weight) is that colour exactly. The samples keep
// their triangles' ids (AOVs read them). `shading`, the tile's, spares the
// per-triangle lookups where no draw or every draw shades one colour
// (dense-mesh; MetalRoughSpheresNoTextures).
template <int kSamples>
void wholePixelsOfOneColour(const TileFrame& frame, TileDrawShading shading, TileScratch& s) {
  if (!shading.anyOneColour) return;
  const std::size_t triangles = s.visibleTriangles.size();
  s.oneColourDraw.resize(triangles + 1);
  s.oneColourDraw[0] = kNoTriangle;
  if (shading.allOneColour) {
    for (std::size_t i = 0; i < triangles; ++i) s.oneColourDraw[i + 1] = s.visibleTriangles[i].draw;
  } else {
    bool oneColour = false;
    std::uint32_t last = kNoTriangle;
    for (std::size_t i = 0; i < triangles; ++i) {
      const std::uint32_t draw = s.visibleTriangles[i].draw;
      if (draw != last) oneColour = frame.draws[draw].shade.shadesOneColour(), last = draw;
      s.oneColourDraw[i + 1] = oneColour ? draw : kNoTriangle;
    }
  }
  const TileBuffers* const planes = s.planes.get();
  const std::uint32_t* const drawOf = s.oneColourDraw.data();
  std::uint32_t* const differs = s.sampleDiffers.data();
  std::size_t mixed = 0;
  for (const std::uint16_t p : s.mixedPixels) {
    const std::uint32_t draw = drawOf[planes[0].visible[p] + 1];
    bool whole = draw != kNoTriangle;
    for (int k = 1; k < kSamples; ++k) whole &= drawOf[planes[k].visible[p] + 1] == draw;
    s.mixedPixels[mixed] = p;
    mixed += whole ? 0 : 1;
    differs[p] = whole ? 0 : differs[p];
  }
  s.mixedPixels.resize(mixed);
}

// Pixel p's colour from its samples' (premultiplied RGBA), kResolve: box
// filtered into plane 0, summed pairwise as TileKernels::averageSamples sums the planes
// (the same bits); else each into its own plane.
template <int kSamples, bool kResolve>
void writeSampleColors(float (&value)[4][kSamples], std::uint16_t p, TileBuffers* planes) {
  const float weight = 1.0f / float(kSamples);  // a power of two: exact
  for (int c = 0; c < 4; ++c) {
    if constexpr (kResolve) {
      for (int width = 1; width < kSamples; width *= 2)
        for (int k = 0; k + width < kSamples; k += 2 * width) value[c][k] += value[c][k + width];
      planes[0].color[c][p] = value[c][0] * weight;
    } else {
      for (int k = 0; k < kSamples; ++k) planes[k].color[c][p] = value[c][k];
    }
  }
}

// The mixed pixels' sample colours: each job's (s.jobColor: RGB, in
// s.sortedJobs' order) at the samples it holds, the clear colour at those
// none holds, a pixel at a time, as the resolve needs them (written alone,
// this ran no faster than the loop over each job's samples it replaced,
// though cachegrind put a mispredict a pixel in that loop). kResolve:
// straight to their box-filtered colour in plane 0, summed pairwise as
// TileKernels::averageSamples sums the planes (the same bits), the other planes' colours
// never written nor read (dense-mesh at 4 samples: the resolve stage 5.3 ->
// 3.0 ms a frame at 1 thread, where it is 3.3 at one sample).
template <int kSamples, bool kSorted, bool kResolve>
void writeJobColors(const TileFrame& frame, TileScratch& s) {
  const float* const color = s.jobColor.data();
  for (std::size_t i = 0; i < s.mixedPixels.size(); ++i) {
    const std::uint8_t* const slot = s.sampleSlot.data() + i * kSamples;
    float value[4][kSamples];
    for (int k = 0; k < kSamples; ++k) {
      const bool clear = slot[k] == kClearSlot;
      const std::uint32_t job = clear ? 0 : s.pixelFirstJob[i] + slot[k];
      const float* const rgb =
          clear ? &frame.clearColor[0] : color + 3 * std::size_t(kSorted ? s.sortedAt[job] : job);
      for (int c = 0; c < 3; ++c) value[c][k] = rgb[c];
      value[3][k] = clear ? frame.clearColor[3] : 1.0f;  // opaque and masked draws
    }
    writeSampleColors<kSamples, kResolve>(value, s.mixedPixels[i], s.planes.get());
  }
}

// A mixed pixel's sample colours where the tile's triangles are all of one
// draw that shades one colour (TileDrawShading): `color` (RGB, the kernel's
// for that draw) at the samples a triangle holds, the clear colour at the
// others, as writeJobColors would write them from that draw's jobs, every
// one of that colour; the jobs are neither collected, sorted nor shaded
// (most of MetalRoughSpheresNoTextures' tiles at 4 samples, where each
// holds one sphere).
template <int kSamples, bool kResolve>
void writeCoverageColors(const TileFrame& frame, const float* color, TileScratch& s) {
  TileBuffers* const planes = s.planes.get();
  for (const std::uint16_t p : s.mixedPixels) {
    float value[4][kSamples];
    for (int k = 0; k < kSamples; ++k) {
      const bool clear = planes[k].visible[p] == kNoTriangle;
      for (int c = 0; c < 3; ++c) value[c][k] = clear ? frame.clearColor[c] : color[c];
      value[3][k] = clear ? frame.clearColor[3] : 1.0f;  // opaque and masked draws
    }
    writeSampleColors<kSamples, kResolve>(value, p, planes);
  }
}

// Multisampled shading, once per pixel and visible triangle. Pixels whose
// samples one triangle holds (or none) are shaded in plane 0 at their centre
// like a one-sample tile; only plane 0 holds their colour (fillSamplePlanes
// copies it where something else will draw). Every other pixel's triangles
// are jobs, each shaded at the mean of its samples' positions (inside the
// triangle) and written to its samples, its uncovered samples taking the
// clear colour; or, box-filtered with no forward draw to come, their mean
// written to plane 0, the pixel resolved.
void shadePixels(const TileFrame& frame, const TileKernels& kernels, TileScratch& s) {
  const int samples = frame.samples.count;
  TileBuffers* const planes = s.planes.get();
  const TileDrawShading shading = tileDrawShading(frame.draws, s);
  const bool oneColourDraw = shading.oneDraw && shading.allOneColour;
  withSampleCount(samples, [&](auto count) {
    constexpr int kSamples = decltype(count)::value;
    if (oneColourDraw)
      findMixedPixels<kSamples, true>(s);
    else
      findMixedPixels<kSamples, false>(s);
  });
  s.allMixed = false;
  if (s.visibleTriangles.empty()) return;
  if (!oneColourDraw)
    withSampleCount(samples, [&](auto count) {
      wholePixelsOfOneColour<decltype(count)::value>(frame, shading, s);
    });

  rebaseShadePlanes(frame.draws, planes[0], SampleOffset{}, shading.allOneColour, s);
  // Plane 0's ids without the mixed pixels while its other pixels are
  // shaded, so that a one-draw tile takes the kernel's scan of the tile as at
  // one sample; restored after.
  if (oneColourDraw) {
    s.mixedPlaneZeroIds.resize(s.mixedPixels.size());
    for (std::size_t i = 0; i < s.mixedPixels.size(); ++i) {
      s.mixedPlaneZeroIds[i] = planes[0].visible[s.mixedPixels[i]];
      planes[0].visible[s.mixedPixels[i]] = kNoTriangle;
    }
  } else {
    withSampleCount(samples,
                    [&](auto count) { collectPixelJobs<decltype(count)::value>(frame, s); });
  }
  shadePlane(frame.draws, kernels, planes[0].visible, planes[0], s);
  for (std::size_t i = 0; i < s.mixedPixels.size(); ++i)
    planes[0].visible[s.mixedPixels[i]] = s.mixedPlaneZeroIds[i];
  // Box-filtered with nothing drawn after: resolved here.
  const bool resolve = s.pixelFilter == nullptr && s.forward.empty();
  if (oneColourDraw) {
    if (s.mixedPixels.empty()) return;
    // The draw's colour, from the kernel: one job, at a mixed pixel's centre
    // with one of the tile's triangles (its colour is the same at any).
    const std::uint16_t p = s.mixedPixels[0];
    const ShadeJob job{float(TileBuffers::xAt(p)), float(TileBuffers::yAt(p)), 0, p};
    float color[3];
    ShadeRun run;
    run.planes = s.shadePlanes.data();
    run.jobs = &job;
    run.jobCount = 1;
    run.jobColor = color;
    kernels.shade(frame.draws[s.visibleTriangles[0].draw].shade, run, planes[0]);
    withSampleCount(samples, [&](auto count) {
      constexpr int kSamples = decltype(count)::value;
      if (resolve)
        writeCoverageColors<kSamples, true>(frame, color, s);
      else
        writeCoverageColors<kSamples, false>(frame, color, s);
    });
    return;
  }
  if (s.jobs.empty()) return;

  const std::uint32_t runs = sortJobsByRun(s);
  s.jobColor.resize(3 * s.sortedJobs.size());
  for (std::uint32_t r = 0; r < runs; ++r) {
    const std::uint32_t first = s.runJobs[r], count = s.runJobs[r + 1] - first;
    if (count == 0) continue;
    ShadeRun run;
    run.planes = s.shadePlanes.data();
    run.jobs = s.sortedJobs.data() + first;
    run.jobCount = int(count);
    run.jobColor = s.jobColor.data() + 3 * first;
    kernels.shade(frame.draws[s.visibleTriangles[s.sortedJobs[first].triangle].draw].shade, run,
                  planes[0]);
  }
  withSampleCount(samples, [&](auto count) {
    constexpr int kSamples = decltype(count)::value;
    const auto write = [&]<bool kSorted>() {
      if (resolve)
        writeJobColors<kSamples, kSorted, true>(frame, s);
      else
        writeJobColors<kSamples, kSorted, false>(frame, s);
    };
    if (runs == 1)
      write.template operator()<false>();
    else
      write.template operator()<true>();
  });
}

// Before forward draws write into a tile shaded per pixel: plane 0's colour
// of the pixels whose samples agree copied to the other planes, and every
// pixel resolved from all its samples.
void fillSamplePlanes(const TileFrame& frame, TileScratch& s) {
  frame.kernels.wide->copyAgreeingSamples(s.planes.get(), frame.samples.count,
                                          s.sampleDiffers.data());
  s.allMixed = true;
}

// Shading pass: each pixel's visible triangles once, or with several samples
// shaded one by one, each plane as a one-sample tile shaded where its sample
// is shaded (shadingOffset: its cell's centre at 4 and 16 samples).
void shadingPass(const TileFrame& frame, const TileKernels& kernels, TileScratch& s) {
  if (frame.samples.count > 1 && !frame.shadeSamples) return shadePixels(frame, kernels, s);
  s.allMixed = true;
  if (s.visibleTriangles.empty()) return;
  const bool allOneColour = tileDrawShading(frame.draws, s).allOneColour;
  for (int k = 0; k < frame.samples.count; ++k) {
    TileBuffers& plane = s.planes[k];
    rebaseShadePlanes(frame.draws, plane, shadingOffset(frame.samples, k), allOneColour, s);
    shadePlane(frame.draws, kernels, plane.visible, plane, s);
  }
}

// Whether a forward draw's fragments are composited per sample in depth
// order (tile/blended_fragments.h): glTF BLEND surfaces, which write no
// depth, whose order is exact that way where surfaces interpenetrate or a
// draw overlaps itself, which no order of draws is. Draws with blend state
// of their own composite in submission order.
bool composedInDepthOrder(const ShadeState& shade) {
  return shade.depthOrdered;
}

// Whether a frame's tiles need the fragment store (its memory and the
// TileWorkspace's sizing).
bool someDrawComposedInDepthOrder(const std::vector<Draw>& draws) {
  return std::any_of(draws.begin(), draws.end(),
                     [](const Draw& draw) { return composedInDepthOrder(draw.shade); });
}

// Whether a forward draw shades once per pixel (TileKernels::
// shadeBlendedPixels): with several samples at the pixel rate, where the
// draw is not shaded per sample anyway (ShadeState::
// shadedPerSampleAtPixelRate), unless it shades one colour, which every
// sample gets alike: in one pass per sample plane, the same bits in less
// time (intersecting-glass, 4 samples, 1080p: 26.6 ms per sample, 27.8 in
// two passes).
bool shadedPerPixel(const TileFrame& frame, const ShadeState& shade) {
  return frame.samples.count > 1 && !frame.shadeSamples && !shade.shadedPerSampleAtPixelRate() &&
         !shade.shadesOneColour();
}

// Calls draw(triangle, planes, plane) for every sample plane, with the
// triangle and its depth plane moved to that plane's sample, and its next
// planeCount - 1 planes (1/w, attributes) to where the sample is shaded.
template <class DrawAtSample>
void forEachSample(const TileFrame& frame, const TileTriangle& t, int planeCount,
                   DrawAtSample&& draw) {
  if (frame.samples.count == 1) return draw(*t.triangle, t.planes, 0);
  Plane moved[2 + kMaxShadedAttributes];
  for (int k = 0; k < frame.samples.count; ++k) {
    const SampleOffset o = frame.samples.offsets[k];
    const SampleOffset shaded = frame.shadeSamples ? shadingOffset(frame.samples, k) : o;
    if (planeCount > 0) moved[0] = t.planes[0].atSample(o);
    for (int j = 1; j < planeCount; ++j) moved[j] = t.planes[j].atSample(shaded);
    draw(atSample(*t.triangle, o), moved, k);
  }
}

// The range a triangle's depth takes over its part of the tile, widened by
// a pixel each way (a sample lies within half a pixel of its centre) and by
// depthPlaneMargin (the per-sample planes' and lanes' float roundings).
struct DepthRange {
  double low, high;
};
DepthRange depthRangeInTile(const TileTriangle& t, const TileBuffers& tile) {
  const TriangleRecord& r = *t.triangle;
  const Plane& z = t.planes[0];  // at pixel (px, py): c + dx (px - minX) + dy (py - minY)
  const int x0 = std::max(int(r.minX), tile.originX) - 1 - r.minX;
  const int x1 = std::min(int(r.maxX), tile.originX + tile.width - 1) + 1 - r.minX;
  const int y0 = std::max(int(r.minY), tile.originY) - 1 - r.minY;
  const int y1 = std::min(int(r.maxY), tile.originY + tile.height - 1) + 1 - r.minY;
  const double dx = z.dx, dy = z.dy, c = z.c;
  const double low = c + std::min(dx * x0, dx * x1) + std::min(dy * y0, dy * y1);
  const double high = c + std::max(dx * x0, dx * x1) + std::max(dy * y0, dy * y1);
  const double margin = depthPlaneMargin(
      c, dx, dy, std::max({std::abs(x0), std::abs(x1), std::abs(y0), std::abs(y1)}));
  return {low - margin, high + margin};
}

// Whether the tile's blended triangles composed in depth order, from the
// first one on, arrive far to near at every sample they share: each one
// nowhere behind any before it over the tile. Then no sample is late, and
// the order pass, which would mark none, is skipped: a draw's own triangles
// at one depth, or draws sorted back to front that do not interpenetrate
// (alpha-quads' layers), pay nothing for it.
bool blendedArriveFarToNear(const TileFrame& frame, const TileScratch& s, std::size_t first) {
  const TileBuffers& tile = s.planes[0];
  constexpr double kFar = std::numeric_limits<double>::infinity();
  double nearest = frame.depthGreater ? -kFar : kFar;  // of those so far
  for (std::size_t j = first; j < s.forward.size(); ++j) {
    const TileTriangle& t = s.forward[j];
    if (!composedInDepthOrder(frame.draws[t.draw].shade)) continue;
    const DepthRange range = depthRangeInTile(t, tile);
    if (!(frame.depthGreater ? range.low >= nearest : range.high <= nearest)) return false;
    nearest = frame.depthGreater ? std::max(nearest, range.high) : std::min(nearest, range.low);
  }
  return true;
}

// The forward triangles in order. At the first blended one composed in depth
// order (the renderer puts blended draws after the opaque ones, so the depth
// is final there), the order pass over it and the rest; their late samples'
// fragments are composited after the last.
void forwardDraws(const TileFrame& frame, TileScratch& s) {
  bool ordered = false;
  for (std::size_t i = 0; i < s.forward.size(); ++i) {
    const TileTriangle& t = s.forward[i];
    const TileKernels& kernel = frame.kernels.forWidth(t.triangle->maxX - t.triangle->minX + 1);
    const ShadeState& shade = frame.draws[t.draw].shade;
    const bool inDepthOrder = composedInDepthOrder(shade);
    if (inDepthOrder && !ordered) {
      ordered = true;
      s.blended.begin(frame.samples.count, frame.depthGreater);
      const bool inOrder = blendedArriveFarToNear(frame, s, i);
      if (!inOrder) s.blended.beginOrderPass();
      for (std::size_t j = i; j < s.forward.size() && !inOrder; ++j) {
        const TileTriangle& later = s.forward[j];
        const ShadeState& laterShade = frame.draws[later.draw].shade;
        if (!composedInDepthOrder(laterShade)) continue;
        const TileKernels& k =
            frame.kernels.forWidth(later.triangle->maxX - later.triangle->minX + 1);
        forEachSample(frame, later, 1, [&](const TriangleRecord& r, const Plane* p, int plane) {
          k.orderBlended(r, p, laterShade, s.planes[plane], s.blended, plane);
        });
      }
    }
    if (inDepthOrder && shadedPerPixel(frame, shade)) {
      forEachSample(frame, t, 1, [&](const TriangleRecord& r, const Plane* p, int plane) {
        kernel.coverBlended(r, p, shade, s.planes[plane], s.blended, plane);
      });
      kernel.shadeBlendedPixels(*t.triangle, t.planes, shade, frame.samples, s.planes.get(),
                                s.blended);
      continue;
    }
    BlendedFragments* const deferred = inDepthOrder ? &s.blended : nullptr;
    forEachSample(frame, t, 2 + shade.attributes.count,
                  [&](const TriangleRecord& r, const Plane* p, int plane) {
                    kernel.rasterize(r, p, shadeAtSample(frame, s, t.draw, plane), s.planes[plane],
                                     deferred, plane);
                  });
  }
  if (ordered && !s.blended.empty())
    frame.kernels.wide->compositeBlended(s.blended, s.planes.get());
}

// The samples into plane 0 (colour and depth) and Frame::coverage, by the
// frame's pixel filter; a wide filter's pixels near a shared tile border are
// finished after every tile (renderTiles).
void resolveSamples(int tileIndex, const TileFrame& frame, TileScratch& s, Frame& out) {
  const int samples = frame.samples.count;
  if (s.pixelFilter) {
    const bool perPixel = samples > 1 && !s.allMixed;  // shadePixels' sampleDiffers holds
    filterTileSamples(tileIndex, *s.pixelFilter, s.planes.get(),
                      perPixel ? s.sampleDiffers.data() : nullptr, s.filter, out);
  } else {
    if (frame.coverage) boxCoverage(s.planes.get(), samples, frame.clearDepth, out);
    if (samples > 1 && s.allMixed) frame.kernels.wide->averageSamples(s.planes.get(), samples);
  }
  if (samples > 1)
    frame.kernels.wide->nearestSampleDepth(s.planes.get(), samples, frame.depthGreater);
}

// The jobs of the AOVs the kernels compute (lod and anisotropy, the shading
// AOVs): per pixel, the nearest sample's triangle at the pixel centre, as the
// shading pass would shade it, where wants(its draw's ShadeState) holds;
// clear(frame pixel) for every pixel first. Sorted by run into
// s.sortedJobs; returns the number of runs (0: no job).
template <class Wants, class Clear>
std::uint32_t collectAovJobs(const TileFrame& frame, TileScratch& s, const Frame& out,
                             const Wants& wants, const Clear& clear) {
  const TileBuffers& tile = s.planes[0];
  if (!s.visibleTriangles.empty())
    rebaseShadePlanes(frame.draws, tile, SampleOffset{},
                      tileDrawShading(frame.draws, s).allOneColour, s);
  s.jobs.clear();
  for (int y = 0; y < tile.height; ++y)
    for (int x = 0; x < tile.width; ++x) {
      const int p = TileBuffers::index(x, y);
      const std::uint32_t id =
          nearestSampleTriangle(s.planes.get(), frame.samples.count, frame.depthGreater, p);
      clear(std::size_t(tile.originY + y) * std::size_t(out.width) + std::size_t(tile.originX + x));
      if (id != kNoTriangle && wants(frame.draws[s.visibleTriangles[id].draw].shade))
        s.jobs.push_back({float(x), float(y), id, std::uint16_t(p)});
    }
  if (s.jobs.empty()) return 0;
  return sortJobsByRun(s);
}

// The frame pixel of a sorted job.
std::size_t jobPixel(const TileScratch& s, std::size_t job, const Frame& out) {
  const TileBuffers& tile = s.planes[0];
  const int p = s.sortedJobs[job].pixel;
  return std::size_t(tile.originY + TileBuffers::yAt(p)) * std::size_t(out.width) +
         std::size_t(tile.originX + TileBuffers::xAt(p));
}

// Calls kernel(its draw's ShadeState, first job, job count) for each run of s.sortedJobs.
template <class Kernel>
void forEachAovRun(const TileFrame& frame, const TileScratch& s, std::uint32_t runs,
                   const Kernel& kernel) {
  for (std::uint32_t r = 0; r < runs; ++r) {
    const std::uint32_t first = s.runJobs[r], jobs = s.runJobs[r + 1] - first;
    if (jobs == 0) continue;
    const std::uint32_t draw = s.visibleTriangles[s.sortedJobs[first].triangle].draw;
    kernel(frame.draws[draw].shade, first, jobs);
  }
}

// The lod and anisotropy AOVs (docs/cli.md "AOVs"): the nearest sample's
// triangle looked up by the kernel at the pixel centre as the shading pass
// would (TileKernels::footprintLevels), one kernel call per run of a
// textured draw's pixels; 0 and 0 where no textured surface is.
void writeFootprintAovs(const TileFrame& frame, const TileKernels& kernels, TileScratch& s,
                        Frame& out) {
  const AovSet set = frame.aov->aovs;
  const std::uint32_t runs = collectAovJobs(
      frame, s, out, [](const ShadeState& shade) { return shade.textured; },
      [&](std::size_t pixel) {
        if (hasAov(set, Aov::Lod)) out.lod[pixel] = 0.0f;
        if (hasAov(set, Aov::Anisotropy)) out.anisotropy[pixel] = 0.0f;
      });
  if (runs == 0) return;
  const std::size_t count = s.sortedJobs.size();
  s.jobColor.resize(2 * count);
  float* const lod = s.jobColor.data();
  float* const anisotropy = lod + count;
  forEachAovRun(frame, s, runs,
                [&](const ShadeState& shade, std::uint32_t first, std::uint32_t jobs) {
                  kernels.footprintLevels(shade, s.shadePlanes.data(), &s.sortedJobs[first],
                                          int(jobs), lod + first, anisotropy + first);
                });
  for (std::size_t j = 0; j < count; ++j) {
    const std::size_t pixel = jobPixel(s, j, out);
    if (hasAov(set, Aov::Lod)) out.lod[pixel] = lod[j];
    if (hasAov(set, Aov::Anisotropy)) out.anisotropy[pixel] = anisotropy[j];
  }
}

// The shading AOVs (docs/cli.md "AOVs"): the nearest sample's triangle
// shaded again by the kernel at the pixel centre, as the shading pass shaded
// it, its terms kept apart (TileKernels::shadingAovs); 0 where no surface is.
void writeShadingAovs(const TileFrame& frame, const TileKernels& kernels, TileScratch& s,
                      Frame& out) {
  const AovSet set = frame.aov->aovs;
  struct Target {
    Aov aov;
    std::vector<float>* frame;
    int channel, channels;
  };
  const Target targets[] = {{Aov::Albedo, &out.albedo, kAlbedoChannel, 3},
                            {Aov::Roughness, &out.roughness, kRoughnessChannel, 1},
                            {Aov::Metallic, &out.metallic, kMetallicChannel, 1},
                            {Aov::Emission, &out.emission, kEmissionChannel, 3},
                            {Aov::Diffuse, &out.diffuse, kDiffuseChannel, 3},
                            {Aov::Specular, &out.specular, kSpecularChannel, 3}};
  const std::uint32_t runs = collectAovJobs(
      frame, s, out, [](const ShadeState&) { return true; },
      [&](std::size_t pixel) {
        for (const Target& t : targets)
          if (hasAov(set, t.aov))
            for (int c = 0; c < t.channels; ++c)
              (*t.frame)[std::size_t(t.channels) * pixel + std::size_t(c)] = 0.0f;
      });
  if (runs == 0) return;
  const std::size_t count = s.sortedJobs.size();
  s.jobColor.resize(kShadingAovFloats * count);
  float* const terms = s.jobColor.data();
  forEachAovRun(
      frame, s, runs, [&](const ShadeState& shade, std::uint32_t first, std::uint32_t jobs) {
        // The run's own block of kShadingAovFloats x jobs floats.
        float* const run = terms + kShadingAovFloats * first;
        kernels.shadingAovs(shade, s.shadePlanes.data(), &s.sortedJobs[first], int(jobs), run);
        if (shade.material == nullptr && frame.aov->albedoScale != 1.0f)
          for (std::size_t i = 0; i < 3 * std::size_t(jobs); ++i)
            run[kAlbedoChannel * std::size_t(jobs) + i] *= frame.aov->albedoScale;
      });
  forEachAovRun(frame, s, runs, [&](const ShadeState&, std::uint32_t first, std::uint32_t jobs) {
    const float* run = terms + kShadingAovFloats * first;
    for (std::uint32_t j = 0; j < jobs; ++j) {
      const std::size_t pixel = jobPixel(s, first + j, out);
      for (const Target& t : targets)
        if (hasAov(set, t.aov))
          for (int c = 0; c < t.channels; ++c)
            (*t.frame)[std::size_t(t.channels) * pixel + std::size_t(c)] =
                run[std::size_t(t.channel + c) * jobs + j];
    }
  });
}

// binned: the triangles the front end binned to the tile, over every chunk.
void renderTile(int tileIndex, std::uint32_t binned, const TileFrame& frame, TileScratch& s,
                Frame& out, TileTimes& times) {
  const double start = stageClockMs();
  const int samples = frame.samples.count;
  // A tile no triangle reaches holds the clear colour and depth at every
  // sample, so plane 0 stands for all of them: their box-filtered mean and
  // nearest depth are its values exactly, and its coverage 0 is theirs. The
  // other planes are neither cleared nor read (their clears, mixed-pixel
  // scan and nearest-depth pass were ~125K instructions a tile at 4
  // samples, and 394 of MetalRoughSpheresNoTextures' 510 tiles at 1080p are
  // background). A wide pixel filter's border rings and the AOVs take the
  // general path.
  const bool background = binned == 0 && frame.pixelFilter == nullptr && frame.aov == nullptr;
  const int clearedPlanes = background ? 1 : samples;
  for (int k = 0; k < clearedPlanes; ++k) {
    TileBuffers& tile = s.planes[k];
    tile.originX = (tileIndex % frame.grid.tilesX) * kTileSize;
    tile.originY = (tileIndex / frame.grid.tilesX) * kTileSize;
    tile.width = std::min(kTileSize, frame.grid.width - tile.originX);
    tile.height = std::min(kTileSize, frame.grid.height - tile.originY);
    clearTile(tile, frame.clearColor, frame.clearDepth,
              k == 0 || frame.shadeSamples);  // shadePixels fills the others
  }
  if (background) {
    const double cleared = stageClockMs();
    if (frame.coverage) boxCoverage(s.planes.get(), 1, frame.clearDepth, out);
    if (frame.background) frame.kernels.wide->compositeBackground(*frame.background, s.planes[0]);
    resolveTile(s.planes[0], out);
    times.raster = cleared - start;
    times.resolve = stageClockMs() - cleared;
    return;
  }
  s.visibleTriangles.clear();
  s.visibleSources.clear();
  s.forward.clear();
  if (frame.samples.count == 1)
    visibilityPass<false>(tileIndex, frame, s);
  else
    visibilityPass<true>(tileIndex, frame, s);
  const double visible = stageClockMs();
  shadingPass(frame, *frame.kernels.wide, s);
  const double shaded = stageClockMs();
  if (samples > 1 && !s.allMixed && !s.forward.empty()) fillSamplePlanes(frame, s);
  forwardDraws(frame, s);
  const double rastered = stageClockMs();
  // Before resolveSamples, which folds the samples' depths into plane 0.
  if (frame.aov && (frame.aov->aovs & ~(kFootprintAovs | kShadingAovs)) != 0)
    writeSurfaceAovs(*frame.aov, s.planes.get(), samples, frame.depthGreater, s.visibleTriangles,
                     s.visibleSources, s.aovTriangles, out);
  if (frame.aov && (frame.aov->aovs & kFootprintAovs) != 0)
    writeFootprintAovs(frame, *frame.kernels.wide, s, out);
  if (frame.aov && (frame.aov->aovs & kShadingAovs) != 0)
    writeShadingAovs(frame, *frame.kernels.wide, s, out);
  // The environment behind the surfaces: under each sample a wide pixel
  // filter weighs, else under the resolved pixels (the same average: the
  // composite is linear in the colour).
  if (frame.background && frame.pixelFilter)
    for (int k = 0; k < samples; ++k)
      frame.kernels.wide->compositeBackground(*frame.background, s.planes[k]);
  resolveSamples(tileIndex, frame, s, out);
  if (frame.background && !frame.pixelFilter)
    frame.kernels.wide->compositeBackground(*frame.background, s.planes[0]);
  resolveTile(s.planes[0], out);
  times.raster = (visible - start) + (rastered - shaded);
  times.shade = shaded - visible;
  times.resolve = stageClockMs() - rastered;
}

}  // namespace

std::uint64_t tileMemoryBytes(const TileGrid& grid, int samples, int threads,
                              int pixelFilterChannels, AovSet aovs,
                              const std::vector<Draw>& draws) {
  const std::uint64_t slots = std::uint64_t(samples) * TileBuffers::kPixels;
  const bool blended = someDrawComposedInDepthOrder(draws);
  // The fragment layers, counts and the order pass (blended_fragments.h).
  const std::uint64_t fragments = blended ? slots * BlendedFragments::kBytesPerSample : 0;
  // A TileScratch's lists. A vector that grows by doubling or resizing is
  // counted twice its bound; visibleTriangles and shadePlanes are reserved
  // at theirs. Per visible triangle: its entry and shading planes, its run,
  // renumbering, and its run's four list offsets and jobs offset; with
  // AOVs its source triangle and AovTriangle.
  const std::uint64_t perTriangle =
      sizeof(TileTriangle) + kShadePlaneStride * sizeof(float) + sizeof(std::uint32_t) +
      2 * 6 * sizeof(std::uint32_t) +
      (aovs != 0 ? 2 * (sizeof(std::uint32_t) + sizeof(AovTriangle)) : 0);
  // Shading jobs, at most one per sample slot (a pixel's triangles shaded
  // once each): the job, its sorted copy, its place there and its colour
  // (RGB, or lod and anisotropy); and each slot's job.
  const std::uint64_t perJob =
      2 * (2 * sizeof(ShadeJob) + 3 * sizeof(float) + sizeof(std::uint32_t) + sizeof(std::uint8_t));
  // Per pixel: plane 0's ids copied, the differing samples, the mixed pixels
  // and their first jobs, the run lists' groups and pixels, and each lane
  // group's run.
  // With the shading AOVs, their terms per pixel's job (the colour list
  // holds them).
  const std::uint64_t perPixel =
      2 * (3 * sizeof(std::uint32_t) + 3 * sizeof(std::uint16_t) + sizeof(std::uint32_t)) +
      ((aovs & kShadingAovs) != 0 ? 2 * kShadingAovFloats * sizeof(float) : 0);
  const std::uint64_t perWorker =
      std::uint64_t(samples) * (sizeof(TileBuffers) + sizeof(ShadeState)) + fragments +
      std::uint64_t(maxVisibleTriangles(samples)) * perTriangle + slots * perJob +
      std::uint64_t(TileBuffers::kPixels) * perPixel +
      (pixelFilterChannels > 0 ? pixelFilterScratchBytes(pixelFilterChannels) : 0);
  const std::uint64_t rings = std::uint64_t(grid.tileCount()) * kBorderRingPixels *
                              std::uint64_t(pixelFilterChannels) * sizeof(float);
  // The frame's MixedPixelTables, shared by the workers.
  const std::uint64_t tables = mixedPixelTablesBytes(samples);
  const int workers = std::clamp(grid.tileCount(), 1, std::max(threads, 1));
  return std::uint64_t(workers) * perWorker + rings + tables;
}

struct TileWorkspace::Kept {
  // What sizes the scratches (tileMemoryBytes' inputs but the grid).
  struct Sizing {
    int samples = 0, threads = 0, filterChannels = 0;
    bool aovs = false, blended = false;
    bool operator==(const Sizing&) const = default;
  } sizing;
  std::vector<std::unique_ptr<TileScratch>> scratches;  // per worker, made by its first tile
};

TileWorkspace::TileWorkspace() : kept(std::make_unique<Kept>()) {}
TileWorkspace::~TileWorkspace() = default;

void renderTiles(const TileFrame& frame, const Executor& executor, TileWorkspace& workspace,
                 Frame& out, std::vector<TileTimes>& times) {
  const std::size_t tiles = std::size_t(frame.grid.tileCount());
  times.assign(tiles, TileTimes{});
  // Heavy tiles first, so the last tasks to finish are short ones: a tile's
  // cost estimated as its binned triangles plus a constant for its pixels
  // (a triangle's visibility and setup cost about what a few shaded pixel
  // groups do). Each tile writes only its own part of the frame, so the
  // order changes no output.
  constexpr std::uint32_t kPixelsCost = 64;
  std::vector<std::uint32_t> binned(tiles, 0);                        // per tile, over every chunk
  std::vector<std::pair<std::uint32_t, std::uint32_t>> order(tiles);  // (cost, tile)
  for (std::size_t t = 0; t < tiles; ++t) {
    for (const FrontEndChunk& chunk : frame.chunks)
      binned[t] += chunk.bins.tileStart[t + 1] - chunk.bins.tileStart[t];
    order[t] = {kPixelsCost + binned[t], std::uint32_t(t)};
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  // A wide pixel filter's rings: per tile, its sums for the pixels of its
  // neighbours (tile/pixel_filter.h), read by the second pass.
  std::unique_ptr<float[]> rings;
  std::optional<PixelFilterFrame> filter;
  if (frame.pixelFilter) {
    filter.emplace(PixelFilterFrame{*frame.pixelFilter, frame.grid.tilesX, frame.grid.tilesY,
                                    frame.clearDepth, frame.coverage, nullptr});
    rings.reset(new float[tiles * kBorderRingPixels * std::size_t(filter->channels())]);
    filter->borderRings = rings.get();
  }
  const MixedPixelTables mixedTables = mixedPixelTables(frame.samples);
  TileWorkspace::Kept& kept = *workspace.kept;
  const TileWorkspace::Kept::Sizing sizing{frame.samples.count, executor.threadCount(),
                                           filter ? filter->channels() : 0, frame.aov != nullptr,
                                           someDrawComposedInDepthOrder(frame.draws)};
  if (!(sizing == kept.sizing)) {
    kept.scratches.clear();
    kept.scratches.resize(std::size_t(sizing.threads));
    kept.sizing = sizing;
  }
  executor.parallelFor(tiles, 1, [&](std::size_t begin, std::size_t end) {
    std::unique_ptr<TileScratch>& scratch = kept.scratches[std::size_t(executor.workerIndex())];
    if (!scratch) scratch = std::make_unique<TileScratch>(frame.samples.count);
    // This frame's: renderTile leaves nothing else in the scratch that the
    // next tile, or the next frame, reads.
    scratch->pixelFilter = filter ? &*filter : nullptr;
    scratch->mixedTables = &mixedTables;
    scratch->coverageDraw = kNoCoverageDraw;  // a draw index of its frame
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t t = order[i].second;
      renderTile(int(t), binned[t], frame, *scratch, out, times[t]);
    }
  });
  if (!filter) return;
  executor.parallelFor(tiles, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      const double start = stageClockMs();
      finishTileBorders(int(t), *filter, out);
      times[t].resolve += stageClockMs() - start;
    }
  });
}

}  // namespace quadra
