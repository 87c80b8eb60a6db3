// Tests for the sRGB transfer functions and image files in and out. Every
// expected value comes from an independent source: the IEC 61966-2-1 formula
// in double, or the files read and written with OpenEXR and libpng directly.
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "io/image_io.h"
#include "io/srgb8.h"
#include "png_reader.h"
#include "texture/image.h"
#include "texture/texel_format.h"

namespace quadra {
namespace {

namespace fs = std::filesystem;

double srgbDecodeReference(double e) {
  return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

double srgbEncodeReference(double l) {
  l = std::min(1.0, std::max(0.0, l));
  return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
}

// ---- sRGB transfer functions ------------------------------------------------

// float pow and the float constants put the result within a few float ulps of
// the double formula; 1e-6 relative is about 8 ulps.
TEST(Srgb, DecodeMatchesFormula) {
  for (int i = 0; i <= 200000; ++i) {
    const float e = float(i) / 200000.0f;
    const double expected = srgbDecodeReference(double(e));
    EXPECT_NEAR(srgbToLinear(e), expected, 1e-6 * expected + 1e-12) << "e=" << e;
  }
  EXPECT_EQ(srgbToLinear(std::numeric_limits<float>::quiet_NaN()), 0.0f);
}

TEST(Srgb, EncodeMatchesFormulaAndClamps) {
  for (int i = 0; i <= 200000; ++i) {
    // Quadratic spacing puts many points in the linear toe and around its end.
    const float l = float(i) * float(i) / (200000.0f * 200000.0f);
    const double expected = srgbEncodeReference(double(l));
    EXPECT_NEAR(linearToSrgb(l), expected, 1e-6 * expected + 1e-12) << "l=" << l;
  }
  EXPECT_EQ(linearToSrgb(-0.5f), 0.0f);
  EXPECT_EQ(linearToSrgb(3.0f), 1.0f);
  EXPECT_EQ(linearToSrgb(std::numeric_limits<float>::infinity()), 1.0f);
  EXPECT_EQ(linearToSrgb(-std::numeric_limits<float>::infinity()), 0.0f);
  EXPECT_EQ(linearToSrgb(std::numeric_limits<float>::quiet_NaN()), 0.0f);
}

TEST(Srgb, EightBitTableIsCorrectlyRoundedFormula) {
  for (int code = 0; code < 256; ++code) {
    const float expected = float(srgbDecodeReference(code / 255.0));
    EXPECT_EQ(srgb8ToLinear(std::uint8_t(code)), expected) << "code=" << code;
  }
}

TEST(Srgb, LinearRoundTrip) {
  for (int i = 0; i <= 100000; ++i) {
    const float l = float(i) / 100000.0f;
    // Encode then decode amplifies the relative error by at most the curve's
    // log-slope, 2.4: a few float ulps end to end.
    EXPECT_NEAR(srgbToLinear(linearToSrgb(l)), l, 2e-6 * l + 1e-9) << "l=" << l;
  }
}

// The PNG writer's pow-free encoder returns the definition's code for every
// float: around each step (where a wrong step would show first), over a
// sweep of the range, and for the special values. The steps are also checked
// against the formula in double, so a wrong definition cannot pass either.
TEST(Srgb, EightBitEncoderMatchesItsDefinitionOnEveryFloat) {
  const Srgb8Encoder encoder;
  const auto next = [](float f, int ulps) {
    return std::bit_cast<float>(std::bit_cast<std::uint32_t>(f) + std::uint32_t(ulps));
  };
  for (int code = 1; code < 256; ++code) {
    const float step = encoder.step(code);
    for (int ulps = -2; ulps <= 2; ++ulps) {
      const float value = next(step, ulps);
      EXPECT_EQ(encoder(value), srgb8Code(value)) << "value " << value;
    }
    EXPECT_EQ(srgb8Code(step), code);
    EXPECT_EQ(srgb8Code(next(step, -1)), code - 1);
    // Where the exact curve crosses code - 1/2, to float rounding of the curve.
    const double exact = srgbEncodeReference(double(step));
    EXPECT_NEAR(exact * 255.0, code - 0.5, 1e-3) << "code " << code;
  }
  // Every 61st float from 0 to 2 (17 million values).
  for (std::uint32_t bits = 0; bits <= std::bit_cast<std::uint32_t>(2.0f); bits += 61) {
    const float value = std::bit_cast<float>(bits);
    ASSERT_EQ(encoder(value), srgb8Code(value)) << "value " << value;
  }
  for (float special :
       {0.0f, -0.0f, -1.0f, 1.0f, 1e30f, std::numeric_limits<float>::infinity(),
        -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
        std::numeric_limits<float>::denorm_min()})
    EXPECT_EQ(encoder(special), srgb8Code(special)) << "value " << special;
}

// ---- shared fixtures --------------------------------------------------------

class ImageFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("quadra_io_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::size_t entriesInDir() const {
    return std::size_t(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }

  fs::path dir_;
};

Frame randomFrame(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> colour(-0.25f, 4.0f);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Frame frame;
  frame.width = w;
  frame.height = h;
  frame.rgba.resize(std::size_t(w) * h * 4);
  frame.depth.resize(std::size_t(w) * h);
  for (float& v : frame.rgba) v = colour(rng);
  for (float& z : frame.depth) z = unit(rng);
  return frame;
}

// The error contract: one line, starting with the path.
void expectErrorNaming(const std::function<void()>& action, const std::string& path,
                       const std::string& problemPart = "") {
  try {
    action();
    ADD_FAILURE() << "no Error thrown for " << path;
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(problemPart), std::string::npos) << message;
  }
}

std::uint32_t floatBits(float f) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof(bits));
  return bits;
}

