// MikkTSpace tangents (scene/tangent_space.h): the algorithm of Morten S.
// Mikkelsen's thesis "Simulation of Wrinkled Surfaces Revisited" (2008) and
// of his reference implementation (github.com/mmikk/MikkTSpace,
// mikktspace.c), whose steps are followed here so that the tangents agree
// with the ones exporters store:
//  1. weld the corners whose position, normal and texture coordinate are
//     equal (the vertices the algorithm sees);
//  2. per triangle, the first-order tangent and bitangent (dp/ds, dp/dt),
//     the orientation (the sign of the triangle's signed uv area), and
//     whether the triangle is healthy (non-zero uv area and derivatives);
//     triangles whose positions coincide are left out (degenerate);
//  3. triangles are neighbours across an edge they share in opposite
//     directions; around each vertex, the neighbours of one orientation
//     connected through shared edges form a group (a triangle with unusable
//     uvs joins the first group that reaches it, taking its orientation);
//  4. each group's tangent at its vertex: each member's tangent projected
//     onto the vertex normal's plane, normalized, weighted by the member's
//     corner angle (between its two edges at the vertex, projected alike),
//     summed and normalized; w is the group's orientation;
//  5. a degenerate triangle's corner takes the tangent of a healthy corner
//     on the same welded vertex.
// The reference's angular threshold is its default (180 degrees): a group
// splits only where members' projected tangent and bitangent point exactly
// opposite ways. It handles quads too; glTF meshes are triangles here.
#include "scene/tangent_space.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

namespace quadra {

namespace {

using glm::dvec3;

// The welding key: the 8 floats of a corner, -0 read as +0 (the reference
// compares by value).
struct CornerKey {
  float values[8];
  bool operator==(const CornerKey& other) const {
    return std::memcmp(values, other.values, sizeof(values)) == 0;
  }
};

struct CornerKeyHash {
  std::size_t operator()(const CornerKey& key) const {
    std::uint64_t hash = 1469598103934665603ull;
    for (const float value : key.values) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &value, sizeof(bits));
      hash = (hash ^ bits) * 1099511628211ull;
    }
    return std::size_t(hash ^ (hash >> 29));
  }
};

float positiveZero(float value) {
  return value == 0.0f ? 0.0f : value;
}

// Far from zero in the reference's sense (a normal float's magnitude).
bool notZero(double value) {
  return std::fabs(value) > double(std::numeric_limits<float>::min());
}

dvec3 normalizedOrZero(const dvec3& v) {
  const double length = glm::length(v);
  return notZero(length) ? v / length : v;
}

// v minus its component along the unit normal n, normalized where not zero.
dvec3 projected(const dvec3& v, const dvec3& n) {
  return normalizedOrZero(v - glm::dot(n, v) * n);
}

// A unit vector orthogonal to n (the tangent of a corner the algorithm
// gives none), the same for the same n.
glm::vec3 anyOrthogonal(const glm::vec3& n) {
  if (!(glm::dot(n, n) > 0.0f) || !std::isfinite(glm::dot(n, n))) return {1.0f, 0.0f, 0.0f};
  const glm::vec3 axis =
      std::fabs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::normalize(axis - glm::dot(axis, n) / glm::dot(n, n) * n);
}

struct Triangle {
  dvec3 tangent{0.0}, bitangent{0.0};  // first order, unit, signed by orientation
  bool orientPreserving = false;
  bool groupWithAny = true;         // unusable uvs: joins any group
  bool degenerate = false;          // two positions equal: left out
  int neighbour[3] = {-1, -1, -1};  // across edge i (corner i to corner i+1)
  int group[3] = {-1, -1, -1};      // the group each corner belongs to
};

struct Group {
  int vertex = 0;  // welded vertex
  bool orientPreserving = false;
  std::vector<int> triangles;
};

