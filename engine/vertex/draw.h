// Draw: one instance of one mesh with its resolved material state: the unit
// the front end iterates (vertex → clip → setup → bin) and the tile stage
// shades. The renderer builds the frame's draw list in submission order:
// opaque and masked draws first, then blended draws back to front.
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "shading/material_shading.h"
#include "texture/texture_view.h"

namespace quadra {

// Where each interpolated attribute lives in a transformed vertex (after the
// four clip-space position floats) and in a triangle's plane list (after the
// z and 1/w planes). -1: not interpolated, because nothing reads it.
struct AttributeLayout {
  int texcoord = -1;   // u, v
  int color = -1;      // r, g, b, a
  int normal = -1;     // view-space x, y, z
  int position = -1;   // view-space x, y, z (lit shading)
  int tangent = -1;    // view-space x, y, z and the bitangent's sign w (normal maps)
  int texcoord1 = -1;  // TEXCOORD_1's u, v as stored (lit shading)
  int count = 0;
};

struct DrawGeometry {
  const Mesh* mesh = nullptr;
  glm::mat4 modelView{1.0f};
  glm::mat4 projection{1.0f};
  int texcoordSet = 0;
  // The material's texture transform (scene.h TextureTransform), applied to
  // each vertex's coordinates: it is affine, so interpolating the transformed
  // coordinates gives the transformed interpolation, and the derivatives the
  // LOD is chosen from follow. Off for the identity, which keeps those draws'
  // bits.
  bool transformTexcoords = false;
  glm::mat3x2 texcoordTransform{1.0f};
  bool cullBackFaces = true;
  bool frontIsClockwise = false;  // the world matrix mirrors (negative determinant)
  // The world matrix mirrors, whichever faces the draw state culls.
  bool mirrored = false;
  // Lit shading of a double-sided material: a back face's normal and tangent
  // frame face the viewer (LIGHTING.md), by setup negating the planes of
  // these attributes (bit k: attribute k) on back faces.
  std::uint32_t negatedOnBackFaces = 0;
  // Lit shading of a mesh without NORMAL: setup gives attributes
  // [faceNormal, faceNormal + 3) each triangle's own normal (-1: none).
  int faceNormal = -1;
  AttributeLayout attributes;
  // The instance's morph weights and joint matrices (scene/deformation.h),
  // owned by the scene; both empty for a draw nothing deforms, which reads
  // its mesh as stored.
  std::span<const float> morphWeights;
  std::span<const glm::mat4> jointMatrices;
};

// Colour, or the perspective-correct texture coordinates (R, G) or their
// derivatives as the sampler gets them (R, G, B, A = du/dx, dv/dx, du/dy, dv/dy).
enum class ShadeOutput : std::uint8_t { Color, TexCoord, Derivatives };

// Everything the tile stage needs to shade a draw's pixels.
struct ShadeState {
  glm::vec4 baseColor{1.0f};
  bool textured = false;
  TextureView texture;
  bool vertexColor = false;
  bool lit = false;
  // Lit shading (Shading::Pbr) of this draw's material, owned by the frame's
  // draw list; null for the other shadings. Such a draw has lit set and
  // neither textured nor vertexColor: the material reads its own.
  const MaterialShading* material = nullptr;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  // A masked draw's cutoff differs per sample (RenderSettings::alphaToCoverage;
  // the tile stage's shadeAtSample).
  bool alphaToCoverage = false;
  // The depth test as the kernels run it: the draw's compare resolved for the
  // frame's depth mode (compareForDepth), Always when its test is off.
  CompareFunction depthCompare = CompareFunction::Less;
  // Reversed depth (api/camera.h DepthMode): nearer is greater. What
  // hierarchical depth keeps and the depth-ordered composite sorts by, and
  // the visibility pass's test (two-pass draws test "nearer").
  bool depthGreater = false;
  bool depthWrite = true;
  // How a fragment combines with the sample's colour; off: it replaces it.
  // In submission order, per sample (scene/scene.h DrawState).
  BlendState blend;
  // glTF BLEND materials: premultiplied "over", composited per sample in
  // depth order (tile/blended_fragments.h) instead of submission order.
  bool depthOrdered = false;
  // What the pixels receive; anything but Color is a test view (DebugView),
  // which the tile kernels compile as separate specializations.
  ShadeOutput output = ShadeOutput::Color;
  DerivativeMode derivatives = DerivativeMode::Analytic;
  // Texture footprints are scaled by this: 1/sqrt(samples) where each
  // sample is shaded (ShadingRate::Sample, and shadedPerSampleAtPixelRate
  // draws of a multisampled frame), else 1.
  float footprintScale = 1.0f;
  // Visibility and shading passes (tile/tile_kernel.h) instead of the forward
  // path: opaque and masked draws with analytic derivatives. The renderer puts
  // every such draw before the forward ones.
  bool twoPass = false;
  AttributeLayout attributes;
  // Whether every pixel the draw shades gets the same colour (its base
  // colour: no texture, vertex colour or lighting), whichever of its
  // triangles holds it and wherever. The tile kernels' readsPlanes is the
  // same test on their template parameters: such a draw's planes are
  // neither rebased nor gathered for shading.
  bool shadesOneColour() const {
    return !textured && !vertexColor && !lit && output == ShadeOutput::Color;
  }
  // Whether a multisampled frame shading once per pixel still shades this
  // draw at every sample: the forward draws, but for the depth-ordered
  // blended ones with analytic footprints, which are shaded once per pixel
  // (tile/tile_kernel.h shadeBlendedPixels; quad differences need each lane
  // at its own pixel centre).
  bool shadedPerSampleAtPixelRate() const {
    return !twoPass && !(depthOrdered && derivatives == DerivativeMode::Analytic);
  }
};

struct Draw {
  DrawGeometry geometry;
  ShadeState shade;
};

}  // namespace quadra
