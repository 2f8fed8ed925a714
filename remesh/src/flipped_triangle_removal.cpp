// Paper §2.4: the flipped (and zero-area) triangles left by the merge are removed by local operations:
// collapses, flips, vertex moves, splits at the input surface, and as a last resort
// region_retriangulation.cpp.
#include <stdexcept>

#include "prm/vec3.h"
#include "openmesh_edits.h"
#include "seam_optimizer.h"

namespace prm::remesh {

// The loops below add and delete faces as they go, so they walk the face indices that exist when a round
// starts. (Not OpenMesh's skipping iterators: when the face at the range's end index is deleted, they step
// over the end and run off the face array.)
size_t SeamOptimizer::remove_bad_triangles() {
  size_t repairs = 0;
  // Rounds of local fixes; when a round fixes nothing, the next may also move grid vertices (which then stop
  // being grid vertices). Stops when no bad triangle is left or a round with grid moves fixes nothing.
  bool allow_lattice = false;
  for (int round = 0; round < 32; ++round) {
    size_t fixed = 0, bad = 0;
    for (int i = 0, n = static_cast<int>(mesh_.n_faces()); i < n; ++i) {
      const FH f(i);
      if (mesh_.status(f).deleted() || face_ok(f)) continue;
      ++bad;
      if (repair_face(f) || relocate_vertex(f, allow_lattice) ||
          (allow_lattice && (collapse_face(f) || split_edge_on_surface(f) || split_face_on_surface(f))))
        ++fixed;
    }
    repairs += fixed;
    if (bad == 0) break;
    if (fixed == 0) {
      if (allow_lattice) break;
      allow_lattice = true;
    }
  }
  // What the local moves could not fix: the region around each bad face is removed and triangulated afresh.
  for (int round = 0; round < 8; ++round) {
    size_t fixed = 0, bad = 0;
    for (int i = 0, n = static_cast<int>(mesh_.n_faces()); i < n; ++i) {
      const FH f(i);
      if (mesh_.status(f).deleted() || face_ok(f)) continue;
      ++bad;
      if (retriangulate_around(f)) ++fixed;
    }
    repairs += fixed;
    if (bad == 0 || fixed == 0) break;
  }
  return repairs;
}

// Fix one bad face: collapse one of its edges (moving a non-grid vertex first) or flip one of its edges.
bool SeamOptimizer::repair_face(FH f) {
  HH best;
  int best_rank = -1;
  for (auto h : mesh_.fh_range(f))
    for (HH k : {h, mesh_.opposite_halfedge_handle(h)}) {
      const VH x = mesh_.from_vertex_handle(k);
      const int rank = mv(x).lattice ? 1 : 2;
      if (rank > best_rank && collapse_improves(k)) {
        best = k;
        best_rank = rank;
      }
    }
  if (best.is_valid()) {
    remesh::collapse(mesh_, best);
    return true;
  }
  // A flip that leaves fewer bad triangles among the two it touches.
  for (auto h : mesh_.fh_range(f)) {
    const EH e = mesh_.edge_handle(h);
    if (mesh_.is_boundary(e) || !is_flip_ok(mesh_, e)) continue;
    const HH o = mesh_.opposite_halfedge_handle(h);
    const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
    const VH d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
    const int before =
        !triangle_ok(a, b, c, pos(a), pos(b), pos(c)) + !triangle_ok(b, a, d, pos(b), pos(a), pos(d));
    const bool ok1 = triangle_ok(c, a, d, pos(c), pos(a), pos(d)),
               ok2 = triangle_ok(d, b, c, pos(d), pos(b), pos(c));
    // Both new triangles keep some area, so that no zero-area triangle is made.
    const bool area1 = norm(cross(pos(a) - pos(c), pos(d) - pos(c))) > min_norm_;
    const bool area2 = norm(cross(pos(b) - pos(d), pos(c) - pos(d))) > min_norm_;
    if (area1 && area2 && (!ok1 + !ok2) < before) {
      mesh_.flip(e);
      return true;
    }
  }
  return false;
}

// For repairs: the collapse x -> y removes at least one bad triangle and turns no good triangle bad.
bool SeamOptimizer::collapse_improves(HH h) {
  if (!is_collapse_ok(mesh_, h) || moves_boundary(h)) return false;
  const VH x = mesh_.from_vertex_handle(h), y = mesh_.to_vertex_handle(h);
  const Vec3 py = pos(y), px = pos(x);
  int bad_before = 0, bad_after = 0;
  for (auto oh : mesh_.voh_range(x)) {
    if (mesh_.is_boundary(oh)) continue;
    const VH a = mesh_.to_vertex_handle(oh), b = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(oh));
    const bool ok_before = triangle_ok(x, a, b, px, pos(a), pos(b));
    bad_before += !ok_before;
    if (a == y || b == y) continue;
    const bool ok_after = triangle_ok(y, a, b, py, pos(a), pos(b));
    if (ok_before && !ok_after) return false;
    bad_after += !ok_after;
  }
  return bad_after < bad_before;
}

