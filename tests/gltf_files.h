// Writing glTF files for tests: a document built from JSON fragments and one
// binary buffer (written as .gltf + .bin or as .glb), a scratch folder per
// test, PNGs encoded with stored deflate blocks (exact bytes, no
// compression), base64 for data URIs, and the loader's one-line error.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/gltf_loader.h"

namespace quadra::gltf_files {

namespace fs = std::filesystem;

constexpr int kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125,
              kFloat = 5126;

// ---- file writing helpers -----------------------------------------------------------

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ =
        fs::temp_directory_path() / ("quadra_gltf_" + std::string(info->test_suite_name()) + "_" +
                                     info->name() + "_" + std::to_string(std::random_device{}()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

inline void writeBytes(const std::string& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), std::streamsize(size));
  ASSERT_TRUE(out.good()) << path;
}

inline void writeText(const std::string& path, const std::string& text) {
  writeBytes(path, text.data(), text.size());
}

inline void putU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}

inline void putU32BigEndian(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 3; i >= 0; --i) out.push_back(std::uint8_t(v >> (8 * i)));
}

// A glTF document under construction: arrays of JSON objects plus one binary
// buffer, written out as .gltf + .bin or as a .glb.
struct Doc {
  std::vector<std::uint8_t> bin;
  std::vector<std::string> bufferViews, accessors, meshes, nodes, scenes, materials, textures,
      images, samplers, cameras;
  std::string extraTopLevel;  // e.g. "\"extensionsRequired\":[\"X\"]"
  int defaultScene = -1;

  template <typename T>
  int addView(const std::vector<T>& data, int stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    const std::size_t offset = bin.size();
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(data.data());
    bin.insert(bin.end(), bytes, bytes + data.size() * sizeof(T));
    std::string view = "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
                       ",\"byteLength\":" + std::to_string(data.size() * sizeof(T));
    if (stride) view += ",\"byteStride\":" + std::to_string(stride);
    bufferViews.push_back(view + "}");
    return int(bufferViews.size()) - 1;
  }

  int addAccessor(int view, int componentType, std::uint64_t count, const std::string& type,
                  const std::string& extra = "") {
    std::string a = "{";
    if (view >= 0) a += "\"bufferView\":" + std::to_string(view) + ",";
    a += "\"componentType\":" + std::to_string(componentType) +
         ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type + "\"";
    if (!extra.empty()) a += "," + extra;
    accessors.push_back(a + "}");
    return int(accessors.size()) - 1;
  }

