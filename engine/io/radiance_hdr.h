// Radiance .hdr (RGBE) images, read from memory: the header, the resolution
// line, and flat, old-style run-length and new-style (per-channel)
// run-length encoded scanlines, every length and offset checked against the
// bytes there are. The decisions (EXPOSURE, orientations, the RGBE to float
// convention) are docs/lighting.md "Environments".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "io/rgb_image.h"

namespace quadra {

// Whether the bytes start with a Radiance header's "#?".
bool isRadianceHdr(const std::uint8_t* data, std::size_t size);

// One RGBE texel's channel: (m + 0.5) 2^(e - 136), 0 when e is 0; exact in
// float for every m and e (Greg Ward's colr_color in Radiance's color.c).
float rgbeChannel(std::uint8_t mantissa, std::uint8_t exponent);

// Decodes a whole .hdr file's bytes; `admit` sees the size before the pixels
// are allocated. Throws Error("<source>: <problem>") for anything malformed
// or truncated, a format other than 32-bit_rle_rgbe, or a transposed
// orientation (+X/-X first).
RgbImage decodeRadianceHdr(const std::uint8_t* data, std::size_t size, const std::string& source,
                           const AdmitImageSize& admit);

}  // namespace quadra