// ---- EXR --------------------------------------------------------------------

struct ExrPlanes {
  int width = 0;
  int height = 0;
  std::vector<std::string> channelNames;
  std::vector<std::vector<float>> planes;  // R, G, B, A, Z
};

ExrPlanes readExrDirectly(const std::string& path) {
  Imf::InputFile in(path.c_str());
  ExrPlanes out;
  const Imath::Box2i window = in.header().dataWindow();
  EXPECT_EQ(window.min.x, 0);
  EXPECT_EQ(window.min.y, 0);
  out.width = window.max.x + 1;
  out.height = window.max.y + 1;
  for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) {
    out.channelNames.push_back(it.name());
    EXPECT_EQ(it.channel().type, Imf::FLOAT) << it.name();
  }
  Imf::FrameBuffer buffer;
  out.planes.assign(5, std::vector<float>(std::size_t(out.width) * out.height));
  const char* names[5] = {"R", "G", "B", "A", "Z"};
  for (int c = 0; c < 5; ++c) {
    buffer.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(out.planes[c].data()),
                                       sizeof(float), sizeof(float) * std::size_t(out.width)));
  }
  in.setFrameBuffer(buffer);
  in.readPixels(0, out.height - 1);
  return out;
}

// The coverage goes out as one more FLOAT channel, "mask", bit for bit.
TEST_F(ImageFiles, ExrRoundTripKeepsTheCoverageAsMask) {
  Frame frame = randomFrame(37, 23, 2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  frame.coverage.resize(frame.depth.size());
  for (float& v : frame.coverage) v = unit(rng);
  frame.coverage[0] = 0.0f, frame.coverage[1] = 1.0f;
  const std::string path = file("mask.exr");
  writeExr(frame, path);
  Imf::InputFile in(path.c_str());
  std::vector<std::string> names;
  for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
    names.push_back(it.name());
  EXPECT_EQ(names, (std::vector<std::string>{"A", "B", "G", "R", "Z", "mask"}));
  std::vector<float> mask(frame.coverage.size(), -1.0f);
  Imf::FrameBuffer buffer;
  buffer.insert("mask", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(mask.data()), sizeof(float),
                                   sizeof(float) * std::size_t(frame.width)));
  in.setFrameBuffer(buffer);
  in.readPixels(0, frame.height - 1);
  for (std::size_t i = 0; i < mask.size(); ++i)
    ASSERT_EQ(floatBits(mask[i]), floatBits(frame.coverage[i])) << i;
}

