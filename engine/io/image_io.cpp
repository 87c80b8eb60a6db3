// Image files in and out. Writers go through a temporary beside the target and
// rename on success, so a failed write never leaves a partial file under the
// requested name. libpng's and libjpeg's errors are confined to
// setjmp-guarded functions that hold no C++ objects, and OpenEXR's exceptions
// become quadra::Error.
#include "io/image_io.h"

#include <png.h>
// jpeglib.h needs FILE and size_t declared first: png.h above declares them.
#include <jpeglib.h>
#include <unistd.h>
#include <zlib.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <memory>
#include <new>
#include <system_error>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/file_bytes.h"
#include "core/large_buffer.h"
#include "core/parallel.h"
#include "io/srgb8.h"
#include "texture/texel_format.h"

namespace quadra {

namespace {

std::string tooLargeText(std::int64_t width, std::int64_t height) {
  return "image too large (" + std::to_string(width) + "x" + std::to_string(height) +
         "; the limit is 2^28 texels, e.g. 16384x16384)";
}

std::string errnoText(int err, const char* fallback) {
  return err != 0 ? std::error_code(err, std::generic_category()).message() : fallback;
}

// Library messages may span lines; quadra's errors are one line.
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

std::string lowerExtension(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// A temporary file beside the target; removed unless commit() renamed it into
// place. The name carries the process and thread so concurrent writers of the
// same path do not share a temporary.
class TempFile {
 public:
  explicit TempFile(const std::string& target)
      : target_(target),
        path_(target + ".tmp-" + std::to_string(::getpid()) + "-" +
              std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id()))) {}
  ~TempFile() {
    if (!committed_) std::remove(path_.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& path() const { return path_; }

  void commit() {
    errno = 0;
    if (std::rename(path_.c_str(), target_.c_str()) != 0) {
      throw makeError(target_, "cannot replace file (" + errnoText(errno, "rename failed") + ")");
    }
    committed_ = true;
  }

 private:
  std::string target_;
  std::string path_;
  bool committed_ = false;
};

// One EXR channel of a surface AOV: its name (layer.channel), the frame
// plane it is read from and that plane's floats (or uints) per pixel.
struct ExrPlane {
  const char* channel;
  Imf::PixelType type;
  const char* base;
  std::size_t size;  // elements in the plane
  int stride;        // elements per pixel
};

// The frame's surface AOV channels (docs/cli.md "AOVs"), those it has.
std::vector<ExrPlane> exrAovPlanes(const Frame& frame) {
  std::vector<ExrPlane> planes;
  const auto floats = [&](const std::vector<float>& plane,
                          std::initializer_list<const char*> names) {
    int c = 0;
    if (plane.empty()) return;
    for (const char* name : names)
      planes.push_back({name, Imf::FLOAT, reinterpret_cast<const char*>(plane.data() + c++),
                        plane.size(), int(names.size())});
  };
  floats(frame.normal, {"N.X", "N.Y", "N.Z"});
  floats(frame.position, {"P.X", "P.Y", "P.Z"});
  floats(frame.uv, {"uv.U", "uv.V"});
  floats(frame.motion, {"motion.X", "motion.Y"});
  floats(frame.lod, {"lod"});
  floats(frame.anisotropy, {"anisotropy"});
  floats(frame.albedo, {"albedo.R", "albedo.G", "albedo.B"});
  floats(frame.roughness, {"roughness"});
  floats(frame.metallic, {"metallic"});
  floats(frame.emission, {"emission.R", "emission.G", "emission.B"});
  floats(frame.diffuse, {"diffuse.R", "diffuse.G", "diffuse.B"});
  floats(frame.specular, {"specular.R", "specular.G", "specular.B"});
  const auto ids = [&](const std::vector<std::uint32_t>& plane, const char* name) {
    if (!plane.empty())
      planes.push_back(
          {name, Imf::UINT, reinterpret_cast<const char*>(plane.data()), plane.size(), 1});
  };
  ids(frame.primitiveId, "id.primitive");
  ids(frame.nodeId, "id.node");
  ids(frame.materialId, "id.material");
  return planes;
}

Imath::M44f toImath(const glm::mat4& m) {
  // glm is column-major for column vectors, Imath row-major for row
  // vectors: the same 16 numbers in the same order.
  Imath::M44f out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[i][j] = m[i][j];
  return out;
}

void checkFrame(const Frame& frame, const std::string& path, bool needsDepth) {
  if (frame.width <= 0 || frame.height <= 0) throw makeError(path, "cannot write an empty image");
  const std::size_t pixels = std::size_t(frame.width) * std::size_t(frame.height);
  if (frame.rgba.size() != pixels * 4) {
    throw makeError(path, "frame colour buffer does not match its size");
  }
  if (needsDepth && frame.depth.empty()) {
    throw makeError(path, "the frame has no depth for the Z channel (render it with frameDepth)");
  }
  if (needsDepth && frame.depth.size() != pixels) {
    throw makeError(path, "frame depth buffer does not match its size");
  }
  if (!frame.coverage.empty() && frame.coverage.size() != pixels) {
    throw makeError(path, "frame coverage buffer does not match its size");
  }
  for (const ExrPlane& plane : exrAovPlanes(frame))
    if (plane.size != pixels * std::size_t(plane.stride))
      throw makeError(path,
                      std::string("frame ") + plane.channel + " buffer does not match its size");
}

// ---- EXR --------------------------------------------------------------------

// ExrSettings' compressions, by name and as OpenEXR's.
struct ExrCompressionName {
  ExrCompression compression;
  const char* name;
  Imf::Compression exr;
};
constexpr ExrCompressionName kExrCompressions[] = {
    {ExrCompression::None, "none", Imf::NO_COMPRESSION},
    {ExrCompression::Rle, "rle", Imf::RLE_COMPRESSION},
    {ExrCompression::Zips, "zips", Imf::ZIPS_COMPRESSION},
    {ExrCompression::Zip, "zip", Imf::ZIP_COMPRESSION},
    {ExrCompression::Piz, "piz", Imf::PIZ_COMPRESSION},
};

void writeExrStream(const Frame& frame, std::ofstream& stream, const std::string& name,
                    const ExrSettings& settings, const Executor* executor) {
  Imf::Header header(frame.width, frame.height);
  for (const ExrCompressionName& c : kExrCompressions)
    if (c.compression == settings.compression) header.compression() = c.exr;
  // zlib's fastest level: a 1080p frame writes in 125 ms instead of 300 at
  // OpenEXR's default level 4, for files 10% larger (builtin:flyover,
  // 2026-11-27), and a sequence's frames/s is its writer's when writing is
  // the slower half.
  header.zipCompressionLevel() = 1;
  const Imf::PixelType colour = settings.halfColour ? Imf::HALF : Imf::FLOAT;
  for (const char* channel : {"R", "G", "B", "A"})
    header.channels().insert(channel, Imf::Channel(colour));
  header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
  if (!frame.coverage.empty()) header.channels().insert(kCoverageChannel, Imf::Channel(Imf::FLOAT));
  const std::vector<ExrPlane> aovs = exrAovPlanes(frame);
  for (const ExrPlane& plane : aovs)
    header.channels().insert(plane.channel, Imf::Channel(plane.type));
  if (frame.metadata.hasCamera) {
    Imf::addWorldToCamera(header, toImath(frame.metadata.worldToCamera));
    Imf::addWorldToNDC(header, toImath(frame.metadata.worldToNDC));
  }
  for (const auto& [name, value] : frame.metadata.strings)
    header.insert(name, Imf::StringAttribute(value));
  const Imath::V2i origin(0, 0);
  Imf::FrameBuffer buffer;
  const char* const rgbaNames[4] = {"R", "G", "B", "A"};
  if (!settings.halfColour)
    for (int c = 0; c < 4; ++c)
      buffer.insert(rgbaNames[c], Imf::Slice::Make(Imf::FLOAT, frame.rgba.data() + c, origin,
                                                   frame.width, frame.height, 4 * sizeof(float),
                                                   std::size_t(frame.width) * 4 * sizeof(float)));
  const std::size_t planeRow = std::size_t(frame.width) * sizeof(float);
  buffer.insert("Z", Imf::Slice::Make(Imf::FLOAT, frame.depth.data(), origin, frame.width,
                                      frame.height, sizeof(float), planeRow));
  if (!frame.coverage.empty())
    buffer.insert(kCoverageChannel,
                  Imf::Slice::Make(Imf::FLOAT, frame.coverage.data(), origin, frame.width,
                                   frame.height, sizeof(float), planeRow));
  for (const ExrPlane& plane : aovs) {
    const std::size_t element = 4;  // FLOAT and UINT
    const std::size_t pixelBytes = element * std::size_t(plane.stride);
    buffer.insert(plane.channel,
                  Imf::Slice::Make(plane.type, plane.base, origin, frame.width, frame.height,
                                   pixelBytes, pixelBytes * std::size_t(frame.width)));
  }
  Imf::StdOFStream exrStream(stream, name.c_str());
  // The OutputFile's destructor writes the scanline offset table; it swallows
  // errors there, which the caller detects from the stream's state afterwards.
  Imf::OutputFile file(exrStream, header);
  if (!settings.halfColour) {
    file.setFrameBuffer(buffer);
    file.writePixels(frame.height);
    return;
  }
  // OpenEXR writes a slice only into a channel of its own type, so half
  // colour is converted first (the texel encoder's rounding: to nearest
  // even, NaN stored as 0), a band of rows at a time into one small buffer:
  // converted whole into a fresh 16 MB buffer, a 1080p frame's faulting in
  // made half colour cost 160-220 ms to write uncompressed against float's
  // 30-80; in bands 53-70 against 40-44 (builtin:flyover to /dev/shm,
  // --stats write=, 2026-11-28, the shared VM at load 9).
  constexpr int kBandRows = 64;
  const std::size_t rowHalves = std::size_t(frame.width) * 4;
  std::vector<std::uint16_t> halves(rowHalves * kBandRows);
  for (int first = 0; first < frame.height; first += kBandRows) {
    const int rows = std::min(kBandRows, frame.height - first);
    const auto convert = [&](std::size_t begin, std::size_t end) {
      encodeTexels(TexelFormat::Rgba16F,
                   frame.rgba.data() + (std::size_t(first) + begin) * rowHalves,
                   (end - begin) * std::size_t(frame.width),
                   reinterpret_cast<std::uint8_t*>(halves.data() + begin * rowHalves));
    };
    if (executor)
      executor->parallelFor(std::size_t(rows), 8, convert);
    else
      convert(0, std::size_t(rows));
    Imf::FrameBuffer band = buffer;
    for (int c = 0; c < 4; ++c)
      band.insert(rgbaNames[c], Imf::Slice::Make(Imf::HALF, halves.data() + c, Imath::V2i(0, first),
                                                 frame.width, rows, sizeof(std::uint16_t) * 4,
                                                 sizeof(std::uint16_t) * rowHalves));
    file.setFrameBuffer(band);
    file.writePixels(rows);
  }
}

}  // namespace

const char* exrCompressionName(ExrCompression compression) {
  for (const ExrCompressionName& c : kExrCompressions)
    if (c.compression == compression) return c.name;
  return "?";
}

bool parseExrCompression(const std::string& name, ExrCompression& out) {
  for (const ExrCompressionName& c : kExrCompressions)
    if (name == c.name) {
      out = c.compression;
      return true;
    }
  return false;
}

std::string exrCompressionNames() {
  std::string names;
  for (const ExrCompressionName& c : kExrCompressions)
    names += (names.empty() ? "" : ", ") + std::string(c.name);
  return names;
}

void writeExr(const Frame& frame, const std::string& path, const ExrSettings& settings,
              const Executor* executor) {
  checkFrame(frame, path, true);
  TempFile temp(path);
  std::ofstream stream;
  errno = 0;
  stream.open(temp.path(), std::ios::binary | std::ios::out | std::ios::trunc);
  if (!stream) {
    throw makeError(path, "cannot create file (" + errnoText(errno, "open failed") + ")");
  }
  try {
    writeExrStream(frame, stream, path, settings, executor);  // messages name the real target
  } catch (const std::exception& e) {
    throw makeError(path, "cannot write EXR (" + oneLine(e.what()) + ")");
  }
  stream.close();
  if (stream.fail()) throw makeError(path, "cannot write EXR (write failed)");
  temp.commit();
}

// ---- PNG out ----------------------------------------------------------------

namespace {

// The PNG's pixel data is one zlib stream; quadra cuts it into bands of rows,
// each encoded and deflated on its own (a sync flush ends each band, so the
// bands concatenate into one valid stream, as pigz does) and written as IDAT
// chunks in order. Bands are fixed in rows, not in threads, so the bytes are
// the same for any thread count. Filter None and zlib level 3 are what
// libpng's fast simplified writer used before (PNG_IMAGE_FLAG_FAST).
constexpr int kPngBandRows = 32;
constexpr int kPngZlibLevel = 3;

struct PngBand {
  std::vector<std::uint8_t> deflated;
  uLong adler = 0;  // of the band's filtered rows
  std::size_t rawBytes = 0;
  bool failed = false;
};

void deflateBand(const Frame& frame, ToneMap toneMap, int firstRow, int rows, bool last,
                 PngBand& band) {
  const std::size_t rowBytes = 1 + std::size_t(frame.width) * 4;  // filter byte, then RGBA
  std::vector<std::uint8_t> raw(rowBytes * std::size_t(rows));
  for (int y = 0; y < rows; ++y) {
    std::uint8_t* row = &raw[std::size_t(y) * rowBytes];
    row[0] = 0;  // filter type None
    const float* rgba = &frame.rgba[std::size_t(firstRow + y) * std::size_t(frame.width) * 4];
    encodeDisplayRow(toneMap, rgba, frame.width, row + 1);
  }
  band.rawBytes = raw.size();
  band.adler = adler32(adler32(0, nullptr, 0), raw.data(), uInt(raw.size()));
  z_stream z{};
  // Raw deflate (no zlib header per band); the file carries one header.
  if (deflateInit2(&z, kPngZlibLevel, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    band.failed = true;
    return;
  }
  band.deflated.resize(deflateBound(&z, uLong(raw.size())) + 64);
  z.next_in = raw.data();
  z.avail_in = uInt(raw.size());
  z.next_out = band.deflated.data();
  z.avail_out = uInt(band.deflated.size());
  const int status = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
  band.failed =
      z.avail_out == 0 || (last ? status != Z_STREAM_END : (status != Z_OK || z.avail_in != 0));
  band.deflated.resize(band.deflated.size() - z.avail_out);
  deflateEnd(&z);
}

void putBigEndian32(std::uint32_t value, std::uint8_t* out) {
  for (int i = 0; i < 4; ++i) out[i] = std::uint8_t(value >> (24 - 8 * i));
}

// One chunk: length, type, data, CRC of type and data.
bool writePngChunk(std::FILE* file, const char type[4], const std::uint8_t* data,
                   std::size_t size) {
  std::uint8_t head[8];
  putBigEndian32(std::uint32_t(size), head);
  std::memcpy(head + 4, type, 4);
  uLong crc = crc32(crc32(0, nullptr, 0), head + 4, 4);
  if (size > 0) crc = crc32(crc, data, uInt(size));
  std::uint8_t tail[4];
  putBigEndian32(std::uint32_t(crc), tail);
  return std::fwrite(head, 1, 8, file) == 8 &&
         (size == 0 || std::fwrite(data, 1, size, file) == size) &&
         std::fwrite(tail, 1, 4, file) == 4;
}

}  // namespace

void writePng(const Frame& frame, const std::string& path, const Executor* executor,
              ToneMap toneMap) {
  checkFrame(frame, path, false);
  const int bands = (frame.height + kPngBandRows - 1) / kPngBandRows;
  std::vector<PngBand> deflated(static_cast<std::size_t>(bands));
  const auto deflateBands = [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b) {
      const int first = int(b) * kPngBandRows;
      deflateBand(frame, toneMap, first, std::min(kPngBandRows, frame.height - first),
                  b + 1 == deflated.size(), deflated[b]);
    }
  };
  if (executor)
    executor->parallelFor(deflated.size(), 1, deflateBands);
  else
    deflateBands(0, deflated.size());
  for (const PngBand& band : deflated)
    if (band.failed) throw makeError(path, "cannot write PNG (zlib could not compress it)");

