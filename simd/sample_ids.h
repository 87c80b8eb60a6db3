// The multisampled shading pass's comparisons of sample ids, in the SSE2
// baseline (tile/tile_stage.cpp): which of a pixel's four samples hold the
// same triangle (pixelJobsKey: three compares where the scalar comparisons
// of each pair took ~45 instructions a pixel), and the list of the pixels
// whose samples differ (findMixedPixels: four pixels a step, where a step a
// pixel chained each list position on the last).
#pragma once

#include <emmintrin.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

// Always inlined, as simd/transpose.h says why.
#define QUADRA_SAMPLE_IDS_INLINE inline __attribute__((always_inline))

namespace quadra::simd {

// Bits 0-3: sample j's id equals sample (j + 1) mod 4's; bits 4-5: sample
// j's equals sample j + 2's (j = 0, 1); bits 6-9: sample j's is `none`.
QUADRA_SAMPLE_IDS_INLINE std::uint32_t fourIdsSharing(std::uint32_t id0, std::uint32_t id1,
                                                      std::uint32_t id2, std::uint32_t id3,
                                                      std::uint32_t none) {
  const __m128i ids = _mm_setr_epi32(int(id0), int(id1), int(id2), int(id3));
  const __m128i next = _mm_shuffle_epi32(ids, _MM_SHUFFLE(0, 3, 2, 1));
  const __m128i across = _mm_shuffle_epi32(ids, _MM_SHUFFLE(1, 0, 3, 2));
  const auto bits = [](__m128i equal) { return _mm_movemask_ps(_mm_castsi128_ps(equal)); };
  const int adjacent = bits(_mm_cmpeq_epi32(ids, next));
  const int opposite = bits(_mm_cmpeq_epi32(ids, across)) & 3;
  const int empty = bits(_mm_cmpeq_epi32(ids, _mm_set1_epi32(int(none))));
  return std::uint32_t(adjacent | opposite << 4 | empty << 6);
}

// Per 4-bit mask, its set bits' positions as 16-bit lanes, lowest first.
inline constexpr std::array<std::uint64_t, 16> kSetBitPositions = [] {
  std::array<std::uint64_t, 16> positions{};
  for (int mask = 0; mask < 16; ++mask) {
    int lane = 0;
    for (int bit = 0; bit < 4; ++bit)
      if (mask >> bit & 1) positions[mask] |= std::uint64_t(bit) << (16 * lane++);
  }
  return positions;
}();

// Appends to list[count...] the indices first + j (j < 4) where values[j] is
// not zero, and returns the new count. Writes four entries whatever it
// keeps: the list needs room for three past its end.
QUADRA_SAMPLE_IDS_INLINE std::size_t appendNonZeroIndices(const std::uint32_t* values,
                                                          std::uint16_t first, std::uint16_t* list,
                                                          std::size_t count) {
  const __m128i four = _mm_loadu_si128(reinterpret_cast<const __m128i*>(values));
  const int zero = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(four, _mm_setzero_si128())));
  const int kept = ~zero & 15;
  const std::uint64_t indices = kSetBitPositions[std::size_t(kept)] + first * 0x0001000100010001ull;
  std::memcpy(list + count, &indices, sizeof(indices));
  return count + std::size_t((0x4332322132212110ull >> (4 * kept)) & 15);  // kept's bit count
}

}  // namespace quadra::simd
