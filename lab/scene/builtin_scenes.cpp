// The built-in scenes (builtin:NAME): procedural meshes and textures that need
// no files, for benchmarks (checker-plane, alpha-quads, dense-mesh) and the
// CLI's default picture (showcase). Every mesh winds counter-clockwise seen
// from its front, and carries normals, so lit shading works everywhere.
#include "lab/scene/builtin_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "api/camera.h"
#include "core/error.h"
#include "lab/scene/hard_case_scenes.h"
#include "lab/texture/test_textures.h"

namespace quadra {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float radians(float degrees) {
  return degrees * kPi / 180.0f;
}

// Camera-to-world of a camera at eye looking at target (+Y up): the inverse of
// the view matrix, so the camera looks down its -Z as glTF cameras do.
Camera perspectiveCamera(const glm::vec3& eye, const glm::vec3& target, float yfovDegrees,
                         float znear) {
  Camera camera;
  camera.type = Camera::Type::Perspective;
  camera.world = glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
  camera.yfov = radians(yfovDegrees);
  camera.znear = znear;
  camera.zfar = 0.0f;  // infinite
  return camera;
}

// ---- meshes -----------------------------------------------------------------------

// Appends a quad c ± u ± v facing u × v, with texture v = 0 along c + v.
void addQuad(Mesh& mesh, const glm::vec3& center, const glm::vec3& u, const glm::vec3& v) {
  const auto base = std::uint32_t(mesh.positions.size());
  const glm::vec3 normal = glm::normalize(glm::cross(u, v));
  const glm::vec3 corners[4] = {center - u - v, center + u - v, center + u + v, center - u + v};
  const glm::vec2 uvs[4] = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}};
  for (int i = 0; i < 4; ++i) {
    mesh.positions.push_back(corners[i]);
    mesh.normals.push_back(normal);
    mesh.texcoords[0].push_back(uvs[i]);
  }
  // (u, u + v) from the first corner: their cross product is along u × v.
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// The unit quad [-1, 1]^2 in the z = 0 plane, facing +Z.
Mesh makeQuad(int material) {
  Mesh mesh;
  addQuad(mesh, glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  mesh.material = material;
  return mesh;
}

// The cube [-1, 1]^3, one textured quad per face.
Mesh makeCube(int material) {
  Mesh mesh;
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  // For each face normal n and up direction v, u = v × n makes u × v = n.
  const glm::vec3 faces[6][2] = {{x, y}, {-x, y}, {z, y}, {-z, y}, {y, -z}, {-y, z}};
  for (const auto& [n, v] : faces) addQuad(mesh, n, glm::cross(v, n), v);
  mesh.material = material;
  return mesh;
}

// The square y = 0, |x|, |z| <= halfSize, facing +Y, with texcoords (x, z) / period.
Mesh makeGroundPlane(float halfSize, float period, int material) {
  Mesh mesh;
  const float h = halfSize;
  mesh.positions = {{-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h}};
  for (const glm::vec3& p : mesh.positions) {
    mesh.normals.push_back(glm::vec3(0.0f, 1.0f, 0.0f));
    mesh.texcoords[0].push_back(glm::vec2(p.x, p.z) / period);
  }
  // Seen from above (+Y), -x,-z → -x,+z → +x,+z turns counter-clockwise.
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.material = material;
  return mesh;
}

}  // namespace

