// MikkTSpace tangents (scene/tangent_space.h) against independent answers:
// planar meshes whose uv map is affine have the analytic tangent dp/du (in
// double) and w the sign of the map's orientation; NormalTangentMirrorTest
// stores the tangents its exporter's MikkTSpace made, which generation must
// reproduce corner by corner; splitting vertices must keep every corner's
// tangent, every attribute and the triangle order.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "gltf_reference.h"
#include "scene/gltf_loader.h"
#include "scene/tangent_space.h"

namespace quadra {
namespace {

// A planar grid of (n+1)^2 vertices on the plane spanned by the orthonormal
// e1, e2 through `origin`, with (s, t) in [0, 1]^2 and the affine map
// (u, 1 - v) = M (s, t) + c (M = [[a, b], [c, d]] by rows).
struct Plane {
  glm::dvec3 origin, e1, e2;
  glm::dmat2 map;  // columns: d(u, 1 - v)/ds, d(u, 1 - v)/dt
};

Mesh planarGrid(const Plane& plane, int n) {
  Mesh mesh;
  const glm::dvec3 normal = glm::cross(plane.e1, plane.e2);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const glm::dvec2 st(double(i) / n, double(j) / n);
      mesh.positions.push_back(glm::vec3(plane.origin + st.x * plane.e1 + st.y * plane.e2));
      mesh.normals.push_back(glm::vec3(normal));
      const glm::dvec2 uvFlipped = plane.map * st + glm::dvec2(0.25, -0.5);
      mesh.texcoords[0].push_back(glm::vec2(float(uvFlipped.x), float(1.0 - uvFlipped.y)));
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::uint32_t v = std::uint32_t(j * (n + 1) + i);
      const std::uint32_t right = v + 1, up = v + std::uint32_t(n + 1), diagonal = up + 1;
      mesh.indices.insert(mesh.indices.end(), {v, right, diagonal, v, diagonal, up});
    }
  }
  return mesh;
}

// dp/du for the plane's map, normalized, and the orientation's sign.
glm::dvec4 analyticTangent(const Plane& plane) {
  const glm::dmat2 inverse = glm::inverse(plane.map);  // d(s, t)/d(u, 1 - v)
  const glm::dvec3 dpdu = inverse[0].x * plane.e1 + inverse[0].y * plane.e2;
  return glm::dvec4(glm::normalize(dpdu), glm::determinant(plane.map) > 0.0 ? 1.0 : -1.0);
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

void expectPlanar(const Plane& plane) {
  Mesh mesh = planarGrid(plane, 3);
  const glm::dvec4 expected = analyticTangent(plane);
  const std::vector<glm::vec4> corners = mikkTSpaceCorners(mesh, 0);
  ASSERT_EQ(corners.size(), mesh.indices.size());
  for (const glm::vec4& t : corners) {
    EXPECT_LT(angleBetween(glm::dvec3(t), glm::dvec3(expected)), 1e-5);
    EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-6f);
    EXPECT_EQ(t.w, float(expected.w));
  }
  // One tangent per vertex: nothing to split.
  const std::size_t vertices = mesh.positions.size();
  const TangentSplit split = generateTangents(mesh, 0);
  EXPECT_EQ(split.added, 0u);
  EXPECT_EQ(mesh.positions.size(), vertices);
  ASSERT_EQ(mesh.tangents.size(), vertices);
}

TEST(TangentSpace, AnAxisAlignedQuadHasTheAnalyticTangent) {
  // u along +X, v down the image with +Y up: T = +X, w = +1.
  expectPlanar({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, glm::dmat2(1.0)});
}

TEST(TangentSpace, ATiltedPlaneWithASkewedScaledUvMapHasTheAnalyticTangent) {
  const glm::dvec3 e1 = glm::normalize(glm::dvec3(1, 2, 2));
  const glm::dvec3 e2 = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), e1));
  // Columns: (a, c) and (b, d); determinant 0.5 * 3 - (-0.7) * 0.4 > 0.
  expectPlanar({{0.5, -1, 2}, e1, e2, glm::dmat2(0.5, 0.4, -0.7, 3.0)});
}

