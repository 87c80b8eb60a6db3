// Ripmap construction (ripmap.h).
#include "texture/ripmap.h"

#include <algorithm>

#include "texture/mip_chain.h"

namespace quadra {

namespace {

int levelsDownTo1(int size) {
  int count = 1;
  while (size > 1 && count < TextureView::kMaxLevels) size /= 2, ++count;
  return count;
}

}  // namespace

Ripmap::Ripmap(const Image& level0, TexelFormat format, const Executor* executor,
               std::optional<float> coverageCutoff)
    : countX(levelsDownTo1(level0.width)), countY(levelsDownTo1(level0.height)) {
  storage.reserve(std::size_t(countX) * std::size_t(countY));
  const double coverage0 = coverageCutoff ? alphaCoverage(level0, *coverageCutoff, executor) : 0.0;
  // Levels are reduced from their neighbours before any alpha scale, so
  // scales do not compound; only the stored copy is scaled.
  const auto store = [&](const Image& level, bool isLevel0) {
    if (!coverageCutoff || isLevel0) {
      storage.emplace_back(level, format);
      return;
    }
    Image scaled = level;
    scaleAlphaToCoverage(scaled, *coverageCutoff, coverage0, executor);
    storage.emplace_back(scaled, format);
  };
  // Only the float level each new one is reduced from is kept: the first of
  // the current row and the previous level in it.
  Image rowStart = level0;
  for (int j = 0; j < countY; ++j) {
    if (j > 0)
      rowStart =
          downsampleBox(rowStart, rowStart.width, std::max(1, rowStart.height / 2), executor);
    store(rowStart, j == 0);
    Image previous = rowStart;
    for (int i = 1; i < countX; ++i) {
      previous =
          downsampleBox(previous, std::max(1, previous.width / 2), previous.height, executor);
      store(previous, false);
    }
  }
  for (const PaddedLevel& level : storage) levels.push_back(level.view());
}

}  // namespace quadra
