// Panorama files and built-in names to EnvironmentImages: the file's kind by
// its first bytes (not its name), the size rule before any pixel memory, the
// memory budget, then the texel rule (docs/lighting.md "Environments").
#include "shading/environment_source.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>
#include <vector>

#include "core/error.h"
#include "core/file_bytes.h"
#include "io/image_io.h"
#include "io/radiance_hdr.h"
#include "shading/builtin_environments.h"
#include "texture/image.h"

namespace quadra {

namespace {

constexpr std::string_view kBuiltinEnvironmentPrefix = "builtin:";

enum class PanoramaKind { Hdr, Exr, Unknown };

// The first bytes decide; a missing or unreadable file is an Error here.
PanoramaKind sniffPanorama(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw makeError(path, "cannot open file (" +
                              (ec ? ec.message() : std::string("No such file or directory")) + ")");
  if (!std::filesystem::is_regular_file(status)) throw makeError(path, "not a regular file");
  errno = 0;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  if (!file)
    throw makeError(path, "cannot open file (" +
                              std::error_code(errno, std::generic_category()).message() + ")");
  std::uint8_t magic[4] = {};
  const std::size_t got = std::fread(magic, 1, sizeof(magic), file.get());
  if (got == 0) throw makeError(path, "empty or unreadable file");
  const std::uint8_t exrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
  if (got == 4 && std::memcmp(magic, exrMagic, 4) == 0) return PanoramaKind::Exr;
  if (isRadianceHdr(magic, got)) return PanoramaKind::Hdr;
  return PanoramaKind::Unknown;
}

}  // namespace

TexelRepairs applyTexelRule(float* values, std::size_t count) {
  TexelRepairs repairs;
  for (std::size_t i = 0; i < count; ++i) {
    const float v = values[i];
    if (v > 0.0f && v <= kMaxEnvironmentRadiance) continue;
    if (std::isnan(v)) {
      ++repairs.notANumber;
      values[i] = 0.0f;
    } else if (v < 0.0f) {
      ++repairs.negative;
      values[i] = 0.0f;
    } else if (v > kMaxEnvironmentRadiance) {
      ++repairs.clamped;
      values[i] = kMaxEnvironmentRadiance;
    } else {
      values[i] = 0.0f;  // -0 becomes +0
    }
  }
  return repairs;
}

void checkEnvironmentSize(const std::string& name, std::int64_t width, std::int64_t height) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width <= 0 || height <= 0 || width * height < 2)
    throw makeError(name, "a panorama needs at least 2 texels (this one is " + size + ")");
  if (width > kMaxImagePixels || height > kMaxImagePixels || width * height > kMaxImagePixels)
    throw makeError(
        name, "panorama too large (" + size + "; the limit is 2^28 texels, e.g. 16384x16384)");
}

EnvironmentImage readEnvironmentFile(const std::string& path, MemoryBudget& budget,
                                     TexelRepairs* repairs) {
  const PanoramaKind kind = sniffPanorama(path);
  if (kind == PanoramaKind::Unknown)
    throw makeError(path, "not a Radiance .hdr or OpenEXR panorama");
  const AdmitImageSize admit = [&](std::int64_t width, std::int64_t height) {
    checkEnvironmentSize(path, width, height);
    budget.charge("environment " + path + " decoded to " + std::to_string(width) + "x" +
                      std::to_string(height),
                  std::uint64_t(width) * std::uint64_t(height) * 3 * sizeof(float));
  };
  RgbImage pixels;
  if (kind == PanoramaKind::Exr) {
    pixels = readExrRgb(path, admit);
  } else {
    std::error_code ec;
    const std::uintmax_t fileSize = std::filesystem::file_size(path, ec);
    if (!ec)
      budget.charge("environment " + path + " (" + std::to_string(fileSize) + " bytes)", fileSize);
    const std::vector<std::uint8_t> bytes = readWholeFile(path);
    try {
      pixels = decodeRadianceHdr(bytes.data(), bytes.size(), path, admit);
    } catch (const std::bad_alloc&) {
      throw makeError(path, "out of memory while decoding .hdr");
    }
  }
  EnvironmentImage image;
  image.name = path;
  image.width = pixels.width;
  image.height = pixels.height;
  image.rgb = std::move(pixels.rgb);
  const TexelRepairs rule = applyTexelRule(image.rgb.data(), image.rgb.size());
  if (repairs) *repairs = rule;
  return image;
}

EnvironmentImage loadEnvironment(const std::string& source, MemoryBudget& budget,
                                 TexelRepairs* repairs) {
  if (source.rfind(kBuiltinEnvironmentPrefix, 0) != 0)
    return readEnvironmentFile(source, budget, repairs);
  const std::string_view name = std::string_view(source).substr(kBuiltinEnvironmentPrefix.size());
  // The name is checked before the charge: an unknown one is its own Error.
  EnvironmentImage image = builtinEnvironment(name);
  budget.charge("environment " + source + " (" + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + ")",
                std::uint64_t(image.rgb.size()) * sizeof(float));
  if (repairs) *repairs = TexelRepairs{};
  return image;
}

}  // namespace quadra
