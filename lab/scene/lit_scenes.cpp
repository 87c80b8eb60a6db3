// Lit test scenes and panoramas (see lit_scenes.h).
#include "lab/scene/lit_scenes.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "lab/scene/builtin_scenes.h"

namespace quadra {

Scene metalRoughSpheresScene(int columns, int rows, const glm::vec3& baseColor) {
  Scene scene;
  scene.name = "builtin:metal-rough-spheres";
  constexpr float kSpacing = 2.5f;
  for (int row = 0; row < rows; ++row)
    for (int column = 0; column < columns; ++column) {
      Material material;
      material.baseColorFactor = glm::vec4(baseColor, 1.0f);
      material.roughnessFactor = columns > 1 ? float(column) / float(columns - 1) : 0.5f;
      material.metallicFactor = rows > 1 ? float(row) / float(rows - 1) : 1.0f;
      scene.materials.push_back(material);
      scene.meshes.push_back(makeSphere(32, 64, int(scene.materials.size()) - 1));
      Instance instance;
      instance.mesh = int(scene.meshes.size()) - 1;
      instance.world = glm::translate(
          glm::mat4(1.0f), glm::vec3((float(column) - 0.5f * float(columns - 1)) * kSpacing,
                                     (float(row) - 0.5f * float(rows - 1)) * kSpacing, 0.0f));
      scene.instances.push_back(instance);
    }
  Camera camera;
  camera.yfov = 0.6f;
  camera.znear = 0.1f;
  const float extent = 0.5f * kSpacing * float(std::max(columns, rows)) + 0.5f;
  camera.world = glm::translate(
      glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, extent / std::tan(0.5f * camera.yfov) + 1.0f));
  scene.cameras.push_back(camera);
  return scene;
}

Scene litPlaneScene(const Material& material, float halfSize) {
  Scene scene;
  scene.name = "builtin:lit-plane";
  scene.materials.push_back(material);
  Mesh mesh;
  const float h = halfSize;
  mesh.positions = {{-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h}};
  for (const glm::vec3& p : mesh.positions) {
    mesh.normals.push_back(glm::vec3(0.0f, 1.0f, 0.0f));
    mesh.texcoords[0].push_back(glm::vec2(p.x, p.z) / (2.0f * h) + 0.5f);
  }
  mesh.indices = {0, 1, 2, 0, 2, 3};  // counter-clockwise seen from +Y
  mesh.material = 0;
  scene.meshes.push_back(mesh);
  scene.instances.push_back(Instance{});
  return scene;
}

namespace {

EnvironmentImage environmentOf(const std::string& name, int width, int height,
                               glm::vec3 (*texel)(int, int, int, int)) {
  EnvironmentImage image;
  image.name = name;
  image.width = width;
  image.height = height;
  image.rgb.resize(image.texelCount() * 3);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const glm::vec3 c = texel(i, j, width, height);
      float* out = image.rgb.data() + 3 * (std::size_t(j) * std::size_t(width) + std::size_t(i));
      out[0] = c.r;
      out[1] = c.g;
      out[2] = c.b;
    }
  return image;
}

}  // namespace

EnvironmentImage uniformEnvironment(const glm::vec3& radiance, int width, int height) {
  EnvironmentImage image =
      environmentOf("uniform", width, height, [](int, int, int, int) { return glm::vec3(0.0f); });
  for (std::size_t i = 0; i < image.rgb.size(); i += 3)
    for (int c = 0; c < 3; ++c) image.rgb[i + std::size_t(c)] = radiance[c];
  return image;
}

EnvironmentImage splitEnvironment(const glm::vec3& sky, const glm::vec3& ground, int width,
                                  int height) {
  EnvironmentImage image = uniformEnvironment(ground, width, height);
  image.name = "split";
  for (int j = 0; j < height / 2; ++j)
    for (int i = 0; i < width; ++i)
      for (int c = 0; c < 3; ++c)
        image.rgb[3 * (std::size_t(j) * std::size_t(width) + std::size_t(i)) + std::size_t(c)] =
            sky[c];
  return image;
}

EnvironmentImage sunnySkyEnvironment(int width, int height) {
  return environmentOf("sunny-sky", width, height, [](int i, int j, int w, int h) {
    const float v = (float(j) + 0.5f) / float(h);
    const int sunI = int(0.3f * float(w)), sunJ = int(0.25f * float(h));
    if (std::abs(i - sunI) <= 1 && std::abs(j - sunJ) <= 1) return glm::vec3(2000.0f);
    if (v > 0.5f) return glm::vec3(0.12f, 0.1f, 0.08f);  // ground
    const float t = v / 0.5f;                            // 0 at the zenith, 1 at the horizon
    const float u = (float(i) + 0.5f) / float(w);
    return glm::mix(glm::vec3(0.15f, 0.3f, 0.8f), glm::vec3(0.9f, 0.9f, 1.0f), t) *
           (1.0f + 0.3f * std::sin(6.2831853f * u));
  });
}

}  // namespace quadra