class MikkTSpace {
 public:
  MikkTSpace(const Mesh& mesh, int texcoordSet) : mesh_(mesh) {
    const std::size_t corners = mesh.indices.size();
    position_.resize(corners);
    normal_.resize(corners);
    uv_.resize(corners);
    const std::vector<glm::vec2>& uvs = mesh.texcoords[texcoordSet];
    for (std::size_t c = 0; c < corners; ++c) {
      const std::uint32_t v = mesh.indices[c];
      position_[c] = mesh.positions[v];
      const glm::vec2 uv = uvs.empty() ? glm::vec2(0.0f) : uvs[v];
      uv_[c] = glm::vec2(uv.x, 1.0f - uv.y);
    }
    if (!mesh.normals.empty()) {
      for (std::size_t c = 0; c < corners; ++c) normal_[c] = mesh.normals[mesh.indices[c]];
    } else {
      // glTF 2.0 §3.7.2.1: without normals, flat ones.
      for (std::size_t t = 0; t + 2 < corners; t += 3) {
        const glm::vec3 face =
            glm::cross(position_[t + 1] - position_[t], position_[t + 2] - position_[t]);
        const float length = glm::length(face);
        const glm::vec3 n = length > 0.0f && std::isfinite(length) ? face / length : face;
        normal_[t] = normal_[t + 1] = normal_[t + 2] = n;
      }
    }
    for (glm::vec3& n : normal_) {
      const float length = glm::length(n);
      if (length > 0.0f && std::isfinite(length)) n /= length;
    }
  }

  std::vector<glm::vec4> run() {
    weld();
    initTriangles();
    buildNeighbours();
    buildGroups();
    std::vector<glm::vec4> out(mesh_.indices.size(), glm::vec4(0.0f));
    std::vector<char> done(out.size(), 0);
    evaluateGroups(out, done);
    fillDegenerate(out, done);
    for (std::size_t c = 0; c < out.size(); ++c) {
      const glm::vec3 t(out[c]);
      if (!done[c] || !std::isfinite(glm::dot(t, t)) || !(glm::dot(t, t) > 0.0f))
        out[c] = glm::vec4(anyOrthogonal(normal_[c]), 1.0f);
    }
    return out;
  }

 private:
  void weld() {
    const std::size_t corners = mesh_.indices.size();
    welded_.resize(corners);
    std::unordered_map<CornerKey, int, CornerKeyHash> ids;
    ids.reserve(corners);
    for (std::size_t c = 0; c < corners; ++c) {
      CornerKey key{{positiveZero(position_[c].x), positiveZero(position_[c].y),
                     positiveZero(position_[c].z), positiveZero(normal_[c].x),
                     positiveZero(normal_[c].y), positiveZero(normal_[c].z), positiveZero(uv_[c].x),
                     positiveZero(uv_[c].y)}};
      welded_[c] = ids.try_emplace(key, int(c)).first->second;  // the first corner names it
    }
  }

  void initTriangles() {
    const std::size_t count = mesh_.indices.size() / 3;
    triangles_.resize(count);
    for (std::size_t f = 0; f < count; ++f) {
      Triangle& tri = triangles_[f];
      const std::size_t c = 3 * f;
      const glm::vec3 &p0 = position_[welded_[c]], &p1 = position_[welded_[c + 1]],
                      &p2 = position_[welded_[c + 2]];
      tri.degenerate = p0 == p1 || p0 == p2 || p1 == p2;
      if (tri.degenerate) continue;
      const dvec3 d1 = dvec3(p1) - dvec3(p0), d2 = dvec3(p2) - dvec3(p0);
      const glm::dvec2 t1(uv_[welded_[c]]), t2(uv_[welded_[c + 1]]), t3(uv_[welded_[c + 2]]);
      const glm::dvec2 t21 = t2 - t1, t31 = t3 - t1;
      const double signedArea = t21.x * t31.y - t21.y * t31.x;
      const dvec3 os = t31.y * d1 - t21.y * d2;   // dp/ds times the area
      const dvec3 ot = -t31.x * d1 + t21.x * d2;  // dp/dt times the area
      tri.orientPreserving = signedArea > 0.0;
      if (!notZero(signedArea)) continue;
      const double sign = tri.orientPreserving ? 1.0 : -1.0;
      const double lengthS = glm::length(os), lengthT = glm::length(ot);
      if (notZero(lengthS)) tri.tangent = os * (sign / lengthS);
      if (notZero(lengthT)) tri.bitangent = ot * (sign / lengthT);
      const double area = std::fabs(signedArea);
      tri.groupWithAny = !(notZero(lengthS / area) && notZero(lengthT / area));
    }
  }