TEST_F(ImageFiles, ExrRoundTripIsBitExactIncludingDepth) {
  Frame frame = randomFrame(37, 23, 1);
  frame.rgba[5] = 1e-40f;  // a denormal must survive too
  frame.rgba[6] = -0.0f;
  frame.depth[3] = 1.0f;
  const std::string path = file("frame.exr");
  writeExr(frame, path);
  const ExrPlanes exr = readExrDirectly(path);
  ASSERT_EQ(exr.width, 37);
  ASSERT_EQ(exr.height, 23);
  EXPECT_EQ(exr.channelNames, (std::vector<std::string>{"A", "B", "G", "R", "Z"}));
  for (std::size_t i = 0; i < frame.depth.size(); ++i) {
    for (int c = 0; c < 4; ++c) {
      ASSERT_EQ(floatBits(exr.planes[c][i]), floatBits(frame.rgba[i * 4 + c])) << i << "," << c;
    }
    ASSERT_EQ(floatBits(exr.planes[4][i]), floatBits(frame.depth[i])) << i;
  }
  EXPECT_EQ(entriesInDir(), 1u);  // no temporary left behind
}

// Every compression --exr-compression offers is lossless: FLOAT channels
// read back bit for bit, and HALF colour as each float rounded to the
// nearest half by Imath (out of half's range: infinity), Z and mask FLOAT
// either way; and the file names the compression asked for.
TEST_F(ImageFiles, ExrCompressionsRoundTripExactly) {
  Frame frame = randomFrame(61, 37, 4);
  // Runs and repeated rows too, which RLE and the predictors act on.
  std::fill(frame.rgba.begin(), frame.rgba.begin() + std::ptrdiff_t(frame.rgba.size() / 3), 0.5f);
  frame.rgba[5] = 1e-40f, frame.rgba[6] = -0.0f, frame.rgba[7] = 70000.0f, frame.rgba[8] = 3e-6f;
  frame.coverage.assign(frame.depth.size(), 0.25f);
  frame.coverage[3] = 1.0f / 3.0f;
  const std::pair<ExrCompression, Imf::Compression> compressions[] = {
      {ExrCompression::None, Imf::NO_COMPRESSION},
      {ExrCompression::Rle, Imf::RLE_COMPRESSION},
      {ExrCompression::Zips, Imf::ZIPS_COMPRESSION},
      {ExrCompression::Zip, Imf::ZIP_COMPRESSION},
      {ExrCompression::Piz, Imf::PIZ_COMPRESSION}};
  EXPECT_EQ(exrCompressionNames(), "none, rle, zips, zip, piz");
  for (const auto& [compression, expected] : compressions)
    for (const bool half : {false, true}) {
      SCOPED_TRACE(std::string(exrCompressionName(compression)) + (half ? " half" : " float"));
      ExrCompression parsed = ExrCompression::Zip;
      ASSERT_TRUE(parseExrCompression(exrCompressionName(compression), parsed));
      EXPECT_EQ(parsed, compression);
      const std::string path = file("compressed.exr");
      writeExr(frame, path, ExrSettings{compression, half});
      Imf::InputFile in(path.c_str());
      EXPECT_EQ(in.header().compression(), expected);
      const char* names[6] = {"R", "G", "B", "A", "Z", "mask"};
      std::vector<std::vector<float>> planes(6, std::vector<float>(frame.depth.size()));
      Imf::FrameBuffer buffer;
      for (int c = 0; c < 6; ++c) {
        const Imf::Channel* channel = in.header().channels().findChannel(names[c]);
        ASSERT_NE(channel, nullptr) << names[c];
        EXPECT_EQ(channel->type, half && c < 4 ? Imf::HALF : Imf::FLOAT) << names[c];
        buffer.insert(names[c],
                      Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(planes[c].data()),
                                 sizeof(float), sizeof(float) * std::size_t(frame.width)));
      }
      in.setFrameBuffer(buffer);
      in.readPixels(0, frame.height - 1);
      for (std::size_t i = 0; i < frame.depth.size(); ++i) {
        for (int c = 0; c < 4; ++c) {
          const float written = frame.rgba[i * 4 + std::size_t(c)];
          const float expectedValue = half ? float(Imath::half(written)) : written;
          ASSERT_EQ(floatBits(planes[c][i]), floatBits(expectedValue)) << i << "," << c;
        }
        ASSERT_EQ(floatBits(planes[4][i]), floatBits(frame.depth[i])) << i;
        ASSERT_EQ(floatBits(planes[5][i]), floatBits(frame.coverage[i])) << i;
      }
    }
  ExrCompression unchanged = ExrCompression::Piz;
  EXPECT_FALSE(parseExrCompression("dwaa", unchanged));
  EXPECT_FALSE(parseExrCompression("ZIP", unchanged));
  EXPECT_EQ(unchanged, ExrCompression::Piz);
}

