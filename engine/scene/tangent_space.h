// Tangents for normal maps where a glTF primitive gives none: the MikkTSpace
// algorithm (Morten S. Mikkelsen, "Simulation of Wrinkled Surfaces
// Revisited", 2008, and his reference implementation mikktspace.c, the
// tangent space glTF 2.0 §3.7.2.1 asks clients to compute), written here from
// its description. Run on (u, 1 - v), which gives the TANGENT.w that glTF
// files store (../shared/LIGHTING.md "The material").
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace quadra {

// One tangent per triangle corner (corner c is mesh.indices[c]) of
// MikkTSpace run on the mesh's positions, its normals (or, where it has
// none, each triangle's own normal, as the vertex stage draws it) and
// (u, 1 - v) of mesh.texcoords[texcoordSet]: xyz a unit vector orthogonal to
// the corner's normal, w = +1 or -1, the bitangent's sign (B = w N x T).
// Corners the algorithm leaves without a tangent (triangles degenerate in
// position and uv alike, with no healthy neighbour at the vertex) get a unit
// vector orthogonal to the normal and w = +1: never NaN.
std::vector<glm::vec4> mikkTSpaceCorners(const Mesh& mesh, int texcoordSet);

struct TangentSplit {
  std::size_t split = 0;  // vertices whose corners' tangents differ
  std::size_t added = 0;  // vertices appended for them
};

// Fills mesh.tangents with mikkTSpaceCorners. Where the corners of one
// vertex disagree (a vertex whose triangles form separate groups around it,
// or mirrored uv halves sharing a vertex; every corner without NORMAL), the
// vertex is copied, every attribute with it (skin influences, morph deltas),
// and those corners' indices moved to the copy: the tangents are exactly the
// algorithm's, the triangles keep their order, and the first tangent seen
// keeps the original vertex.
TangentSplit generateTangents(Mesh& mesh, int texcoordSet);

}  // namespace quadra
