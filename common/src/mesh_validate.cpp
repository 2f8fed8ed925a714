// Sort-based edge tables and union-find: linear-logarithmic in the number of faces.
#include "prm/mesh_validate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <string>

#include "prm/error.h"
#include "prm/vec3.h"

namespace prm {
namespace {

struct UnionFind {
  std::vector<uint32_t> p;
  explicit UnionFind(size_t n) : p(n) { std::iota(p.begin(), p.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
  }
  void unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) p[std::max(a, b)] = std::min(a, b);
  }
};

struct HalfEdge {
  uint32_t lo, hi;  // sorted vertex pair
  uint32_t face;
  uint8_t corner;  // the edge runs from corner to corner + 1
  bool forward;    // from lo to hi
};

}  // namespace

int MeshReport::genus_sum() const {
  int g = 0;
  for (const ComponentReport& c : per_component) {
    if (c.genus < 0) return -1;
    g += c.genus;
  }
  return g;
}

MeshReport validate_mesh(const Mesh& m) {
  MeshReport r;
  const size_t nv = m.positions.size(), nf = m.triangles.size();
  r.vertices = nv;
  r.faces = nf;
  for (const Tri& t : m.triangles)
    for (uint32_t v : t)
      if (v >= nv)
        throw std::invalid_argument("validate_mesh: a triangle uses vertex " + std::to_string(v) + " of " +
                                    std::to_string(nv));
  // The first few offenders of each kind, for messages; the text is only built while there is room for it.
  enum Kind { kRepeated, kZeroArea, kDuplicate, kInconsistent, kNonManifoldEdge, kNonManifoldVertex, kKinds };
  constexpr int kPerKind = 3;
  int shown[kKinds] = {0};
  auto want_example = [&](Kind k) { return shown[k] < kPerKind; };
  auto example = [&](Kind k, std::string s) {
    ++shown[k];
    r.examples.push_back(std::move(s));
  };
  // Bounding box.
  if (nv) {
    r.bbox_min = r.bbox_max = m.positions[0];
    for (const Vec3& p : m.positions)
      for (size_t a = 0; a < 3; ++a) {
        r.bbox_min[a] = std::min(r.bbox_min[a], p[a]);
        r.bbox_max[a] = std::max(r.bbox_max[a], p[a]);
      }
    r.diagonal = norm(r.bbox_max - r.bbox_min);
  }
  const double area_eps = 1e-14 * r.diagonal * r.diagonal;

  // Face checks.
  std::vector<uint8_t> referenced(nv, 0);
  std::vector<std::array<uint32_t, 4>> sorted_faces;
  sorted_faces.reserve(nf);
  for (uint32_t f = 0; f < nf; ++f) {
    const Tri& t = m.triangles[f];
    for (uint32_t v : t) referenced[v] = 1;
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++r.repeated_index_faces;
      if (want_example(kRepeated))
        example(kRepeated, "face " + std::to_string(f) + " uses vertex " +
                               std::to_string(t[0] == t[1] || t[0] == t[2] ? t[0] : t[1]) + " twice");
    } else if (norm(triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]])) <=
               2 * area_eps) {
      ++r.zero_area_faces;
      if (want_example(kZeroArea)) example(kZeroArea, "face " + std::to_string(f) + " has zero area");
    }
    std::array<uint32_t, 3> s = t;
    std::sort(s.begin(), s.end());
    sorted_faces.push_back({s[0], s[1], s[2], f});
  }
  std::sort(sorted_faces.begin(), sorted_faces.end());
  for (size_t i = 1; i < sorted_faces.size(); ++i)
    if (sorted_faces[i][0] == sorted_faces[i - 1][0] && sorted_faces[i][1] == sorted_faces[i - 1][1] &&
        sorted_faces[i][2] == sorted_faces[i - 1][2]) {
      ++r.duplicate_faces;
      if (want_example(kDuplicate))
        example(kDuplicate, "face " + std::to_string(sorted_faces[i][3]) + " repeats face " +
                                std::to_string(sorted_faces[i - 1][3]));
    }
  for (uint8_t u : referenced) r.unreferenced_vertices += !u;

  // Edges.
  std::vector<HalfEdge> he;
  he.reserve(3 * nf);
  for (uint32_t f = 0; f < nf; ++f)
    for (uint8_t k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
      if (a == b) continue;
      he.push_back({std::min(a, b), std::max(a, b), f, k, a < b});
    }
  std::sort(he.begin(), he.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.face < y.face;
  });
  UnionFind faces(nf);
  UnionFind corners(3 * nf);  // corners of one vertex joined across manifold edges: fans
  std::vector<uint32_t> boundary_from, boundary_to, boundary_face;  // boundary edges in face direction
  std::vector<uint32_t> edge_component;  // one face per edge, for per-component edge counts
  auto corner_of = [&](uint32_t f, uint32_t v) {
    for (uint32_t k = 0; k < 3; ++k)
      if (m.triangles[f][k] == v) return 3 * f + k;
    return 3 * f;
  };
  for (size_t i = 0; i < he.size();) {
    size_t j = i + 1;
    while (j < he.size() && he[j].lo == he[i].lo && he[j].hi == he[i].hi) ++j;
    const size_t n = j - i;
    ++r.edges;
    edge_component.push_back(he[i].face);
    for (size_t k = i + 1; k < j; ++k) faces.unite(he[i].face, he[k].face);
    if (n == 1) {
      ++r.boundary_edges;
      const Tri& t = m.triangles[he[i].face];
      boundary_from.push_back(t[he[i].corner]);
      boundary_to.push_back(t[(he[i].corner + 1) % 3]);
      boundary_face.push_back(he[i].face);
    } else if (n == 2) {
      if (he[i].forward == he[i + 1].forward) {
        if (!r.inconsistent_edges) r.first_inconsistent_edge = {he[i].lo, he[i].hi};
        ++r.inconsistent_edges;
        if (want_example(kInconsistent))
          example(kInconsistent, "faces " + std::to_string(he[i].face) + " and " +
                                     std::to_string(he[i + 1].face) + " traverse edge (" +
                                     std::to_string(he[i].lo) + ", " + std::to_string(he[i].hi) +
                                     ") the same way");
      }
      for (uint32_t v : {he[i].lo, he[i].hi})
        corners.unite(corner_of(he[i].face, v), corner_of(he[i + 1].face, v));
    } else {
      if (!r.non_manifold_edges) r.first_non_manifold_edge = {he[i].lo, he[i].hi};
      ++r.non_manifold_edges;
      if (want_example(kNonManifoldEdge))
        example(kNonManifoldEdge, "edge (" + std::to_string(he[i].lo) + ", " + std::to_string(he[i].hi) +
                                      ") has " + std::to_string(n) + " faces");
      // Faces around a vertex that meet at an edge belong to one fan, even at a non-manifold edge: a vertex
      // is only called non-manifold for a pinch (as MANIFEST.md counts them); the edge is reported on its
      // own.
      for (size_t k = i + 1; k < j; ++k)
        for (uint32_t v : {he[i].lo, he[i].hi})
          corners.unite(corner_of(he[i].face, v), corner_of(he[k].face, v));
    }
    i = j;
  }

  // Fans per vertex.
  std::vector<uint32_t> fan_count(nv, 0);
  std::vector<uint8_t> root_seen(3 * nf, 0);
  for (uint32_t f = 0; f < nf; ++f)
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t c = 3 * f + k;
      const uint32_t root = corners.find(c);
      if (!root_seen[root]) {
        root_seen[root] = 1;
        ++fan_count[m.triangles[f][k]];
      }
    }
  for (uint32_t v = 0; v < nv; ++v)
    if (fan_count[v] > 1) {
      if (!r.non_manifold_vertices) r.first_non_manifold_vertex = v;
      ++r.non_manifold_vertices;
      if (want_example(kNonManifoldVertex))
        example(kNonManifoldVertex, "vertex " + std::to_string(v) + " joins " + std::to_string(fan_count[v]) +
                                        " fans of faces (pinched)");
    }

  // Boundary loops: follow boundary edges head to tail; a vertex with several outgoing boundary edges
  // (pinched) still ends every loop, since each edge is used once. loop_face keeps a face of each loop (for
  // its component).
  std::vector<uint32_t> loop_face;
  {
    std::vector<uint32_t> order(boundary_from.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return boundary_from[a] < boundary_from[b]; });
    std::vector<uint8_t> used(boundary_from.size(), 0);
    auto next_edge = [&](uint32_t v) -> int64_t {
      auto it = std::lower_bound(order.begin(), order.end(), v,
                                 [&](uint32_t e, uint32_t x) { return boundary_from[e] < x; });
      for (; it != order.end() && boundary_from[*it] == v; ++it)
        if (!used[*it]) return *it;
      return -1;
    };
    for (uint32_t e0 = 0; e0 < boundary_from.size(); ++e0) {
      if (used[e0]) continue;
      loop_face.push_back(boundary_face[e0]);
      int64_t e = e0;
      while (e >= 0 && !used[static_cast<size_t>(e)]) {
        used[static_cast<size_t>(e)] = 1;
        e = next_edge(boundary_to[static_cast<size_t>(e)]);
      }
    }
  }
  r.boundary_loops = loop_face.size();

  // Components.
  std::vector<int64_t> comp_index(nf, -1);
  std::vector<ComponentReport> comps;
  std::vector<uint32_t> comp_of_face(nf);
  for (uint32_t f = 0; f < nf; ++f) {
    const uint32_t root = faces.find(f);
    if (comp_index[root] < 0) {
      comp_index[root] = static_cast<int64_t>(comps.size());
      comps.emplace_back();
    }
    comp_of_face[f] = static_cast<uint32_t>(comp_index[root]);
    ++comps[comp_of_face[f]].faces;
  }
  // A vertex may belong to several components (two surfaces touching at a point): count (component, vertex)
  // pairs, and fans of faces per pair, so that each component is judged on its own.
  {
    struct CornerKey {
      uint32_t comp, vertex, fan;
      bool operator<(const CornerKey& o) const {
        return comp != o.comp ? comp < o.comp : vertex != o.vertex ? vertex < o.vertex : fan < o.fan;
      }
      bool operator==(const CornerKey& o) const {
        return comp == o.comp && vertex == o.vertex && fan == o.fan;
      }
    };
    std::vector<CornerKey> keys;
    keys.reserve(3 * nf);
    for (uint32_t f = 0; f < nf; ++f)
      for (uint32_t k = 0; k < 3; ++k)
        keys.push_back({comp_of_face[f], m.triangles[f][k], corners.find(3 * f + k)});
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    for (size_t i = 0; i < keys.size();) {
      size_t j = i + 1;
      while (j < keys.size() && keys[j].comp == keys[i].comp && keys[j].vertex == keys[i].vertex) ++j;
      ++comps[keys[i].comp].vertices;
      if (j - i > 1) comps[keys[i].comp].manifold = false;  // a pinch inside the component
      i = j;
    }
  }
  for (uint32_t f : edge_component) ++comps[comp_of_face[f]].edges;
  for (uint32_t f : loop_face) ++comps[comp_of_face[f]].boundary_loops;
  for (size_t i = 0; i < he.size();) {
    size_t j = i + 1;
    while (j < he.size() && he[j].lo == he[i].lo && he[j].hi == he[i].hi) ++j;
    if (j - i > 2 || (j - i == 2 && he[i].forward == he[i + 1].forward))
      comps[comp_of_face[he[i].face]].manifold = false;
    i = j;
  }
  for (ComponentReport& c : comps) {
    c.euler = static_cast<long>(c.vertices) - static_cast<long>(c.edges) + static_cast<long>(c.faces);
    const long twice = 2 - c.euler - static_cast<long>(c.boundary_loops);
    c.genus = c.manifold && twice >= 0 && twice % 2 == 0 ? static_cast<int>(twice / 2) : -1;
  }
  // The whole mesh's V - E + F over referenced vertices (a vertex shared by two components counts once).
  r.euler =
      static_cast<long>(nv - r.unreferenced_vertices) - static_cast<long>(r.edges) + static_cast<long>(nf);
  std::sort(comps.begin(), comps.end(),
            [](const ComponentReport& a, const ComponentReport& b) { return a.faces > b.faces; });
  r.components = comps.size();
  r.per_component = std::move(comps);
  return r;
}

