// Environments in (issue 46): the Radiance .hdr decoder against the test's
// own encoder (flat, new- and old-style run-length), EXR panoramas read back
// bit for bit, the shared panorama, LIGHTING.md's direction mapping (the
// lab's double-precision helper) against synthetic panoramas and the
// built-ins, the built-ins against their formulas in docs/lighting.md
// (written again here in double with libm), the texel rule, every bad input
// failing in one line, and `quadra env`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "cli_helpers.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "io/image_io.h"
#include "io/radiance_hdr.h"
#include "lab/reference/environment_lookup.h"
#include "shading/builtin_environments.h"
#include "shading/environment_source.h"

namespace quadra {
namespace {

struct Rgbe {
  std::uint8_t r, g, b, e;
  bool operator==(const Rgbe&) const = default;
};

// Ward's reading of one channel (Radiance color.c, colr_color), in double.
double wardChannel(std::uint8_t m, std::uint8_t e) {
  return e == 0 ? 0.0 : (m + 0.5) * std::ldexp(1.0, int(e) - 136);
}

std::string hdrHeader(int width, int height, const std::string& orientation = "") {
  std::string text = "#?RADIANCE\n# made by the test\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=2.5\n\n";
  text += orientation.empty()
              ? "-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n"
              : orientation + "\n";
  return text;
}

void putTexel(std::string& out, const Rgbe& t) {
  out += char(t.r);
  out += char(t.g);
  out += char(t.b);
  out += char(t.e);
}

// Flat: four bytes a texel (no texel may read as an old-style repeat).
std::string flatHdr(int width, int height, const std::vector<Rgbe>& texels,
                    const std::string& orientation = "") {
  std::string out = hdrHeader(width, height, orientation);
  for (const Rgbe& t : texels) putTexel(out, t);
  return out;
}

// New-style run-length: per scanline 2, 2, width, then each channel as runs
// (of 3 or more equal bytes, at most 127) and literals (at most 128).
std::string rleHdr(int width, int height, const std::vector<Rgbe>& texels) {
  std::string out = hdrHeader(width, height);
  for (int y = 0; y < height; ++y) {
    out += char(2);
    out += char(2);
    out += char(width >> 8);
    out += char(width & 255);
    for (int c = 0; c < 4; ++c) {
      std::vector<std::uint8_t> bytes;
      for (int x = 0; x < width; ++x) {
        const Rgbe& t = texels[std::size_t(y) * width + x];
        bytes.push_back(c == 0 ? t.r : c == 1 ? t.g : c == 2 ? t.b : t.e);
      }
      std::size_t x = 0;
      std::vector<std::uint8_t> literal;
      const auto flush = [&] {
        if (literal.empty()) return;
        out += char(literal.size());
        for (std::uint8_t b : literal) out += char(b);
        literal.clear();
      };
      while (x < bytes.size()) {
        std::size_t run = 1;
        while (x + run < bytes.size() && bytes[x + run] == bytes[x] && run < 127) ++run;
        if (run >= 3) {
          flush();
          out += char(128 + run);
          out += char(bytes[x]);
          x += run;
        } else {
          literal.push_back(bytes[x++]);
          if (literal.size() == 128) flush();
        }
      }
      flush();
    }
  }
  return out;
}

// Old-style: flat texels, where each run of a texel repeated after itself is
// (1, 1, 1, count's low byte) then (1, 1, 1, the next byte), Radiance's order.
std::string oldRleHdr(int width, int height, const std::vector<Rgbe>& texels) {
  std::string out = hdrHeader(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width;) {
      const Rgbe& t = texels[std::size_t(y) * width + x];
      putTexel(out, t);
      int repeats = 0;
      while (x + 1 + repeats < width && texels[std::size_t(y) * width + x + 1 + repeats] == t)
        ++repeats;
      for (int shifted = repeats; shifted > 0; shifted >>= 8)
        putTexel(out, {1, 1, 1, std::uint8_t(shifted & 255)});
      x += 1 + repeats;
    }
  }
  return out;
}

std::vector<Rgbe> randomTexels(int count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<Rgbe> texels;
  for (int i = 0; i < count; ++i) {
    Rgbe t{std::uint8_t(rng() % 256), std::uint8_t(rng() % 256), std::uint8_t(rng() % 256),
           std::uint8_t(rng() % 256)};
    if (t.r == 1 && t.g == 1 && t.b == 1) t.r = 7;  // not an old-style repeat
    if (i % 17 == 3) t.e = 0;
    if (i % 23 == 5) t.e = 255;
    if (i % 29 == 7) t.e = 1;
    texels.push_back(t);
  }
  return texels;
}

// Texels with runs in every channel: stretches of one texel, and channels
// that stay the same while others change.
std::vector<Rgbe> runnyTexels(int width, int height, std::uint32_t seed) {
  std::vector<Rgbe> texels = randomTexels(width * height, seed);
  std::mt19937 rng(seed + 1);
  for (std::size_t i = 1; i < texels.size(); ++i) {
    if (rng() % 4 != 0) texels[i] = texels[i - 1];
    if (rng() % 3 == 0) texels[i].e = 130;
  }
  return texels;
}

fs::path writeBytes(const std::string& name, const std::string& bytes) {
  const fs::path path = tempPath(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

RgbImage decode(const std::string& bytes) {
  return decodeRadianceHdr(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                           "memory.hdr", [](std::int64_t, std::int64_t) {});
}

// Every decoded value is Ward's double value, exactly.
void expectTexels(const RgbImage& image, int width, int height, const std::vector<Rgbe>& texels) {
  ASSERT_EQ(image.width, width);
  ASSERT_EQ(image.height, height);
  ASSERT_EQ(image.rgb.size(), std::size_t(width) * height * 3);
  for (std::size_t i = 0; i < texels.size(); ++i) {
    const Rgbe& t = texels[i];
    const std::uint8_t m[3] = {t.r, t.g, t.b};
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(double(image.rgb[3 * i + c]), wardChannel(m[c], t.e))
          << "texel " << i << " channel " << c;
  }
}

// The start of a new-style run-length scanline of 64 texels.
const std::string kScanline64("\x02\x02\x00\x40", 4);

MemoryBudget bigBudget() {
  return MemoryBudget(kDefaultMaxMemory, "test");
}

// ---- the RGBE convention and the decoder -----------------------------------

TEST(EnvironmentHdr, RgbeChannelIsWardsConventionExactInFloat) {
  for (int e = 0; e < 256; ++e)
    for (int m = 0; m < 256; ++m) {
      const double expected = wardChannel(std::uint8_t(m), std::uint8_t(e));
      const float got = rgbeChannel(std::uint8_t(m), std::uint8_t(e));
      ASSERT_EQ(double(got), expected) << "m " << m << " e " << e;
      ASSERT_TRUE(std::isfinite(got));
    }
  EXPECT_EQ(rgbeChannel(128, 129), 1.00390625f);  // (128.5) 2^-7
}

TEST(EnvironmentHdr, FlatFileDecodesTexelByTexel) {
  const std::vector<Rgbe> texels = randomTexels(13 * 7, 1);
  expectTexels(decode(flatHdr(13, 7, texels)), 13, 7, texels);
}

TEST(EnvironmentHdr, RunLengthFileDecodesTexelByTexel) {
  for (int width : {8, 40, 300}) {
    SCOPED_TRACE(width);
    const std::vector<Rgbe> texels = runnyTexels(width, 9, std::uint32_t(width));
    const std::string bytes = rleHdr(width, 9, texels);
    EXPECT_LT(bytes.size(), hdrHeader(width, 9).size() + texels.size() * 4);  // runs were used
    expectTexels(decode(bytes), width, 9, texels);
  }
}

TEST(EnvironmentHdr, OldStyleRepeatsDecodeTexelByTexel) {
  // Repeats of up to 299 (two repeat texels: 43, then 1 << 8) and short
  // scanlines (under 8 texels, which the new encoding cannot hold).
  for (int width : {5, 600}) {
    SCOPED_TRACE(width);
    std::vector<Rgbe> texels = randomTexels(width * 3, 5);
    for (int x = 1; x < width && x < 300; ++x) texels[std::size_t(width) + x] = texels[width];
    if (width > 4) texels[3] = texels[2];
    const std::string bytes = oldRleHdr(width, 3, texels);
    EXPECT_LT(bytes.size(), hdrHeader(width, 3).size() + texels.size() * 4);
    expectTexels(decode(bytes), width, 3, texels);
  }
}

TEST(EnvironmentHdr, OrientationsAreFlippedIntoTopDownLeftToRight) {
  const int w = 6, h = 4;
  const std::vector<Rgbe> texels = randomTexels(w * h, 9);
  const RgbImage standard = decode(flatHdr(w, h, texels));
  const RgbImage bottomUp = decode(flatHdr(w, h, texels, "+Y 4 +X 6"));
  const RgbImage mirrored = decode(flatHdr(w, h, texels, "-Y 4 -X 6"));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const float value = standard.rgb[3 * (std::size_t(y) * w + x) + c];
        EXPECT_EQ(bottomUp.rgb[3 * (std::size_t(h - 1 - y) * w + x) + c], value);
        EXPECT_EQ(mirrored.rgb[3 * (std::size_t(y) * w + (w - 1 - x)) + c], value);
      }
  try {
    decode(flatHdr(w, h, texels, "+X 6 -Y 4"));
    ADD_FAILURE() << "a transposed file was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("transposed"), std::string::npos) << e.what();
  }
}

TEST(EnvironmentHdr, SharedPanoramaDecodes) {
  const std::string path = std::string(QUADRA_ASSETS_DIR) + "/environments/chinese_garden_1k.hdr";
  if (!fs::exists(path)) GTEST_SKIP() << path << " is absent";
  MemoryBudget budget = bigBudget();
  const EnvironmentImage env = readEnvironmentFile(path, budget);
  ASSERT_EQ(env.width, 1024);
  ASSERT_EQ(env.height, 512);
  EXPECT_EQ(env.name, path);
  double top = 0, bottom = 0, peak = 0;
  int peakRow = -1;
  for (int j = 0; j < env.height; ++j)
    for (int i = 0; i < env.width; ++i)
      for (int c = 0; c < 3; ++c) {
        const float v = env.texel(i, j)[c];
        ASSERT_TRUE(std::isfinite(v) && v > 0.0f) << i << "," << j;
        if (v > peak) peak = v, peakRow = j;
        (j < env.height / 2 ? top : bottom) += v;
      }
  EXPECT_GT(top, 4 * bottom);  // the sunny sky above the garden's ground
  EXPECT_GT(peak, 10000.0);    // the sun, unclipped
  EXPECT_LT(peakRow, env.height / 2);
  // Charged: the file's bytes, then the texels.
  EXPECT_EQ(budget.used(), fs::file_size(path) + std::uint64_t(1024) * 512 * 12);
}

// ---- EXR panoramas ----------------------------------------------------------

TEST(EnvironmentExr, FrameWrittenByWriteExrReadsBackBitForBit) {
  Frame frame;
  frame.width = 37;
  frame.height = 19;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> value(0.0f, 1000.0f);
  frame.rgba.resize(std::size_t(frame.width) * frame.height * 4);
  for (float& v : frame.rgba) v = value(rng);
  frame.depth.assign(std::size_t(frame.width) * frame.height, 0.5f);
  const fs::path path = tempPath("frame.exr");
  writeExr(frame, path.string());
  MemoryBudget budget = bigBudget();
  const EnvironmentImage env = readEnvironmentFile(path.string(), budget);
  ASSERT_EQ(env.width, frame.width);
  ASSERT_EQ(env.height, frame.height);
  for (std::size_t i = 0; i < env.texelCount(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(env.rgb[3 * i + c], frame.rgba[4 * i + c]) << i;
}

TEST(EnvironmentExr, WriteExrRgbReadsBackBitForBit) {
  std::vector<float> rgb(40 * 20 * 3);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> value(0.0f, 1e6f);
  for (float& v : rgb) v = value(rng);
  rgb[5] = 1e-42f;  // subnormal
  const fs::path path = tempPath("rgb.exr");
  writeExrRgb(rgb.data(), 40, 20, path.string());
  MemoryBudget budget = bigBudget();
  const EnvironmentImage env = readEnvironmentFile(path.string(), budget);
  ASSERT_EQ(env.width, 40);
  ASSERT_EQ(env.height, 20);
  EXPECT_EQ(env.rgb, rgb);
}

// ---- the direction mapping and the orientation ------------------------------

TEST(EnvironmentMapping, DirectionsMapAsLightingMdSays) {
  // u < 0: any u (at the poles every u is the same direction).
  const auto expectUv = [](glm::dvec3 d, double u, double v) {
    const glm::dvec2 uv = ref::equirectUv(d);
    if (u >= 0) {
      EXPECT_NEAR(uv.x, u, 1e-15) << d.x << "," << d.y << "," << d.z;
    }
    EXPECT_NEAR(uv.y, v, 1e-15) << d.x << "," << d.y << "," << d.z;
  };
  expectUv({0, 0, -1}, 0.5, 0.5);   // where a default glTF camera looks
  expectUv({1, 0, 0}, 0.75, 0.5);   // +X right of centre
  expectUv({-1, 0, 0}, 0.25, 0.5);  // -X left of it
  expectUv({0, 0, 1}, 1.0, 0.5);    // +Z at the seam
  expectUv({0, 1, 0}, -1, 0.0);     // +Y: the top row
  expectUv({0, -1, 0}, -1, 1.0);    // -Y: the bottom row
  expectUv(glm::normalize(glm::dvec3(0, 1, -1)), 0.5, 0.25);
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> unit(0.001, 0.999);
  for (int k = 0; k < 1000; ++k) {
    const glm::dvec2 uv(unit(rng), unit(rng));
    const glm::dvec2 back = ref::equirectUv(ref::equirectDirection(uv));
    EXPECT_NEAR(back.x, uv.x, 1e-12);
    EXPECT_NEAR(back.y, uv.y, 1e-12);
  }
}

// A panorama whose texel (i, j) holds (i, j): each texel centre's direction
// reads back its own indices through the lab's mapping and bilinear lookup,
// from an .hdr and from an .exr, so neither decoder flips or shifts.
TEST(EnvironmentMapping, TexelCentresReadBackTheirOwnIndices) {
  const int w = 16, h = 8;
  std::vector<Rgbe> texels;
  std::vector<float> rgb;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      // (2m + 1) 2^(e - 137) with e = 137: R = 2i + 1, G = 2j + 1.
      texels.push_back({std::uint8_t(i), std::uint8_t(j), 0, 137});
      rgb.insert(rgb.end(), {float(2 * i + 1), float(2 * j + 1), 1.0f});
    }
  const fs::path hdr = writeBytes("indices.hdr", flatHdr(w, h, texels));
  const fs::path exr = tempPath("indices.exr");
  writeExrRgb(rgb.data(), w, h, exr.string());
  for (const fs::path& path : {hdr, exr}) {
    SCOPED_TRACE(path.string());
    MemoryBudget budget = bigBudget();
    const EnvironmentImage env = readEnvironmentFile(path.string(), budget);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const glm::dvec3 d = ref::equirectDirection({(i + 0.5) / w, (j + 0.5) / h});
        const glm::dvec3 l = ref::environmentRadiance(env, d);
        EXPECT_NEAR(l.x, 2 * i + 1, 1e-9) << i << "," << j;
        EXPECT_NEAR(l.y, 2 * j + 1, 1e-9) << i << "," << j;
      }
    // -Z lies between the two middle columns; +Y above the first row.
    EXPECT_NEAR(ref::environmentRadiance(env, {0, 0, -1}).x, w, 1e-9);
    EXPECT_NEAR(ref::environmentRadiance(env, {0, 1, 0}).y, 1.0, 1e-9);
    EXPECT_NEAR(ref::environmentRadiance(env, {0, -1, 0}).y, 2 * h - 1, 1e-9);
    // +X three quarters across: between columns 11 and 12 (u = 0.75).
    EXPECT_NEAR(ref::environmentRadiance(env, {1, 0, 0}).x, 24.0, 1e-9);
  }
}

// ---- the built-ins -----------------------------------------------------------

// docs/lighting.md "Built-in environments", again in double with libm.
double docSmoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

glm::dvec3 docStudio(const glm::dvec3& d) {
  const glm::dvec3 key = glm::normalize(glm::dvec3(-1, 1, 1));
  const glm::dvec3 rim = glm::normalize(glm::dvec3(1, 0.5, -1));
  const double background = 0.12 + (0.5 + 0.3 * d.y - 0.12) * docSmoothstep(-0.1, 0.1, d.y);
  return glm::dvec3(background + 6 * docSmoothstep(0.94, 0.985, glm::dot(d, key)) +
                    3 * docSmoothstep(0.95, 0.99, glm::dot(d, rim)));
}

glm::dvec3 docSky(const glm::dvec3& d) {
  const glm::dvec3 sun = glm::normalize(glm::dvec3(0.25, 0.3, -1));
  const glm::dvec3 horizon(0.85, 0.9, 1.0), zenith(0.15, 0.3, 0.75), ground(0.1, 0.09, 0.08);
  const double a = 1 - std::pow(1 - std::max(d.y, 0.0), 3);
  const glm::dvec3 sky = horizon + (zenith - horizon) * a;
  return ground + (sky - ground) * docSmoothstep(-0.02, 0.02, d.y) +
         glm::dvec3(15000, 13500, 11250) * docSmoothstep(0.99978, 0.9999, glm::dot(d, sun));
}

// Each texel is the formula at its centre rounded to float: within half a
// float ulp, plus 1e-7 for the sun's rim, where the formula's slope (about
// 1e8 per unit of cosine) turns the direction's last double bits into that.
void expectBuiltin(const std::string& name, int width, int height,
                   glm::dvec3 (*formula)(const glm::dvec3&)) {
  SCOPED_TRACE(name);
  const EnvironmentImage env = builtinEnvironment(name);
  EXPECT_EQ(env.name, "builtin:" + name);
  ASSERT_EQ(env.width, width);
  ASSERT_EQ(env.height, height);
  ASSERT_EQ(env.rgb.size(), env.texelCount() * 3);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const glm::dvec3 expected =
          formula(ref::equirectDirection({(i + 0.5) / width, (j + 0.5) / height}));
      for (int c = 0; c < 3; ++c) {
        const double got = env.texel(i, j)[c];
        ASSERT_NEAR(got, expected[c], std::abs(expected[c]) * 0x1p-24 + 1e-7)
            << "texel " << i << "," << j << " channel " << c;
      }
    }
}

TEST(BuiltinEnvironments, TexelsAreTheFormulasAtTexelCentres) {
  EXPECT_EQ(builtinEnvironmentNames(), (std::vector<std::string>{"studio", "sky", "white"}));
  EXPECT_EQ(std::string(kDefaultEnvironment), "builtin:studio");
  expectBuiltin("studio", 1024, 512, docStudio);
  expectBuiltin("sky", 1024, 512, docSky);
  expectBuiltin("white", 64, 32, [](const glm::dvec3&) { return glm::dvec3(1.0); });
}

TEST(BuiltinEnvironments, LightsSitWhereTheirDirectionsMap) {
  // The sky's brightest texel is the one the sun's direction maps into, and
  // the top row is sky, the bottom ground.
  const EnvironmentImage sky = builtinEnvironment("sky");
  double weight = 0, sumI = 0, sumJ = 0;
  for (int j = 0; j < sky.height; ++j)
    for (int i = 0; i < sky.width; ++i)
      if (const double r = sky.texel(i, j)[0]; r > 10) {
        weight += r;
        sumI += r * i;
        sumJ += r * j;
      }
  const glm::dvec2 uv = ref::equirectUv(glm::normalize(glm::dvec3(0.25, 0.3, -1)));
  EXPECT_NEAR(sumI / weight, uv.x * sky.width - 0.5, 0.25);
  EXPECT_NEAR(sumJ / weight, uv.y * sky.height - 0.5, 0.25);
  EXPECT_GT(sky.texel(0, 0)[2], sky.texel(0, 0)[0]);  // blue above
  EXPECT_LT(sky.texel(0, sky.height - 1)[2], 0.1f);   // ground below
  // The studio's key light is up front left: brighter there than behind right.
  const EnvironmentImage studio = builtinEnvironment("studio");
  const glm::dvec3 key = glm::normalize(glm::dvec3(-1, 1, 1));
  EXPECT_NEAR(ref::environmentRadiance(studio, key).x, 6 + 0.5 + 0.3 * key.y, 1e-3);
  EXPECT_NEAR(ref::environmentRadiance(studio, -key).x, 0.12, 1e-3);
}

TEST(BuiltinEnvironments, AreTheSameBitsEachTime) {
  EXPECT_EQ(builtinEnvironment("sky").rgb, builtinEnvironment("sky").rgb);
}

TEST(BuiltinEnvironments, UnknownNameIsAnError) {
  try {
    builtinEnvironment("stduio");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "builtin:stduio: unknown built-in environment (studio, sky, white)");
  }
  MemoryBudget budget = bigBudget();
  const EnvironmentImage env = loadEnvironment("builtin:white", budget);
  EXPECT_EQ(env.width, 64);
  EXPECT_EQ(budget.used(), std::uint64_t(64) * 32 * 12);
}