  // Edges sorted by (smaller vertex, larger vertex, triangle); each edge
  // pairs with the next one of the same two vertices running the other way
  // whose triangle has that edge free, as the reference pairs them.
  void buildNeighbours() {
    struct Edge {
      int lo, hi, tri, edge;
    };
    std::vector<Edge> edges;
    edges.reserve(mesh_.indices.size());
    for (std::size_t f = 0; f < triangles_.size(); ++f) {
      if (triangles_[f].degenerate) continue;
      for (int i = 0; i < 3; ++i) {
        const int a = vertexOf(f, i), b = vertexOf(f, (i + 1) % 3);
        edges.push_back({std::min(a, b), std::max(a, b), int(f), i});
      }
    }
    std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
      return std::tie(x.lo, x.hi, x.tri, x.edge) < std::tie(y.lo, y.hi, y.tri, y.edge);
    });
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const Edge& a = edges[i];
      Triangle& ta = triangles_[std::size_t(a.tri)];
      if (ta.neighbour[a.edge] != -1) continue;
      const int fromA = vertexOf(std::size_t(a.tri), a.edge);
      for (std::size_t j = i + 1; j < edges.size() && edges[j].lo == a.lo && edges[j].hi == a.hi;
           ++j) {
        const Edge& b = edges[j];
        Triangle& tb = triangles_[std::size_t(b.tri)];
        const int fromB = vertexOf(std::size_t(b.tri), b.edge);
        if (fromB != fromA && tb.neighbour[b.edge] == -1) {
          ta.neighbour[a.edge] = b.tri;
          tb.neighbour[b.edge] = a.tri;
          break;
        }
      }
    }
  }

  int vertexOf(std::size_t triangle, int corner) const {
    return welded_[3 * triangle + std::size_t(corner)];
  }

  int cornerAt(std::size_t triangle, int vertex) const {
    for (int i = 0; i < 3; ++i)
      if (vertexOf(triangle, i) == vertex) return i;
    return -1;
  }

  // From each unassigned corner of a healthy triangle, the group of the
  // triangles reached through neighbours around that vertex with the same
  // orientation, depth first, the edge after the corner before the edge
  // before it (the reference's recursion, on an explicit stack).
  void buildGroups() {
    for (std::size_t f = 0; f < triangles_.size(); ++f) {
      const Triangle& tri = triangles_[f];
      if (tri.degenerate || tri.groupWithAny) continue;
      for (int i = 0; i < 3; ++i) {
        if (triangles_[f].group[i] != -1) continue;
        const int g = int(groups_.size());
        groups_.push_back({vertexOf(f, i), tri.orientPreserving, {}});
        std::vector<int> stack{int(f)};
        while (!stack.empty()) {
          const int t = stack.back();
          stack.pop_back();
          const int pushed = assign(t, g);
          if (pushed < 0) continue;
          Triangle& member = triangles_[std::size_t(t)];
          const int right = member.neighbour[(pushed + 2) % 3];
          const int left = member.neighbour[pushed];
          if (right >= 0) stack.push_back(right);
          if (left >= 0) stack.push_back(left);
        }
      }
    }
  }

  // Adds triangle t to group g at g's vertex; the corner, or -1 when t
  // belongs elsewhere or already joined.
  int assign(int t, int g) {
    Group& group = groups_[std::size_t(g)];
    Triangle& tri = triangles_[std::size_t(t)];
    const int i = cornerAt(std::size_t(t), group.vertex);
    if (i < 0 || tri.group[i] != -1) return -1;
    if (tri.groupWithAny && tri.group[0] == -1 && tri.group[1] == -1 && tri.group[2] == -1)
      tri.orientPreserving = group.orientPreserving;  // the first group decides
    if (tri.orientPreserving != group.orientPreserving) return -1;
    tri.group[i] = g;
    group.triangles.push_back(t);
    return i;
  }

  dvec3 projectedTangent(int t, const dvec3& n) const {
    return projected(triangles_[std::size_t(t)].tangent, n);
  }
  dvec3 projectedBitangent(int t, const dvec3& n) const {
    return projected(triangles_[std::size_t(t)].bitangent, n);
  }

  // The members' angle-weighted tangent at the group's vertex.
  dvec3 evaluate(const Group& group, const std::vector<int>& members) const {
    dvec3 sum(0.0);
    for (const int t : members) {
      const Triangle& tri = triangles_[std::size_t(t)];
      if (tri.groupWithAny) continue;
      const int i = cornerAt(std::size_t(t), group.vertex);
      const std::size_t corner = 3 * std::size_t(t) + std::size_t(i);
      const dvec3 n(normal_[std::size_t(welded_[corner])]);
      const dvec3 p1(position_[std::size_t(welded_[corner])]);
      const dvec3 p0(position_[std::size_t(vertexOf(std::size_t(t), (i + 2) % 3))]);
      const dvec3 p2(position_[std::size_t(vertexOf(std::size_t(t), (i + 1) % 3))]);
      const dvec3 e1 = projected(p0 - p1, n), e2 = projected(p2 - p1, n);
      const double angle = std::acos(std::clamp(glm::dot(e1, e2), -1.0, 1.0));
      sum += angle * projectedTangent(t, n);
    }
    return normalizedOrZero(sum);
  }

  void evaluateGroups(std::vector<glm::vec4>& out, std::vector<char>& done) const {
    // Groups larger than this skip the pairwise test (quadratic), which
    // splits only exactly opposite tangents.
    constexpr std::size_t kPairwiseLimit = 256;
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      const Group& group = groups_[g];
      std::vector<int> sorted = group.triangles;
      std::sort(sorted.begin(), sorted.end());
      std::vector<std::pair<std::vector<int>, dvec3>> subgroups;
      for (const int f : group.triangles) {
        const int i = cornerAt(std::size_t(f), group.vertex);
        const std::size_t corner = 3 * std::size_t(f) + std::size_t(i);
        const dvec3 n(normal_[std::size_t(welded_[corner])]);
        std::vector<int> members;
        if (sorted.size() > kPairwiseLimit) {
          members = sorted;
        } else {
          const dvec3 os = projectedTangent(f, n), ot = projectedBitangent(f, n);
          for (const int t : sorted) {
            const bool any =
                triangles_[std::size_t(f)].groupWithAny || triangles_[std::size_t(t)].groupWithAny;
            if (any || t == f ||
                (glm::dot(os, projectedTangent(t, n)) > -1.0 &&
                 glm::dot(ot, projectedBitangent(t, n)) > -1.0))
              members.push_back(t);
          }
        }
        auto found = std::find_if(subgroups.begin(), subgroups.end(),
                                  [&](const auto& s) { return s.first == members; });
        if (found == subgroups.end()) {
          const dvec3 tangent = evaluate(group, members);
          subgroups.emplace_back(std::move(members), tangent);
          found = subgroups.end() - 1;
        }
        out[corner] = glm::vec4(glm::vec3(found->second), group.orientPreserving ? 1.0f : -1.0f);
        done[corner] = 1;
      }
    }
  }

  // A degenerate triangle's corner copies the first healthy corner (in
  // triangle order) on its welded vertex.
  void fillDegenerate(std::vector<glm::vec4>& out, std::vector<char>& done) const {
    std::unordered_map<int, std::size_t> firstHealthy;
    bool anyDegenerate = false;
    for (std::size_t f = 0; f < triangles_.size(); ++f) {
      if (triangles_[f].degenerate) {
        anyDegenerate = true;
        continue;
      }
      for (std::size_t c = 3 * f; c < 3 * f + 3; ++c) firstHealthy.try_emplace(welded_[c], c);
    }
    if (!anyDegenerate) return;
    for (std::size_t f = 0; f < triangles_.size(); ++f) {
      if (!triangles_[f].degenerate) continue;
      for (std::size_t c = 3 * f; c < 3 * f + 3; ++c) {
        const auto source = firstHealthy.find(welded_[c]);
        if (source == firstHealthy.end()) continue;
        out[c] = out[source->second];
        done[c] = done[source->second];
      }
    }
  }

  const Mesh& mesh_;
  std::vector<glm::vec3> position_, normal_;  // per corner
  std::vector<glm::vec2> uv_;                 // per corner, (u, 1 - v)
  std::vector<int> welded_;                   // per corner: its welded vertex (a corner)
  std::vector<Triangle> triangles_;
  std::vector<Group> groups_;
};