TEST_F(ImageFiles, ReadImageReturnsWrittenExrColours) {
  const Frame frame = randomFrame(19, 31, 2);
  const std::string path = file("colours.EXR");
  writeFrame(frame, path);  // upper-case extension still selects EXR
  const Image image = readImage(path);
  ASSERT_EQ(image.width, 19);
  ASSERT_EQ(image.height, 31);
  ASSERT_EQ(image.rgba.size(), frame.rgba.size());
  for (std::size_t i = 0; i < frame.rgba.size(); ++i) {
    ASSERT_EQ(floatBits(image.rgba[i]), floatBits(frame.rgba[i])) << i;
  }
}

// A file written with the OpenEXR API: offset data window, a subset of channels.
void writeSparseExr(const std::string& path, const Imath::Box2i& window,
                    const std::vector<std::pair<std::string, Imf::PixelType>>& channels,
                    const std::vector<std::vector<float>>& values) {
  Imf::Header header(Imath::Box2i(Imath::V2i(-10, -10), Imath::V2i(40, 40)), window);
  for (const auto& [name, type] : channels) header.channels().insert(name, Imf::Channel(type));
  const int width = window.max.x - window.min.x + 1;
  const int height = window.max.y - window.min.y + 1;
  std::vector<std::vector<half>> halves(values.size());
  Imf::FrameBuffer buffer;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    if (channels[c].second == Imf::HALF) {
      halves[c].assign(values[c].begin(), values[c].end());
      buffer.insert(channels[c].first, Imf::Slice::Make(Imf::HALF, halves[c].data(), window));
    } else {
      buffer.insert(channels[c].first, Imf::Slice::Make(Imf::FLOAT, values[c].data(), window));
    }
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(buffer);
  out.writePixels(height);
  (void)width;
}

TEST_F(ImageFiles, ReadImageRespectsDataWindowAndFillsMissingChannels) {
  const Imath::Box2i window(Imath::V2i(5, -3), Imath::V2i(12, 4));  // 8 x 8
  std::vector<float> green(64), blue(64);
  for (int i = 0; i < 64; ++i) {
    green[std::size_t(i)] = float(i) * 0.25f;  // exact in half as well
    blue[std::size_t(i)] = -float(i);
  }
  const std::string path = file("sparse.exr");
  writeSparseExr(path, window, {{"G", Imf::FLOAT}, {"B", Imf::HALF}}, {green, blue});
  const Image image = readImage(path);
  ASSERT_EQ(image.width, 8);
  ASSERT_EQ(image.height, 8);
  for (int i = 0; i < 64; ++i) {
    const float* t = &image.rgba[std::size_t(i) * 4];
    EXPECT_EQ(t[0], 0.0f) << i;
    EXPECT_EQ(t[1], green[std::size_t(i)]) << i;
    EXPECT_EQ(t[2], blue[std::size_t(i)]) << i;
    EXPECT_EQ(t[3], 1.0f) << i;
  }
}

TEST_F(ImageFiles, ReadImageTreatsLuminanceOnlyExrAsGrey) {
  const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(3, 1));
  const std::vector<float> y = {0.f, 0.5f, 1.f, 2.f, 3.f, 4.f, 5.f, 6.f};
  const std::vector<float> a = {1.f, 0.f, 0.5f, 1.f, 1.f, 1.f, 0.25f, 1.f};
  const std::string path = file("grey.exr");
  writeSparseExr(path, window, {{"Y", Imf::FLOAT}, {"A", Imf::FLOAT}}, {y, a});
  const Image image = readImage(path);
  ASSERT_EQ(image.width, 4);
  ASSERT_EQ(image.height, 2);
  for (std::size_t i = 0; i < y.size(); ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(image.rgba[i * 4 + std::size_t(c)], y[i]) << i;
    EXPECT_EQ(image.rgba[i * 4 + 3], a[i]) << i;
  }
}

// ---- PNG out ----------------------------------------------------------------