void check_remesh_range(const Mesh& mesh) {
  if (mesh.positions.empty()) throw InputError("the mesh has no vertices");
  auto g = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return std::string(buf);
  };
  Vec3 lo = mesh.positions[0], hi = mesh.positions[0];
  double largest = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    for (size_t a = 0; a < 3; ++a) {
      const double x = mesh.positions[v][a];
      if (!(std::fabs(x) <= kMaxRemeshCoordinate))  // also NaN
        throw InputError("vertex " + std::to_string(v) + " has the coordinate " + g(x) +
                         ": coordinates must be finite and at most " + g(kMaxRemeshCoordinate) +
                         " in magnitude (lengths are squared and multiplied by areas, which would overflow); scale the "
                         "mesh down");
      lo[a] = std::min(lo[a], x);
      hi[a] = std::max(hi[a], x);
      largest = std::max(largest, std::fabs(x));
    }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  if (extent == 0) throw InputError("all the vertices coincide (the bounding box is a point): there is no surface");
  if (extent < kMinRemeshExtent || extent < kMinRemeshExtentRelative * largest)
    throw InputError("the bounding box is " + g(extent) + " wide at coordinates up to " + g(largest) +
                     ": too narrow to quantize (at least " + g(kMinRemeshExtent) + " and " +
                     g(kMinRemeshExtentRelative) + " of the largest coordinate); scale or move the mesh");
  double area = 0;
  for (const Tri& t : mesh.triangles)
    if (t[0] < mesh.positions.size() && t[1] < mesh.positions.size() && t[2] < mesh.positions.size())
      area += triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
  if (!(area > kMinRemeshAreaRelative * extent * extent))
    throw InputError("the faces have no area (" + g(area) + " in a box " + g(extent) +
                     " wide): the vertices lie on a line, there is no surface");
}

}  // namespace prm