template <typename T>
void appendCopy(std::vector<T>& values, std::uint32_t from) {
  if (values.empty()) return;
  const T copy = values[from];
  values.push_back(copy);
}

// Appends a copy of vertex `from` with every attribute; its index.
std::uint32_t copyVertex(Mesh& mesh, std::uint32_t from) {
  if (mesh.positions.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("tangent generation needs more vertices than 32-bit indices hold");
  appendCopy(mesh.positions, from);
  appendCopy(mesh.normals, from);
  for (auto& set : mesh.texcoords) appendCopy(set, from);
  appendCopy(mesh.colors, from);
  appendCopy(mesh.tangents, from);
  for (auto& set : mesh.joints) appendCopy(set, from);
  for (auto& set : mesh.weights) appendCopy(set, from);
  for (MorphTarget& target : mesh.targets) {
    appendCopy(target.positions, from);
    appendCopy(target.normals, from);
    for (auto& set : target.texcoords) appendCopy(set, from);
    appendCopy(target.colors, from);
    appendCopy(target.tangents, from);
  }
  return std::uint32_t(mesh.positions.size() - 1);
}

}  // namespace

std::vector<glm::vec4> mikkTSpaceCorners(const Mesh& mesh, int texcoordSet) {
  return MikkTSpace(mesh, texcoordSet).run();
}