TEST(TangentSpace, AMirroredUvMapGivesWMinusOne) {
  expectPlanar({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, glm::dmat2(-1.0, 0.0, 0.0, 1.0)});
  const glm::dvec3 e1 = glm::normalize(glm::dvec3(0, 1, 1));
  expectPlanar({{0, 0, 0}, e1, glm::dvec3(1, 0, 0), glm::dmat2(2.0, 0.5, 1.0, -0.25)});
}

TEST(TangentSpace, DegenerateUvsAndPositionsGiveUnitTangentsNeverNaN) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 2}, {2, 2, 2}, {3, 2, 2}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  mesh.texcoords[0] = {{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}, {0, 0}, {1, 0}, {0, 1}};
  mesh.indices = {0, 1, 2, 3, 4, 5};  // all uvs equal; two positions equal
  generateTangents(mesh, 0);
  ASSERT_EQ(mesh.tangents.size(), mesh.positions.size());
  for (std::size_t v = 0; v < mesh.tangents.size(); ++v) {
    const glm::vec4 t = mesh.tangents[v];
    EXPECT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) << v;
    EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-6f) << v;
    EXPECT_NEAR(glm::dot(glm::vec3(t), mesh.normals[v]), 0.0f, 1e-6f) << v;
    EXPECT_TRUE(t.w == 1.0f || t.w == -1.0f) << v;
  }
  // Without normals, each triangle's own normal: tangents lie in its plane.
  mesh.normals.clear();
  mesh.tangents.clear();
  mesh.texcoords[0] = {{0, 0}, {1, 0}, {0, 1}, {0, 0}, {1, 0}, {0, 1}};
  generateTangents(mesh, 0);
  EXPECT_LT(angleBetween(glm::dvec3(mesh.tangents[0]), {1, 0, 0}), 1e-6);
}

// Two triangles sharing an edge whose uv halves mirror across it: the shared
// vertices' corners disagree on w, so they are copied with all attributes.
TEST(TangentSpace, CornersThatDisagreeSplitTheirVertexWithEveryAttribute) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.normals.assign(4, glm::vec3(0, 0, 1));
  // The second triangle's u runs the other way: mirrored about the diagonal.
  mesh.texcoords[0] = {{0, 1}, {1, 1}, {1, 0}, {2, 1}};
  mesh.texcoords[1] = {{9, 9}, {8, 8}, {7, 7}, {6, 6}};
  mesh.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
  mesh.joints[0] = {{1, 0, 0, 0}, {2, 0, 0, 0}, {3, 0, 0, 0}, {4, 0, 0, 0}};
  mesh.weights[0].assign(4, glm::vec4(1, 0, 0, 0));
  mesh.targets.resize(1);
  mesh.targets[0].positions = {{0, 0, 1}, {0, 0, 2}, {0, 0, 3}, {0, 0, 4}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  const Mesh before = mesh;
  const std::vector<glm::vec4> corners = mikkTSpaceCorners(mesh, 0);
  EXPECT_EQ(corners[0].w, 1.0f);
  EXPECT_EQ(corners[3].w, -1.0f);
  const TangentSplit split = generateTangents(mesh, 0);
  EXPECT_EQ(split.split, 2u);  // vertices 0 and 2
  EXPECT_EQ(split.added, 2u);
  ASSERT_EQ(mesh.positions.size(), 6u);
  ASSERT_EQ(mesh.indices.size(), before.indices.size());
  for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
    const std::uint32_t now = mesh.indices[c], was = before.indices[c];
    EXPECT_EQ(mesh.tangents[now], corners[c]) << c;
    EXPECT_EQ(mesh.positions[now], before.positions[was]) << c;
    EXPECT_EQ(mesh.normals[now], before.normals[was]) << c;
    EXPECT_EQ(mesh.texcoords[0][now], before.texcoords[0][was]) << c;
    EXPECT_EQ(mesh.texcoords[1][now], before.texcoords[1][was]) << c;
    EXPECT_EQ(mesh.colors[now], before.colors[was]) << c;
    EXPECT_EQ(mesh.joints[0][now], before.joints[0][was]) << c;
    EXPECT_EQ(mesh.weights[0][now], before.weights[0][was]) << c;
    EXPECT_EQ(mesh.targets[0].positions[now], before.targets[0].positions[was]) << c;
  }
  // The first triangle keeps its vertices.
  EXPECT_EQ(std::vector<std::uint32_t>(mesh.indices.begin(), mesh.indices.begin() + 3),
            std::vector<std::uint32_t>({0, 1, 2}));
}

