// glTF materials (the metallic-roughness material's textures and factors,
// KHR_texture_transform on each textureInfo, and KHR_materials_emissive_strength,
// _ior, _specular and _unlit), textures, samplers and images → Scene
// materials and textures, made only for what a drawn primitive uses: an image
// is decoded only when some used material reads it, once per colour space
// its uses need (sRGB for base colour, emissive and specular colour; linear
// for the data textures, glTF 2.0 §3.9), and textures sharing an image and a
// decode share one decoded Image.
#include <tiny_gltf.h>

#include <algorithm>
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

// A factor from the file: finite, and clamped into [lo, hi], the range the
// schema gives it, with a note when it lay outside.
float factorIn(const ModelRef& ref, double value, float lo, float hi, const std::string& what,
               std::vector<std::string>& notes) {
  if (!(std::fabs(value) <= double(FLT_MAX))) throw ref.fail(what + " is not a finite number");
  const float factor = float(value);
  if (factor >= lo && factor <= hi) return factor;
  const float clamped = std::clamp(factor, lo, hi);
  notes.push_back(ref.note(what + " " + std::to_string(value) + " lies outside [" +
                           std::to_string(lo) + ", " + std::to_string(hi) + "]; using " +
                           std::to_string(clamped)));
  return clamped;
}

// A number member of an extension object, `fallback` when absent.
double numberMember(const ModelRef& ref, const tinygltf::Value& object, const char* key,
                    double fallback, const std::string& what) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsNumber()) throw ref.fail(what + " " + key + " is not a number");
  return value.GetNumberAsDouble();
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
  const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
  const std::vector<double>& factor = pbr.baseColorFactor;
  if (factor.size() != 4) throw ref_.fail(what + " baseColorFactor does not have 4 numbers");
  material.baseColorFactor =
      glm::vec4(float(factor[0]), float(factor[1]), float(factor[2]), float(factor[3]));
  material.alphaMode = alphaMode(ref_, gltfMaterial, source.alphaMode);
  material.alphaCutoff = float(source.alphaCutoff);
  material.doubleSided = source.doubleSided;
  material.fileIndex = gltfMaterial;

  const auto transformOf = [](const tinygltf::ExtensionMap& extensions) {
    const auto found = extensions.find("KHR_texture_transform");
    return found == extensions.end() ? nullptr : &found->second;
  };
  if (pbr.baseColorTexture.index != -1) {
    const MaterialTexture baseColor =
        materialTexture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                        transformOf(pbr.baseColorTexture.extensions), what + " baseColorTexture",
                        TextureUse::Colour);
    material.baseColorTexture = baseColor.texture;
    material.baseColorTexCoord = baseColor.texCoord;
    material.baseColorTransform = baseColor.transform;
  }
  material.metallicFactor =
      factorIn(ref_, pbr.metallicFactor, 0.0f, 1.0f, what + " metallicFactor", notes_);
  material.roughnessFactor =
      factorIn(ref_, pbr.roughnessFactor, 0.0f, 1.0f, what + " roughnessFactor", notes_);
  if (pbr.metallicRoughnessTexture.index != -1)
    material.metallicRoughness =
        materialTexture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                        transformOf(pbr.metallicRoughnessTexture.extensions),
                        what + " metallicRoughnessTexture", TextureUse::Data);
  if (source.normalTexture.index != -1) {
    material.normal = materialTexture(source.normalTexture.index, source.normalTexture.texCoord,
                                      transformOf(source.normalTexture.extensions),
                                      what + " normalTexture", TextureUse::Data);
    // Any finite scale: the specification does not bound it.
    material.normalScale = factorIn(ref_, source.normalTexture.scale, -FLT_MAX, FLT_MAX,
                                    what + " normalTexture scale", notes_);
  }
  if (source.occlusionTexture.index != -1) {
    material.occlusion =
        materialTexture(source.occlusionTexture.index, source.occlusionTexture.texCoord,
                        transformOf(source.occlusionTexture.extensions), what + " occlusionTexture",
                        TextureUse::Data);
    material.occlusionStrength = factorIn(ref_, source.occlusionTexture.strength, 0.0f, 1.0f,
                                          what + " occlusionTexture strength", notes_);
  }
  if (source.emissiveTexture.index != -1)
    material.emissive =
        materialTexture(source.emissiveTexture.index, source.emissiveTexture.texCoord,
                        transformOf(source.emissiveTexture.extensions), what + " emissiveTexture",
                        TextureUse::Colour);
  if (!source.emissiveFactor.empty()) {
    if (source.emissiveFactor.size() != 3)
      throw ref_.fail(what + " emissiveFactor does not have 3 numbers");
    for (int c = 0; c < 3; ++c)
      material.emissiveFactor[c] = factorIn(ref_, source.emissiveFactor[std::size_t(c)], 0.0f, 1.0f,
                                            what + " emissiveFactor", notes_);
  }
  readExtensions(source, what, material);
  materials_.push_back(material);
  materialOf_[gltfMaterial] = int(materials_.size()) - 1;
  return int(materials_.size()) - 1;
}