// Declared in builtin_scenes.h (the lit test scenes use it too).
// Unit sphere with `stacks` rings from the +Y pole and `slices` segments; u runs
// around, v from the top pole (0) to the bottom (1). 2 * slices * (stacks - 1)
// triangles: the pole rows have one triangle per segment.
Mesh makeSphere(int stacks, int slices, int material) {
  Mesh mesh;
  const std::size_t rowLength = std::size_t(slices) + 1;  // seam vertex duplicated for u = 1
  const std::size_t vertexCount = (std::size_t(stacks) + 1) * rowLength;
  mesh.positions.resize(vertexCount);
  mesh.normals.resize(vertexCount);
  mesh.texcoords[0].resize(vertexCount);
  std::vector<float> sinPhi(rowLength), cosPhi(rowLength);
  for (std::size_t l = 0; l < rowLength; ++l) {
    const float phi = 2.0f * kPi * float(l) / float(slices);
    sinPhi[l] = std::sin(phi);
    cosPhi[l] = std::cos(phi);
  }
  for (int s = 0; s <= stacks; ++s) {
    const float theta = kPi * float(s) / float(stacks);
    const float ringRadius = std::sin(theta), height = std::cos(theta);
    for (std::size_t l = 0; l < rowLength; ++l) {
      const std::size_t i = std::size_t(s) * rowLength + l;
      // φ = 0 faces +Z; increasing φ moves towards +X.
      const glm::vec3 p(ringRadius * sinPhi[l], height, ringRadius * cosPhi[l]);
      mesh.positions[i] = p;
      mesh.normals[i] = p;
      mesh.texcoords[0][i] = glm::vec2(float(l) / float(slices), float(s) / float(stacks));
    }
  }
  mesh.indices.reserve(std::size_t(slices) * std::size_t(stacks - 1) * 6);
  for (int s = 0; s < stacks; ++s) {
    for (int l = 0; l < slices; ++l) {
      // a above b, d right of a: (a, b, c) and (a, c, d) wind CCW seen from outside.
      const auto a = std::uint32_t(std::size_t(s) * rowLength + std::size_t(l));
      const auto b = std::uint32_t(a + rowLength), c = b + 1, d = a + 1;
      if (s != 0) mesh.indices.insert(mesh.indices.end(), {a, c, d});
      if (s != stacks - 1) mesh.indices.insert(mesh.indices.end(), {a, b, c});
    }
  }
  mesh.material = material;
  return mesh;
}

namespace {

// ---- textures ---------------------------------------------------------------------

Image makeImage(int width, int height, const std::function<glm::vec4(int, int)>& texel) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec4 value = texel(x, y);
      std::copy_n(&value.x, 4, image.texel(x, y));
    }
  }
  return image;
}

// A smooth hue sweep across u, brightness across v, dark grid lines every 32
// texels and a small dot in each cell: detail at several frequencies.
Image makeGradientGridImage(int size) {
  return makeImage(size, size, [size](int x, int y) {
    const float u = (float(x) + 0.5f) / float(size), v = (float(y) + 0.5f) / float(size);
    const glm::vec3 hue = 0.5f + 0.5f * glm::cos(2.0f * kPi * (u + glm::vec3(0.0f, 0.33f, 0.67f)));
    glm::vec3 color = hue * (0.35f + 0.65f * (1.0f - v));
    const int cx = x % 32, cy = y % 32;
    if (cx < 2 || cy < 2) color *= 0.15f;
    const int dx = cx - 17, dy = cy - 17;
    if (dx * dx + dy * dy <= 9) color = glm::vec3(1.0f);
    return glm::vec4(color, 1.0f);
  });
}

// Orange tiles with round holes (alpha 0), for alpha MASK.
Image makeHolesImage(int size) {
  return makeImage(size, size, [size](int x, int y) {
    const int cell = size / 4;
    const float dx = float(x % cell) + 0.5f - 0.5f * float(cell);
    const float dy = float(y % cell) + 0.5f - 0.5f * float(cell);
    const bool hole = dx * dx + dy * dy < 0.09f * float(cell * cell);
    return hole ? glm::vec4(0.0f) : glm::vec4(0.9f, 0.35f, 0.05f, 1.0f);
  });
}

int addTexture(Scene& scene, Image image, const SamplerState& sampler = {}) {
  auto shared = std::make_shared<const Image>(std::move(image));
  scene.textures.push_back(std::make_shared<const Texture>(std::move(shared), sampler));
  return int(scene.textures.size()) - 1;
}

int addMaterial(Scene& scene, const Material& material) {
  scene.materials.push_back(material);
  return int(scene.materials.size()) - 1;
}

int addMesh(Scene& scene, Mesh mesh) {
  scene.meshes.push_back(std::move(mesh));
  return int(scene.meshes.size()) - 1;
}

glm::mat4 placement(const glm::vec3& at, float yawDegrees, const glm::vec3& scale) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), at);
  m = glm::rotate(m, radians(yawDegrees), glm::vec3(0.0f, 1.0f, 0.0f));
  return glm::scale(m, scale);
}

