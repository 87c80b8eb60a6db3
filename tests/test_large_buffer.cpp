// resizeLarge (core/large_buffer.h): mapping the memory ahead must change
// only the speed, never what the vector holds.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/large_buffer.h"
#include "core/parallel.h"

namespace quadra {
namespace {

TEST(LargeBuffer, GrowingKeepsTheOldElementsAndFillsTheNewOnes) {
  const Executor two(2);
  for (const Executor* executor : {static_cast<const Executor*>(nullptr), &two}) {
    std::vector<std::uint32_t> v = {7, 8, 9};
    const std::size_t count = (std::size_t(5) << 20) + 3;  // 20 MiB: several mapped pieces
    resizeLarge(v, count, std::uint32_t(0xABCD), executor);
    ASSERT_EQ(v.size(), count);
    EXPECT_EQ(v[0], 7u);
    EXPECT_EQ(v[1], 8u);
    EXPECT_EQ(v[2], 9u);
    std::size_t wrong = 0;
    for (std::size_t i = 3; i < count; ++i) wrong += v[i] != 0xABCDu;
    EXPECT_EQ(wrong, 0u);
  }
}

TEST(LargeBuffer, ShrinkingAndSmallSizesBehaveAsResize) {
  std::vector<float> v(100, 1.0f);
  resizeLarge(v, 10, 2.0f);
  EXPECT_EQ(v, std::vector<float>(10, 1.0f));
  resizeLarge(v, 12, 2.0f);
  EXPECT_EQ(v.back(), 2.0f);
  EXPECT_EQ(v.size(), 12u);
  resizeLarge(v, 0);
  EXPECT_TRUE(v.empty());
}

}  // namespace
}  // namespace quadra