// Straight colours (some above 1, some negative) with alphas that include 0
// and 1, stored premultiplied as the renderer does.
Frame premultipliedFrame(int w, int h, unsigned seed) {
  Frame frame = randomFrame(w, h, seed);
  std::mt19937 rng(seed + 100);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (std::size_t i = 0; i < frame.rgba.size(); i += 4) {
    float alpha = unit(rng);
    if (i % 28 == 0) alpha = 0.0f;
    if (i % 36 == 0) alpha = 1.0f;
    for (int c = 0; c < 3; ++c) frame.rgba[i + c] = (frame.rgba[i + c] / 3.0f) * alpha;
    frame.rgba[i + 3] = alpha;
  }
  frame.rgba[0] = std::numeric_limits<float>::quiet_NaN();
  return frame;
}

int expectedColourCode(double premultiplied, double alpha) {
  if (std::isnan(premultiplied)) return 0;
  const double straight = alpha > 0.0 ? premultiplied / alpha : premultiplied;
  return int(std::floor(srgbEncodeReference(straight) * 255.0 + 0.5));
}

TEST_F(ImageFiles, PngMatchesIndependentSrgbEncode) {
  const Frame frame = premultipliedFrame(41, 17, 3);
  const std::string path = file("frame.png");
  writePng(frame, path);
  const Rgba8 png = readPngDirectly(path);
  ASSERT_EQ(png.width, 41);
  ASSERT_EQ(png.height, 17);
  int exact = 0;
  for (std::size_t i = 0; i < frame.rgba.size(); i += 4) {
    const double alpha = frame.rgba[i + 3];
    for (int c = 0; c < 3; ++c) {
      const int expected = expectedColourCode(frame.rgba[i + c], alpha);
      ASSERT_LE(std::abs(int(png.bytes[i + c]) - expected), 1) << "texel " << i / 4 << " c" << c;
      exact += int(png.bytes[i + c]) == expected;
    }
    const int expectedAlpha = int(std::floor(std::min(1.0, alpha) * 255.0 + 0.5));
    ASSERT_LE(std::abs(int(png.bytes[i + 3]) - expectedAlpha), 1) << "texel " << i / 4;
  }
  // Off-by-one is only allowed at rounding ties, which are rare.
  EXPECT_GT(exact, int(frame.rgba.size() / 4 * 3 * 99 / 100));
  EXPECT_EQ(entriesInDir(), 1u);
}

TEST_F(ImageFiles, ReadImageDecodesWrittenPng) {
  const Frame frame = premultipliedFrame(13, 29, 4);
  const std::string path = file("decode.Png");
  writeFrame(frame, path);
  const Rgba8 png = readPngDirectly(path);
  const Image image = readImage(path);
  ASSERT_EQ(image.width, 13);
  ASSERT_EQ(image.height, 29);
  for (std::size_t i = 0; i < png.bytes.size(); ++i) {
    const double code = png.bytes[i] / 255.0;
    const double expected = i % 4 == 3 ? code : srgbDecodeReference(code);
    ASSERT_NEAR(image.rgba[i], expected, 1e-7 * expected + 1e-12) << i;
  }
}

// ---- PNG in: files written with libpng's full API --------------------------

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The PNG's rows are compressed in bands in parallel: the bytes must not
// depend on the threads, and libpng must read back every row (heights that
// are and are not multiples of the band, down to one row).
TEST_F(ImageFiles, PngBytesAreTheSameOnAnyThreadCount) {
  const Executor two(2), three(3);
  for (const auto& [width, height] : {std::pair{37, 101}, std::pair{5, 64}, std::pair{1, 1}}) {
    const Frame frame = premultipliedFrame(width, height, unsigned(width + height));
    writePng(frame, file("serial.png"));
    writePng(frame, file("two.png"), &two);
    writeFrame(frame, file("three.png"), &three);
    const std::string serial = readBytes(file("serial.png"));
    EXPECT_EQ(readBytes(file("two.png")), serial) << width << "x" << height;
    EXPECT_EQ(readBytes(file("three.png")), serial) << width << "x" << height;
    const Rgba8 png = readPngDirectly(file("two.png"));
    ASSERT_EQ(png.width, width);
    ASSERT_EQ(png.height, height);
    for (std::size_t i = 0; i < frame.rgba.size(); i += 4) {
      const double alpha = frame.rgba[i + 3];
      for (int c = 0; c < 3; ++c)
        ASSERT_LE(std::abs(int(png.bytes[i + c]) - expectedColourCode(frame.rgba[i + c], alpha)), 1)
            << "texel " << i / 4;
    }
  }
}