void MaterialTable::readExtensions(const tinygltf::Material& source, const std::string& what,
                                   Material& material) {
  const auto extension = [&](const char* name) -> const tinygltf::Value* {
    const auto found = source.extensions.find(name);
    if (found == source.extensions.end()) return nullptr;
    if (!found->second.IsObject()) throw ref_.fail(what + " " + name + " is not an object");
    return &found->second;
  };
  if (const tinygltf::Value* strength = extension("KHR_materials_emissive_strength")) {
    const std::string where = what + " KHR_materials_emissive_strength emissiveStrength";
    material.emissiveStrength =
        factorIn(ref_, numberMember(ref_, *strength, "emissiveStrength", 1.0, where), 0.0f, FLT_MAX,
                 where, notes_);
  }
  if (const tinygltf::Value* ior = extension("KHR_materials_ior")) {
    // The schema: at least 1 (the ratified one also admits 0); other values
    // are clamped to 1.
    const std::string where = what + " KHR_materials_ior ior";
    const double value = numberMember(ref_, *ior, "ior", 1.5, where);
    material.ior = value == 0.0 ? 0.0f : factorIn(ref_, value, 1.0f, FLT_MAX, where, notes_);
  }
  if (const tinygltf::Value* specular = extension("KHR_materials_specular")) {
    const std::string where = what + " KHR_materials_specular";
    material.specularFactor =
        factorIn(ref_, numberMember(ref_, *specular, "specularFactor", 1.0, where), 0.0f, 1.0f,
                 where + " specularFactor", notes_);
    if (specular->Has("specularColorFactor")) {
      const tinygltf::Value& colour = specular->Get("specularColorFactor");
      if (!colour.IsArray() || colour.ArrayLen() != 3)
        throw ref_.fail(where + " specularColorFactor does not have 3 numbers");
      for (int c = 0; c < 3; ++c) {
        if (!colour.Get(c).IsNumber())
          throw ref_.fail(where + " specularColorFactor is not 3 numbers");
        material.specularColorFactor[c] = factorIn(ref_, colour.Get(c).GetNumberAsDouble(), 0.0f,
                                                   FLT_MAX, where + " specularColorFactor", notes_);
      }
    }
    if (specular->Has("specularTexture"))
      material.specular = extensionTexture(specular->Get("specularTexture"),
                                           where + " specularTexture", TextureUse::AlphaOnly);
    if (specular->Has("specularColorTexture"))
      material.specularColor =
          extensionTexture(specular->Get("specularColorTexture"), where + " specularColorTexture",
                           TextureUse::Colour);
  }
  if (extension("KHR_materials_unlit")) material.unlit = true;
}

