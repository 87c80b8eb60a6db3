// Radiance .hdr decoding. The format as Greg Ward's Radiance reads it
// (src/common/header.c, color.c, resolu.c): a header of lines ending in an
// empty line, a resolution line, then one scanline after another, each either
// new-style run-length encoded (2, 2, width's high and low byte, then each of
// R, G, B, E as runs and literals) or flat RGBE quadruples in which (1, 1, 1,
// n) repeats the previous texel n << (8 x the repeats just before it) times
// (the old-style encoding). Nothing is trusted: every count is checked
// against the scanline and the bytes left.
#include "io/radiance_hdr.h"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace quadra {

namespace {

// The longest scanline the new-style encoding can hold (its length is 15
// bits) and the shortest Radiance writes with it.
constexpr std::size_t kMinRleWidth = 8, kMaxRleWidth = 0x7fff;

class HdrBytes {
 public:
  HdrBytes(const std::uint8_t* data, std::size_t size, const std::string& source)
      : data_(data), size_(size), source_(source) {}

  // The next line without its '\n' and trailing blanks; an Error where none ends.
  std::string_view line(const char* what) {
    const auto* begin = data_ + at_;
    const auto* end = std::find(begin, data_ + size_, std::uint8_t('\n'));
    if (end == data_ + size_)
      throw fail("truncated header (no end to the " + std::string(what) + ")");
    at_ = std::size_t(end - data_) + 1;
    std::string_view text(reinterpret_cast<const char*>(begin), std::size_t(end - begin));
    while (!text.empty() && (text.back() == '\r' || text.back() == ' ' || text.back() == '\t'))
      text.remove_suffix(1);
    return text;
  }

  std::size_t left() const { return size_ - at_; }
  const std::uint8_t* take(std::size_t count) {
    const std::uint8_t* at = data_ + at_;
    at_ += count;
    return at;
  }
  const std::uint8_t* peek() const { return data_ + at_; }

  Error fail(const std::string& problem) const { return makeError(source_, problem); }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
  const std::string& source_;
};

struct HdrResolution {
  std::int64_t width = 0, height = 0;
  bool bottomUp = false;     // +Y: the first scanline is the bottom row
  bool rightToLeft = false;  // -X: each scanline runs right to left
};

// A size in a resolution line: decimal digits only, at most 9 of them.
bool parseHdrSize(std::string_view text, std::int64_t& out) {
  if (text.empty() || text.size() > 9) return false;
  out = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
    out = out * 10 + (c - '0');
  }
  return true;
}

std::vector<std::string_view> hdrWords(std::string_view text) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < text.size() && text[i] != ' ' && text[i] != '\t') ++i;
    if (i > start) out.push_back(text.substr(start, i - start));
  }
  return out;
}

void readHeader(HdrBytes& in) {
  const std::string_view magic = in.line("first line");
  if (magic.substr(0, 2) != "#?") throw in.fail("not a Radiance .hdr file (no #? first line)");
  for (;;) {
    const std::string_view text = in.line("header");
    if (text.empty()) return;
    if (text.substr(0, 7) != "FORMAT=") continue;  // EXPOSURE and the rest: ignored
    const std::string_view format = text.substr(7);
    if (format == "32-bit_rle_rgbe") continue;
    if (format == "32-bit_rle_xyze")
      throw in.fail("XYZE .hdr files are not supported (only FORMAT=32-bit_rle_rgbe)");
    throw in.fail("unknown .hdr format '" + std::string(format) +
                  "' (only FORMAT=32-bit_rle_rgbe)");
  }
}

HdrResolution readResolution(HdrBytes& in) {
  const std::string_view text = in.line("resolution line");
  const std::vector<std::string_view> w = hdrWords(text);
  const auto isAxis = [](std::string_view s, char axis) {
    return s.size() == 2 && (s[0] == '-' || s[0] == '+') && s[1] == axis;
  };
  HdrResolution r;
  if (w.size() == 4 && isAxis(w[0], 'Y') && isAxis(w[2], 'X')) {
    if (!parseHdrSize(w[1], r.height) || !parseHdrSize(w[3], r.width))
      throw in.fail("bad resolution line '" + std::string(text) + "' (sizes of 1 to 9 digits)");
    r.bottomUp = w[0][0] == '+';
    r.rightToLeft = w[2][0] == '-';
  } else if (w.size() == 4 && isAxis(w[0], 'X') && isAxis(w[2], 'Y')) {
    throw in.fail("resolution line '" + std::string(text) +
                  "': column-ordered (transposed) .hdr files are not supported");
  } else {
    throw in.fail("bad resolution line '" + std::string(text) + "' (expected e.g. -Y 512 +X 1024)");
  }
  if (r.width == 0 || r.height == 0)
    throw in.fail("empty image (" + std::to_string(r.width) + "x" + std::to_string(r.height) + ")");
  return r;
}