  template <typename T>
  int addData(const std::vector<T>& data, int componentType, int components,
              const std::string& extra = "") {
    static const char* const types[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
    const int view = addView(data);
    return addAccessor(view, componentType, data.size() / std::size_t(components),
                       types[components], extra);
  }

  int addMesh(const std::string& primitivesJson) {
    meshes.push_back("{\"primitives\":[" + primitivesJson + "]}");
    return int(meshes.size()) - 1;
  }

  int addNode(const std::string& body) {
    nodes.push_back("{" + body + "}");
    return int(nodes.size()) - 1;
  }

  std::string json(const std::string& bufferUri) const {
    std::string j = "{\"asset\":{\"version\":\"2.0\"}";
    auto array = [&j](const char* name, const std::vector<std::string>& items) {
      if (items.empty()) return;
      j += std::string(",\"") + name + "\":[";
      for (std::size_t i = 0; i < items.size(); ++i) j += (i ? "," : "") + items[i];
      j += "]";
    };
    if (!bin.empty()) {
      std::string buffer = "{\"byteLength\":" + std::to_string(bin.size());
      if (!bufferUri.empty()) buffer += ",\"uri\":\"" + bufferUri + "\"";
      j += ",\"buffers\":[" + buffer + "}]";
    }
    array("bufferViews", bufferViews);
    array("accessors", accessors);
    array("meshes", meshes);
    array("nodes", nodes);
    if (scenes.empty() && !nodes.empty()) {
      j += ",\"scenes\":[{\"nodes\":[0]}]";
    } else {
      array("scenes", scenes);
    }
    if (defaultScene >= 0) j += ",\"scene\":" + std::to_string(defaultScene);
    array("materials", materials);
    array("textures", textures);
    array("images", images);
    array("samplers", samplers);
    array("cameras", cameras);
    if (!extraTopLevel.empty()) j += "," + extraTopLevel;
    return j + "}";
  }

  std::string writeGltf(const TempDir& dir, const std::string& name) const {
    const std::string binName = name + ".bin";
    if (!bin.empty()) writeBytes(dir.file(binName), bin.data(), bin.size());
    const std::string path = dir.file(name + ".gltf");
    writeText(path, json(binName));
    return path;
  }

  std::vector<std::uint8_t> glbBytes() const {
    std::string text = json("");
    while (text.size() % 4) text += ' ';
    std::vector<std::uint8_t> payload = bin;
    while (payload.size() % 4) payload.push_back(0);
    std::vector<std::uint8_t> out;
    const std::size_t total = 12 + 8 + text.size() + (payload.empty() ? 0 : 8 + payload.size());
    putU32(out, 0x46546C67);
    putU32(out, 2);
    putU32(out, std::uint32_t(total));
    putU32(out, std::uint32_t(text.size()));
    putU32(out, 0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    if (!payload.empty()) {
      putU32(out, std::uint32_t(payload.size()));
      putU32(out, 0x004E4942);
      out.insert(out.end(), payload.begin(), payload.end());
    }
    return out;
  }

  std::string writeGlb(const TempDir& dir, const std::string& name) const {
    const std::vector<std::uint8_t> bytes = glbBytes();
    const std::string path = dir.file(name + ".glb");
    writeBytes(path, bytes.data(), bytes.size());
    return path;
  }
};

inline std::string primitive(const std::map<std::string, int>& attributes, int indices = -1,
                             int mode = -1, int material = -1) {
  std::string p = "{\"attributes\":{";
  bool first = true;
  for (const auto& [name, accessor] : attributes) {
    p += (first ? "\"" : ",\"") + name + "\":" + std::to_string(accessor);
    first = false;
  }
  p += "}";
  if (indices >= 0) p += ",\"indices\":" + std::to_string(indices);
  if (mode >= 0) p += ",\"mode\":" + std::to_string(mode);
  if (material >= 0) p += ",\"material\":" + std::to_string(material);
  return p + "}";
}

inline std::uint32_t crc32(const std::vector<std::uint8_t>& data) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::uint8_t byte : data) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

inline void pngChunk(std::vector<std::uint8_t>& png, const char* type,
                     const std::vector<std::uint8_t>& data) {
  putU32BigEndian(png, std::uint32_t(data.size()));
  std::vector<std::uint8_t> typed(type, type + 4);
  typed.insert(typed.end(), data.begin(), data.end());
  png.insert(png.end(), typed.begin(), typed.end());
  putU32BigEndian(png, crc32(typed));
}

// RGBA samples (8- or 16-bit values), row-major.
inline std::vector<std::uint8_t> encodePng(int width, int height, int bits,
                                           const std::vector<std::uint16_t>& rgba) {
  std::vector<std::uint8_t> raw;
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);  // filter: none
    for (int i = 0; i < width * 4; ++i) {
      const std::uint16_t v = rgba[std::size_t(y) * width * 4 + i];
      if (bits == 16) raw.push_back(std::uint8_t(v >> 8));
      raw.push_back(std::uint8_t(v));
    }
  }
  std::vector<std::uint8_t> zlib = {0x78, 0x01};
  for (std::size_t at = 0; at < raw.size() || at == 0; at += 65535) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    zlib.push_back(at + n >= raw.size() ? 1 : 0);
    zlib.insert(zlib.end(),
                {std::uint8_t(n), std::uint8_t(n >> 8), std::uint8_t(~n), std::uint8_t(~n >> 8)});
    zlib.insert(zlib.end(), raw.begin() + std::ptrdiff_t(at), raw.begin() + std::ptrdiff_t(at + n));
  }
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t byte : raw) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  putU32BigEndian(zlib, (b << 16) | a);
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> header;
  putU32BigEndian(header, std::uint32_t(width));
  putU32BigEndian(header, std::uint32_t(height));
  header.insert(header.end(), {std::uint8_t(bits), 6, 0, 0, 0});
  pngChunk(png, "IHDR", header);
  pngChunk(png, "IDAT", zlib);
  pngChunk(png, "IEND", {});
  return png;
}

inline std::string base64(const std::vector<std::uint8_t>& data) {
  static const char* const digits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < data.size(); i += 3) {
    const std::size_t remaining = data.size() - i;
    std::uint32_t group = std::uint32_t(data[i]) << 16;
    if (remaining > 1) group |= std::uint32_t(data[i + 1]) << 8;
    if (remaining > 2) group |= data[i + 2];
    out += digits[(group >> 18) & 63];
    out += digits[(group >> 12) & 63];
    out += remaining > 1 ? digits[(group >> 6) & 63] : '=';
    out += remaining > 2 ? digits[group & 63] : '=';
  }
  return out;
}

// ---- error helpers -------------------------------------------------------------------

inline std::string loadError(const std::string& path, const LoadOptions& options = {}) {
  try {
    loadGltf(path, options);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded without an error";
  return "";
}

// The message names the file first, is one line, and mentions the problem.
inline void expectError(const std::string& path, const std::string& problem,
                        const LoadOptions& options = {}) {
  const std::string message = loadError(path, options);
  EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NE(message.find(problem), std::string::npos)
      << "expected '" << problem << "' in: " << message;
}

}  // namespace quadra::gltf_files
