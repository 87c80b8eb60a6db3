// Tile stage scheduling and the per-tile loop: the visibility pass over the
// two-pass draws' triangles, the shading pass over their visible pixels draw
// by draw, then the forward draws, then the tile's resolve. The per-pixel work
// is in the ISA kernels (tile_kernel_impl.h).
#include "tile/tile_stage.h"

#include <algorithm>
#include <memory>
#include <utility>

#include "core/error.h"
#include "core/parallel.h"
#include "core/stage_clock.h"
#include "tile/tile_resolve.h"

namespace quadra {

namespace {

// One task's working memory, reused from tile to tile.
struct TileScratch {
  TileBuffers tile;
  std::vector<TileTriangle> visibleTriangles;  // indexed by TileBuffers::visible
  std::vector<TileTriangle> forward;           // forward-path triangles, in order
  std::vector<float> shadePlanes;              // kShadePlaneStride per visible triangle
  std::vector<std::uint32_t> runOf;            // per visible triangle: its draw's run
  std::vector<std::uint32_t> groupRun;  // per lane group: its run, if all its pixels have one
  // Per run: where its whole groups and its other pixels start in the lists.
  std::vector<std::uint32_t> runGroups, runPixels, groupCursor, pixelCursor;
  std::vector<std::uint16_t> groupList, pixelList;
};

// How far ahead the visibility pass fetches triangle records and planes.
constexpr std::uint32_t kRecordLookahead = 8, kPlaneLookahead = 4;

// Both ends of a run of bytes that may straddle two cache lines.
void prefetch(const void* begin, std::size_t bytes) {
  __builtin_prefetch(begin);
  __builtin_prefetch(static_cast<const char*>(begin) + bytes - 1);
}

void clearTile(TileBuffers& tile, const glm::vec4& clearColor, float clearDepth) {
  std::fill(std::begin(tile.depth), std::end(tile.depth), clearDepth);
  std::fill(std::begin(tile.visible), std::end(tile.visible), kNoTriangle);
  std::fill(std::begin(tile.blockDepthMin), std::end(tile.blockDepthMin), clearDepth);
  std::fill(std::begin(tile.blockDepthMax), std::end(tile.blockDepthMax), clearDepth);
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

// Visibility pass: every two-pass triangle binned to the tile, in submission
// order; the forward ones are kept for after the shading pass (the renderer
// puts every two-pass draw before them). A tile where forward shading wins
// (forwardWins) sends every triangle forward: the same bits either way.
void visibilityPass(int tileIndex, const std::vector<Draw>& draws,
                    const std::vector<FrontEndChunk>& chunks, const TileKernelSelection& kernels,
                    TileScratch& s) {
  const bool allForward = forwardWins(tileIndex, draws, chunks);
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
      const auto id = std::uint32_t(s.visibleTriangles.size());
      if (kernels.forWidth(t.maxX - t.minX + 1).visibility(t, entry.planes, shade, id, s.tile))
        s.visibleTriangles.push_back(entry);
    }
  }
}

// Every visible triangle's 1/w and attribute planes, rebased to the tile.
void rebaseShadePlanes(const std::vector<Draw>& draws, TileScratch& s) {
  s.shadePlanes.resize(s.visibleTriangles.size() * kShadePlaneStride);
  for (std::size_t i = 0; i < s.visibleTriangles.size(); ++i) {
    const TileTriangle& v = s.visibleTriangles[i];
    const int planeCount = 1 + draws[v.draw].shade.attributes.count;
    float* out = &s.shadePlanes[i * kShadePlaneStride];
    for (int j = 0; j < planeCount; ++j) {
      const Plane q = planeInTile(v.planes[1 + j], *v.triangle, s.tile);
      out[3 * j] = q.dx, out[3 * j + 1] = q.dy, out[3 * j + 2] = q.c;
    }
  }
}

// Shading pass: per draw (triangles are in submission order, so a draw's are
// consecutive) a run of its whole lane groups, shaded in place, and of its
// other visible pixels, packed into lanes; the triangles' planes rebased to
// the tile once.
void shadingPass(const std::vector<Draw>& draws, const TileKernels& kernels, TileScratch& s) {
  const std::size_t triangles = s.visibleTriangles.size();
  if (triangles == 0) return;
  rebaseShadePlanes(draws, s);
  // One draw: the kernel finds its groups itself, at two compares per group.
  if (s.visibleTriangles.front().draw == s.visibleTriangles.back().draw &&
      triangles < kMaxScannedTriangles) {
    ShadeRun run;
    run.scanTile = true;
    run.endTriangle = std::uint32_t(triangles);
    run.planes = s.shadePlanes.data();
    kernels.shade(draws[s.visibleTriangles.front().draw].shade, run, s.tile);
    return;
  }
  s.runOf.resize(triangles);
  std::uint32_t runs = 0;
  for (std::size_t i = 0; i < triangles; ++i) {
    if (i > 0 && s.visibleTriangles[i].draw != s.visibleTriangles[i - 1].draw) ++runs;
    s.runOf[i] = runs;
  }
  ++runs;

  // Each lane group: the run all its pixels belong to, or kMixed.
  constexpr std::uint32_t kMixed = 0xFFFFFFFFu;
  const int lanes = kernels.lanes;
  const int groups = TileBuffers::kPixels / lanes;
  const std::uint32_t* visible = s.tile.visible;
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
    kernels.shade(draws[s.visibleTriangles[firstTriangle].draw].shade, run, s.tile);
  }
}