// ---- the texel rule ------------------------------------------------------------

TEST(EnvironmentTexelRule, NanNegativeAndHugeValuesAreRepairedAndCounted) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> rgb = {0.5f,  nan,  -1.0f,         inf,    -inf,    -0.0f,
                            1e38f, 2.0f, 4294967296.0f, 1e-40f, -1e-40f, 0.0f};
  const fs::path path = tempPath("odd.exr");
  writeExrRgb(rgb.data(), 2, 2, path.string());
  MemoryBudget budget = bigBudget();
  TexelRepairs repairs;
  const EnvironmentImage env = readEnvironmentFile(path.string(), budget, &repairs);
  const std::vector<float> expected = {0.5f,          0.0f,   0.0f,          4294967296.0f,
                                       0.0f,          0.0f,   4294967296.0f, 2.0f,
                                       4294967296.0f, 1e-40f, 0.0f,          0.0f};
  ASSERT_EQ(env.rgb.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(env.rgb[i], expected[i]) << i;
    EXPECT_FALSE(std::signbit(env.rgb[i])) << i;  // -0 became +0
  }
  EXPECT_EQ(repairs.notANumber, 1u);
  EXPECT_EQ(repairs.negative, 3u);  // -1, -inf, -1e-40
  EXPECT_EQ(repairs.clamped, 2u);   // inf, 1e38
  EXPECT_EQ(repairs.total(), 6u);
  EXPECT_EQ(kMaxEnvironmentRadiance, 4294967296.0f);
}

