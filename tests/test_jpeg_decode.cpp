// JPEG decoding (io/image_io.h decodeJpeg, readImage): images encoded here with
// libjpeg's own compressor, decoded by quadra, checked against the source
// pixels they were encoded from (JPEG at quality 100 without chroma
// subsampling stays within a few codes), against libjpeg's 8-bit output
// converted by the sRGB formula in double, and for the errors a damaged
// stream must give.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>

#include "core/error.h"
#include "io/image_io.h"
#include "texture/image.h"

namespace quadra {
namespace {

double srgbDecodeReference(double e) {
  return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

struct Source {
  int width = 0, height = 0, components = 3;
  std::vector<std::uint8_t> samples;  // row-major, `components` per pixel
};

// A gradient with a few sharp steps: smooth parts JPEG keeps to a code or
// two, edges where a wrong colour conversion or channel order would show.
Source pattern(int width, int height, int components) {
  Source s{width, height, components, {}};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < components; ++c) {
        const int value = c == 0                       ? 40 + 3 * x
                          : c == 1                     ? 200 - 2 * y
                          : (x / 16 + y / 16) % 2 == 0 ? 90
                                                       : 150;
        s.samples.push_back(std::uint8_t(value));
      }
  return s;
}

std::vector<std::uint8_t> encode(const Source& s, J_COLOR_SPACE space, bool progressive) {
  jpeg_compress_struct info{};
  jpeg_error_mgr errors{};
  info.err = jpeg_std_error(&errors);
  jpeg_create_compress(&info);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&info, &buffer, &size);
  info.image_width = JDIMENSION(s.width);
  info.image_height = JDIMENSION(s.height);
  info.input_components = s.components;
  info.in_color_space = space;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, 100, TRUE);
  for (int c = 0; c < info.num_components; ++c)
    info.comp_info[c].h_samp_factor = info.comp_info[c].v_samp_factor = 1;  // 4:4:4
  if (progressive) jpeg_simple_progression(&info);
  jpeg_start_compress(&info, TRUE);
  while (info.next_scanline < info.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(
        &s.samples[std::size_t(info.next_scanline) * std::size_t(s.width * s.components)]);
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  std::vector<std::uint8_t> bytes(buffer, buffer + size);
  std::free(buffer);
  return bytes;
}

// libjpeg's own 8-bit RGB output for the bytes.
std::vector<std::uint8_t> referenceCodes(const std::vector<std::uint8_t>& bytes) {
  jpeg_decompress_struct info{};
  jpeg_error_mgr errors{};
  info.err = jpeg_std_error(&errors);
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  info.out_color_space = JCS_RGB;
  jpeg_start_decompress(&info);
  std::vector<std::uint8_t> codes(std::size_t(info.output_width) * info.output_height * 3);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = &codes[std::size_t(info.output_scanline) * info.output_width * 3];
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return codes;
}

Image decode(const std::vector<std::uint8_t>& bytes, const std::string& source = "test.jpg") {
  return decodeJpeg(bytes.data(), bytes.size(), source);
}

void expectDecodesSource(const Source& s, const std::vector<std::uint8_t>& bytes) {
  const Image image = decode(bytes);
  ASSERT_EQ(image.width, s.width);
  ASSERT_EQ(image.height, s.height);
  const std::vector<std::uint8_t> codes = referenceCodes(bytes);
  int worst = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const float* texel = image.texel(x, y);
      const std::size_t pixel = std::size_t(y) * std::size_t(s.width) + std::size_t(x);
      for (int c = 0; c < 3; ++c) {
        const std::uint8_t code = codes[pixel * 3 + std::size_t(c)];
        // The conversion: the correctly rounded float of the formula.
        ASSERT_EQ(texel[c], float(srgbDecodeReference(code / 255.0)))
            << "(" << x << "," << y << ") channel " << c;
        const int source =
            s.samples[pixel * std::size_t(s.components) + std::size_t(s.components == 1 ? 0 : c)];
        worst = std::max(worst, std::abs(int(code) - source));
      }
      ASSERT_EQ(texel[3], 1.0f);
    }
  EXPECT_LE(worst, 3) << "decoded codes stray from the encoded source";
}

TEST(JpegDecode, BaselineRgbDecodesToItsSource) {
  const Source s = pattern(67, 45, 3);  // not a multiple of the 8x8 blocks
  expectDecodesSource(s, encode(s, JCS_RGB, false));
}

TEST(JpegDecode, ProgressiveRgbDecodesToItsSource) {
  const Source s = pattern(64, 40, 3);
  expectDecodesSource(s, encode(s, JCS_RGB, true));
}

TEST(JpegDecode, GreyscaleBecomesGreyRgb) {
  const Source s = pattern(33, 20, 1);
  const std::vector<std::uint8_t> bytes = encode(s, JCS_GRAYSCALE, false);
  expectDecodesSource(s, bytes);
  const Image image = decode(bytes);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      EXPECT_EQ(image.texel(x, y)[0], image.texel(x, y)[1]);
      EXPECT_EQ(image.texel(x, y)[0], image.texel(x, y)[2]);
    }
}

void expectError(const std::vector<std::uint8_t>& bytes, const std::string& part) {
  try {
    decode(bytes, "bad.jpg");
    ADD_FAILURE() << "no error; expected one containing '" << part << "'";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("bad.jpg"), std::string::npos) << message;
    EXPECT_NE(message.find(part), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// Cut anywhere, including inside the entropy-coded data where libjpeg would
// only warn and fill the rest with grey: an error, not a partial image.
TEST(JpegDecode, TruncatedOrDamagedStreamsAreErrors) {
  const Source s = pattern(64, 64, 3);
  for (const bool progressive : {false, true}) {
    const std::vector<std::uint8_t> bytes = encode(s, JCS_RGB, progressive);
    for (const std::size_t keep :
         {std::size_t(3), bytes.size() / 10, bytes.size() / 2, bytes.size() - 2}) {
      SCOPED_TRACE(keep);
      expectError(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + long(keep)),
                  "invalid or truncated JPEG");
    }
  }
  expectError({0x89, 'P', 'N', 'G'}, "not a JPEG image");
}

TEST(JpegDecode, CmykIsRefusedWithAClearError) {
  Source s = pattern(16, 16, 3);
  s.components = 4;
  s.samples.clear();
  for (int i = 0; i < 16 * 16; ++i) s.samples.insert(s.samples.end(), {10, 20, 30, 40});
  expectError(encode(s, JCS_CMYK, false), "CMYK");
}

// readImage takes JPEG files too (quadra sample --texture, report textures):
// the same decoder, the same floats; a cut file names its path.
TEST(JpegDecode, ReadImageReadsJpegFiles) {
  const Source s = pattern(40, 24, 3);
  const std::vector<std::uint8_t> bytes = encode(s, JCS_RGB, false);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("quadra_jpeg_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "texture.jpg").string();
  const auto write = [&](std::size_t count) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(count));
  };
  write(bytes.size());
  const Image fromFile = readImage(path), fromMemory = decode(bytes);
  ASSERT_EQ(fromFile.width, fromMemory.width);
  ASSERT_EQ(fromFile.height, fromMemory.height);
  EXPECT_EQ(fromFile.rgba, fromMemory.rgba);
  write(bytes.size() / 2);
  try {
    readImage(path);
    ADD_FAILURE() << "a truncated JPEG file was read";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("invalid or truncated JPEG"), std::string::npos) << message;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace quadra
