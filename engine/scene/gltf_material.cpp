// glTF materials (with KHR_texture_transform on the base colour texture),
// textures, samplers and images → Scene materials and textures, made only for what a drawn
// primitive uses: an image is decoded (sRGB → linear float RGBA) only when some used material's
// baseColorTexture reads it, and textures sharing an image share one decoded Image.
#include <tiny_gltf.h>

#include <cctype>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include "core/parallel.h"
#include "io/image_io.h"
#include "scene/gltf_internal.h"
#include "texture/texel_format.h"

namespace quadra::gltf {

namespace {

WrapMode wrapMode(const ModelRef& ref, int sampler, int code) {
  switch (code) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT:
      return WrapMode::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return WrapMode::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return WrapMode::MirroredRepeat;
  }
  throw ref.fail("sampler " + std::to_string(sampler) + " has unknown wrap mode " +
                 std::to_string(code));
}

// glTF's minFilter codes are OpenGL's: the first word filters within a mip
// level (minLinear), the second chooses between levels.
void setMinFilter(const ModelRef& ref, int sampler, int code, SamplerState& state) {
  state.minLinear = code != TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST &&
                    code != TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
  switch (code) {
    case -1:  // unset: the implementation chooses; mipmapped is the safe choice
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR:
      state.minFilter = Filter::Trilinear;
      return;
    case TINYGLTF_TEXTURE_FILTER_NEAREST:
      state.minFilter = Filter::Nearest;
      return;
    case TINYGLTF_TEXTURE_FILTER_LINEAR:
      state.minFilter = Filter::Bilinear;
      return;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
      state.minFilter = Filter::NearestMip;
      return;
  }
  throw ref.fail("sampler " + std::to_string(sampler) + " has unknown minFilter " +
                 std::to_string(code));
}

SamplerState samplerState(const ModelRef& ref, int index) {
  SamplerState state;  // glTF's defaults: repeat, linear magnification, mipmapped
  if (index == -1) return state;
  if (index < 0 || std::size_t(index) >= ref.model.samplers.size()) {
    throw ref.fail("sampler " + std::to_string(index) + " does not exist");
  }
  const tinygltf::Sampler& sampler = ref.model.samplers[std::size_t(index)];
  state.wrapU = wrapMode(ref, index, sampler.wrapS);
  state.wrapV = wrapMode(ref, index, sampler.wrapT);
  if (sampler.magFilter != -1 && sampler.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST &&
      sampler.magFilter != TINYGLTF_TEXTURE_FILTER_LINEAR) {
    throw ref.fail("sampler " + std::to_string(index) + " has unknown magFilter " +
                   std::to_string(sampler.magFilter));
  }
  state.magLinear = sampler.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST;
  setMinFilter(ref, index, sampler.minFilter, state);
  return state;
}

// A number from the file that a float holds finitely.
float finiteFloat(const ModelRef& ref, const tinygltf::Value& value, const std::string& what) {
  const double number = value.IsNumber() ? value.GetNumberAsDouble() : 0.0;
  if (!value.IsNumber() || !(std::fabs(number) <= double(FLT_MAX))) {
    throw ref.fail(what + " is not a finite number");
  }
  return float(number);
}

glm::vec2 finiteVec2(const ModelRef& ref, const tinygltf::Value& value, const std::string& what) {
  if (!value.IsArray() || value.ArrayLen() != 2) throw ref.fail(what + " does not have 2 numbers");
  return {finiteFloat(ref, value.Get(0), what), finiteFloat(ref, value.Get(1), what)};
}

// KHR_texture_transform on a textureInfo: offset, rotation, scale, and a
// texCoord that replaces the textureInfo's own when present.
TextureTransform textureTransform(const ModelRef& ref, const tinygltf::Value& extension,
                                  const std::string& where, int& texCoord) {
  const std::string what = where + " KHR_texture_transform";
  if (!extension.IsObject()) throw ref.fail(what + " is not an object");
  TextureTransform transform;
  if (extension.Has("offset"))
    transform.offset = finiteVec2(ref, extension.Get("offset"), what + " offset");
  if (extension.Has("rotation"))
    transform.rotation = finiteFloat(ref, extension.Get("rotation"), what + " rotation");
  if (extension.Has("scale"))
    transform.scale = finiteVec2(ref, extension.Get("scale"), what + " scale");
  if (extension.Has("texCoord")) {
    const tinygltf::Value& set = extension.Get("texCoord");
    if (!set.IsInt() || set.GetNumberAsInt() < 0)
      throw ref.fail(what + " texCoord is not a non-negative integer");
    texCoord = set.GetNumberAsInt();
  }
  return transform;
}

AlphaMode alphaMode(const ModelRef& ref, int material, const std::string& name) {
  if (name == "OPAQUE" || name.empty()) return AlphaMode::Opaque;
  if (name == "MASK") return AlphaMode::Mask;
  if (name == "BLEND") return AlphaMode::Blend;
  throw ref.fail("material " + std::to_string(material) + " has unknown alphaMode '" + name + "'");
}

std::string percentDecode(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) &&
        std::isxdigit(uint8_t(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace

bool stashImageBytes(tinygltf::Image* image, int imageIndex, std::string*, std::string*, int, int,
                     const unsigned char* bytes, int size, void* userData) {
  // bufferView images: the bufferView is not checked yet, so its bytes are not
  // touched here; they are read later through bufferViewBytes.
  if (image->bufferView != -1 || size <= 0) return true;
  auto& stash = *static_cast<ImageStash*>(userData);
  stash.encoded[imageIndex].assign(bytes, bytes + size);
  return true;
}

MaterialTable::MaterialTable(const ModelRef& ref, const ImageStash& stash,
                             std::vector<std::string>& notes)
    : ref_(ref), stash_(stash), notes_(notes) {}

int MaterialTable::sceneMaterial(int gltfMaterial) {
  if (gltfMaterial == -1) return -1;
  if (gltfMaterial < 0 || std::size_t(gltfMaterial) >= ref_.model.materials.size()) {
    throw ref_.fail("material " + std::to_string(gltfMaterial) + " does not exist (the file has " +
                    std::to_string(ref_.model.materials.size()) + ")");
  }
  if (const auto known = materialOf_.find(gltfMaterial); known != materialOf_.end()) {
    return known->second;
  }
  const tinygltf::Material& source = ref_.model.materials[std::size_t(gltfMaterial)];
  const std::string what = "material " + std::to_string(gltfMaterial);
  Material material;
  const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
  if (factor.size() != 4) throw ref_.fail(what + " baseColorFactor does not have 4 numbers");
  material.baseColorFactor =
      glm::vec4(float(factor[0]), float(factor[1]), float(factor[2]), float(factor[3]));
  material.alphaMode = alphaMode(ref_, gltfMaterial, source.alphaMode);
  material.alphaCutoff = float(source.alphaCutoff);
  material.doubleSided = source.doubleSided;
  material.fileIndex = gltfMaterial;

  const tinygltf::TextureInfo& baseColor = source.pbrMetallicRoughness.baseColorTexture;
  if (baseColor.index != -1) {
    material.baseColorTexture = sceneTexture(baseColor.index, what);
    int texCoord = baseColor.texCoord;
    if (const auto found = baseColor.extensions.find("KHR_texture_transform");
        found != baseColor.extensions.end()) {
      material.baseColorTransform =
          textureTransform(ref_, found->second, what + " baseColorTexture", texCoord);
    }
    if (texCoord == 0 || texCoord == 1) {
      material.baseColorTexCoord = texCoord;
    } else {
      notes_.push_back(ref_.note(what + " baseColorTexture reads TEXCOORD_" +
                                 std::to_string(texCoord) +
                                 ", which is not supported; using TEXCOORD_0"));
    }
  }
  materials_.push_back(material);
  materialOf_[gltfMaterial] = int(materials_.size()) - 1;
  return int(materials_.size()) - 1;
}

int MaterialTable::texcoordSetRead(int sceneMaterialIndex) const {
  if (sceneMaterialIndex < 0) return -1;
  const Material& material = materials_[std::size_t(sceneMaterialIndex)];
  return material.baseColorTexture < 0 ? -1 : material.baseColorTexCoord;
}

int MaterialTable::sceneTexture(int gltfTexture, const std::string& what) {
  const auto& textures = ref_.model.textures;
  if (gltfTexture < 0 || std::size_t(gltfTexture) >= textures.size()) {
    throw ref_.fail(what + " refers to texture " + std::to_string(gltfTexture) +
                    ", which does not exist");
  }
  if (const auto known = textureOf_.find(gltfTexture); known != textureOf_.end()) {
    return known->second;
  }
  const tinygltf::Texture& texture = textures[std::size_t(gltfTexture)];
  if (texture.source == -1) {
    // Only an extension (e.g. KHR_texture_basisu) gives this texture an image.
    notes_.push_back(ref_.note("texture " + std::to_string(gltfTexture) +
                               " has no glTF 2.0 image source; " + what + " drawn untextured"));
    textureOf_[gltfTexture] = -1;
    return -1;
  }
  if (texture.source < 0 || std::size_t(texture.source) >= ref_.model.images.size()) {
    throw ref_.fail("texture " + std::to_string(gltfTexture) + " refers to image " +
                    std::to_string(texture.source) + ", which does not exist");
  }
  textures_.push_back({texture.source, samplerState(ref_, texture.sampler)});
  textureOf_[gltfTexture] = int(textures_.size()) - 1;
  return int(textures_.size()) - 1;
}

namespace {

std::uint32_t bigEndian(const std::uint8_t* p, int bytes) {
  std::uint32_t value = 0;
  for (int i = 0; i < bytes; ++i) value = value << 8 | p[i];
  return value;
}

// Width and height from a PNG or JPEG header, read before decoding so an
// oversized image is refused before anything is allocated for it; false
// when the header is not one of those (the decoder then reports the error).
bool encodedImageSize(const std::uint8_t* data, std::uint64_t size, std::uint32_t& width,
                      std::uint32_t& height) {
  if (size >= 24 && isPng(data, std::size_t(size)) && std::memcmp(data + 12, "IHDR", 4) == 0) {
    width = bigEndian(data + 16, 4);
    height = bigEndian(data + 20, 4);
    return true;
  }
  if (size < 4 || data[0] != 0xFF || data[1] != 0xD8) return false;
  // JPEG: walk the marker segments to the first start-of-frame.
  for (std::uint64_t at = 2; at + 9 <= size;) {
    if (data[at] != 0xFF) return false;
    const std::uint8_t marker = data[at + 1];
    const bool startOfFrame =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (startOfFrame) {
      height = bigEndian(data + at + 5, 2);
      width = bigEndian(data + at + 7, 2);
      return true;
    }
    at += 2 + bigEndian(data + at + 2, 2);
  }
  return false;
}

// Half floats keep every step of an 8-bit sRGB source (texel_format.h) at
// half the memory of float; a 16-bit source's steps need float. rgba8srgb
// would halve the memory again, losslessly, but samples slower
// (texel_format.h gives the measurements).
TexelFormat storageFor(int bitsPerChannel) {
  return bitsPerChannel == 8 ? TexelFormat::Rgba16F : TexelFormat::Rgba32F;
}

}  // namespace

std::string MaterialTable::imageName(int imageIndex) const {
  const tinygltf::Image& source = ref_.model.images[std::size_t(imageIndex)];
  return "image " + std::to_string(imageIndex) +
         (source.uri.empty() ? "" : " ('" + percentDecode(source.uri) + "')");
}

ByteRange MaterialTable::encodedImage(int imageIndex) const {
  const tinygltf::Image& source = ref_.model.images[std::size_t(imageIndex)];
  if (source.bufferView != -1) return bufferViewBytes(ref_, source.bufferView);
  if (const auto stashed = stash_.encoded.find(imageIndex); stashed != stash_.encoded.end())
    return {stashed->second.data(), stashed->second.size()};
  throw ref_.fail(imageName(imageIndex) +
                  (source.uri.empty() ? " has no data" : ": file cannot be read"));
}

void MaterialTable::chargeDecode(int imageIndex) const {
  ByteRange bytes;
  try {
    bytes = encodedImage(imageIndex);
  } catch (const Error&) {
    return;  // decodeImage reports it, in image order
  }
  std::uint32_t width = 0, height = 0;
  if (!encodedImageSize(bytes.data, bytes.size, width, height) ||
      std::uint64_t(width) * height > std::uint64_t(kMaxImagePixels))
    return;  // decodeImage refuses it
  ref_.charge(imageName(imageIndex) + " decoded to " + std::to_string(width) + "x" +
                  std::to_string(height) + " linear float",
              std::uint64_t(width) * height * sizeof(float) * 4);
}

std::shared_ptr<const Image> MaterialTable::decodeImage(int imageIndex, TexelFormat& storage,
                                                        const Executor& executor) const {
  const std::string what = imageName(imageIndex);
  const ByteRange bytes = encodedImage(imageIndex);
  if (bytes.size == 0 || bytes.size > std::uint64_t(INT_MAX)) {
    throw ref_.fail(what + " has " + std::to_string(bytes.size) + " bytes of data");
  }
  std::uint32_t width = 0, height = 0;
  if (encodedImageSize(bytes.data, bytes.size, width, height) &&
      std::uint64_t(width) * height > std::uint64_t(kMaxImagePixels)) {
    throw ref_.fail(what + " is " + std::to_string(width) + "x" + std::to_string(height) +
                    ", more than the limit of 2^28 texels (e.g. 16384x16384)");
  }
  // The two formats glTF allows, each a row at a time straight into the
  // linear Image: PNG through libpng (the library that writes quadra's PNGs),
  // JPEG through libjpeg-turbo (stb_image, the glTF library's, took three
  // times as long on a 2048² progressive JPEG and copied the image twice).
  const bool png = isPng(bytes.data, std::size_t(bytes.size));
  if (!png && !isJpeg(bytes.data, std::size_t(bytes.size)))
    throw ref_.fail(what + " is neither PNG nor JPEG (the formats glTF allows)");
  int bits = 8;
  Image image;
  try {
    image = png ? decodePng(bytes.data, std::size_t(bytes.size), what, &bits, &executor)
                : decodeJpeg(bytes.data, std::size_t(bytes.size), what, &executor);
  } catch (const Error& e) {
    throw ref_.fail(e.what());
  }
  storage = storageFor(bits);
  return std::make_shared<const Image>(std::move(image));
}

void MaterialTable::finish(Scene& scene) {
  std::vector<int> imageIndices;
  for (const PendingTexture& texture : textures_) imageIndices.push_back(texture.image);
  const std::set<int> unique(imageIndices.begin(), imageIndices.end());
  imageIndices.assign(unique.begin(), unique.end());

  // Each image's decoded size, from its header, against the budget before
  // any is decoded (decoding runs in parallel; charging in image order keeps
  // the message the same every run).
  for (const int image : imageIndices) chargeDecode(image);
  // PNG/JPEG decoding dominates load time for textured models: one task per
  // image. Errors are kept per image and the first in index order is thrown,
  // so the message does not depend on scheduling.
  std::vector<std::shared_ptr<const Image>> images(imageIndices.size());
  std::vector<TexelFormat> storage(imageIndices.size(), TexelFormat::Rgba32F);
  std::vector<std::string> errors(imageIndices.size());
  const Executor serial(1);
  const Executor& executor = ref_.executor ? *ref_.executor : serial;
  executor.parallelFor(imageIndices.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      try {
        images[i] = decodeImage(imageIndices[i], storage[i], executor);
      } catch (const Error& e) {
        errors[i] = e.what();
      } catch (const std::exception& e) {  // e.g. bad_alloc for a huge image
        errors[i] = ref_.fail("image " + std::to_string(imageIndices[i]) + ": " + e.what()).what();
      }
    }
  });
  for (const std::string& error : errors) {
    if (!error.empty()) throw Error(error);
  }

  std::map<int, std::size_t> slotOf;
  for (std::size_t i = 0; i < imageIndices.size(); ++i) slotOf[imageIndices[i]] = i;
  scene.textures.clear();
  for (const PendingTexture& texture : textures_) {
    const std::size_t slot = slotOf.at(texture.image);
    scene.textures.push_back(
        std::make_shared<const Texture>(images[slot], texture.sampler, storage[slot]));
  }
  scene.materials = std::move(materials_);
}

}  // namespace quadra::gltf