// ---- bad input: one line naming the file and the problem ---------------------

void expectLoadError(const std::string& path, const std::string& problem,
                     std::uint64_t budgetBytes = kDefaultMaxMemory) {
  SCOPED_TRACE(problem);
  MemoryBudget budget(budgetBytes, "test");
  try {
    loadEnvironment(path, budget);
    ADD_FAILURE() << path << " loaded";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(EnvironmentBadInput, FailsInOneLineNamingFileAndProblem) {
  const std::vector<Rgbe> texels = runnyTexels(64, 4, 2);
  const std::string rle = rleHdr(64, 4, texels);
  const std::string header = hdrHeader(64, 4);
  const auto file = [](const std::string& name, const std::string& bytes) {
    return writeBytes(name, bytes).string();
  };
  expectLoadError((testDir() / "missing.hdr").string(), "cannot open file");
  expectLoadError(testDir().string(), "not a regular file");
  expectLoadError(file("empty.hdr", ""), "empty");
  expectLoadError(file("magic.hdr", "P6\n4 4\n255\n"), "not a Radiance .hdr or OpenEXR");
  expectLoadError(file("header.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n"), "truncated header");
  expectLoadError(file("noresolution.hdr", "#?RADIANCE\n\n"), "truncated header");
  expectLoadError(file("resolution.hdr", "#?RADIANCE\n\n-Y 4 +X four\n"), "bad resolution line");
  expectLoadError(file("xyze.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 2\n"), "XYZE");
  expectLoadError(
      file("truncated-rle.hdr", rle.substr(0, header.size() + (rle.size() - header.size()) / 2)),
      "ends early");
  expectLoadError(file("truncated-flat.hdr",
                       flatHdr(4, 4, randomTexels(16, 3)).substr(0, hdrHeader(4, 4).size() + 20)),
                  "ends early");
  std::string overrun = header + kScanline64 + char(128 + 65) + "x";
  expectLoadError(file("overrun.hdr", overrun), "a run of 65 where 64 texels are left");
  expectLoadError(file("zero-run.hdr", header + kScanline64 + std::string(1, '\0')), "a run of 0");
  expectLoadError(file("width.hdr", header + std::string("\x02\x02\x00\x41", 4)),
                  "run-length encoded for 65");
  expectLoadError(file("repeat.hdr", hdrHeader(4, 1) + "\x01\x01\x01\x02"), "no texel before it");
  expectLoadError(file("zero.hdr", "#?RADIANCE\n\n-Y 0 +X 4\n"), "empty image");
  expectLoadError(file("one.hdr", flatHdr(1, 1, {{10, 10, 10, 128}})), "at least 2 texels");
  expectLoadError(file("huge.hdr", "#?RADIANCE\n\n-Y 100000 +X 200000\n"), "too large");
  expectLoadError(file("budget.hdr", "#?RADIANCE\n\n-Y 4096 +X 8192\n"), "over the memory budget",
                  std::uint64_t(64) << 20);
  const std::vector<float> one = {1.0f, 2.0f, 3.0f};
  const fs::path oneExr = tempPath("one.exr");
  writeExrRgb(one.data(), 1, 1, oneExr.string());
  expectLoadError(oneExr.string(), "at least 2 texels");
  std::vector<float> rgb(64 * 32 * 3, 1.0f);
  const fs::path exr = tempPath("whole.exr");
  writeExrRgb(rgb.data(), 64, 32, exr.string());
  expectLoadError(exr.string(), "over the memory budget", 4096);
  expectLoadError(file("truncated.exr", bytesOf(exr).substr(0, bytesOf(exr).size() / 2)),
                  "invalid or truncated EXR");
}

// ---- quadra env ------------------------------------------------------------------

std::vector<float> exrTexels(const fs::path& path) {
  MemoryBudget budget = bigBudget();
  return readEnvironmentFile(path.string(), budget).rgb;
}

TEST(EnvCommand, WritesABuiltinsTexelsExactly) {
  const fs::path out = tempPath("studio.exr");
  const RunResult r = run("env builtin:studio --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("quadra env source=builtin:studio width=1024 height=512 nan=0 negative=0 "
                       "clamped=0\n"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(exrTexels(out), builtinEnvironment("studio").rgb);
  // A bare name, and no name at all, mean the same.
  const fs::path bare = tempPath("bare.exr"), none = tempPath("none.exr");
  ASSERT_EQ(run("env sky --out " + bare.string()).exitCode, 0);
  EXPECT_EQ(exrTexels(bare), builtinEnvironment("sky").rgb);
  ASSERT_EQ(run("env --out " + none.string()).exitCode, 0);
  EXPECT_EQ(exrTexels(none), builtinEnvironment("studio").rgb);
}

TEST(EnvCommand, ConvertsAFileAsQuadraReadsIt) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> rgb = {1.0f, nan, -2.0f, 3.0f, 4.0f, 5.0f};
  const fs::path in = tempPath("in.exr"), out = tempPath("out.exr");
  writeExrRgb(rgb.data(), 2, 1, in.string());
  const RunResult r = run("env " + in.string() + " --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("width=2 height=1 nan=1 negative=1 clamped=0"), std::string::npos) << r.out;
  EXPECT_EQ(exrTexels(out), (std::vector<float>{1.0f, 0.0f, 0.0f, 3.0f, 4.0f, 5.0f}));
  const std::vector<Rgbe> texels = runnyTexels(40, 3, 8);
  const fs::path hdr = writeBytes("in.hdr", rleHdr(40, 3, texels));
  ASSERT_EQ(run("env " + hdr.string() + " --out " + out.string()).exitCode, 0);
  const std::vector<float> fromCli = exrTexels(out);
  ASSERT_EQ(fromCli.size(), texels.size() * 3);
  for (std::size_t i = 0; i < texels.size(); ++i)
    EXPECT_EQ(double(fromCli[3 * i]),
              std::min(wardChannel(texels[i].r, texels[i].e), 4294967296.0))  // the texel rule
        << i;
}

TEST(EnvCommand, BadInputWritesNothing) {
  const fs::path dir = emptyFolder("env-bad");
  const fs::path out = dir / "x.exr";
  const std::string bad = writeBytes("bad.hdr", hdrHeader(64, 4) + kScanline64).string();
  struct Case {
    std::string arguments, mentions;
    int status;
  };
  const Case cases[] = {
      {bad + " --out " + out.string(), "bad.hdr: truncated .hdr", 1},
      {(dir / "missing.hdr").string() + " --out " + out.string(), "missing.hdr: cannot open", 1},
      {"builtin:stduio --out " + out.string(), "(did you mean studio?)", 2},
      {"stduio --out " + out.string(), "(did you mean studio?)", 2},
      {"studio", "--out is required", 2},
      {"studio --out " + (dir / "x.png").string(), "must be a .exr file", 2},
      {"studio sky --out " + out.string(), "more than one environment", 2},
      {"builtin:studio --max-memory 1M --out " + out.string(), "over the memory budget", 1},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.arguments);
    const RunResult r = run("env " + c.arguments);
    EXPECT_EQ(r.exitCode, c.status);
    expectOneLineError(r, c.mentions);
    EXPECT_EQ(fileNames(dir), std::vector<std::string>{}) << "a file was written";
  }
}

}  // namespace
}  // namespace quadra