MaterialTexture MaterialTable::materialTexture(int index, int texCoord,
                                               const tinygltf::Value* transform,
                                               const std::string& what, TextureUse use) {
  MaterialTexture out;
  out.texture = sceneTexture(index, what, use);
  if (transform) out.transform = textureTransform(ref_, *transform, what, texCoord);
  if (texCoord == 0 || texCoord == 1) {
    out.texCoord = texCoord;
  } else {
    notes_.push_back(ref_.note(what + " reads TEXCOORD_" + std::to_string(texCoord) +
                               ", which is not supported; using TEXCOORD_0"));
  }
  return out;
}

MaterialTexture MaterialTable::extensionTexture(const tinygltf::Value& info,
                                                const std::string& what, TextureUse use) {
  if (!info.IsObject()) throw ref_.fail(what + " is not an object");
  if (!info.Has("index") || !info.Get("index").IsInt())
    throw ref_.fail(what + " has no integer index");
  int texCoord = 0;
  if (info.Has("texCoord")) {
    if (!info.Get("texCoord").IsInt() || info.Get("texCoord").GetNumberAsInt() < 0)
      throw ref_.fail(what + " texCoord is not a non-negative integer");
    texCoord = info.Get("texCoord").GetNumberAsInt();
  }
  const tinygltf::Value* transform = nullptr;
  if (info.Has("extensions") && info.Get("extensions").Has("KHR_texture_transform"))
    transform = &info.Get("extensions").Get("KHR_texture_transform");
  return materialTexture(info.Get("index").GetNumberAsInt(), texCoord, transform, what, use);
}

PrimitiveNeeds MaterialTable::needsOf(int sceneMaterialIndex) const {
  PrimitiveNeeds needs;
  if (sceneMaterialIndex < 0) return needs;
  const Material& material = materials_[std::size_t(sceneMaterialIndex)];
  if (material.baseColorTexture >= 0) needs.texcoordSets[material.baseColorTexCoord] = true;
  for (const MaterialTexture* texture :
       {&material.metallicRoughness, &material.normal, &material.occlusion, &material.emissive,
        &material.specular, &material.specularColor}) {
    if (texture->present()) needs.texcoordSets[texture->texCoord] = true;
  }
  if (material.normal.present()) needs.normalMapSet = material.normal.texCoord;
  return needs;
}

int MaterialTable::sceneTexture(int gltfTexture, const std::string& what, TextureUse use) {
  const auto& textures = ref_.model.textures;
  if (gltfTexture < 0 || std::size_t(gltfTexture) >= textures.size()) {
    throw ref_.fail(what + " refers to texture " + std::to_string(gltfTexture) +
                    ", which does not exist");
  }
  if (const auto known = textureOf_.find({gltfTexture, use}); known != textureOf_.end()) {
    return known->second;
  }
  const tinygltf::Texture& texture = textures[std::size_t(gltfTexture)];
  if (texture.source == -1) {
    // Only an extension (e.g. KHR_texture_basisu) gives this texture an image.
    notes_.push_back(ref_.note("texture " + std::to_string(gltfTexture) +
                               " has no glTF 2.0 image source; " + what + " drawn untextured"));
    textureOf_[{gltfTexture, use}] = -1;
    return -1;
  }
  if (texture.source < 0 || std::size_t(texture.source) >= ref_.model.images.size()) {
    throw ref_.fail("texture " + std::to_string(gltfTexture) + " refers to image " +
                    std::to_string(texture.source) + ", which does not exist");
  }
  textures_.push_back({texture.source, samplerState(ref_, texture.sampler), use, gltfTexture});
  textureOf_[{gltfTexture, use}] = int(textures_.size()) - 1;
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

std::shared_ptr<const Image> MaterialTable::decodeImage(int imageIndex, ImageColour colour,
                                                        TexelFormat& storage,
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
    image = png ? decodePng(bytes.data, std::size_t(bytes.size), what, &bits, &executor, colour)
                : decodeJpeg(bytes.data, std::size_t(bytes.size), what, &executor, colour);
  } catch (const Error& e) {
    throw ref_.fail(e.what());
  }
  storage = storageFor(bits);
  return std::make_shared<const Image>(std::move(image));
}

