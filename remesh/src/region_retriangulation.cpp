// The last resort of the flipped-triangle removal (paper §2.4; ours): the region around a bad face is removed
// and triangulated afresh, the best-shaped valid triangulation of its boundary polygon.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "prm/vec3.h"
#include "openmesh_edits.h"
#include "seam_optimizer.h"

namespace prm::remesh {

// Last resort for a bad face: remove the vertices in S (the face's corners, then with their neighbours) and
// triangulate the hole their stars leave afresh: the triangulation of the hole's polygon whose worst triangle
// is best shaped among those whose every triangle is valid and makes no edge that exists already (dynamic
// programming over the polygon's diagonals). The region must be a disk, so the topology does not change.
bool SeamOptimizer::retriangulate_region(const std::vector<VH>& S) {
  std::vector<FH> F;
  for (VH v : S)
    for (auto f : mesh_.vf_range(v))
      if (std::find(F.begin(), F.end(), f) == F.end()) F.push_back(f);
  auto in_region = [&](FH f) { return f.is_valid() && std::find(F.begin(), F.end(), f) != F.end(); };
  // The boundary loop, as halfedges of the region's faces whose other side is outside.
  std::vector<HH> border;
  for (FH f : F)
    for (auto h : mesh_.fh_range(f))
      if (!in_region(mesh_.opposite_face_handle(h))) border.push_back(h);
  const size_t n = border.size();
  if (n < 3 || n > 40) return false;
  std::vector<VH> ring{mesh_.from_vertex_handle(border[0])};
  HH cur = border[0];
  for (size_t k = 1; k < n; ++k) {
    const VH end = mesh_.to_vertex_handle(cur);
    HH next;
    for (HH h : border)
      if (mesh_.from_vertex_handle(h) == end) {
        if (next.is_valid()) return false;  // the loop passes a vertex twice
        next = h;
      }
    if (!next.is_valid() || next == border[0]) return false;  // several loops
    ring.push_back(end);
    cur = next;
  }
  if (mesh_.to_vertex_handle(cur) != ring[0]) return false;
  for (VH v : ring)
    if (std::find(S.begin(), S.end(), v) != S.end()) return false;
  // A disk: V - E + F = 1 with V = |S| + n, E = n + interior edges, F = |F|.
  {
    std::vector<EH> edges;
    for (FH f : F)
      for (auto e : mesh_.fe_range(f))
        if (std::find(edges.begin(), edges.end(), e) == edges.end()) edges.push_back(e);
    if (static_cast<long>(S.size() + n) - static_cast<long>(edges.size()) + static_cast<long>(F.size()) != 1)
      return false;
  }
  if (n == 3) {
    // One triangle: not when the other side already has it.
    const HH o = mesh_.find_halfedge(ring[1], ring[0]);
    if (o.is_valid() && !mesh_.is_boundary(o) &&
        mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o)) == ring[2])
      return false;
  }
  auto chord_free = [&](size_t i, size_t j) {
    if (j == i + 1 || (i == 0 && j == n - 1)) return true;  // a side of the polygon
    return !mesh_.find_halfedge(ring[i], ring[j]).is_valid();
  };
  std::vector<double> best(n * n, HUGE_VAL);
  std::vector<size_t> split(n * n, 0);
  for (size_t len = 2; len < n; ++len)
    for (size_t i = 0; i + len < n; ++i) {
      const size_t j = i + len;
      double b = -HUGE_VAL;
      if (chord_free(i, j)) {
        for (size_t k = i + 1; k < j; ++k) {
          const double sub = std::min(best[i * n + k], best[k * n + j]);
          if (!(sub > b)) continue;
          const VH a = ring[i], c = ring[k], d = ring[j];
          if (!triangle_ok(a, c, d, pos(a), pos(c), pos(d))) continue;
          const Vec3 pa = pos(a), pc = pos(c), pd = pos(d);
          const double sq = norm2(pc - pa) + norm2(pd - pc) + norm2(pa - pd);
          const double q = std::min(sub, sq > 0 ? norm(cross(pc - pa, pd - pa)) / sq : 0.0);
          if (q > b) {
            b = q;
            split[i * n + j] = k;
          }
        }
      }
      best[i * n + j] = b;
    }
  if (!(best[n - 1] > 0)) return false;
  // Only S's vertices go with the faces. A ring vertex on the mesh boundary may have every face in F (its boundary
  // edges are then sides of the polygon): OpenMesh's delete_face(f, true) would delete it too, and the new faces
  // would stand on a deleted vertex (CGAL's elephant-with-holes at --target-error 1e-4, issue 22).
  for (FH f : F) mesh_.delete_face(f, false);
  for (VH v : S) mesh_.delete_vertex(v, false);
  // Post-order: every triangle added is an ear of what is left of the hole.
  std::vector<std::array<size_t, 3>> tris;
  std::vector<std::pair<size_t, size_t>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const size_t k = split[i * n + j];
    tris.push_back({i, k, j});
    stack.push_back({i, k});
    stack.push_back({k, j});
  }
  for (auto it = tris.rbegin(); it != tris.rend(); ++it) {
    const FH f = add_triangle(mesh_, ring[(*it)[0]], ring[(*it)[1]], ring[(*it)[2]]);
    if (!f.is_valid()) throw std::logic_error("seam repair: a retriangulated region did not close");
  }
  return true;
}

bool SeamOptimizer::retriangulate_around(FH f) {
  std::vector<VH> corners;
  for (auto v : mesh_.fv_range(f)) corners.push_back(v);
  for (VH v : corners)
    if (retriangulate_region({v})) return true;
  for (size_t k = 0; k < 3; ++k)
    if (retriangulate_region({corners[k], corners[(k + 1) % 3]})) return true;
  if (retriangulate_region(corners)) return true;
  // The corners and their neighbours.
  std::vector<VH> S = corners;
  for (VH v : corners)
    for (auto w : mesh_.vv_range(v))
      if (std::find(S.begin(), S.end(), w) == S.end()) S.push_back(w);
  return retriangulate_region(S);
}

}  // namespace prm::remesh