struct PngSpec {
  int width = 0;
  int height = 0;
  int colourType = PNG_COLOR_TYPE_RGB;
  int bitDepth = 8;
  bool interlaced = false;
  std::vector<png_color> palette;
  std::vector<png_byte> paletteAlpha;
};

// Only plain data lives in this frame, so libpng's longjmp skips no destructor.
bool writePngWithLibpng(const char* path, const PngSpec& spec, png_bytepp rows) {
  std::FILE* fp = std::fopen(path, "wb");
  if (fp == nullptr) return false;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(fp);
    return false;
  }
  png_init_io(png, fp);
  png_set_IHDR(png, info, png_uint_32(spec.width), png_uint_32(spec.height), spec.bitDepth,
               spec.colourType, spec.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (!spec.palette.empty()) {
    png_set_PLTE(png, info, spec.palette.data(), int(spec.palette.size()));
  }
  if (!spec.paletteAlpha.empty()) {
    png_set_tRNS(png, info, spec.paletteAlpha.data(), int(spec.paletteAlpha.size()), nullptr);
  }
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::fclose(fp) == 0;
}

int channelsOf(int colourType) {
  switch (colourType) {
    case PNG_COLOR_TYPE_GRAY:
      return 1;
    case PNG_COLOR_TYPE_GRAY_ALPHA:
      return 2;
    case PNG_COLOR_TYPE_RGB:
      return 3;
    case PNG_COLOR_TYPE_RGB_ALPHA:
      return 4;
    default:
      return 1;  // palette index
  }
}

// Random sample codes, then the file: big-endian 16-bit, MSB-first sub-byte.
std::vector<unsigned> writeRandomPng(const std::string& path, const PngSpec& spec, unsigned seed) {
  const int channels = channelsOf(spec.colourType);
  const unsigned maxCode =
      spec.palette.empty() ? (1u << spec.bitDepth) - 1 : unsigned(spec.palette.size()) - 1;
  std::mt19937 rng(seed);
  std::vector<unsigned> codes(std::size_t(spec.width) * spec.height * channels);
  for (unsigned& code : codes) code = rng() % (maxCode + 1);
  codes[0] = 0;
  codes[1 % codes.size()] = maxCode;
  const std::size_t rowBytes = (std::size_t(spec.width) * channels * spec.bitDepth + 7) / 8;
  std::vector<png_byte> bytes(rowBytes * spec.height, 0);
  for (int y = 0; y < spec.height; ++y) {
    for (int s = 0; s < spec.width * channels; ++s) {
      const unsigned code = codes[std::size_t(y) * spec.width * channels + s];
      png_byte* row = &bytes[std::size_t(y) * rowBytes];
      if (spec.bitDepth == 16) {
        row[2 * s] = png_byte(code >> 8);
        row[2 * s + 1] = png_byte(code & 0xff);
      } else {
        const int bit = s * spec.bitDepth;
        row[bit / 8] |= png_byte(code << (8 - spec.bitDepth - bit % 8));
      }
    }
  }
  std::vector<png_bytep> rows(std::size_t(spec.height));
  for (int y = 0; y < spec.height; ++y) rows[std::size_t(y)] = &bytes[std::size_t(y) * rowBytes];
  EXPECT_TRUE(writePngWithLibpng(path.c_str(), spec, rows.data()));
  return codes;
}

// What texel i should decode to, from the codes alone.
std::array<double, 4> expectedTexel(const PngSpec& spec, const std::vector<unsigned>& codes,
                                    std::size_t i) {
  const int channels = channelsOf(spec.colourType);
  const double maxCode = double((1u << spec.bitDepth) - 1);
  const unsigned* t = &codes[i * std::size_t(channels)];
  if (!spec.palette.empty()) {
    const png_color& p = spec.palette[t[0]];
    const double a = t[0] < spec.paletteAlpha.size() ? spec.paletteAlpha[t[0]] / 255.0 : 1.0;
    return {srgbDecodeReference(p.red / 255.0), srgbDecodeReference(p.green / 255.0),
            srgbDecodeReference(p.blue / 255.0), a};
  }
  const bool grey = channels <= 2;
  const bool alpha = channels == 2 || channels == 4;
  std::array<double, 4> out;
  for (int c = 0; c < 3; ++c) out[c] = srgbDecodeReference(t[grey ? 0 : c] / maxCode);
  out[3] = alpha ? t[channels - 1] / maxCode : 1.0;
  return out;
}

