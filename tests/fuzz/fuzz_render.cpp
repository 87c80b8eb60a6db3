// Fuzz target render: the front end and tile stage with what the glTF loader
// never lets through but an embedder can hand the API: triangles, normals,
// texture coordinates, colours, instance and camera matrices whose floats
// include NaN, Inf, denormals and 1e38 magnitudes, with render settings
// (samples, depth mode, shading, filter, ...) from the same bytes. Each scene
// is drawn at a small size through every ISA path the CPU has. A scene keeps
// Scene's own invariants (indices in range, attribute arrays empty or one per
// position), as every Scene the engine receives must.
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "api/renderer.h"
#include "core/error.h"
#include "fuzz_support.h"

namespace {

using quadra::fuzz::ByteReader;
using quadra::fuzz::supportedIsas;

// Mostly ordinary magnitudes, with the values that break arithmetic often
// enough that combinations of them are reached.
float anyFloat(ByteReader& in) {
  constexpr float kSpecial[] = {std::numeric_limits<float>::quiet_NaN(),
                                std::numeric_limits<float>::infinity(),
                                -std::numeric_limits<float>::infinity(),
                                1e-40f,  // denormal
                                -1e-45f,
                                1e38f,
                                -1e38f,
                                FLT_MAX,
                                0.0f,
                                -0.0f,
                                1.0f,
                                -1.0f};
  switch (in.in(0, 7)) {
    case 0:
      return kSpecial[in.in(0, std::size(kSpecial) - 1)];
    case 1:
      return std::bit_cast<float>(in.u32());
    default:
      return in.unit(4.0f);
  }
}

glm::mat4 anyMatrix(ByteReader& in, const glm::mat4& usual) {
  if (in.flag()) return usual;
  glm::mat4 m;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) m[c][r] = anyFloat(in);
  return m;
}

std::shared_ptr<const quadra::Texture> smallTexture(quadra::WrapMode wrap) {
  auto image = std::make_shared<quadra::Image>(4, 4);
  for (std::size_t i = 0; i < image->rgba.size(); ++i) image->rgba[i] = float(i % 7) / 6.0f;
  quadra::SamplerState state;
  state.wrapU = state.wrapV = wrap;
  return std::make_shared<const quadra::Texture>(image, state);
}

quadra::Mesh anyMesh(ByteReader& in, int materials) {
  quadra::Mesh mesh;
  const int vertices = in.in(1, 24);
  const int triangles = in.in(0, 16);
  const bool normals = in.flag(), texcoords = in.flag(), colors = in.flag();
  for (int i = 0; i < vertices; ++i) {
    mesh.positions.push_back({anyFloat(in), anyFloat(in), anyFloat(in)});
    if (normals) mesh.normals.push_back({anyFloat(in), anyFloat(in), anyFloat(in)});
    if (texcoords)
      for (auto& set : mesh.texcoords) set.push_back({anyFloat(in), anyFloat(in)});
    if (colors) mesh.colors.push_back({anyFloat(in), anyFloat(in), anyFloat(in), anyFloat(in)});
  }
  for (int i = 0; i < 3 * triangles; ++i)
    mesh.indices.push_back(std::uint32_t(in.in(0, vertices - 1)));
  mesh.material = in.in(-1, materials - 1);
  return mesh;
}

quadra::Scene anyScene(ByteReader& in) {
  using namespace quadra;
  Scene scene;
  scene.name = "fuzz";
  const WrapMode wrap = WrapMode(in.in(0, 3));
  scene.textures.push_back(smallTexture(wrap));
  const int materials = in.in(0, 3);
  for (int i = 0; i < materials; ++i) {
    Material m;
    m.baseColorFactor = {anyFloat(in), anyFloat(in), anyFloat(in), anyFloat(in)};
    m.baseColorTexture = in.flag() ? 0 : -1;
    m.baseColorTexCoord = in.in(0, 1);
    m.alphaMode = AlphaMode(in.in(0, 2));
    m.alphaCutoff = anyFloat(in);
    m.doubleSided = in.flag();
    scene.materials.push_back(m);
  }
  const int meshes = in.in(1, 3);
  for (int i = 0; i < meshes; ++i) scene.meshes.push_back(anyMesh(in, materials));
  const int instances = in.in(1, 3);
  for (int i = 0; i < instances; ++i)
    scene.instances.push_back({in.in(0, meshes - 1), anyMatrix(in, glm::mat4(1.0f))});
  return scene;
}

quadra::Camera anyCamera(ByteReader& in, const quadra::Scene& scene) {
  quadra::Camera camera = quadra::defaultCamera(scene);
  if (in.flag()) return camera;
  camera.type = in.flag() ? quadra::Camera::Type::Orthographic : quadra::Camera::Type::Perspective;
  camera.yfov = anyFloat(in);
  camera.xmag = anyFloat(in);
  camera.ymag = anyFloat(in);
  camera.znear = anyFloat(in);
  camera.zfar = anyFloat(in);
  camera.world = anyMatrix(in, camera.world);
  return camera;
}

quadra::RenderSettings anySettings(ByteReader& in) {
  using namespace quadra;
  RenderSettings s;
  s.width = in.in(1, 64);
  s.height = in.in(1, 48);
  if (in.flag()) s.filter = kEveryFilter[in.in(0, std::size(kEveryFilter) - 1)];
  s.maxAniso = in.in(1, 16);
  s.lodBias = anyFloat(in);
  s.lodRule = in.flag() ? LodRule::Gl : LodRule::Box;
  s.shading = in.flag() ? Shading::Lit : Shading::Unlit;
  s.depth = in.flag() ? DepthMode::Reversed : DepthMode::Standard;
  s.debugView = DebugView(in.in(0, 3));
  s.derivatives = in.flag() ? DerivativeMode::Quad : DerivativeMode::Analytic;
  s.opaqueShading = in.flag() ? OpaqueShading::Forward : OpaqueShading::TwoPass;
  s.samples = 1 << in.in(0, 4);
  s.shadingRate = in.flag() ? ShadingRate::Sample : ShadingRate::Pixel;
  s.pixelFilter = in.flag() ? PixelFilter::BlackmanHarris : PixelFilter::Box;
  s.frameCoverage = in.flag();
  s.alphaToCoverage = in.flag();
  return s;
}

}  // namespace

void quadra::fuzz::runRender(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const RenderSettings settings = anySettings(in);
  const Scene scene = anyScene(in);
  const Camera camera = anyCamera(in, scene);
  // Two threads: the binning front end merges per-thread bins.
  static std::vector<std::unique_ptr<Renderer>> renderers = [] {
    std::vector<std::unique_ptr<Renderer>> all;
    for (Isa isa : supportedIsas())
      all.push_back(std::make_unique<Renderer>(RendererConfig{.threads = 2, .isa = isa}));
    return all;
  }();
  Frame frame;
  for (const auto& renderer : renderers) {
    try {
      renderer->render(scene, camera, settings, frame);
    } catch (const Error&) {
      // Settings or a camera the renderer refuses, in one line: expected.
    }
  }
}
