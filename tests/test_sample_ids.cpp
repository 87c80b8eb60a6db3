// simd/sample_ids.h against the scalar comparisons it stands for: every
// pattern of four sample ids (which share a triangle, which hold none), and
// every set of differing pixels in a step of four.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "simd/sample_ids.h"

namespace quadra {
namespace {

constexpr std::uint32_t kNone = 0xFFFFFFFFu;

TEST(SampleIds, FourIdsSharingIsEachPairsEqualityAndEachEmptySample) {
  // Ids drawn from three triangles and none: every partition of four
  // samples, with and without empty ones, and ids whose low or high bits
  // alone differ.
  const std::uint32_t values[] = {0u, 1u, 0x80000000u, kNone};
  const int pairs[6][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}, {1, 3}};
  int checked = 0;
  for (int pattern = 0; pattern < 256; ++pattern) {
    std::uint32_t ids[4];
    for (int k = 0; k < 4; ++k) ids[k] = values[pattern >> (2 * k) & 3];
    std::uint32_t expected = 0;
    for (int bit = 0; bit < 6; ++bit)
      expected |= std::uint32_t(ids[pairs[bit][0]] == ids[pairs[bit][1]]) << bit;
    for (int k = 0; k < 4; ++k) expected |= std::uint32_t(ids[k] == kNone) << (6 + k);
    EXPECT_EQ(simd::fourIdsSharing(ids[0], ids[1], ids[2], ids[3], kNone), expected)
        << ids[0] << " " << ids[1] << " " << ids[2] << " " << ids[3];
    ++checked;
  }
  EXPECT_EQ(checked, 256);
}

TEST(SampleIds, AppendNonZeroIndicesKeepsTheNonZeroOnesInOrder) {
  for (int mask = 0; mask < 16; ++mask) {
    std::uint32_t values[4];
    for (int j = 0; j < 4; ++j) values[j] = (mask >> j & 1) ? (j == 2 ? 0x80000000u : 7u) : 0u;
    const std::uint16_t first = 4092;            // a tile's last step
    std::vector<std::uint16_t> list = {11, 22};  // kept ahead of the appended ones
    list.resize(2 + 4, 0xBEEF);                  // room for four
    const std::size_t count = simd::appendNonZeroIndices(values, first, list.data(), 2);
    std::vector<std::uint16_t> expected = {11, 22};
    for (int j = 0; j < 4; ++j)
      if (values[j] != 0) expected.push_back(std::uint16_t(first + j));
    ASSERT_EQ(count, expected.size()) << mask;
    list.resize(count);
    EXPECT_EQ(list, expected) << mask;
  }
}

}  // namespace
}  // namespace quadra