// ---- scenes -----------------------------------------------------------------------

Scene checkerPlane() {
  Scene scene;
  scene.name = "builtin:checker-plane";
  SamplerState sampler;
  sampler.wrapU = sampler.wrapV = WrapMode::Repeat;
  sampler.magLinear = true;
  sampler.minFilter = Filter::Trilinear;
  Material material;
  material.baseColorTexture = addTexture(scene, makeCheckerTexture(512, 512, 64), sampler);
  const int mesh = addMesh(scene, makeGroundPlane(1000.0f, 4.0f, addMaterial(scene, material)));
  scene.instances.push_back({mesh, glm::mat4(1.0f)});
  scene.cameras.push_back(
      perspectiveCamera({0.0f, 1.5f, 0.0f}, {0.0f, 0.5f, -10.0f}, 60.0f, 0.05f));
  return scene;
}

// Overdraw-heavy blending: five half-transparent textured quads, back to front
// in submission order, over an opaque textured background. With yfov 60° and
// a 16:9 view, the view at distance d is 2.05 d wide and 1.15 d high.
Scene alphaQuads() {
  Scene scene;
  scene.name = "builtin:alpha-quads";
  const float halfHeightPerDistance = std::tan(radians(30.0f));
  const float halfWidthPerDistance = halfHeightPerDistance * 16.0f / 9.0f;
  const int texture = addTexture(scene, makeGradientGridImage(256));

  Material background;
  background.baseColorTexture = texture;
  const int backgroundMesh = addMesh(scene, makeQuad(addMaterial(scene, background)));
  const float backDistance = 10.0f;  // 20% margin so the quad fills any 16:9 view
  scene.instances.push_back(
      {backgroundMesh, placement({0.0f, 0.0f, -backDistance}, 0.0f,
                                 {1.2f * halfWidthPerDistance * backDistance,
                                  1.2f * halfHeightPerDistance * backDistance, 1.0f})});

  const glm::vec3 tints[5] = {{1.0f, 0.3f, 0.3f},
                              {0.3f, 1.0f, 0.3f},
                              {0.3f, 0.3f, 1.0f},
                              {1.0f, 1.0f, 0.3f},
                              {0.3f, 1.0f, 1.0f}};
  // Offsets in view fractions: each quad is 72% x 72% of the view (52% of its
  // area) and stays inside it.
  const glm::vec2 offsets[5] = {
      {-0.12f, 0.1f}, {0.12f, 0.1f}, {0.0f, 0.0f}, {-0.12f, -0.1f}, {0.12f, -0.1f}};
  for (int i = 0; i < 5; ++i) {
    Material blend;
    blend.baseColorFactor = glm::vec4(tints[i], 0.5f);
    blend.baseColorTexture = texture;
    blend.alphaMode = AlphaMode::Blend;
    const int mesh = addMesh(scene, makeQuad(addMaterial(scene, blend)));
    const float d = 8.0f - float(i);  // farthest first
    const glm::vec3 at(2.0f * offsets[i].x * halfWidthPerDistance * d,
                       2.0f * offsets[i].y * halfHeightPerDistance * d, -d);
    scene.instances.push_back({mesh, placement(at, 0.0f,
                                               {0.72f * halfWidthPerDistance * d,
                                                0.72f * halfHeightPerDistance * d, 1.0f})});
  }
  scene.cameras.push_back(perspectiveCamera({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 60.0f, 0.1f));
  return scene;
}

// Triangle throughput: 2,000,000 small textured triangles on a unit sphere
// seen from 2.5 units, where it spans about 80% of the view's height.
// A sphere of 8 k^2 triangles (2k rings of 4k): k = 500 is the 2-million
// triangle builtin:dense-mesh; builtin:dense-mesh:N picks k for about N.
Scene denseMesh(int k, const std::string& name) {
  Scene scene;
  scene.name = name;
  Material material;
  material.baseColorTexture = addTexture(scene, makeGradientGridImage(1024));
  const int mesh = addMesh(scene, makeSphere(k + 1, 4 * k, addMaterial(scene, material)));
  scene.instances.push_back({mesh, glm::mat4(1.0f)});
  scene.cameras.push_back(perspectiveCamera({0.0f, 0.0f, 2.5f}, {0.0f, 0.0f, 0.0f}, 60.0f, 0.1f));
  return scene;
}

// Rainbow vertex colours from the normal direction.
void paintByNormal(Mesh& mesh) {
  mesh.colors.clear();
  for (const glm::vec3& n : mesh.normals) mesh.colors.push_back(glm::vec4(0.5f + 0.5f * n, 1.0f));
}

// The showcase's props, textured as there: a checker ground plane, a
// gradient-grid cube, a ball coloured by its normal (`stacks` rings, twice
// as many segments) and an alpha-masked panel with round holes, their
// textures, materials and meshes added in that order.
struct ShowcaseMeshes {
  int ground, cube, ball, mask;
  int gradientTexture;  // the cube's
};
ShowcaseMeshes addShowcaseMeshes(Scene& scene, int stacks) {
  Material ground, cube, sphere, mask;
  ground.baseColorTexture = addTexture(scene, makeCheckerTexture(256, 256, 32));
  ground.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  cube.baseColorTexture = addTexture(scene, makeGradientGridImage(256));
  mask.baseColorTexture = addTexture(scene, makeHolesImage(128));
  mask.alphaMode = AlphaMode::Mask;
  mask.doubleSided = true;
  ShowcaseMeshes meshes{};
  meshes.gradientTexture = cube.baseColorTexture;
  meshes.ground = addMesh(scene, makeGroundPlane(20.0f, 4.0f, addMaterial(scene, ground)));
  meshes.cube = addMesh(scene, makeCube(addMaterial(scene, cube)));
  Mesh ball = makeSphere(stacks, 2 * stacks, addMaterial(scene, sphere));
  paintByNormal(ball);
  meshes.ball = addMesh(scene, std::move(ball));
  meshes.mask = addMesh(scene, makeQuad(addMaterial(scene, mask)));
  return meshes;
}

// The default picture: textures at several scales, occlusion, vertex colour,
// alpha mask and blending, all in one view.
Scene showcase() {
  Scene scene;
  scene.name = "builtin:showcase";
  const ShowcaseMeshes meshes = addShowcaseMeshes(scene, 48);
  Material glass;
  glass.baseColorFactor = glm::vec4(0.4f, 0.7f, 1.0f, 0.4f);
  glass.baseColorTexture = meshes.gradientTexture;
  glass.alphaMode = AlphaMode::Blend;
  glass.doubleSided = true;
  const int groundMesh = meshes.ground, cubeMesh = meshes.cube, sphereMesh = meshes.ball,
            maskMesh = meshes.mask;
  const int glassMesh = addMesh(scene, makeQuad(addMaterial(scene, glass)));

  scene.instances.push_back({groundMesh, glm::mat4(1.0f)});
  scene.instances.push_back({cubeMesh, placement({-2.6f, 0.75f, 0.0f}, 30.0f, glm::vec3(0.75f))});
  scene.instances.push_back({cubeMesh, placement({0.0f, 0.6f, -2.2f}, -20.0f, glm::vec3(0.6f))});
  scene.instances.push_back({cubeMesh, placement({2.7f, 1.0f, -0.6f}, 55.0f, glm::vec3(1.0f))});
  scene.instances.push_back({sphereMesh, placement({0.4f, 0.9f, 1.0f}, 0.0f, glm::vec3(0.9f))});
  scene.instances.push_back({maskMesh, placement({-1.2f, 1.2f, -3.6f}, 15.0f, {1.6f, 1.2f, 1.0f})});
  // Blended last, in front of the sphere, so it composites over everything.
  scene.instances.push_back({glassMesh, placement({1.9f, 0.9f, 2.3f}, -25.0f, {0.9f, 0.9f, 1.0f})});
  scene.cameras.push_back(perspectiveCamera({0.0f, 2.6f, 6.6f}, {0.0f, 0.9f, -0.6f}, 50.0f, 0.1f));
  return scene;
}

// An opaque backdrop for the glass scenes: a view-filling quad at distance 10
// shaded by smooth vertex colours, so what differs between renders is the
// order of the layers in front of it, not texture filtering.
void addBackdrop(Scene& scene) {
  Material backdrop;
  Mesh quad = makeQuad(addMaterial(scene, backdrop));
  quad.colors = {{0.9f, 0.9f, 0.8f, 1.0f},
                 {0.2f, 0.3f, 0.35f, 1.0f},
                 {0.1f, 0.1f, 0.1f, 1.0f},
                 {0.6f, 0.55f, 0.2f, 1.0f}};
  scene.instances.push_back({addMesh(scene, std::move(quad)),
                             placement({0.0f, 0.0f, -10.0f}, 0.0f, {24.0f, 16.0f, 1.0f})});
}

// Three half-transparent panes through one centre, red and green turned
// about the vertical by -35 and +35 degrees, blue tilted about the horizontal
// by 50: each pair crosses along a line, so every pane is in front of each
// other one on one side of it. Their centres coincide, so no order of draws
// is right; compositing per sample in depth order is.
Scene intersectingGlass() {
  Scene scene;
  scene.name = "builtin:intersecting-glass";
  addBackdrop(scene);
  const glm::vec4 tints[3] = {
      {1.0f, 0.15f, 0.1f, 0.5f}, {0.1f, 0.9f, 0.2f, 0.45f}, {0.15f, 0.3f, 1.0f, 0.55f}};
  const glm::vec3 centre(0.0f, 0.0f, -4.0f);
  glm::mat4 panes[3];
  panes[0] = placement(centre, -35.0f, {1.6f, 1.1f, 1.0f});
  panes[1] = placement(centre, 35.0f, {1.6f, 1.1f, 1.0f});
  panes[2] = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), centre), radians(50.0f),
                                    glm::vec3(1.0f, 0.0f, 0.0f)),
                        {1.3f, 1.3f, 1.0f});
  for (int i = 0; i < 3; ++i) {
    Material glass;
    glass.baseColorFactor = tints[i];
    glass.alphaMode = AlphaMode::Blend;
    glass.doubleSided = true;
    scene.instances.push_back({addMesh(scene, makeQuad(addMaterial(scene, glass))), panes[i]});
  }
  scene.cameras.push_back(perspectiveCamera({0.4f, 0.6f, 0.0f}, centre, 50.0f, 0.1f));
  return scene;
}