// One scanline's RGBE bytes, 4 a texel, left to right as stored.
void readScanline(HdrBytes& in, std::size_t width, std::int64_t index, std::uint8_t* out) {
  const auto truncated = [&] {
    return in.fail("truncated .hdr (scanline " + std::to_string(index) + " ends early)");
  };
  const std::uint8_t* p = in.peek();
  if (width >= kMinRleWidth && width <= kMaxRleWidth && in.left() >= 4 && p[0] == 2 && p[1] == 2 &&
      (p[2] & 0x80) == 0) {
    const std::size_t length = std::size_t(p[2]) << 8 | p[3];
    if (length != width)
      throw in.fail("scanline " + std::to_string(index) + " is run-length encoded for " +
                    std::to_string(length) + " texels in an image " + std::to_string(width) +
                    " wide");
    in.take(4);
    for (int channel = 0; channel < 4; ++channel) {
      for (std::size_t x = 0; x < width;) {
        if (in.left() < 1) throw truncated();
        std::size_t count = *in.take(1);
        const bool run = count > 128;
        if (run) count -= 128;
        if (count == 0 || count > width - x)
          throw in.fail("scanline " + std::to_string(index) + ": a run of " +
                        std::to_string(count) + " where " + std::to_string(width - x) +
                        " texels are left");
        if (in.left() < (run ? 1 : count)) throw truncated();
        const std::uint8_t* bytes = in.take(run ? 1 : count);
        for (std::size_t k = 0; k < count; ++k, ++x) out[4 * x + channel] = bytes[run ? 0 : k];
      }
    }
    return;
  }
  int shift = 0;
  for (std::size_t x = 0; x < width;) {
    if (in.left() < 4) throw truncated();
    const std::uint8_t* texel = in.take(4);
    if (texel[0] == 1 && texel[1] == 1 && texel[2] == 1) {
      if (x == 0)
        throw in.fail("scanline " + std::to_string(index) +
                      ": an old-style repeat with no texel before it");
      if (shift > 24) throw in.fail("scanline " + std::to_string(index) + ": too many repeats");
      const std::uint64_t count = std::uint64_t(texel[3]) << shift;
      if (count > width - x)
        throw in.fail("scanline " + std::to_string(index) + ": a repeat of " +
                      std::to_string(count) + " where " + std::to_string(width - x) +
                      " texels are left");
      for (std::uint64_t k = 0; k < count; ++k, ++x)
        std::copy(out + 4 * (x - 1), out + 4 * x, out + 4 * x);
      shift += 8;
    } else {
      std::copy(texel, texel + 4, out + 4 * x);
      ++x;
      shift = 0;
    }
  }
}

}  // namespace

bool isRadianceHdr(const std::uint8_t* data, std::size_t size) {
  return size >= 2 && data[0] == '#' && data[1] == '?';
}

float rgbeChannel(std::uint8_t mantissa, std::uint8_t exponent) {
  if (exponent == 0) return 0.0f;
  // (2m + 1) 2^(e - 137): a 9-bit integer times a power of two in
  // [2^-136, 2^118], so the float is exact (subnormal at worst).
  return float(2 * unsigned(mantissa) + 1) * std::ldexp(1.0f, int(exponent) - 137);
}

RgbImage decodeRadianceHdr(const std::uint8_t* data, std::size_t size, const std::string& source,
                           const AdmitImageSize& admit) {
  HdrBytes in(data, size, source);
  readHeader(in);
  const HdrResolution r = readResolution(in);
  admit(r.width, r.height);
  RgbImage image;
  image.width = int(r.width);
  image.height = int(r.height);
  const std::size_t width = std::size_t(r.width);
  image.rgb.resize(width * std::size_t(r.height) * 3);
  float scale[256];  // rgbeChannel's power of two by exponent, 0 for e = 0
  for (int e = 0; e < 256; ++e) scale[e] = e == 0 ? 0.0f : std::ldexp(1.0f, e - 137);
  std::vector<std::uint8_t> scanline(width * 4);
  for (std::int64_t k = 0; k < r.height; ++k) {
    readScanline(in, width, k, scanline.data());
    const std::size_t row = std::size_t(r.bottomUp ? r.height - 1 - k : k);
    float* out = image.rgb.data() + row * width * 3;
    for (std::size_t x = 0; x < width; ++x) {
      const std::uint8_t* texel = &scanline[4 * x];
      float* to = out + 3 * (r.rightToLeft ? width - 1 - x : x);
      const float s = scale[texel[3]];
      for (int c = 0; c < 3; ++c) to[c] = float(2 * unsigned(texel[c]) + 1) * s;  // rgbeChannel
    }
  }
  return image;
}

}  // namespace quadra