void renderTile(int tileIndex, const TileGrid& grid, const std::vector<Draw>& draws,
                const std::vector<FrontEndChunk>& chunks, const TileKernelSelection& kernels,
                const glm::vec4& clearColor, float clearDepth, TileScratch& s, Frame& frame,
                TileTimes& times) {
  const double start = stageClockMs();
  TileBuffers& tile = s.tile;
  tile.originX = (tileIndex % grid.tilesX) * kTileSize;
  tile.originY = (tileIndex / grid.tilesX) * kTileSize;
  tile.width = std::min(kTileSize, grid.width - tile.originX);
  tile.height = std::min(kTileSize, grid.height - tile.originY);
  clearTile(tile, clearColor, clearDepth);
  s.visibleTriangles.clear();
  s.forward.clear();
  visibilityPass(tileIndex, draws, chunks, kernels, s);
  const double visible = stageClockMs();
  shadingPass(draws, *kernels.wide, s);
  const double shaded = stageClockMs();
  for (const TileTriangle& t : s.forward)
    kernels.forWidth(t.triangle->maxX - t.triangle->minX + 1)
        .rasterize(*t.triangle, t.planes, draws[t.draw].shade, tile);
  const double rastered = stageClockMs();
  resolveTile(tile, frame);
  times.raster = (visible - start) + (rastered - shaded);
  times.shade = shaded - visible;
  times.resolve = stageClockMs() - rastered;
}

}  // namespace

void renderTiles(const TileGrid& grid, const std::vector<Draw>& draws,
                 const std::vector<FrontEndChunk>& chunks, const TileKernelSelection& kernels,
                 const glm::vec4& clearColor, float clearDepth, const Executor& executor,
                 Frame& frame, std::vector<TileTimes>& times) {
  const std::size_t tiles = std::size_t(grid.tileCount());
  times.assign(tiles, TileTimes{});
  // Heavy tiles first, so the last tasks to finish are short ones: a tile's
  // cost estimated as its binned triangles plus a constant for its pixels
  // (a triangle's visibility and setup cost about what a few shaded pixel
  // groups do). Each tile writes only its own part of the frame, so the
  // order changes no output.
  constexpr std::uint32_t kPixelsCost = 64;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> order(tiles);  // (cost, tile)
  for (std::size_t t = 0; t < tiles; ++t) {
    std::uint32_t cost = kPixelsCost;
    for (const FrontEndChunk& chunk : chunks)
      cost += chunk.bins.tileStart[t + 1] - chunk.bins.tileStart[t];
    order[t] = {cost, std::uint32_t(t)};
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  executor.parallelFor(tiles, 1, [&](std::size_t begin, std::size_t end) {
    // Not value-initialized: every tile clears what it reads.
    const std::unique_ptr<TileScratch> scratch(new TileScratch);
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t t = order[i].second;
      renderTile(int(t), grid, draws, chunks, kernels, clearColor, clearDepth, *scratch, frame,
                 times[t]);
    }
  });
}

}  // namespace quadra
