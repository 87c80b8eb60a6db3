// A draw's material as the lit shading (Shading::Pbr) reads it: every
// texture of glTF's metallic-roughness material with the interpolated
// coordinates it reads, the factors, and the frame's light. Built per draw by
// the renderer (api/renderer.cpp), read per lane group by materialRadiance
// (shading/material_lanes.h), which the tile kernels call.
#pragma once

#include <glm/glm.hpp>

#include "texture/texture_view.h"

namespace quadra {

struct LightingView;

// One texture of the material: its view (filter and levels as the frame
// reads them), the TEXCOORD_n set it reads, and its KHR_texture_transform,
// applied per lane (the vertex stage interpolates each set once, as stored,
// however many textures read it).
struct MaterialTextureLookup {
  int texcoord = -1;  // 0 or 1: TEXCOORD_0 or TEXCOORD_1; -1: no texture
  bool transformed = false;
  glm::mat3x2 transform{1.0f};
  TextureView view;
  bool present() const { return texcoord >= 0; }
};

struct MaterialShading {
  MaterialTextureLookup baseColor;  // sRGB-decoded, straight alpha
  MaterialTextureLookup metallicRoughness;
  MaterialTextureLookup normal;
  MaterialTextureLookup occlusion;
  MaterialTextureLookup emissive;
  MaterialTextureLookup specular;
  MaterialTextureLookup specularColor;
  glm::vec4 baseColorFactor{1.0f};
  float metallic = 1.0f, roughness = 1.0f;
  float normalScale = 1.0f;
  float occlusionStrength = 1.0f;
  glm::vec3 emission{0.0f};  // emissiveFactor x emissive strength
  float ior = 1.5f;
  float specularFactor = 1.0f;
  glm::vec3 specularColorFactor{1.0f};
  // Attribute indices (vertex/draw.h AttributeLayout) of the view-space
  // position, normal and tangent, of COLOR_0 (-1: none) and of each
  // TEXCOORD_n set's u (-1: not read).
  int position = -1, normalAttribute = -1, tangent = -1, color = -1;
  int texcoordAttribute[2] = {-1, -1};
  // The camera: its rotation from view space to world space and its
  // position, for the light and the environment, which are in world space.
  glm::mat3 worldFromView{1.0f};
  glm::vec3 eye{0.0f};
  const LightingView* lighting = nullptr;
};

}  // namespace quadra