TangentSplit generateTangents(Mesh& mesh, int texcoordSet) {
  const std::vector<glm::vec4> corners = mikkTSpaceCorners(mesh, texcoordSet);
  const std::size_t vertexCount = mesh.positions.size();
  mesh.tangents.assign(vertexCount, glm::vec4(0.0f));
  std::vector<char> seen(vertexCount, 0);
  // The copies made of each split vertex, with their tangents.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> copies;
  TangentSplit split;
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const std::uint32_t v = mesh.indices[c];
    if (!seen[v]) {
      seen[v] = 1;
      mesh.tangents[v] = corners[c];
      continue;
    }
    if (mesh.tangents[v] == corners[c]) continue;
    std::vector<std::uint32_t>& made = copies[v];
    if (made.empty()) ++split.split;
    const auto same = std::find_if(made.begin(), made.end(), [&](std::uint32_t copy) {
      return mesh.tangents[copy] == corners[c];
    });
    if (same != made.end()) {
      mesh.indices[c] = *same;
      continue;
    }
    const std::uint32_t copy = copyVertex(mesh, v);
    mesh.tangents[copy] = corners[c];
    made.push_back(copy);
    mesh.indices[c] = copy;
    ++split.added;
  }
  // Vertices no triangle uses still get a valid tangent.
  for (std::size_t v = 0; v < vertexCount; ++v) {
    if (seen[v]) continue;
    const glm::vec3 n = mesh.normals.empty() ? glm::vec3(0.0f) : mesh.normals[v];
    mesh.tangents[v] = glm::vec4(anyOrthogonal(n), 1.0f);
  }
  return split;
}

}  // namespace quadra
