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

Ripmap::Ripmap(const Image& level0, TexelFormat format, const Executor* executor)
    : countX(levelsDownTo1(level0.width)), countY(levelsDownTo1(level0.height)) {
  storage.reserve(std::size_t(countX) * std::size_t(countY));
  // Only the float level each new one is reduced from is kept: the first of
  // the current row and the previous level in it.
  Image rowStart = level0;
  for (int j = 0; j < countY; ++j) {
    if (j > 0)
      rowStart =
          downsampleBox(rowStart, rowStart.width, std::max(1, rowStart.height / 2), executor);
    storage.emplace_back(rowStart, format);
    Image previous = rowStart;
    for (int i = 1; i < countX; ++i) {
      previous =
          downsampleBox(previous, std::max(1, previous.width / 2), previous.height, executor);
      storage.emplace_back(previous, format);
    }
  }
  for (const PaddedLevel& level : storage) levels.push_back(level.view());
}

}  // namespace quadra