// Moves a non-grid vertex of f towards the centroid of its neighbours until all its triangles are valid.
// (Non-grid vertices may sit anywhere; the move is a fraction of a grid step, along the surface.)
bool SeamOptimizer::relocate_vertex(FH f, bool allow_lattice) {
  for (auto v : mesh_.fv_range(f)) {
    if ((mv(v).lattice && !allow_lattice) || mesh_.is_boundary(v)) continue;  // the open boundary stays
    Vec3 centroid{0, 0, 0};
    int n = 0;
    for (auto w : mesh_.vv_range(v)) {
      centroid += pos(w);
      ++n;
    }
    if (n == 0) continue;
    centroid = centroid * (1.0 / n);
    const Vec3 old = pos(v);
    // Candidates: towards the centroid of the neighbours, and the input points nearest to those places.
    std::vector<Vec3> candidates;
    std::vector<int32_t> on_face;  // the input face a candidate lies on, or -1
    for (double t : {1.0, 0.5, 0.25, 0.75, 0.125}) {
      candidates.push_back(lerp(old, centroid, t));
      on_face.push_back(-1);
    }
    for (size_t i = 0, k = candidates.size(); i < k; ++i) {
      const auto hit = tree_.closest(candidates[i]);
      if (!hit.found()) continue;
      candidates.push_back(hit.point);
      on_face.push_back(static_cast<int32_t>(hit.face));
    }
    for (size_t ci = 0; ci < candidates.size(); ++ci) {
      const Vec3& p = candidates[ci];
      bool ok = true;
      for (auto oh : mesh_.voh_range(v)) {
        if (mesh_.is_boundary(oh)) continue;
        const VH a = mesh_.to_vertex_handle(oh), b = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(oh));
        if (!triangle_ok(v, a, b, p, pos(a), pos(b))) {
          ok = false;
          break;
        }
      }
      if (ok) {
        MergedVertex& x = m_.vertices[static_cast<size_t>(v.idx())];
        x.position = p;
        x.lattice = false;  // a moved grid vertex is no longer one
        x.on_input = on_face[ci] >= 0;
        if (x.on_input) x.source_face = on_face[ci];
        return true;
      }
    }
  }
  return false;
}