  TempFile temp(path);
  errno = 0;
  std::FILE* file = std::fopen(temp.path().c_str(), "wb");
  if (file == nullptr) {
    throw makeError(path, "cannot create file (" + errnoText(errno, "open failed") + ")");
  }
  static const std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::uint8_t header[13];
  putBigEndian32(std::uint32_t(frame.width), header);
  putBigEndian32(std::uint32_t(frame.height), header + 4);
  header[8] = 8;                             // bits per sample
  header[9] = 6;                             // RGBA
  header[10] = header[11] = header[12] = 0;  // deflate, adaptive filtering, no interlace
  bool ok = std::fwrite(kSignature, 1, 8, file) == 8 && writePngChunk(file, "IHDR", header, 13);
  // The zlib stream: its header, the bands, then the Adler-32 of all rows.
  uLong adler = adler32(0, nullptr, 0);
  for (std::size_t b = 0; b < deflated.size() && ok; ++b) {
    std::vector<std::uint8_t>& data = deflated[b].deflated;
    adler = adler32_combine(adler, deflated[b].adler, z_off_t(deflated[b].rawBytes));
    if (b == 0) data.insert(data.begin(), {0x78, 0x5E});  // deflate, 32 KiB window
    if (b + 1 == deflated.size()) {
      std::uint8_t check[4];
      putBigEndian32(std::uint32_t(adler), check);
      data.insert(data.end(), check, check + 4);
    }
    ok = writePngChunk(file, "IDAT", data.data(), data.size());
  }
  ok = ok && writePngChunk(file, "IEND", nullptr, 0);
  const int writeError = errno;
  const bool closed = std::fclose(file) == 0;
  const int closeError = errno;
  if (!ok) {
    throw makeError(path, "cannot write PNG (" + errnoText(writeError, "write failed") + ")");
  }
  if (!closed) {
    throw makeError(path, "cannot write PNG (" + errnoText(closeError, "close failed") + ")");
  }
  temp.commit();
}

void writeFrame(const Frame& frame, const std::string& path, const Executor* executor,
                const ExrSettings& exr, ToneMap pngToneMap) {
  const std::string ext = lowerExtension(path);
  if (ext == ".exr") return writeExr(frame, path, exr, executor);
  if (ext == ".png") return writePng(frame, path, executor, pngToneMap);
  throw makeError(path, "unsupported output format (use .exr or .png)");
}

// ---- PNG in -----------------------------------------------------------------

namespace {

// Everything libpng may longjmp across: plain data only, so no destructor is
// ever skipped.
struct PngDecoder {
  png_structp png = nullptr;
  png_infop info = nullptr;
  char message[200] = {};
};

struct PngLayout {
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int bitDepth = 0;
  int channels = 0;
  std::size_t rowBytes = 0;
  bool interlaced = false;
  ImageColour colour = ImageColour::Srgb;
};

void pngErrorToMessage(png_structp png, png_const_charp text) {
  auto* decoder = static_cast<PngDecoder*>(png_get_error_ptr(png));
  std::snprintf(decoder->message, sizeof(decoder->message), "%s", text);
  png_longjmp(png, 1);
}

void pngIgnoreWarning(png_structp, png_const_charp) {}

// Bytes in memory as a libpng input (a glTF's embedded or stashed image).
struct PngMemory {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t at;
};

void readPngMemory(png_structp png, png_bytep out, png_size_t count) {
  auto* source = static_cast<PngMemory*>(png_get_io_ptr(png));
  if (count > source->size - source->at) png_error(png, "unexpected end of data");
  std::memcpy(out, source->data + source->at, count);
  source->at += count;
}

// Reads the header and asks libpng for 8/16-bit grey or RGB, with or without
// alpha (palettes and sub-byte depths expanded, grey widened to RGB). No
// gamma or colour-profile chunk is applied: samples are the stored codes.
bool decodePngHeader(PngDecoder& d, PngLayout& layout) {
  if (setjmp(png_jmpbuf(d.png))) return false;
  png_read_info(d.png, d.info);
  png_set_expand(d.png);
  png_set_gray_to_rgb(d.png);
  png_set_interlace_handling(d.png);
  png_read_update_info(d.png, d.info);
  layout.width = png_get_image_width(d.png, d.info);
  layout.height = png_get_image_height(d.png, d.info);
  layout.bitDepth = png_get_bit_depth(d.png, d.info);
  layout.channels = png_get_channels(d.png, d.info);
  layout.rowBytes = png_get_rowbytes(d.png, d.info);
  layout.interlaced = png_get_interlace_type(d.png, d.info) != PNG_INTERLACE_NONE;
  return true;
}

// One row of 8-bit codes, `channels` (3 or 4) per pixel, sRGB colour and
// linear alpha -> linear float RGBA, through the sRGB table fetched once per
// row: through srgb8ToLinear, a call and a guard check per sample, a 2048²
// texture's conversion took a fifth of its model's load. Alpha decodes as
// the 8-bit texel formats decode it (lossless rgba8srgb). PNG and JPEG rows.
// Linear colour (data textures: normals, metallic-roughness, occlusion)
// decodes every channel as alpha does.
void srgb8RowToLinear(const std::uint8_t* samples, std::size_t channels, std::size_t width,
                      float* out, ImageColour colour) {
  if (colour == ImageColour::Linear) {
    for (std::size_t x = 0; x < width; ++x, samples += channels, out += 4) {
      for (std::size_t c = 0; c < 3; ++c) out[c] = float(samples[c]) * kUnorm8Scale;
      out[3] = channels == 4 ? float(samples[3]) * kUnorm8Scale : 1.0f;
    }
    return;
  }
  const float* table = srgb8ToLinearTable();
  for (std::size_t x = 0; x < width; ++x, samples += channels, out += 4) {
    out[0] = table[samples[0]];
    out[1] = table[samples[1]];
    out[2] = table[samples[2]];
    out[3] = channels == 4 ? float(samples[3]) * kUnorm8Scale : 1.0f;
  }
}

// One decoded PNG row (big-endian when 16-bit) -> linear float RGBA.
void pngRowToLinear(const png_byte* samples, const PngLayout& layout, float* out) {
  const std::size_t channels = std::size_t(layout.channels);  // 3 or 4 after png_set_expand
  if (layout.bitDepth == 8)
    return srgb8RowToLinear(samples, channels, layout.width, out, layout.colour);
  const auto code = [&](std::size_t c) {
    return float((unsigned(samples[2 * c]) << 8) | samples[2 * c + 1]) / 65535.0f;
  };
  const bool srgb = layout.colour == ImageColour::Srgb;
  for (png_uint_32 x = 0; x < layout.width; ++x, samples += 2 * channels, out += 4) {
    for (std::size_t c = 0; c < 3; ++c) out[c] = srgb ? srgbToLinear(code(c)) : code(c);
    out[3] = channels == 4 ? code(3) : 1.0f;
  }
}

// Non-interlaced images go a row at a time through one row buffer, straight
// into the Image: no whole-image buffer of codes.
bool decodePngRowByRow(PngDecoder& d, const PngLayout& layout, png_bytep row, Image& image) {
  if (setjmp(png_jmpbuf(d.png))) return false;
  for (png_uint_32 y = 0; y < layout.height; ++y) {
    png_read_row(d.png, row, nullptr);
    pngRowToLinear(row, layout, image.texel(0, int(y)));
  }
  png_read_end(d.png, nullptr);
  return true;
}

bool decodePngRows(PngDecoder& d, png_bytepp rows) {
  if (setjmp(png_jmpbuf(d.png))) return false;
  png_read_image(d.png, rows);
  png_read_end(d.png, nullptr);
  return true;
}

// Decodes one PNG from a FILE positioned after its signature or from memory;
// errors name `source` (a path, or what the caller calls the bytes).
class PngReader {
 public:
  PngReader() {
    decoder_.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &decoder_, pngErrorToMessage,
                                          pngIgnoreWarning);
    if (decoder_.png != nullptr) decoder_.info = png_create_info_struct(decoder_.png);
    if (decoder_.info == nullptr) throw std::bad_alloc();
  }
  ~PngReader() { png_destroy_read_struct(&decoder_.png, &decoder_.info, nullptr); }
  PngReader(const PngReader&) = delete;
  PngReader& operator=(const PngReader&) = delete;

