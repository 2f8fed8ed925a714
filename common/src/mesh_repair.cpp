// prm repair: drop degenerate and duplicate faces, flip away zero-area slivers, close every hole by the triangulation
// of its boundary loop that folds least (hole_triangulation.h), or, for a long loop or one that no triangulation
// closes, with a fan around the centroid of its boundary loop (paper §4: "patching each hole with a closed triangle
// fan centered at the average of all vertices bounding the hole"). Sort-based; refuses what it cannot repair without
// guessing (non-manifold or inconsistently oriented input).
#include "prm/mesh_repair.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <unordered_set>

#include "hole_triangulation.h"
#include "prm/error.h"
#include "prm/mesh_validate.h"
#include "prm/vec3.h"

namespace prm {
namespace {

// Holes are triangulated (O(n^3) in a loop's n vertices) up to this length, and while the loops triangulated so far
// took at most this many candidate triangles in all (about n^3 / 6 a loop; ~1 s): the rest get the centroid fan, so
// that a hostile input's many long holes cost no more than that.
constexpr size_t kMaxTriangulatedLoop = 400;
constexpr double kTriangulationBudget = 6e7;

bool repeats_vertex(const Tri& t) {
  return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
}

double area2(const Mesh& m, const Tri& t) {
  return norm(triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
}

// Zero-area triangles with three distinct vertices: one vertex lies on the segment of the other two (a
// "cap"). Flipping that longest edge with the neighbouring triangle splits the neighbour at the middle vertex
// and removes the sliver without changing the surface. Done only when the flip is safe: the neighbour exists,
// the new edge is not already an edge, and both new triangles have area. Returns the number of flips; the
// rest stay (counted by the caller).
size_t flip_zero_area_faces(Mesh& m, double eps2) {
  std::vector<uint32_t> zero;
  for (uint32_t f = 0; f < m.triangles.size(); ++f)
    if (area2(m, m.triangles[f]) <= eps2) zero.push_back(f);
  if (zero.empty()) return 0;
  std::vector<std::vector<uint32_t>> faces_of = faces_around_vertices(m);
  auto has_directed = [&](uint32_t f, uint32_t a, uint32_t b) {
    const Tri& t = m.triangles[f];
    for (int k = 0; k < 3; ++k)
      if (t[k] == a && t[(k + 1) % 3] == b) return true;
    return false;
  };
  auto edge_exists = [&](uint32_t a, uint32_t b) {
    for (uint32_t f : faces_of[a])
      for (uint32_t v : m.triangles[f])
        if (v == b) return true;
    return false;
  };
  auto move_face = [&](uint32_t f, uint32_t from, uint32_t to) {
    auto& list = faces_of[from];
    list.erase(std::find(list.begin(), list.end(), f));
    faces_of[to].push_back(f);
  };
  size_t flips = 0;
  // A flip can make a neighbour's sliver flippable: a few passes, each bounded by the number of slivers.
  for (int pass = 0; pass < 4; ++pass) {
    size_t before = flips;
    for (uint32_t f : zero) {
      const Tri t = m.triangles[f];
      if (area2(m, t) > eps2) continue;
      // The longest edge (a, b) in face order; c is the vertex opposite, on the segment.
      int k = 0;
      double best = -1;
      for (int i = 0; i < 3; ++i) {
        const double len = norm2(m.positions[t[(i + 1) % 3]] - m.positions[t[i]]);
        if (len > best) best = len, k = i;
      }
      const uint32_t a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      uint32_t g = UINT32_MAX;
      for (uint32_t h : faces_of[a])
        if (h != f && has_directed(h, b, a)) g = h;
      if (g == UINT32_MAX) continue;
      const Tri& u = m.triangles[g];
      const uint32_t d = u[0] != a && u[0] != b ? u[0] : u[1] != a && u[1] != b ? u[1] : u[2];
      if (d == c || edge_exists(c, d)) continue;
      const Tri f_new = {c, a, d}, g_new = {c, d, b};
      if (area2(m, f_new) <= eps2 || area2(m, g_new) <= eps2) continue;
      m.triangles[f] = f_new;
      m.triangles[g] = g_new;
      move_face(f, b, d);
      move_face(g, a, c);
      ++flips;
    }
    if (flips == before) break;
  }
  return flips;
}

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

}  // namespace

// Corners of one vertex are joined across every edge with two faces; a vertex whose corners form several
// groups is pinched. Requires no edge with three or more faces. Returns the number of vertices added.
size_t split_pinched_vertices(Mesh& m) {
  const size_t nf = m.triangles.size();
  struct HalfEdge {
    uint32_t lo, hi, corner;  // corner: 3 * face + k, the edge runs from corner k to corner k + 1
  };
  std::vector<HalfEdge> he;
  he.reserve(3 * nf);
  for (uint32_t f = 0; f < nf; ++f)
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
      he.push_back({std::min(a, b), std::max(a, b), 3 * f + k});
    }
  std::sort(he.begin(), he.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.corner < y.corner;
  });
  UnionFind corners(3 * nf);
  auto next_corner = [](uint32_t c) { return c - c % 3 + (c % 3 + 1) % 3; };
  auto vertex_at = [&](uint32_t c) { return m.triangles[c / 3][c % 3]; };
  for (size_t i = 0; i + 1 < he.size(); ++i) {
    if (he[i].lo != he[i + 1].lo || he[i].hi != he[i + 1].hi) continue;
    // The two corners at each end of the shared edge belong to the same fan.
    const uint32_t c1 = he[i].corner, c2 = he[i + 1].corner;
    const uint32_t c1n = next_corner(c1), c2n = next_corner(c2);
    if (vertex_at(c1) == vertex_at(c2)) {
      corners.unite(c1, c2);
      corners.unite(c1n, c2n);
    } else {
      corners.unite(c1, c2n);
      corners.unite(c1n, c2);
    }
  }
  std::vector<uint32_t> first_root(m.positions.size(), UINT32_MAX);
  std::vector<uint32_t> copy_of_root(3 * nf, UINT32_MAX);
  size_t added = 0;
  for (uint32_t c = 0; c < 3 * nf; ++c) {
    const uint32_t v = vertex_at(c), root = corners.find(c);
    if (first_root[v] == UINT32_MAX) first_root[v] = root;
    if (root == first_root[v]) continue;
    if (copy_of_root[root] == UINT32_MAX) {
      copy_of_root[root] = static_cast<uint32_t>(m.positions.size());
      m.positions.push_back(m.positions[v]);
      for (Property& p : m.vertex_properties)
        if (p.values.size() + 1 == m.positions.size()) p.values.push_back(p.values[v]);
      ++added;
    }
    m.triangles[c / 3][c % 3] = copy_of_root[root];
  }
  return added;
}

