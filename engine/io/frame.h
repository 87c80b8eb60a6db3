// Frame: a rendered image in memory, what the tile stage resolves its tiles
// into and the writers (io/image_io.h) read: premultiplied linear RGBA float,
// window-space depth in [0,1] and, when asked for, coverage and the surface
// AOVs (docs/cli.md "AOVs"), plus what an EXR header records about the render.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace quadra {

// The surface AOVs a render can fill besides colour, depth and coverage, as
// bits of a set (RenderSettings::aovs). Each is taken from the nearest
// depth-writing surface of the pixel, evaluated at the pixel centre (docs/cli.md
// "AOVs"); blended draws write none. The shading AOVs (albedo to specular)
// are the lit shading's terms (Shading::Pbr), which the beauty sums.
enum class Aov : std::uint32_t {
  Normal = 1u << 0,      // N.X, N.Y, N.Z: world-space shading normal, unit length
  Position = 1u << 1,    // P.X, P.Y, P.Z: world-space position
  Uv = 1u << 2,          // uv.U, uv.V: TEXCOORD_0 as stored
  Motion = 1u << 3,      // motion.X, motion.Y: window pixels moved since the previous pose
  Ids = 1u << 4,         // id.primitive, id.node, id.material (uint32)
  Lod = 1u << 5,         // lod: the mip level the base colour texture's filter reads
  Anisotropy = 1u << 6,  // anisotropy: its probe count (1 but for the anisotropic filter)
  Albedo = 1u << 7,      // albedo.R/G/B: base colour after textures and COLOR_0, linear
  Roughness = 1u << 8,   // roughness: perceptual, after the texture and Toksvig
  Metallic = 1u << 9,    // metallic: after the texture
  Emission = 1u << 10,   // emission.R/G/B: emitted radiance (x emissive strength)
  Diffuse = 1u << 11,    // diffuse.R/G/B: the diffuse lobe's radiance, environment + lights
  Specular = 1u << 12,   // specular.R/G/B: the specular lobe's radiance, environment + lights
};
// The AOVs the sampler's level choice fills (tile stage, after the shading pass).
constexpr std::uint32_t kFootprintAovs = std::uint32_t(Aov::Lod) | std::uint32_t(Aov::Anisotropy);
// The AOVs the lit shading's terms fill (tile stage, after the shading pass).
constexpr std::uint32_t kShadingAovs = std::uint32_t(Aov::Albedo) | std::uint32_t(Aov::Roughness) |
                                       std::uint32_t(Aov::Metallic) | std::uint32_t(Aov::Emission) |
                                       std::uint32_t(Aov::Diffuse) | std::uint32_t(Aov::Specular);
using AovSet = std::uint32_t;
constexpr bool hasAov(AovSet set, Aov aov) {
  return (set & std::uint32_t(aov)) != 0;
}
// 4-byte channels per pixel: each AOV's, and a set's in all (3 ids for Ids).
constexpr int aovChannels(Aov aov) {
  if (aov == Aov::Lod || aov == Aov::Anisotropy || aov == Aov::Roughness || aov == Aov::Metallic)
    return 1;
  return aov == Aov::Uv || aov == Aov::Motion ? 2 : 3;
}
constexpr int aovChannels(AovSet set) {
  int channels = 0;
  for (const Aov aov :
       {Aov::Normal, Aov::Position, Aov::Uv, Aov::Motion, Aov::Ids, Aov::Lod, Aov::Anisotropy,
        Aov::Albedo, Aov::Roughness, Aov::Metallic, Aov::Emission, Aov::Diffuse, Aov::Specular})
    if (hasAov(set, aov)) channels += aovChannels(aov);
  return channels;
}

// The id AOVs' value where no surface is (and id.material's for the glTF
// default material).
constexpr std::uint32_t kNoId = 0xFFFFFFFFu;

// What an EXR header records about the render besides its pixels: the
// camera as OpenEXR's standard worldToCamera and worldToNDC attributes (set
// by the renderer), and string attributes (name, value) a caller adds, such
// as quadra's version and the render settings.
struct FrameMetadata {
  bool hasCamera = false;
  glm::mat4 worldToCamera{1.0f};  // glTF view matrix: camera looks down -Z
  glm::mat4 worldToNDC{1.0f};     // projection x view: x, y in [-1, 1] up, depth [0, 1]
  std::vector<std::pair<std::string, std::string>> strings;
};

struct Frame {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // width * height * 4, row 0 at the top, premultiplied
  // width * height, or empty when the render was asked for none
  // (RenderSettings::frameDepth); 1 = far plane / nothing drawn.
  std::vector<float> depth;
  // The embedder's own memory to resolve into instead of rgba / depth (the
  // public API's targets whose rows are contiguous, so that its frame costs
  // no copy): width * height * 4 floats, 16-byte aligned / width * height
  // floats. The render then leaves rgba / depth empty. Set for each render.
  float* rgbaInto = nullptr;
  float* depthInto = nullptr;
  float* colorPixels() { return rgbaInto ? rgbaInto : rgba.data(); }
  float* depthPixels() { return depthInto ? depthInto : depth.empty() ? nullptr : depth.data(); }
  // width * height, or empty when the render was asked for none
  // (RenderSettings::frameCoverage): the fraction of the pixel's samples that
  // a depth-writing (opaque or masked) triangle holds, filtered as the colour is.
  std::vector<float> coverage;
  // The AOVs of RenderSettings::aovs, row-major like depth, interleaved per
  // pixel (normal x, y, z; …); each empty when not asked for. Clear values
  // where no depth-writing surface is: 0 for the floats, kNoId for the ids.
  std::vector<float> normal;    // 3 per pixel
  std::vector<float> position;  // 3 per pixel
  std::vector<float> uv;        // 2 per pixel
  std::vector<float> motion;    // 2 per pixel: x right, y down, in pixels
  std::vector<std::uint32_t> primitiveId, nodeId, materialId;  // 1 per pixel each
  // 1 per pixel each; 0 where no textured depth-writing surface is.
  std::vector<float> lod, anisotropy;
  // The lit shading's terms (docs/cli.md "AOVs"): 3 per pixel (albedo,
  // emission, diffuse, specular) or 1 (roughness, metallic); 0 where no
  // depth-writing surface is, and albedo alone where an unlit one is.
  std::vector<float> albedo, roughness, metallic, emission, diffuse, specular;
  FrameMetadata metadata;
};

}  // namespace quadra