struct Agreement {
  double maxAngle = 0.0;  // radians, over corners
  std::size_t corners = 0, signsAgree = 0, within = 0;
};

// Generated tangents against the ones `model` stores, every corner.
Agreement compareWithStored(const std::string& model, bool flipV = false) {
  const Scene scene = loadGltf(assetPath(model));
  Agreement result;
  for (const Mesh& stored : scene.meshes) {
    if (stored.tangents.empty()) continue;
    Mesh stripped = stored;
    stripped.tangents.clear();
    if (flipV)
      for (glm::vec2& uv : stripped.texcoords[0]) uv.y = 1.0f - uv.y;
    const std::vector<glm::vec4> corners = mikkTSpaceCorners(stripped, 0);
    for (std::size_t c = 0; c < corners.size(); ++c) {
      const glm::vec4 want = stored.tangents[stored.indices[c]];
      const double angle = angleBetween(glm::dvec3(corners[c]), glm::dvec3(want));
      result.maxAngle = std::max(result.maxAngle, angle);
      result.within += angle <= 1e-3;
      result.signsAgree += corners[c].w == want.w;
      ++result.corners;
    }
  }
  return result;
}

TEST(TangentSpace, NormalTangentMirrorTestsStoredTangentsAreReproduced) {
  const Agreement a = compareWithStored("NormalTangentMirrorTest");
  std::printf("NormalTangentMirrorTest: %zu corners, w agrees on %zu, max angle %.3g rad\n",
              a.corners, a.signsAgree, a.maxAngle);
  EXPECT_EQ(a.corners, 15720u);
  EXPECT_EQ(a.signsAgree, a.corners);
  EXPECT_EQ(a.within, a.corners);
  EXPECT_LT(a.maxAngle, 1e-3);
  // On (u, v) instead of (u, 1 - v) every sign is wrong (LIGHTING.md).
  const Agreement flipped = compareWithStored("NormalTangentMirrorTest", true);
  EXPECT_EQ(flipped.signsAgree, 0u);
}

// The loader's generated tangents, on models none of whose normal-mapped
// primitives store TANGENT, are their corners' own, vertices split only
// where corners disagree.
TEST(TangentSpace, TheLoaderGeneratesTangentsWhereAPrimitiveHasNone) {
  for (const char* model : {"NormalTangentTest", "GlassVaseFlowers", "TextureTransformMultiTest"}) {
    SCOPED_TRACE(model);
    const Scene scene = loadGltf(assetPath(model));
    const tinygltf::Model json = parseReference(assetPath(model));
    std::size_t fileVertices = 0, loadedVertices = 0, generated = 0;
    for (const tinygltf::Mesh& mesh : json.meshes)
      for (const tinygltf::Primitive& p : mesh.primitives)
        if (p.material >= 0 && json.materials[std::size_t(p.material)].normalTexture.index >= 0)
          fileVertices += json.accessors.at(std::size_t(p.attributes.at("POSITION"))).count;
    for (const Mesh& mesh : scene.meshes) {
      if (mesh.material < 0) continue;
      const Material& material = scene.materials[std::size_t(mesh.material)];
      if (!material.normal.present()) continue;
      ++generated;
      loadedVertices += mesh.positions.size();
      ASSERT_EQ(mesh.tangents.size(), mesh.positions.size());
      // Copies of a vertex weld back into it, so the split mesh gives the
      // same corners.
      const std::vector<glm::vec4> corners = mikkTSpaceCorners(mesh, material.normal.texCoord);
      for (std::size_t c = 0; c < corners.size(); ++c)
        ASSERT_EQ(corners[c], mesh.tangents[mesh.indices[c]]) << c;
    }
    EXPECT_GT(generated, 0u);
    EXPECT_GE(loadedVertices, fileVertices);
    std::printf("%s: %zu normal-mapped primitives, %zu vertices in the file, %zu after splitting\n",
                model, generated, fileVertices, loadedVertices);
  }
}

}  // namespace
}  // namespace quadra