Mesh repair_mesh(const Mesh& in, RepairReport* report, const RepairOptions& options) {
  RepairReport local;
  RepairReport& r = report ? *report : local;
  r = RepairReport{};
  const size_t nv = in.positions.size();
  for (const Tri& t : in.triangles)
    for (uint32_t v : t)
      if (v >= nv)
        throw std::invalid_argument("repair_mesh: a triangle uses vertex " + std::to_string(v) + " of " +
                                    std::to_string(nv));
  Mesh m;
  m.positions = in.positions;
  m.comments = in.comments;

  // Faces using a vertex twice, then repeats of an earlier face's vertex set (either orientation; the first
  // stays).
  std::vector<std::pair<std::array<uint32_t, 3>, uint32_t>> keyed;
  keyed.reserve(in.triangles.size());
  for (uint32_t f = 0; f < in.triangles.size(); ++f) {
    const Tri& t = in.triangles[f];
    if (repeats_vertex(t)) {
      ++r.repeated_index_removed;
      continue;
    }
    std::array<uint32_t, 3> s = t;
    std::sort(s.begin(), s.end());
    keyed.push_back({s, f});
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint8_t> keep(in.triangles.size(), 0);
  for (size_t i = 0; i < keyed.size(); ++i) {
    if (i > 0 && keyed[i].first == keyed[i - 1].first) {
      ++r.duplicate_removed;
      continue;
    }
    keep[keyed[i].second] = 1;
  }
  for (uint32_t f = 0; f < in.triangles.size(); ++f)
    if (keep[f]) m.triangles.push_back(in.triangles[f]);

  // What cannot be repaired without guessing.
  const MeshReport check = validate_mesh(m);
  auto edge_name = [](const std::array<uint32_t, 2>& e) {
    return "(" + std::to_string(e[0]) + ", " + std::to_string(e[1]) + ")";
  };
  if (check.non_manifold_edges)
    throw InputError("cannot repair safely: " + std::to_string(check.non_manifold_edges) +
                     " non-manifold edge(s), e.g. edge " + edge_name(check.first_non_manifold_edge) +
                     " has three or more faces");
  if (check.inconsistent_edges)
    throw InputError("cannot repair safely: the faces are not consistently oriented (" +
                     std::to_string(check.inconsistent_edges) + " edge(s), e.g. the two faces of edge " +
                     edge_name(check.first_inconsistent_edge) + " traverse it the same way)");

  // Pinched vertices (several fans of faces meeting at one vertex, every edge manifold): each fan after the
  // first gets its own copy of the vertex. The surface is unchanged; its topology becomes a manifold's.
  if (check.non_manifold_vertices) r.pinched_vertices_split = split_pinched_vertices(m);

  // Zero-area slivers: removing one would open a hole that a fan would refill with zero-area triangles, so
  // flip.
  if (check.zero_area_faces) {
    const double eps2 = 2e-14 * check.diagonal * check.diagonal;  // as validate_mesh()
    r.zero_area_flipped = flip_zero_area_faces(m, eps2);
    const MeshReport after = validate_mesh(m);
    if (after.zero_area_faces)
      r.notes.push_back(
          std::to_string(after.zero_area_faces) +
          " zero-area face(s) kept: no safe flip removes them (coincident vertices or a boundary)");
  }

  // Boundary edges in face direction: half-edges whose reverse no face has. On a manifold, oriented mesh each
  // boundary vertex starts exactly one of them.
  struct HalfEdge {
    uint32_t from, to;
  };
  std::vector<HalfEdge> he;
  he.reserve(3 * m.triangles.size());
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) he.push_back({t[k], t[(k + 1) % 3]});
  std::vector<uint32_t> order(he.size());
  std::iota(order.begin(), order.end(), 0u);
  auto key = [&](uint32_t i) {
    return std::make_pair(std::min(he[i].from, he[i].to), std::max(he[i].from, he[i].to));
  };
  std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return key(x) < key(y); });
  const size_t n_now = m.positions.size();  // pinch splitting added vertices
  std::vector<uint32_t> next(n_now, UINT32_MAX), next_face(n_now, UINT32_MAX);
  size_t boundary_edges = 0;
  for (size_t i = 0; i < order.size();) {
    size_t j = i + 1;
    while (j < order.size() && key(order[j]) == key(order[i])) ++j;
    if (j - i == 1) {
      next[he[order[i]].from] = he[order[i]].to;
      next_face[he[order[i]].from] = order[i] / 3;
      ++boundary_edges;
    }
    i = j;
  }

  // The edges between two boundary vertices, which a hole's triangulation may not repeat.
  std::unordered_set<uint64_t> rim_edges;
  if (boundary_edges && options.fill_holes)
    for (const Tri& t : m.triangles)
      for (int k = 0; k < 3; ++k)
        if (next[t[k]] != UINT32_MAX && next[t[(k + 1) % 3]] != UINT32_MAX)
          rim_edges.insert(edge_key(t[k], t[(k + 1) % 3]));
  const double min_area2 = 2e-14 * check.diagonal * check.diagonal;  // validate_mesh()'s zero area
  double budget = kTriangulationBudget;

  // Close each loop: triangulated where it can be, else with a fan around its centroid (which traverses the loop's
  // edges backwards).
  for (uint32_t start = 0; start < n_now && boundary_edges && options.fill_holes; ++start) {
    if (next[start] == UINT32_MAX) continue;
    std::vector<uint32_t> loop;
    std::vector<Vec3> rim_normal;
    for (uint32_t v = start; next[v] != UINT32_MAX;) {
      loop.push_back(v);
      const Tri& t = m.triangles[next_face[v]];
      const Vec3 n = triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
      const double len = norm(n);
      rim_normal.push_back(len > 0 ? n * (1.0 / len) : Vec3{0, 0, 0});
      const uint32_t w = next[v];
      next[v] = UINT32_MAX;
      v = w;
    }
    boundary_edges -= loop.size();
    ++r.holes_filled;
    const double cost = static_cast<double>(loop.size()) * static_cast<double>(loop.size()) *
                        static_cast<double>(loop.size()) / 6.0;
    // (A loop of three around a lone triangle's back would be closed by that triangle reversed: a pillow of two
    // faces with the same corners. The fan closes it with area.)
    const bool lone_triangle = loop.size() == 3 && next_face[loop[0]] == next_face[loop[1]];
    if (loop.size() <= kMaxTriangulatedLoop && cost <= budget && !lone_triangle) {
      budget -= cost;
      const size_t before = m.triangles.size();
      if (triangulate_hole(m, loop, rim_normal, rim_edges, min_area2, m.triangles)) {
        r.fill_triangles += m.triangles.size() - before;
        continue;
      }
    }
    ++r.holes_fanned;
    Vec3 c{0, 0, 0};
    for (uint32_t u : loop) c += m.positions[u];
    m.positions.push_back(c * (1.0 / static_cast<double>(loop.size())));
    const uint32_t centre = static_cast<uint32_t>(m.positions.size() - 1);
    for (size_t i = 0; i < loop.size(); ++i)
      m.triangles.push_back({centre, loop[(i + 1) % loop.size()], loop[i]});
    r.fill_triangles += loop.size();
  }

  // Vertices no face uses any more (or never did).
  std::vector<uint32_t> id(m.positions.size(), UINT32_MAX);
  for (const Tri& t : m.triangles)
    for (uint32_t v : t) id[v] = 0;
  std::vector<Vec3> pos;
  pos.reserve(m.positions.size());
  for (uint32_t v = 0; v < m.positions.size(); ++v) {
    if (id[v] == UINT32_MAX) {
      ++r.unreferenced_removed;
      continue;
    }
    id[v] = static_cast<uint32_t>(pos.size());
    pos.push_back(m.positions[v]);
  }
  for (Tri& t : m.triangles)
    for (uint32_t& v : t) v = id[v];
  m.positions = std::move(pos);
  return m;
}

std::vector<std::string> repair_summary(const RepairReport& r) {
  std::vector<std::string> out;
  auto add = [&](size_t n, const char* what) {
    if (n) out.push_back(std::to_string(n) + " " + what);
  };
  add(r.repeated_index_removed, "face(s) with a repeated vertex removed");
  add(r.duplicate_removed, "duplicate face(s) removed");
  add(r.zero_area_flipped, "zero-area face(s) flipped away");
  add(r.pinched_vertices_split, "pinched vertex copies made");
  if (r.holes_filled)
    out.push_back(std::to_string(r.holes_filled) + " hole(s) closed with " + std::to_string(r.fill_triangles) +
                  " triangles" +
                  (r.holes_fanned
                       ? " (" + std::to_string(r.holes_fanned) + " of them by a fan around a new centre vertex)"
                       : std::string()));
  add(r.unreferenced_removed, "unreferenced vertices removed");
  return out;
}

}  // namespace prm
