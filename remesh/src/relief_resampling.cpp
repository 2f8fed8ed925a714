#include "relief_resampling.h"

#include <algorithm>
#include <deque>
#include <stdexcept>

#include "collapse_rules.h"
#include "openmesh_edits.h"
#include "openmesh_queries.h"

namespace prm::remesh {
namespace {

// Smallest signed area (in lattice units) a triangle may have after an operation.
constexpr double kMinArea = 1e-12;

class Resampler {
 public:
  Resampler(const SlicedRelief& s, int axis) : s_(s), sign_(axis_sign(axis)) {
    // Reserved, not grown by doubling: the sliced relief is the largest structure of a large input's remesh. A
    // disk's E = V + F - 1, and each hole adds one; E = (3 F + B) / 2 with B boundary edges, as many as the
    // boundary vertices (each on one loop: the slicing splits pinched corners), counts the holes too.
    size_t boundary = 0;
    for (const SliceVertex& v : s.vertices) boundary += v.boundary;
    const size_t edges = std::max(s.vertices.size() + s.faces.size(), (3 * s.faces.size() + boundary) / 2 + 1);
    mesh_.reserve(s.vertices.size(), edges, s.faces.size());
    for (const SliceVertex& v : s.vertices) mesh_.add_vertex(OMesh::Point(v.position[0], v.position[1], v.position[2]));
    for (const auto& f : s.faces) {
      const auto fh =
          add_triangle(mesh_, OMesh::VertexHandle(f[0]), OMesh::VertexHandle(f[1]), OMesh::VertexHandle(f[2]));
      if (!fh.is_valid()) throw std::logic_error("resample_relief: the sliced relief is not a manifold");
    }
  }

  ResampledRelief run() {
    ResampledRelief out;
    out.sliced_vertices = s_.vertices.size();
    out.sliced_faces = s_.faces.size();
    std::deque<int> queue;
    std::vector<uint8_t> queued(s_.vertices.size(), 0);
    std::vector<uint8_t> flips_done(s_.vertices.size(), 0);
    // Corners first (they live inside grid triangles), then crossings (on grid edges).
    for (int pass = 0; pass < 2; ++pass)
      for (size_t v = 0; v < s_.vertices.size(); ++v) {
        const SliceVertex& sv = s_.vertices[v];
        if (!is_movable(sv)) continue;
        if ((pass == 0) != (sv.kind == SliceKind::Corner)) continue;
        queue.push_back(static_cast<int>(v));
        queued[v] = 1;
      }
    std::vector<int> stuck;
    std::vector<int> ring;  // one buffer for all the pops
    while (!queue.empty()) {
      const int x = queue.front();
      queue.pop_front();
      queued[static_cast<size_t>(x)] = 0;
      const OMesh::VertexHandle vx(x);
      if (mesh_.status(vx).deleted()) continue;
      ring.clear();
      for (auto vv : mesh_.vv_range(vx)) ring.push_back(vv.idx());
      if (try_collapse(vx)) {
        ++out.collapses;
        for (int r : ring)
          if (!mesh_.status(OMesh::VertexHandle(r)).deleted() && is_movable(s_.vertices[static_cast<size_t>(r)]) &&
              !queued[static_cast<size_t>(r)]) {
            queue.push_back(r);
            queued[static_cast<size_t>(r)] = 1;
          }
        continue;
      }
      if (flips_done[static_cast<size_t>(x)] < 32 && try_flip(vx)) {
        ++out.flips;
        ++flips_done[static_cast<size_t>(x)];
        queue.push_front(x);
        queued[static_cast<size_t>(x)] = 1;
        continue;
      }
      stuck.push_back(x);
    }
    for (int x : stuck)
      if (!mesh_.status(OMesh::VertexHandle(x)).deleted()) ++out.stuck;
    extract(out);
    return out;
  }

 private:
  const SliceVertex& sv(OMesh::VertexHandle v) const { return s_.vertices[static_cast<size_t>(v.idx())]; }

  double orient(const SliceVertex& a, const SliceVertex& b, const SliceVertex& c) const {
    return sign_ * ((b.F[0] - a.F[0]) * (c.F[1] - a.F[1]) - (c.F[0] - a.F[0]) * (b.F[1] - a.F[1]));
  }