// One double-sided, half-transparent sphere coloured by its normal, seen from
// above: its far side shows through its near side, and both are one draw
// whose triangles run from pole to pole, so within the draw far triangles
// come after near ones as often as before.
Scene overlappingGlass() {
  Scene scene;
  scene.name = "builtin:overlapping-glass";
  addBackdrop(scene);
  Material glass;
  glass.baseColorFactor = glm::vec4(1.0f, 1.0f, 1.0f, 0.45f);
  glass.alphaMode = AlphaMode::Blend;
  glass.doubleSided = true;
  Mesh ball = makeSphere(24, 48, addMaterial(scene, glass));
  paintByNormal(ball);
  scene.instances.push_back(
      {addMesh(scene, std::move(ball)), placement({0.0f, 0.0f, -4.0f}, 20.0f, glm::vec3(1.3f))});
  scene.cameras.push_back(perspectiveCamera({0.0f, 1.8f, 0.0f}, {0.0f, 0.0f, -4.0f}, 50.0f, 0.1f));
  return scene;
}

// ---- animation ----------------------------------------------------------------------

// Appends a node with its rest transform composed as the glTF loader composes
// one (T * R * S), so that poseNodes at any key time rebuilds the same bits.
int addNode(Scene& scene, int parent, const glm::vec3& translation, const glm::quat& rotation,
            const glm::vec3& scale) {
  Node node;
  node.parent = parent;
  node.fileIndex = int(scene.nodes.size());
  node.translation = translation;
  node.rotation = rotation;
  node.scale = scale;
  node.local =
      glm::scale(glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation), scale);
  scene.nodes.push_back(node);
  return int(scene.nodes.size()) - 1;
}