// Where the grid is too coarse for the surface (a thin part, a sharp tip), a bad triangle's edge is split at
// the input point nearest to its midpoint, when the four new triangles are all valid: a vertex that follows
// the surface where the grid cannot.
bool SeamOptimizer::split_edge_on_surface(FH f) {
  HH best;
  double best_len = 0;
  for (auto h : mesh_.fh_range(f)) {
    if (mesh_.is_boundary(mesh_.opposite_halfedge_handle(h))) continue;
    const double len = norm(pos(mesh_.to_vertex_handle(h)) - pos(mesh_.from_vertex_handle(h)));
    const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
    const VH d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(mesh_.opposite_halfedge_handle(h)));
    const auto hit = tree_.closest((pos(a) + pos(b)) * 0.5);
    if (!hit.found()) continue;
    // Faces (a, b, c) and (b, a, d) become (a, m, c), (m, b, c), (b, m, d), (m, a, d).
    MergedVertex mvx;
    mvx.position = hit.point;
    mvx.source_face = static_cast<int32_t>(hit.face);
    m_.vertices.push_back(mvx);
    const VH m(static_cast<int>(m_.vertices.size() - 1));
    const Vec3 pm = hit.point;
    const bool ok = triangle_ok(a, m, c, pos(a), pm, pos(c)) && triangle_ok(m, b, c, pm, pos(b), pos(c)) &&
                    triangle_ok(b, m, d, pos(b), pm, pos(d)) && triangle_ok(m, a, d, pm, pos(a), pos(d));
    m_.vertices.pop_back();
    if (ok && len > best_len) {
      best_len = len;
      best = h;
    }
  }
  if (!best.is_valid()) return false;
  const VH a = mesh_.from_vertex_handle(best), b = mesh_.to_vertex_handle(best);
  const auto hit = tree_.closest((pos(a) + pos(b)) * 0.5);
  MergedVertex mvx;
  mvx.position = hit.point;
  mvx.source_face = static_cast<int32_t>(hit.face);
  m_.vertices.push_back(mvx);
  const VH m = mesh_.add_vertex(OMesh::Point(hit.point[0], hit.point[1], hit.point[2]));
  if (static_cast<size_t>(m.idx()) + 1 != m_.vertices.size())
    throw std::logic_error("seam repair: vertex ids out of step");
  mesh_.split(mesh_.edge_handle(best), m);
  return true;
}

// A small bad triangle at a sharp spot: collapse all three corners into one of them, when every triangle left
// around them is valid (two collapses; the first alone may not be an improvement).
bool SeamOptimizer::collapse_face(FH f) {
  auto it = mesh_.cfv_iter(f);
  const VH corner[3] = {*it, *++it, *++it};
  for (int k = 0; k < 3; ++k) {
    const VH y = corner[k];
    bool ok = true;
    int checked = 0;
    for (int j = 0; j < 3 && ok; ++j) {
      const VH x = corner[j];
      if (x == y) continue;
      for (auto oh : mesh_.voh_range(x)) {
        if (mesh_.is_boundary(oh)) continue;
        VH p = mesh_.to_vertex_handle(oh), q = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(oh));
        int in = (p == corner[0] || p == corner[1] || p == corner[2]) +
                 (q == corner[0] || q == corner[1] || q == corner[2]);
        if (in > 0) continue;  // a triangle with two corners of f disappears
        if (!triangle_ok(y, p, q, pos(y), pos(p), pos(q))) {
          ok = false;
          break;
        }
        ++checked;
      }
    }
    if (!ok || checked == 0) continue;
    const VH x1 = corner[(k + 1) % 3], x2 = corner[(k + 2) % 3];
    HH h1 = mesh_.find_halfedge(x1, y);
    if (!h1.is_valid() || !is_collapse_ok(mesh_, h1) || moves_boundary(h1)) continue;
    remesh::collapse(mesh_, h1);
    const HH h2 = mesh_.find_halfedge(x2, y);
    if (h2.is_valid() && is_collapse_ok(mesh_, h2) && !moves_boundary(h2)) remesh::collapse(mesh_, h2);
    return true;
  }
  return false;
}

// A bad triangle whose edges cannot be split usefully: split the face at the input point nearest to its
// centroid, when the three new triangles are valid.
bool SeamOptimizer::split_face_on_surface(FH f) {
  auto it = mesh_.cfv_iter(f);
  const VH a = *it, b = *++it, c = *++it;
  const auto hit = tree_.closest((pos(a) + pos(b) + pos(c)) * (1.0 / 3.0));
  if (!hit.found()) return false;
  const Vec3 pm = hit.point;
  if (!triangle_ok(a, b, a, pos(a), pos(b), pm) || !triangle_ok(b, c, b, pos(b), pos(c), pm) ||
      !triangle_ok(c, a, c, pos(c), pos(a), pm))
    return false;
  MergedVertex mvx;
  mvx.position = pm;
  mvx.source_face = static_cast<int32_t>(hit.face);
  m_.vertices.push_back(mvx);
  const VH m = mesh_.add_vertex(OMesh::Point(pm[0], pm[1], pm[2]));
  if (static_cast<size_t>(m.idx()) + 1 != m_.vertices.size())
    throw std::logic_error("seam repair: vertex ids out of step");
  mesh_.split(f, m);
  return true;
}

}  // namespace prm::remesh