  Image read(std::FILE* file, const std::string& path) {
    png_init_io(decoder_.png, file);
    png_set_sig_bytes(decoder_.png, 8);
    return decode(path, nullptr, nullptr, ImageColour::Srgb);
  }

  Image read(const std::uint8_t* data, std::size_t size, const std::string& source,
             int* bitsPerChannel, const Executor* executor, ImageColour colour) {
    PngMemory memory{data, size, 0};
    png_set_read_fn(decoder_.png, &memory, readPngMemory);
    return decode(source, bitsPerChannel, executor, colour);
  }

 private:
  Image decode(const std::string& source, int* bitsPerChannel, const Executor* executor,
               ImageColour colour) {
    PngLayout layout;
    if (!decodePngHeader(decoder_, layout)) throw failure(source);
    layout.colour = colour;
    if (std::int64_t(layout.width) * layout.height > kMaxImagePixels) {
      throw makeError(source, tooLargeText(layout.width, layout.height));
    }
    if (bitsPerChannel != nullptr) *bitsPerChannel = layout.bitDepth;
    Image image(static_cast<int>(layout.width), static_cast<int>(layout.height), executor);
    if (!layout.interlaced) {
      std::vector<png_byte> row(layout.rowBytes);
      if (!decodePngRowByRow(decoder_, layout, row.data(), image)) throw failure(source);
      return image;
    }
    std::vector<png_byte> samples;
    resizeLarge(samples, layout.rowBytes * layout.height);
    std::vector<png_bytep> rows(layout.height);
    for (png_uint_32 y = 0; y < layout.height; ++y) rows[y] = &samples[y * layout.rowBytes];
    if (!decodePngRows(decoder_, rows.data())) throw failure(source);
    for (png_uint_32 y = 0; y < layout.height; ++y)
      pngRowToLinear(rows[y], layout, image.texel(0, int(y)));
    return image;
  }

