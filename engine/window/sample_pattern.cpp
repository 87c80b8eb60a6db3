// The multisample patterns (values: sample_pattern.h).
#include "window/sample_pattern.h"

#include <algorithm>
#include <cstdlib>

#include "core/error.h"
#include "window/window_space.h"

namespace quadra {

namespace {

// The pattern with the offsets' other forms (SamplePattern's members after them).
constexpr SamplePattern withDerivedOffsets(SamplePattern pattern) {
  for (int k = 0; k < pattern.count; ++k) {
    for (int j = 0; j < 4; ++j) {
      pattern.quadLaneX[4 * k + j] = pattern.offsets[k].x;
      pattern.quadLaneY[4 * k + j] = pattern.offsets[k].y;
    }
    pattern.pixelOffsetX[k] = double(pattern.offsets[k].x) / kSampleUnitsPerPixel;
    pattern.pixelOffsetY[k] = double(pattern.offsets[k].y) / kSampleUnitsPerPixel;
  }
  return pattern;
}

constexpr SamplePattern kOne = withDerivedOffsets({1, {{0, 0}}});
constexpr SamplePattern kTwo = withDerivedOffsets({2, {{4, 4}, {-4, -4}}});
constexpr SamplePattern kFour = withDerivedOffsets({4, {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}}});
constexpr SamplePattern kEight = withDerivedOffsets(
    {8, {{1, -3}, {-1, 3}, {5, 1}, {-3, -5}, {-5, 5}, {-7, -1}, {3, 7}, {7, -7}}});
constexpr SamplePattern kSixteen = withDerivedOffsets({16,
                                                       {{1, 1},
                                                        {-1, -3},
                                                        {-3, 2},
                                                        {4, -1},
                                                        {-5, -2},
                                                        {2, 5},
                                                        {5, 3},
                                                        {3, -5},
                                                        {-2, 6},
                                                        {0, -7},
                                                        {-4, -6},
                                                        {-6, 4},
                                                        {-8, 0},
                                                        {7, -4},
                                                        {6, 7},
                                                        {-7, -8}}});

// Cell centres in 1/16 pixel, sample by sample (sample_pattern.h says how
// each was chosen; tests/test_multisampling.cpp checks one sample a cell).
constexpr SampleOffset kFourCells[4] = {{-4, -4}, {4, -4}, {-4, 4}, {4, 4}};
constexpr SampleOffset kSixteenCells[16] = {{2, 2},  {-2, -2}, {-2, 2}, {2, -2}, {-6, -2}, {2, 6},
                                            {6, 2},  {6, -6},  {-2, 6}, {2, -6}, {-2, -6}, {-6, 6},
                                            {-6, 2}, {6, -2},  {6, 6},  {-6, -6}};

}  // namespace

SampleOffset shadingOffset(const SamplePattern& pattern, int k) {
  QUADRA_CHECK(k >= 0 && k < pattern.count);
  if (pattern.count == 4) return kFourCells[k];
  if (pattern.count == 16) return kSixteenCells[k];
  return pattern.offsets[k];
}

int SamplePattern::reachSubpixels() const {
  int reach = 0;
  for (int s = 0; s < count; ++s)
    reach = std::max({reach, std::abs(int(offsets[s].x)), std::abs(int(offsets[s].y))});
  return reach * (kSubpixelScale / kSampleUnitsPerPixel);
}

const SamplePattern& samplePattern(int count) {
  switch (count) {
    case 1:
      return kOne;
    case 2:
      return kTwo;
    case 4:
      return kFour;
    case 8:
      return kEight;
    case 16:
      return kSixteen;
    default:
      break;
  }
  QUADRA_CHECK(isSampleCount(count));
  return kOne;
}

}  // namespace quadra
