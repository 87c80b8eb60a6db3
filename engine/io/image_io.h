// Image files in and out: EXR (linear float, with Z and optionally coverage)
// and PNG (sRGB 8-bit).
// Writers never leave a partial file under the requested name: they write a
// temporary beside it and rename on success.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "io/frame.h"
#include "io/rgb_image.h"
#include "io/tone_map.h"
#include "texture/image.h"

namespace quadra {

class Executor;

// The EXR channel of Frame::coverage; the name the --aov list uses for it.
constexpr const char* kCoverageChannel = "mask";

// How an EXR stores its pixels. Only OpenEXR's lossless compressions, so a
// FLOAT channel reads back bit for bit: NONE, RLE, ZIPS (zlib, one scanline a
// block), ZIP (16 scanlines; the default, at zlib's fastest level: see
// writeExrStream) and PIZ (wavelet + Huffman). halfColour stores R, G, B, A
// as HALF (each float rounded to the nearest half, NaN written as 0); Z, mask and the AOVs stay
// FLOAT, as depth, positions and ids need float's precision and range.
enum class ExrCompression : std::uint8_t { None, Rle, Zips, Zip, Piz };
struct ExrSettings {
  ExrCompression compression = ExrCompression::Zip;
  bool halfColour = false;
};
const char* exrCompressionName(ExrCompression compression);
// Parses none|rle|zips|zip|piz; false when unknown.
bool parseExrCompression(const std::string& name, ExrCompression& out);
// The names parseExrCompression accepts, comma separated, for messages.
std::string exrCompressionNames();

// EXR with FLOAT (or, with halfColour, HALF) channels R, G, B, A
// (premultiplied linear) and FLOAT Z, the coverage as kCoverageChannel and
// the surface AOVs the frame has (FLOAT N.X/Y/Z, P.X/Y/Z, uv.U/V,
// motion.X/Y, lod, anisotropy, albedo.R/G/B, roughness, metallic,
// emission.R/G/B, diffuse.R/G/B, specular.R/G/B; UINT id.primitive, id.node, id.material; a
// PNG has no place for them), and in the header the metadata's camera
// (OpenEXR's worldToCamera and worldToNDC) and strings. Half colour is
// converted on `executor`'s threads when one is given (OpenEXR compresses on
// its own pool). Throws Error("<path>: <problem>") on failure.
void writeExr(const Frame& frame, const std::string& path, const ExrSettings& settings = {},
              const Executor* executor = nullptr);
// PNG, 8-bit sRGB RGBA (colour un-premultiplied, then tone mapped: none
// clamps to [0, 1]; io/tone_map.h), encoded and compressed in bands of rows
// in parallel on `executor` when one is given; the file's bytes are the same
// either way.
void writePng(const Frame& frame, const std::string& path, const Executor* executor = nullptr,
              ToneMap toneMap = ToneMap::None);
// Chooses the writer from the extension (.exr or .png, any case); `exr`
// applies to EXR files only, `pngToneMap` to PNG files only.
void writeFrame(const Frame& frame, const std::string& path, const Executor* executor = nullptr,
                const ExrSettings& exr = {}, ToneMap pngToneMap = ToneMap::None);

// Reads a PNG or JPEG (decoded from sRGB to linear; alpha stays linear) or
// an EXR (already linear; missing channels: RGB 0, A 1) into linear float
// RGBA.
Image readImage(const std::string& path);

// An EXR's R, G, B as linear float (a luminance-only file's Y in all three;
// a missing one of R, G, B is 0; alpha and other channels ignored), for
// panoramas; `admit` sees the data window's size before the pixels are
// allocated. Throws Error("<path>: <problem>"), also for a file without R, G,
// B or Y.
RgbImage readExrRgb(const std::string& path, const AdmitImageSize& admit);
// Writes FLOAT R, G, B (rgb: width x height x 3, row by row from the top),
// ZIP compressed (lossless: the floats read back bit for bit), through a
// temporary file as writeExr does.
void writeExrRgb(const float* rgb, int width, int height, const std::string& path);

// How a PNG's or JPEG's colour channels are decoded: from sRGB (colour
// textures, the default) or as linear codes (glTF's data textures: normal,
// metallic-roughness, occlusion), each 8-bit code c to c * kUnorm8Scale as
// alpha always is.
enum class ImageColour : std::uint8_t { Srgb, Linear };

// Whether the bytes start with the PNG signature.
bool isPng(const std::uint8_t* data, std::size_t size);
// Decodes a PNG held in memory as readImage decodes a file (the same samples,
// the same linear floats); bitsPerChannel, when given, receives the file's
// depth after expansion (8 or 16); the image's memory is mapped on
// `executor`'s threads when one is given. Throws Error("<source>: <problem>").
Image decodePng(const std::uint8_t* data, std::size_t size, const std::string& source,
                int* bitsPerChannel = nullptr, const Executor* executor = nullptr,
                ImageColour colour = ImageColour::Srgb);

// Whether the bytes start with a JPEG start-of-image marker.
bool isJpeg(const std::uint8_t* data, std::size_t size);
// Decodes a baseline or progressive JPEG (greyscale, YCbCr or RGB) held in
// memory with libjpeg-turbo to linear float RGBA (sRGB colour, alpha 1), the
// 8-bit codes converted as decodePng converts them. A damaged or truncated
// stream is an error, not a partly grey image. Throws
// Error("<source>: <problem>").
Image decodeJpeg(const std::uint8_t* data, std::size_t size, const std::string& source,
                 const Executor* executor = nullptr, ImageColour colour = ImageColour::Srgb);

}  // namespace quadra