  Error failure(const std::string& source) const {
    return makeError(source, std::string("invalid or truncated PNG (") + decoder_.message + ")");
  }
  PngDecoder decoder_;
};

// ---- JPEG in ----------------------------------------------------------------

// libjpeg-turbo's errors, like libpng's, unwind by longjmp out of functions
// that hold no C++ objects. Its corrupt-data warnings (a truncated or
// damaged stream, which it would fill with grey) are errors here: no image
// is better than a silently wrong one.
struct JpegDecoder {
  jpeg_decompress_struct info{};
  jpeg_error_mgr errors{};
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = {};
};

[[noreturn]] void jpegFail(j_common_ptr info) {
  auto* decoder = reinterpret_cast<JpegDecoder*>(info->client_data);
  (*info->err->format_message)(info, decoder->message);
  std::longjmp(decoder->jump, 1);
}

void jpegMessage(j_common_ptr info, int level) {
  if (level < 0) jpegFail(info);  // a warning: corrupt data
}

bool createJpeg(JpegDecoder& d) {
  if (setjmp(d.jump)) return false;
  jpeg_create_decompress(&d.info);
  return true;
}

bool decodeJpegHeader(JpegDecoder& d, const std::uint8_t* data, std::size_t size) {
  if (setjmp(d.jump)) return false;
  jpeg_mem_src(&d.info, data, static_cast<unsigned long>(size));
  jpeg_read_header(&d.info, TRUE);
  return true;
}

// Starts decompression into 8-bit RGB (greyscale expanded).
bool startJpeg(JpegDecoder& d) {
  if (setjmp(d.jump)) return false;
  d.info.out_color_space = JCS_RGB;
  jpeg_start_decompress(&d.info);
  return true;
}

bool decodeJpegRows(JpegDecoder& d, JSAMPROW row, float* image, std::size_t rowFloats,
                    ImageColour colour) {
  if (setjmp(d.jump)) return false;
  const std::size_t width = d.info.output_width;
  while (d.info.output_scanline < d.info.output_height) {
    const std::size_t y = d.info.output_scanline;
    if (jpeg_read_scanlines(&d.info, &row, 1) != 1) return false;
    srgb8RowToLinear(row, 3, width, image + y * rowFloats, colour);
  }
  jpeg_finish_decompress(&d.info);
  return true;
}

class JpegReader {
 public:
  JpegReader() {
    decoder_.info.err = jpeg_std_error(&decoder_.errors);
    decoder_.errors.error_exit = jpegFail;
    decoder_.errors.emit_message = jpegMessage;
    decoder_.info.client_data = &decoder_;
    if (!createJpeg(decoder_)) throw std::bad_alloc();  // its only failure
  }
  ~JpegReader() { jpeg_destroy_decompress(&decoder_.info); }
  JpegReader(const JpegReader&) = delete;
  JpegReader& operator=(const JpegReader&) = delete;