void checkPngDecode(const std::string& path, const PngSpec& spec, unsigned seed) {
  const std::vector<unsigned> codes = writeRandomPng(path, spec, seed);
  const Image image = readImage(path);
  ASSERT_EQ(image.width, spec.width);
  ASSERT_EQ(image.height, spec.height);
  for (std::size_t i = 0; i < std::size_t(spec.width) * spec.height; ++i) {
    const std::array<double, 4> expected = expectedTexel(spec, codes, i);
    for (int c = 0; c < 4; ++c) {
      // float decode of a 16-bit code: a few ulps (see Srgb.DecodeMatchesFormula).
      ASSERT_NEAR(image.rgba[i * 4 + std::size_t(c)], expected[std::size_t(c)],
                  1e-6 * expected[std::size_t(c)] + 1e-12)
          << path << " texel " << i << " channel " << c;
    }
  }
  // The same bytes from memory (a glTF's images) decode to the same floats.
  const std::string bytes = readBytes(path);
  int bits = 0;
  const Image fromMemory = decodePng(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                     bytes.size(), "in memory", &bits);
  EXPECT_EQ(bits, spec.bitDepth == 16 ? 16 : 8) << path;
  ASSERT_EQ(fromMemory.width, image.width);
  ASSERT_EQ(fromMemory.height, image.height);
  EXPECT_TRUE(fromMemory.rgba == image.rgba) << path;
  // Images read from 8-bit codes keep every bit when stored as sRGB8 codes.
  if (spec.bitDepth > 8) return;
  for (int y = 0; y < spec.height; ++y) {
    for (int x = 0; x < spec.width; ++x) {
      std::uint8_t stored[4];
      float decoded[4];
      encodeTexel(TexelFormat::Rgba8Srgb, image.texel(x, y), stored);
      decodeTexel(TexelFormat::Rgba8Srgb, stored, decoded);
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(decoded[c], image.texel(x, y)[c]) << path << " texel " << x << "," << y;
    }
  }
}

TEST_F(ImageFiles, ReadImageDecodesEveryPngLayout) {
  const struct {
    const char* name;
    int colourType;
    int bitDepth;
    bool interlaced;
  } layouts[] = {
      {"grey8.png", PNG_COLOR_TYPE_GRAY, 8, false},
      {"grey16.png", PNG_COLOR_TYPE_GRAY, 16, false},
      {"grey4.png", PNG_COLOR_TYPE_GRAY, 4, false},
      {"greyalpha16.png", PNG_COLOR_TYPE_GRAY_ALPHA, 16, false},
      {"rgb8.png", PNG_COLOR_TYPE_RGB, 8, false},
      {"rgb16.png", PNG_COLOR_TYPE_RGB, 16, false},
      {"rgba16_interlaced.png", PNG_COLOR_TYPE_RGB_ALPHA, 16, true},
      {"rgba8.png", PNG_COLOR_TYPE_RGB_ALPHA, 8, false},
  };
  unsigned seed = 10;
  for (const auto& layout : layouts) {
    PngSpec spec;
    spec.width = 23;
    spec.height = 11;
    spec.colourType = layout.colourType;
    spec.bitDepth = layout.bitDepth;
    spec.interlaced = layout.interlaced;
    checkPngDecode(file(layout.name), spec, seed++);
  }
}

TEST_F(ImageFiles, ReadImageDecodesPaletteWithTransparency) {
  PngSpec spec;
  spec.width = 9;
  spec.height = 7;
  spec.colourType = PNG_COLOR_TYPE_PALETTE;
  spec.palette = {{0, 0, 0}, {255, 128, 3}, {10, 200, 90}, {255, 255, 255}, {77, 1, 254}};
  spec.paletteAlpha = {255, 0, 128};  // entries past the list are opaque
  checkPngDecode(file("palette.png"), spec, 42);
}

// ---- errors -----------------------------------------------------------------