void MaterialTable::finish(Scene& scene) {
  // Each pending texture's decode: a texture read for its alpha only (alpha
  // is linear in both decodes) takes its image's sRGB decode when another use
  // needs that one anyway, else the linear one.
  std::set<int> srgbImages;
  for (const PendingTexture& texture : textures_)
    if (texture.use == TextureUse::Colour) srgbImages.insert(texture.image);
  const auto colourOf = [&](const PendingTexture& texture) {
    if (texture.use == TextureUse::Colour) return ImageColour::Srgb;
    if (texture.use == TextureUse::Data) return ImageColour::Linear;
    return srgbImages.count(texture.image) ? ImageColour::Srgb : ImageColour::Linear;
  };
  // Pending textures that came out the same (glTF texture, decode) become one
  // scene texture, in order of first use; materials are renumbered to match.
  std::map<std::pair<int, ImageColour>, int> sceneIndexOf;
  std::vector<int> renumbered(textures_.size());
  std::vector<std::size_t> kept;  // pending index of each scene texture
  std::set<std::pair<int, ImageColour>> imageKeys;
  for (std::size_t i = 0; i < textures_.size(); ++i) {
    const ImageColour colour = colourOf(textures_[i]);
    const auto [known, added] =
        sceneIndexOf.try_emplace({textures_[i].gltfTexture, colour}, int(kept.size()));
    if (added) kept.push_back(i);
    renumbered[i] = known->second;
    imageKeys.insert({textures_[i].image, colour});
  }
  const std::vector<std::pair<int, ImageColour>> images(imageKeys.begin(), imageKeys.end());

  // Each image's decoded size, from its header, against the budget before
  // any is decoded (decoding runs in parallel; charging in image order keeps
  // the message the same every run).
  for (const auto& image : images) chargeDecode(image.first);
  // PNG/JPEG decoding dominates load time for textured models: one task per
  // image and decode. Errors are kept per image and the first in index order
  // is thrown, so the message does not depend on scheduling.
  std::vector<std::shared_ptr<const Image>> decoded(images.size());
  std::vector<TexelFormat> storage(images.size(), TexelFormat::Rgba32F);
  std::vector<std::string> errors(images.size());
  const Executor serial(1);
  const Executor& executor = ref_.executor ? *ref_.executor : serial;
  executor.parallelFor(images.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      try {
        decoded[i] = decodeImage(images[i].first, images[i].second, storage[i], executor);
      } catch (const Error& e) {
        errors[i] = e.what();
      } catch (const std::exception& e) {  // e.g. bad_alloc for a huge image
        errors[i] = ref_.fail("image " + std::to_string(images[i].first) + ": " + e.what()).what();
      }
    }
  });
  for (const std::string& error : errors) {
    if (!error.empty()) throw Error(error);
  }

  std::map<std::pair<int, ImageColour>, std::size_t> slotOf;
  for (std::size_t i = 0; i < images.size(); ++i) slotOf[images[i]] = i;
  scene.textures.clear();
  for (const std::size_t pending : kept) {
    const PendingTexture& texture = textures_[pending];
    const std::size_t slot = slotOf.at({texture.image, colourOf(texture)});
    scene.textures.push_back(
        std::make_shared<const Texture>(decoded[slot], texture.sampler, storage[slot]));
  }
  const auto renumber = [&](int& index) {
    if (index >= 0) index = renumbered[std::size_t(index)];
  };
  for (Material& material : materials_) {
    renumber(material.baseColorTexture);
    for (MaterialTexture* texture :
         {&material.metallicRoughness, &material.normal, &material.occlusion, &material.emissive,
          &material.specular, &material.specularColor})
      renumber(texture->texture);
  }
  scene.materials = std::move(materials_);
}

}  // namespace quadra::gltf