// A sampler with one key per time; `values` holds `components` floats per key
// (three groups of them per key for CUBICSPLINE: in-tangent, value, out-tangent).
void addChannel(Animation& animation, int node, AnimatedProperty property,
                Interpolation interpolation, std::vector<float> times, std::vector<float> values) {
  AnimationSampler sampler;
  sampler.interpolation = interpolation;
  sampler.components = property == AnimatedProperty::Rotation ? 4 : 3;
  sampler.times = std::move(times);
  sampler.values = std::move(values);
  animation.samplers.push_back(std::move(sampler));
  animation.channels.push_back({int(animation.samplers.size()) - 1, node, property});
}

void appendQuat(std::vector<float>& values, const glm::quat& q) {
  values.insert(values.end(), {q.x, q.y, q.z, q.w});
}

// The sequence scene (builtin:flyover, 4 s): the camera, on a node, flies an
// arc over the showcase's ground (LINEAR translation, slerped rotation); a
// turntable node carries a cube that spins on its own node (a hierarchy); a
// ball bounces (CUBICSPLINE, tangents from a parabola's speed at the ground)
// and a masked panel turns in steps (STEP). Every interpolation and a moving
// camera, so sequences, motion and resumption are tested without files.
Scene flyover() {
  Scene scene;
  scene.name = "builtin:flyover";
  const ShowcaseMeshes meshes = addShowcaseMeshes(scene, 32);
  const int groundMesh = meshes.ground, cubeMesh = meshes.cube, ballMesh = meshes.ball,
            maskMesh = meshes.mask;

  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const glm::quat none(1.0f, 0.0f, 0.0f, 0.0f);
  const int turntable = addNode(scene, -1, glm::vec3(0.0f), none, glm::vec3(1.0f));
  const int spinner = addNode(scene, turntable, {2.4f, 0.75f, 0.0f}, none, glm::vec3(0.6f));
  const float ballRadius = 0.6f, ballTop = 2.2f;
  const int bouncer = addNode(scene, -1, {-0.6f, ballRadius, 1.2f}, none, glm::vec3(ballRadius));
  const int panel = addNode(scene, -1, {-1.2f, 1.2f, -3.0f}, glm::angleAxis(radians(15.0f), up),
                            {1.6f, 1.2f, 1.0f});
  const glm::vec3 target(0.0f, 0.8f, 0.0f);
  auto eyeAt = [](float t) {  // t in [0, 1] along the flight
    const float angle = radians(-50.0f + 100.0f * t);
    return glm::vec3(7.0f * std::sin(angle), 3.4f - 1.4f * t, 7.0f * std::cos(angle));
  };
  auto lookFrom = [&](const glm::vec3& eye) {
    return glm::quat_cast(glm::mat3(lookAtWorld(eye, target, up)));
  };
  const int cameraNode = addNode(scene, -1, eyeAt(0.0f), lookFrom(eyeAt(0.0f)), glm::vec3(1.0f));

  scene.instances.push_back({groundMesh, glm::mat4(1.0f)});
  scene.instances.push_back({cubeMesh, scene.nodes[std::size_t(spinner)].local, spinner});
  scene.instances.push_back({ballMesh, scene.nodes[std::size_t(bouncer)].local, bouncer});
  scene.instances.push_back({maskMesh, scene.nodes[std::size_t(panel)].local, panel});
  Camera camera = perspectiveCamera(eyeAt(0.0f), target, 50.0f, 0.1f);
  camera.world = cameraWorldOf(scene.nodes[std::size_t(cameraNode)].local);
  camera.node = cameraNode;
  scene.cameras.push_back(camera);
  // The spinner hangs below the turntable: its rest world is the product.
  scene.instances[1].world = scene.nodes[std::size_t(turntable)].local * scene.instances[1].world;

  Animation animation;
  animation.name = "flyover";
  constexpr float kSeconds = 4.0f;
  {  // camera: nine keys along the arc
    std::vector<float> times, translations, rotations;
    for (int k = 0; k <= 8; ++k) {
      const float t = float(k) / 8.0f;
      const glm::vec3 eye = eyeAt(t);
      times.push_back(kSeconds * t);
      translations.insert(translations.end(), {eye.x, eye.y, eye.z});
      appendQuat(rotations, lookFrom(eye));
    }
    addChannel(animation, cameraNode, AnimatedProperty::Translation, Interpolation::Linear, times,
               translations);
    addChannel(animation, cameraNode, AnimatedProperty::Rotation, Interpolation::Linear, times,
               rotations);
  }
  {  // turntable: a full turn in thirds (each key within 180 degrees of the last)
    std::vector<float> rotations;
    for (int k = 0; k <= 3; ++k) appendQuat(rotations, glm::angleAxis(radians(120.0f * k), up));
    addChannel(animation, turntable, AnimatedProperty::Rotation, Interpolation::Linear,
               {0.0f, kSeconds / 3.0f, 2.0f * kSeconds / 3.0f, kSeconds}, rotations);
  }
  {  // spinner: two turns about a tilted axis, a quarter turn a key
    const glm::vec3 axis = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    std::vector<float> times, rotations;
    for (int k = 0; k <= 8; ++k) {
      times.push_back(kSeconds * float(k) / 8.0f);
      appendQuat(rotations, glm::angleAxis(radians(90.0f * float(k)), axis));
    }
    addChannel(animation, spinner, AnimatedProperty::Rotation, Interpolation::Linear, times,
               rotations);
  }
  {  // ball: a bounce every second; at the ground the speed of a parabola
     // peaking at ballTop half a second later, at the top zero
    // (glTF stores tangents per second; the spline scales them by the interval.)
    const float interval = 0.5f;
    const float speed = 2.0f * (ballTop - ballRadius) / interval;
    std::vector<float> times, values;
    for (int k = 0; k <= 8; ++k) {
      const bool atGround = k % 2 == 0;
      const float y = atGround ? ballRadius : ballTop;
      const float in = atGround ? -speed : 0.0f;
      const float out = atGround ? speed : 0.0f;
      times.push_back(interval * float(k));
      values.insert(values.end(), {0.0f, in, 0.0f, -0.6f, y, 1.2f, 0.0f, out, 0.0f});
    }
    addChannel(animation, bouncer, AnimatedProperty::Translation, Interpolation::CubicSpline, times,
               values);
  }
  {  // panel: turns 45 degrees a second, in steps
    std::vector<float> times, rotations;
    for (int k = 0; k <= 4; ++k) {
      times.push_back(float(k));
      appendQuat(rotations, glm::angleAxis(radians(15.0f + 45.0f * float(k)), up));
    }
    addChannel(animation, panel, AnimatedProperty::Rotation, Interpolation::Step, times, rotations);
  }
  scene.animations.push_back(std::move(animation));
  return scene;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
  std::vector<std::string> names = {"showcase",   "checker-plane",      "alpha-quads",
                                    "dense-mesh", "intersecting-glass", "overlapping-glass",
                                    "flyover"};
  for (const std::string& name : hardCaseSceneNames()) names.push_back(name);
  return names;
}

Scene makeBuiltinScene(const std::string& name) {
  if (name == "showcase") return showcase();
  if (name == "checker-plane") return checkerPlane();
  if (name == "alpha-quads") return alphaQuads();
  if (name == "dense-mesh") return denseMesh(500, "builtin:dense-mesh");
  if (name == "intersecting-glass") return intersectingGlass();
  if (name == "overlapping-glass") return overlappingGlass();
  if (name == "flyover") return flyover();
  if (name.rfind("dense-mesh:", 0) == 0) {
    const std::string count = name.substr(std::string("dense-mesh:").size());
    char* end = nullptr;
    const double triangles = std::strtod(count.c_str(), &end);
    if (count.empty() || *end != '\0' || !(triangles >= 8.0 && triangles <= 1e8))
      throw makeError("builtin:" + name, "the triangle count must be a number in 8..1e8");
    const int k = std::max(1, int(std::lround(std::sqrt(triangles / 8.0))));
    return denseMesh(k, "builtin:" + name);
  }
  if (Scene scene; makeHardCaseScene(name, scene)) return scene;
  std::string known;
  for (const std::string& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
  throw makeError("builtin:" + name, "unknown built-in scene (known: " + known + ")");
}

}  // namespace quadra