  // Every triangle around x that survives the collapse x -> y keeps facing the defining vector.
  bool collapse_keeps_orientation(OMesh::VertexHandle x, OMesh::VertexHandle y) const {
    for (auto h : mesh_.voh_range(x)) {
      if (mesh_.is_boundary(h)) continue;
      const auto a = mesh_.to_vertex_handle(h);
      const auto b = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
      if (a == y || b == y) continue;
      if (orient(sv(y), sv(a), sv(b)) <= kMinArea) return false;
    }
    return true;
  }

  // Boundary corners are shared with the neighbouring reliefs: an edge between two of them created here could
  // also be created by another relief, and the merged mesh would not be a manifold. Keep such edges out.
  static bool shared(const SliceVertex& v) { return v.kind == SliceKind::Corner && v.boundary; }
  bool adds_shared_chord(OMesh::VertexHandle x, OMesh::VertexHandle y) const {
    if (!shared(sv(y))) return false;
    for (auto w : mesh_.vv_range(x))
      if (w != y && shared(sv(w)) && !mesh_.find_halfedge(y, w).is_valid()) return true;
    return false;
  }

  bool try_collapse(OMesh::VertexHandle x) {
    const SliceVertex& X = sv(x);
    OMesh::HalfedgeHandle best;
    int best_rank = -1;
    for (auto h : mesh_.voh_range(x)) {
      const auto y = mesh_.to_vertex_handle(h);
      const SliceVertex& Y = sv(y);
      if (!may_collapse_onto(X, Y)) continue;
      // Prefer grid vertices, then vertices on grid edges, then the rest.
      const int rank = Y.kind == SliceKind::Lattice ? 3 : Y.kind == SliceKind::Crossing ? 2 : 1;
      if (rank <= best_rank) continue;
      if (!is_collapse_ok(mesh_, h) || !collapse_keeps_orientation(x, y) || adds_shared_chord(x, y)) continue;
      best = h;
      best_rank = rank;
    }
    if (!best.is_valid()) return false;
    remesh::collapse(mesh_, best);
    return true;
  }

  // Flip an edge x-y whose quad is strictly convex and lies inside one grid cell, lowering x's degree.
  bool try_flip(OMesh::VertexHandle x) {
    const SliceVertex& X = sv(x);
    OMesh::EdgeHandle best;
    double best_quality = kMinArea;
    for (auto h : mesh_.voh_range(x)) {
      const auto e = mesh_.edge_handle(h);
      if (mesh_.is_boundary(e)) continue;
      const auto y = mesh_.to_vertex_handle(h);
      const SliceVertex& Y = sv(y);
      // Keep edges that lie along x's grid line; flip only edges into the interior of a cell.
      if (X.kind == SliceKind::Crossing && on_grid_edge(Y, X.family, X.value, X.segment)) continue;
      const auto c1 = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
      const auto o = mesh_.opposite_halfedge_handle(h);
      const auto c2 = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
      if (!is_flip_ok(mesh_, e) || (shared(sv(c1)) && shared(sv(c2)))) continue;
      // Faces (x, y, c1) and (y, x, c2) become (c1, x, c2) and (c2, y, c1).
      const double q1 = orient(sv(c1), X, sv(c2));
      const double q2 = orient(sv(c2), Y, sv(c1));
      const double q = std::min(q1, q2);
      if (q > best_quality) {
        best_quality = q;
        best = e;
      }
    }
    if (!best.is_valid()) return false;
    mesh_.flip(best);
    return true;
  }

  void extract(ResampledRelief& out) {
    std::vector<int32_t> remap(s_.vertices.size(), -1);
    for (auto v : mesh_.vertices()) {
      if (mesh_.status(v).deleted()) continue;
      remap[static_cast<size_t>(v.idx())] = static_cast<int32_t>(out.vertices.size());
      out.vertices.push_back(sv(v));
    }
    for (auto f : mesh_.faces()) {
      if (mesh_.status(f).deleted()) continue;
      std::array<int32_t, 3> t{};
      int k = 0;
      for (auto v : mesh_.fv_range(f)) t[static_cast<size_t>(k++)] = remap[static_cast<size_t>(v.idx())];
      out.faces.push_back(t);
    }
  }

  const SlicedRelief& s_;
  double sign_;
  OMesh mesh_;
};

}  // namespace

ResampledRelief resample_relief(const SlicedRelief& sliced, int axis) { return Resampler(sliced, axis).run(); }

}  // namespace prm::remesh
