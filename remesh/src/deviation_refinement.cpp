#include "deviation_refinement.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "prm/vec3.h"

namespace prm::remesh {
namespace {

// How far from the split edge towards the wanted point a new vertex may go, tried in this order (an input vertex
// only: a vertex for a straying mesh point goes onto the input or nowhere, else the next round finds it again).
constexpr double kShares[] = {1.0, 0.75, 0.5, 0.25};
// Rounds of insertions (each measures the deviations of the refined mesh again).
constexpr size_t kMaxRounds = 12;
// A point of a triangle this close to an edge (smallest barycentric coordinate) splits the edge, not the triangle.
constexpr double kEdgeBarycentric = 0.02;
// The points of a mesh triangle measured against the input (pr>in): its centroid and its edges' midpoints.
constexpr double kProbes[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};

Vec3 face_normal(const Mesh& m, const Tri& t) {
  return triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
}

// Barycentric coordinates of q (a point of triangle t) in t.
std::array<double, 3> barycentric(const Mesh& m, const Tri& t, const Vec3& q) {
  const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
  const Vec3 v0 = b - a, v1 = c - a, v2 = q - a;
  const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0), d21 = dot(v2, v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  return {1 - v - w, v, w};
}

// The face other than `not_f` that holds vertices a and b (-1 if none).
int64_t other_face(const Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, uint32_t a, uint32_t b,
                   uint32_t not_f) {
  for (uint32_t f : vertex_faces[a]) {
    if (f == not_f) continue;
    const Tri& t = m.triangles[f];
    if (t[0] == b || t[1] == b || t[2] == b) return f;
  }
  return -1;
}

// Does every new triangle face the way the triangle it replaces faced (and keep some area)?
bool faces_agree(const Mesh& m, const Vec3& old_normal, const std::vector<Tri>& tris) {
  const double scale = norm(old_normal);
  for (const Tri& t : tris) {
    const Vec3 n = face_normal(m, t);
    if (!(dot(n, old_normal) > 1e-3 * norm(n) * scale)) return false;
  }
  return true;
}

// A place where the mesh is too far from the input: the point `at` of mesh triangle `face`, and the point of the
// input it should reach (an input vertex the mesh misses, or the input's closest point to a mesh point that strays).
struct Deviation {
  uint32_t face;
  Vec3 at;
  Vec3 wanted;
  double distance2;
  uint32_t input_vertex;  // UINT32_MAX for a mesh point
};

// Inserts a vertex for d into m (splitting d.face, or one of its edges and the triangle across it). False when every
// way of doing so turns a triangle over or touches a triangle changed in this round.
bool insert(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, std::vector<uint8_t>& touched,
            const Deviation& d) {
  const uint32_t f = d.face;
  const Tri t = m.triangles[f];
  const Vec3 old_normal = face_normal(m, t);
  const std::array<double, 3> bc = barycentric(m, t, d.at);
  const uint32_t nv = static_cast<uint32_t>(m.positions.size());
  m.positions.push_back(d.wanted);
  std::array<int, 3> corners = {0, 1, 2};  // the closest edge first: opposite the smallest coordinate
  std::sort(corners.begin(), corners.end(),
            [&](int x, int y) { return bc[static_cast<size_t>(x)] < bc[static_cast<size_t>(y)]; });
  if (bc[static_cast<size_t>(corners[0])] > kEdgeBarycentric) {
    // Inside the triangle: split it in three.
    const std::vector<Tri> tris = {{t[0], t[1], nv}, {t[1], t[2], nv}, {t[2], t[0], nv}};
    for (double share : kShares) {
      if (share < 1 && d.input_vertex == UINT32_MAX) break;
      m.positions[nv] = d.at + share * (d.wanted - d.at);
      if (!faces_agree(m, old_normal, tris)) continue;
      m.triangles[f] = tris[0];
      m.triangles.push_back(tris[1]);
      m.triangles.push_back(tris[2]);
      touched[f] = 1;
      touched.resize(m.triangles.size(), 1);
      return true;
    }
  }
  // Near an edge (or where the split in three turns a triangle over): split an edge and both its triangles. The new
  // vertex at the wanted point or, where that turns a triangle over (beyond a corner or a sharp crease), part of the
  // way there from the edge.
  for (int k : corners) {
    const uint32_t a = t[static_cast<size_t>((k + 1) % 3)], b = t[static_cast<size_t>((k + 2) % 3)],
                   c = t[static_cast<size_t>(k)];
    const int64_t g = other_face(m, vertex_faces, a, b, f);
    if (g < 0 || touched[static_cast<size_t>(g)]) continue;
    const Tri u = m.triangles[static_cast<size_t>(g)];
    uint32_t e = u[0];
    for (uint32_t x : u)
      if (x != a && x != b) e = x;
    const std::vector<Tri> mine = {{a, nv, c}, {nv, b, c}}, theirs = {{b, nv, e}, {nv, a, e}};
    const Vec3 pa = m.positions[a], pb = m.positions[b];
    const double s = std::clamp(dot(d.wanted - pa, pb - pa) / std::max(norm2(pb - pa), 1e-300), 0.1, 0.9);
    const Vec3 on_edge = pa + s * (pb - pa);
    const Vec3 normal_u = face_normal(m, u);
    for (double share : kShares) {
      if (share < 1 && d.input_vertex == UINT32_MAX) break;
      m.positions[nv] = on_edge + share * (d.wanted - on_edge);
      if (!faces_agree(m, old_normal, mine) || !faces_agree(m, normal_u, theirs)) continue;
      m.triangles[f] = mine[0];
      m.triangles.push_back(mine[1]);
      m.triangles[static_cast<size_t>(g)] = theirs[0];
      m.triangles.push_back(theirs[1]);
      touched[f] = 1;
      touched[static_cast<size_t>(g)] = 1;
      touched.resize(m.triangles.size(), 1);
      return true;
    }
  }
  m.positions.pop_back();
  return false;
}

}  // namespace

DeviationRefinementStats refine_deviations(PrmMesh& prm, const Mesh& input, const AabbTree& input_tree,
                                           const DeviationRefinementOptions& options) {
  DeviationRefinementStats st;
  if (!(options.max_deviation > 0) || input.positions.empty()) return st;
  Mesh& m = prm.mesh;
  const size_t budget = static_cast<size_t>(options.max_insert_share * static_cast<double>(m.positions.size()));
  std::vector<uint8_t> used(input.positions.size(), 0);
  for (const Tri& t : input.triangles)
    for (uint32_t v : t) used[v] = 1;
  std::vector<uint8_t> refused(input.positions.size(), 0);
  const double bound2 = options.max_deviation * options.max_deviation;
  std::vector<std::vector<uint32_t>> vertex_faces;
  while (st.rounds < kMaxRounds && st.inserted < budget) {
    ++st.rounds;
    // in>pr: the input vertices far from the mesh.
    const AabbTree tree(m);
    std::vector<AabbTree::Hit> hits(input.positions.size());
    tbb::parallel_for(size_t{0}, input.positions.size(), [&](size_t v) {
      if (used[v] && !refused[v]) hits[v] = tree.closest(input.positions[v]);
    });
    std::vector<Deviation> far;
    for (uint32_t v = 0; v < hits.size(); ++v)
      if (hits[v].found() && hits[v].distance2 > bound2)
        far.push_back({hits[v].face, hits[v].point, input.positions[v], hits[v].distance2, v});
    // pr>in: the mesh's triangles whose centroid or edge midpoints are far from the input.
    std::vector<std::array<AabbTree::Hit, 4>> probes(m.triangles.size());
    tbb::parallel_for(size_t{0}, m.triangles.size(), [&](size_t f) {
      const Tri& t = m.triangles[f];
      for (size_t k = 0; k < 4; ++k) {
        const Vec3 p = kProbes[k][0] * m.positions[t[0]] + kProbes[k][1] * m.positions[t[1]] +
                       kProbes[k][2] * m.positions[t[2]];
        probes[f][k] = input_tree.closest(p);
      }
    });
    for (uint32_t f = 0; f < m.triangles.size(); ++f) {
      const Tri& t = m.triangles[f];
      size_t worst = 4;
      for (size_t k = 0; k < 4; ++k)
        if (probes[f][k].found() && probes[f][k].distance2 > bound2 &&
            (worst == 4 || probes[f][k].distance2 > probes[f][worst].distance2))
          worst = k;
      if (worst == 4) continue;
      const Vec3 p = kProbes[worst][0] * m.positions[t[0]] + kProbes[worst][1] * m.positions[t[1]] +
                     kProbes[worst][2] * m.positions[t[2]];
      far.push_back({f, p, probes[f][worst].point, probes[f][worst].distance2, UINT32_MAX});
    }
    if (far.empty()) break;
    // Farthest first; one insertion per triangle neighbourhood in a round (the rest is measured again next round).
    std::sort(far.begin(), far.end(), [](const Deviation& a, const Deviation& b) {
      if (a.distance2 != b.distance2) return a.distance2 > b.distance2;
      if (a.face != b.face) return a.face < b.face;
      return a.input_vertex < b.input_vertex;
    });
    vertex_faces.assign(m.positions.size(), {});
    for (uint32_t f = 0; f < m.triangles.size(); ++f)
      for (uint32_t v : m.triangles[f]) vertex_faces[v].push_back(f);
    std::vector<uint8_t> touched(m.triangles.size(), 0);
    size_t inserted_this_round = 0;
    for (const Deviation& d : far) {
      if (st.inserted >= budget) break;
      if (touched[d.face]) continue;
      if (insert(m, vertex_faces, touched, d)) {
        ++st.inserted;
        ++inserted_this_round;
      } else {
        ++st.refused;
        if (d.input_vertex != UINT32_MAX) refused[d.input_vertex] = 1;
      }
    }
    if (inserted_this_round == 0) break;
  }
  // Labels: the new vertices are irregular, and every triangle is labelled again (the split ones lost regularity).
  prm.vertex_relief.resize(m.positions.size(), -1);
  prm.lattice_i.resize(m.positions.size(), 0);
  prm.lattice_j.resize(m.positions.size(), 0);
  prm.face_relief.resize(m.triangles.size(), -1);
  prm.face_regular.resize(m.triangles.size(), 0);
  for (size_t f = 0; f < m.triangles.size(); ++f) label_face(prm, f);
  return st;
}

}  // namespace prm::remesh