  Image read(const std::uint8_t* data, std::size_t size, const std::string& source,
             const Executor* executor, ImageColour colour = ImageColour::Srgb) {
    if (!decodeJpegHeader(decoder_, data, size)) throw failure(source);
    const J_COLOR_SPACE space = decoder_.info.jpeg_color_space;
    if (space != JCS_GRAYSCALE && space != JCS_YCbCr && space != JCS_RGB)
      throw makeError(source, "CMYK and YCCK JPEG images are not supported");
    const std::int64_t width = decoder_.info.image_width, height = decoder_.info.image_height;
    if (width * height > kMaxImagePixels) throw makeError(source, tooLargeText(width, height));
    if (!startJpeg(decoder_)) throw failure(source);
    Image image(int(decoder_.info.output_width), int(decoder_.info.output_height), executor);
    std::vector<JSAMPLE> row(std::size_t(image.width) * 3);
    if (!decodeJpegRows(decoder_, row.data(), image.rgba.data(), std::size_t(image.width) * 4,
                        colour))
      throw failure(source);
    return image;
  }

 private:
  Error failure(const std::string& source) const {
    return makeError(source,
                     std::string("invalid or truncated JPEG (") + oneLine(decoder_.message) + ")");
  }
  JpegDecoder decoder_;
};

// ---- EXR in -----------------------------------------------------------------

// Which stored channel feeds each of R, G, B, A; a luminance-only file's Y
// feeds all three colours.
struct ExrSources {
  const char* names[4] = {"R", "G", "B", "A"};
  bool greyFromY = false;
};

ExrSources exrSources(const Imf::ChannelList& channels, const std::string& path) {
  ExrSources sources;
  const bool hasColour =
      channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
  if (!hasColour && channels.findChannel("Y")) {
    if (channels.findChannel("RY") || channels.findChannel("BY")) {
      throw makeError(path, "luminance/chroma EXR images are not supported");
    }
    sources.names[0] = "Y";
    sources.greyFromY = true;
  }
  for (const char* name : sources.names) {
    const Imf::Channel* channel = channels.findChannel(name);
    if (channel && (channel->xSampling != 1 || channel->ySampling != 1)) {
      throw makeError(path, "subsampled EXR channels are not supported");
    }
  }
  return sources;
}

// The data window's size, refused when empty or over kMaxImagePixels.
void exrSize(const Imf::InputFile& file, const std::string& path, std::int64_t& width,
             std::int64_t& height) {
  const Imath::Box2i window = file.header().dataWindow();
  width = std::int64_t(window.max.x) - window.min.x + 1;
  height = std::int64_t(window.max.y) - window.min.y + 1;
  if (width <= 0 || height <= 0) throw makeError(path, "empty EXR data window");
  if (width * height > kMaxImagePixels) throw makeError(path, tooLargeText(width, height));
}

// Reads R, G, B (and A when texelFloats is 4) of the whole data window into
// `pixels`, texelFloats floats a texel, row by row; missing channels are 0
// (A: 1).
void readExrPixels(Imf::InputFile& file, const std::string& path, int texelFloats, float* pixels) {
  const Imath::Box2i window = file.header().dataWindow();
  const std::size_t width = std::size_t(std::int64_t(window.max.x) - window.min.x + 1);
  const ExrSources sources = exrSources(file.header().channels(), path);
  const std::size_t texelBytes = std::size_t(texelFloats) * sizeof(float);
  Imf::FrameBuffer buffer;
  for (int c = 0; c < texelFloats; ++c) {
    if (sources.greyFromY && c > 0 && c < 3) continue;
    const double fill = c == 3 ? 1.0 : 0.0;
    buffer.insert(sources.names[c], Imf::Slice::Make(Imf::FLOAT, pixels + c, window, texelBytes,
                                                     texelBytes * width, 1, 1, fill));
  }
  file.setFrameBuffer(buffer);
  file.readPixels(window.min.y, window.max.y);
  if (sources.greyFromY) {
    const std::size_t floats = width * std::size_t(window.max.y - window.min.y + 1) * texelFloats;
    for (std::size_t i = 0; i < floats; i += std::size_t(texelFloats))
      pixels[i + 1] = pixels[i + 2] = pixels[i];
  }
}

Image readExr(const std::string& path) {
  Imf::InputFile file(path.c_str());
  std::int64_t width = 0, height = 0;
  exrSize(file, path, width, height);
  Image image(static_cast<int>(width), static_cast<int>(height));
  readExrPixels(file, path, 4, image.rgba.data());
  return image;
}

enum class FileKind { Png, Jpeg, Exr, Unknown };

FileKind sniff(std::FILE* file, const std::string& path) {
  unsigned char magic[8] = {};
  errno = 0;
  const std::size_t got = std::fread(magic, 1, sizeof(magic), file);
  if (got < sizeof(magic) && std::ferror(file)) {
    throw makeError(path, "cannot read file (" + errnoText(errno, "read failed") + ")");
  }
  if (got == sizeof(magic) && png_sig_cmp(magic, 0, sizeof(magic)) == 0) return FileKind::Png;
  if (isJpeg(magic, got)) return FileKind::Jpeg;
  const unsigned char exrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
  if (got >= 4 && std::memcmp(magic, exrMagic, 4) == 0) return FileKind::Exr;
  return FileKind::Unknown;
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

bool isPng(const std::uint8_t* data, std::size_t size) {
  return size >= 8 && png_sig_cmp(data, 0, 8) == 0;
}

Image decodePng(const std::uint8_t* data, std::size_t size, const std::string& source,
                int* bitsPerChannel, const Executor* executor, ImageColour colour) {
  if (!isPng(data, size)) throw makeError(source, "not a PNG image");
  try {
    return PngReader().read(data, size, source, bitsPerChannel, executor, colour);
  } catch (const std::bad_alloc&) {
    throw makeError(source, "out of memory while decoding PNG");
  }
}

bool isJpeg(const std::uint8_t* data, std::size_t size) {
  return size >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF;
}

Image decodeJpeg(const std::uint8_t* data, std::size_t size, const std::string& source,
                 const Executor* executor, ImageColour colour) {
  if (!isJpeg(data, size)) throw makeError(source, "not a JPEG image");
  try {
    return JpegReader().read(data, size, source, executor, colour);
  } catch (const std::bad_alloc&) {
    throw makeError(source, "out of memory while decoding JPEG");
  }
}

Image readImage(const std::string& path) {
  errno = 0;
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw makeError(path, "cannot open file (" + errnoText(errno, "open failed") + ")");
  const FileKind kind = sniff(file.get(), path);
  try {
    if (kind == FileKind::Png) return PngReader().read(file.get(), path);
    if (kind == FileKind::Jpeg) {
      // libjpeg reads from memory here, as for glTF images: one decoder setup.
      file.reset();
      const std::vector<std::uint8_t> bytes = readWholeFile(path);
      return JpegReader().read(bytes.data(), bytes.size(), path, nullptr);
    }
    if (kind == FileKind::Exr) {
      file.reset();
      return readExr(path);
    }
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw makeError(path, "out of memory while reading image");
  } catch (const std::exception& e) {
    const char* format = kind == FileKind::Png ? "PNG" : kind == FileKind::Jpeg ? "JPEG" : "EXR";
    throw makeError(path,
                    std::string("invalid or truncated ") + format + " (" + oneLine(e.what()) + ")");
  }
  throw makeError(path, "not a PNG, JPEG or OpenEXR image");
}

RgbImage readExrRgb(const std::string& path, const AdmitImageSize& admit) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::ChannelList& channels = file.header().channels();
    if (!channels.findChannel("R") && !channels.findChannel("G") && !channels.findChannel("B") &&
        !channels.findChannel("Y"))
      throw makeError(path, "EXR has no colour channel (R, G, B or Y)");
    std::int64_t width = 0, height = 0;
    exrSize(file, path, width, height);
    admit(width, height);
    RgbImage image;
    image.width = int(width);
    image.height = int(height);
    image.rgb.resize(std::size_t(width) * std::size_t(height) * 3);
    readExrPixels(file, path, 3, image.rgb.data());
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw makeError(path, "out of memory while reading EXR");
  } catch (const std::exception& e) {
    throw makeError(path, "invalid or truncated EXR (" + oneLine(e.what()) + ")");
  }
}

void writeExrRgb(const float* rgb, int width, int height, const std::string& path) {
  if (width <= 0 || height <= 0) throw makeError(path, "cannot write an empty image");
  TempFile temp(path);
  std::ofstream stream;
  errno = 0;
  stream.open(temp.path(), std::ios::binary | std::ios::out | std::ios::trunc);
  if (!stream)
    throw makeError(path, "cannot create file (" + errnoText(errno, "open failed") + ")");
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    const std::size_t texelBytes = 3 * sizeof(float);
    Imf::FrameBuffer buffer;
    const char* const names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      buffer.insert(names[c], Imf::Slice::Make(Imf::FLOAT, rgb + c, Imath::V2i(0, 0), width, height,
                                               texelBytes, texelBytes * std::size_t(width)));
    }
    Imf::StdOFStream exrStream(stream, path.c_str());
    Imf::OutputFile file(exrStream, header);
    file.setFrameBuffer(buffer);
    file.writePixels(height);
  } catch (const std::exception& e) {
    throw makeError(path, "cannot write EXR (" + oneLine(e.what()) + ")");
  }
  stream.close();
  if (stream.fail()) throw makeError(path, "cannot write EXR (write failed)");
  temp.commit();
}

}  // namespace quadra