TEST_F(ImageFiles, WritingIntoMissingDirectoryFailsCleanly) {
  const Frame frame = randomFrame(4, 4, 5);
  for (const char* name : {"missing/out.exr", "missing/out.png"}) {
    const std::string path = file(name);
    expectErrorNaming([&] { writeFrame(frame, path); }, path);
    EXPECT_FALSE(fs::exists(path));
  }
  EXPECT_EQ(entriesInDir(), 0u);
}

TEST_F(ImageFiles, FailedRenameLeavesNoTemporary) {
  const Frame frame = randomFrame(4, 4, 6);
  for (const char* name : {"taken.exr", "taken.png"}) {
    const std::string path = file(name);
    fs::create_directory(path);  // a directory cannot be replaced by a file
    expectErrorNaming([&] { writeFrame(frame, path); }, path);
    EXPECT_TRUE(fs::is_directory(path));
  }
  EXPECT_EQ(entriesInDir(), 2u);
}

TEST_F(ImageFiles, UnsupportedExtensionIsAnError) {
  const Frame frame = randomFrame(4, 4, 7);
  for (const char* name : {"out.jpg", "out", "out.exr.bak", "dir.png/out"}) {
    const std::string path = file(name);
    expectErrorNaming([&] { writeFrame(frame, path); }, path,
                      "unsupported output format (use .exr or .png)");
  }
  EXPECT_EQ(entriesInDir(), 0u);
}

TEST_F(ImageFiles, MismatchedFrameIsAnErrorNotACrash) {
  Frame frame = randomFrame(4, 4, 8);
  frame.depth.pop_back();
  expectErrorNaming([&] { writeExr(frame, file("short.exr")); }, file("short.exr"));
  frame.rgba.clear();
  expectErrorNaming([&] { writePng(frame, file("short.png")); }, file("short.png"));
  EXPECT_EQ(entriesInDir(), 0u);
}

TEST_F(ImageFiles, OverwriteReplacesExistingFile) {
  const std::string path = file("again.exr");
  writeExr(randomFrame(8, 8, 9), path);
  const Frame second = randomFrame(3, 5, 10);
  writeExr(second, path);
  const Image image = readImage(path);
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 5);
  EXPECT_EQ(image.rgba, second.rgba);
  EXPECT_EQ(entriesInDir(), 1u);
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST_F(ImageFiles, ReadingBadFilesThrowsErrors) {
  expectErrorNaming([&] { readImage(file("absent.png")); }, file("absent.png"));
  expectErrorNaming([&] { readImage(dir_.string()); }, dir_.string());
  writeBytes(file("empty.png"), "");
  expectErrorNaming([&] { readImage(file("empty.png")); }, file("empty.png"));
  writeBytes(file("garbage.exr"), std::string(300, 'x'));
  expectErrorNaming([&] { readImage(file("garbage.exr")); }, file("garbage.exr"));
  // Right magic, nonsense after it.
  writeBytes(file("fake.png"), "\x89PNG\r\n\x1a\n" + std::string(100, '\x7f'));
  expectErrorNaming([&] { readImage(file("fake.png")); }, file("fake.png"));
  writeBytes(file("fake.exr"), std::string("\x76\x2f\x31\x01", 4) + std::string(100, '\x7f'));
  expectErrorNaming([&] { readImage(file("fake.exr")); }, file("fake.exr"));
}

TEST_F(ImageFiles, ReadingTruncatedFilesThrowsErrors) {
  const Frame frame = randomFrame(64, 48, 11);
  for (const char* name : {"cut.png", "cut.exr"}) {
    const std::string whole = file(std::string("whole_") + name);
    writeFrame(frame, whole);
    const std::string bytes = readBytes(whole);
    // The last cut drops only the final byte (inside PNG's IEND chunk).
    for (const std::size_t keep : {bytes.size() / 5, bytes.size() * 3 / 5, bytes.size() - 1}) {
      const std::string path = file(name);
      writeBytes(path, bytes.substr(0, keep));
      expectErrorNaming([&] { readImage(path); }, path);
      if (bytes[1] != 'P') continue;
      expectErrorNaming(
          [&] {
            decodePng(reinterpret_cast<const std::uint8_t*>(bytes.data()), keep, "cut bytes");
          },
          "cut bytes");
    }
  }
}

}  // namespace
}  // namespace quadra
