#include "seam_optimization.h"

#include <cmath>
#include <deque>
#include <queue>
#include <stdexcept>

#include "openmesh_types.h"
#include "prm/vec3.h"

namespace prm::remesh {
namespace {

using VH = OMesh::VertexHandle;
using HH = OMesh::HalfedgeHandle;
using EH = OMesh::EdgeHandle;
using FH = OMesh::FaceHandle;

class SeamOptimizer {
 public:
  SeamOptimizer(MergedMesh& m, const std::vector<Vec3>& normals, const AabbTree& tree, const SeamOptions& o)
      : m_(m), normals_(normals), tree_(tree), cos_max_(std::cos(o.max_normal_angle_deg * M_PI / 180.0)) {
    // Twice the smallest area a triangle may have: a millionth of a grid triangle's size, squared.
    min_norm_ = 1e-12 * o.grid_length * o.grid_length;
    for (const MergedVertex& v : m.vertices) mesh_.add_vertex(OMesh::Point(v.position[0], v.position[1], v.position[2]));
    for (size_t f = 0; f < m.faces.size(); ++f) {
      const auto& t = m.faces[f];
      const FH fh = mesh_.add_face(VH(t[0]), VH(t[1]), VH(t[2]));
      if (!fh.is_valid()) throw std::logic_error("merge_reliefs: the merged mesh is not a manifold");
    }
  }

  SeamStats run() {
    SeamStats s;
    s.loops_broken = merge_coincident();
    s.boundary_collapses = collapse_seam_vertices();
    s.area_flips = reduce_area_by_flips();
    s.repairs = remove_bad_triangles();
    for (auto f : mesh_.faces())
      if (!mesh_.status(f).deleted() && !face_ok(f)) ++s.unrepaired;
    compact();
    for (const MergedVertex& v : m_.vertices)
      if (!v.lattice) ++s.non_lattice_vertices;
    return s;
  }

 private:
  const MergedVertex& mv(VH v) const { return m_.vertices[static_cast<size_t>(v.idx())]; }
  Vec3 pos(VH v) const { return mv(v).position; }
  // Not zero-area, and not flipped: within the allowed angle of the normal of the input face nearest to its
  // centroid (issue 4's definition; where the input folds, as a centroid fan over a non-planar hole does, the
  // input faces at its corners may face both ways, and only the nearest one says which way is out).
  bool triangle_ok(VH a, VH b, VH c, const Vec3& pa, const Vec3& pb, const Vec3& pc) const {
    const Vec3 n = cross(pb - pa, pc - pa);
    const double n2 = norm2(n);
    if (n2 <= min_norm_ * min_norm_) return false;
    const double limit = cos_max_ * std::sqrt(n2);
    // The corners' input faces as a hint: the nearest one bounds the search.
    const Vec3 centroid = (pa + pb + pc) * (1.0 / 3.0);
    AabbTree::Hit hit;
    tree_.closest(centroid, hit);
    (void)a;
    (void)b;
    (void)c;
    return hit.found() && dot(n, normals_[hit.face]) > limit;
  }
  bool face_ok(FH f) const {
    auto it = mesh_.cfv_iter(f);
    const VH a = *it, b = *++it, c = *++it;
    return triangle_ok(a, b, c, pos(a), pos(b), pos(c));
  }
  double face_area2(VH a, VH b, VH c) const { return norm(cross(pos(b) - pos(a), pos(c) - pos(a))); }

  // Collapse x -> y leaves every surviving triangle around x valid?
  bool collapse_ok(HH h) {
    if (!mesh_.is_collapse_ok(h)) return false;
    const VH x = mesh_.from_vertex_handle(h), y = mesh_.to_vertex_handle(h);
    const Vec3 py = pos(y);
    for (auto oh : mesh_.voh_range(x)) {
      if (mesh_.is_boundary(oh)) continue;
      const VH a = mesh_.to_vertex_handle(oh), b = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(oh));
      if (a == y || b == y) continue;
      if (!triangle_ok(y, a, b, py, pos(a), pos(b))) return false;
    }
    return true;
  }

  // For repairs: the collapse x -> y removes at least one bad triangle and turns no good triangle bad.
  bool collapse_improves(HH h) {
    if (!mesh_.is_collapse_ok(h)) return false;
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

  // How far y lies from x's tangent plane (the error of moving x to y), plus a little of the distance.
  double collapse_cost(VH x, VH y) const {
    const Vec3 d = pos(y) - pos(x);
    const double plane = dot(d, normals_[static_cast<size_t>(mv(x).source_face)]);
    return plane * plane + 1e-3 * norm2(d);
  }

  // Loop breaking (paper §2.3): a coincident pair of seam vertices becomes one vertex where the link condition
  // allows. The geometry does not change, so no triangle test is needed.
  size_t merge_coincident() {
    size_t merged = 0;
    for (const auto& [a, b] : m_.coincident) {
      const VH x(b), y(a);
      if (mesh_.status(x).deleted() || mesh_.status(y).deleted()) continue;
      const HH h = mesh_.find_halfedge(x, y);
      if (h.is_valid() && mesh_.is_collapse_ok(h)) {
        mesh_.collapse(h);
        ++merged;
      }
    }
    return merged;
  }

  bool best_lattice_target(VH x, HH& best, double& best_cost) {
    best = HH();
    best_cost = HUGE_VAL;
    for (auto h : mesh_.voh_range(x)) {
      const VH y = mesh_.to_vertex_handle(h);
      if (!mv(y).lattice) continue;
      const double c = collapse_cost(x, y);
      if (c < best_cost && collapse_ok(h)) {
        best_cost = c;
        best = h;
      }
    }
    return best.is_valid();
  }

  size_t collapse_seam_vertices() {
    struct Item {
      double cost;
      int x, y;
      bool operator<(const Item& o) const { return cost > o.cost; }
    };
    std::priority_queue<Item> pq;
    auto push_best = [&](VH x) {
      HH h;
      double c;
      if (!mv(x).lattice && best_lattice_target(x, h, c)) pq.push({c, x.idx(), mesh_.to_vertex_handle(h).idx()});
    };
    for (auto v : mesh_.vertices()) push_best(v);
    size_t count = 0;
    while (!pq.empty()) {
      const Item it = pq.top();
      pq.pop();
      const VH x(it.x), y(it.y);
      if (mesh_.status(x).deleted() || mesh_.status(y).deleted()) continue;
      const HH h = mesh_.find_halfedge(x, y);
      if (!h.is_valid() || !collapse_ok(h)) {
        push_best(x);
        continue;
      }
      mesh_.collapse(h);
      ++count;
      for (auto w : mesh_.vv_range(y)) push_best(w);
    }
    return count;
  }

  bool joins_reliefs(EH e) const {
    const HH h = mesh_.halfedge_handle(e, 0);
    const MergedVertex& a = mv(mesh_.from_vertex_handle(h));
    const MergedVertex& b = mv(mesh_.to_vertex_handle(h));
    return a.relief < 0 || b.relief < 0 || a.relief != b.relief;
  }

  // Flip e if both new triangles are valid and the area shrinks.
  bool try_area_flip(EH e) {
    if (mesh_.status(e).deleted() || mesh_.is_boundary(e) || !mesh_.is_flip_ok(e)) return false;
    const HH h = mesh_.halfedge_handle(e, 0), o = mesh_.halfedge_handle(e, 1);
    const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
    const VH d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
    // Faces (a, b, c) and (b, a, d) become (c, a, d) and (d, b, c).
    const double before = face_area2(a, b, c) + face_area2(b, a, d);
    const double after = face_area2(c, a, d) + face_area2(d, b, c);
    if (!(after < before * (1.0 - 1e-9))) return false;
    if (!triangle_ok(c, a, d, pos(c), pos(a), pos(d)) || !triangle_ok(d, b, c, pos(d), pos(b), pos(c))) return false;
    mesh_.flip(e);
    return true;
  }

  size_t reduce_area_by_flips() {
    std::deque<int> queue;
    std::vector<uint8_t> queued(mesh_.n_edges(), 0);
    for (auto e : mesh_.edges())
      if (!mesh_.status(e).deleted() && joins_reliefs(e)) {
        queue.push_back(e.idx());
        queued[static_cast<size_t>(e.idx())] = 1;
      }
    size_t flips = 0;
    const size_t limit = 50 * mesh_.n_edges() + 1000;
    while (!queue.empty() && flips < limit) {
      const EH e(queue.front());
      queue.pop_front();
      queued[static_cast<size_t>(e.idx())] = 0;
      if (mesh_.status(e).deleted() || !joins_reliefs(e) || !try_area_flip(e)) continue;
      ++flips;
      const HH h = mesh_.halfedge_handle(e, 0), o = mesh_.halfedge_handle(e, 1);
      for (HH k : {mesh_.next_halfedge_handle(h), mesh_.prev_halfedge_handle(h), mesh_.next_halfedge_handle(o),
                   mesh_.prev_halfedge_handle(o)}) {
        const EH n = mesh_.edge_handle(k);
        if (!queued[static_cast<size_t>(n.idx())] && joins_reliefs(n)) {
          queue.push_back(n.idx());
          queued[static_cast<size_t>(n.idx())] = 1;
        }
      }
    }
    return flips;
  }

  // Fix one bad face: collapse one of its edges (moving a non-grid vertex first) or flip one of its edges.
  bool repair_face(FH f) {
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
      mesh_.collapse(best);
      return true;
    }
    // A flip that leaves fewer bad triangles among the two it touches.
    for (auto h : mesh_.fh_range(f)) {
      const EH e = mesh_.edge_handle(h);
      if (mesh_.is_boundary(e) || !mesh_.is_flip_ok(e)) continue;
      const HH o = mesh_.opposite_halfedge_handle(h);
      const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
      const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
      const VH d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
      const int before = !triangle_ok(a, b, c, pos(a), pos(b), pos(c)) + !triangle_ok(b, a, d, pos(b), pos(a), pos(d));
      const bool ok1 = triangle_ok(c, a, d, pos(c), pos(a), pos(d)), ok2 = triangle_ok(d, b, c, pos(d), pos(b), pos(c));
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

  // Moves a non-grid vertex of f towards the centroid of its neighbours until all its triangles are valid.
  // (Non-grid vertices may sit anywhere; the move is a fraction of a grid step, along the surface.)
  bool relocate_vertex(FH f, bool allow_lattice) {
    for (auto v : mesh_.fv_range(f)) {
      if (mv(v).lattice && !allow_lattice) continue;
      Vec3 centroid{0, 0, 0};
      int n = 0;
      for (auto w : mesh_.vv_range(v)) {
        centroid += pos(w);
        ++n;
      }
      if (n == 0) continue;
      centroid = centroid * (1.0 / n);
      const Vec3 old = pos(v);
      for (double t : {1.0, 0.5, 0.25, 0.75, 0.125}) {
        const Vec3 p = lerp(old, centroid, t);
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
          m_.vertices[static_cast<size_t>(v.idx())].position = p;
          m_.vertices[static_cast<size_t>(v.idx())].lattice = false;  // a moved grid vertex is no longer one
          return true;
        }
      }
    }
    return false;
  }

  size_t remove_bad_triangles() {
    size_t repairs = 0;
    // Rounds of local fixes; when a round fixes nothing, the next may also move grid vertices (which then stop
    // being grid vertices). Stops when no bad triangle is left or a round with grid moves fixes nothing.
    bool allow_lattice = false;
    for (int round = 0; round < 32; ++round) {
      size_t fixed = 0, bad = 0;
      for (auto f : mesh_.faces()) {
        if (mesh_.status(f).deleted() || face_ok(f)) continue;
        ++bad;
        if (repair_face(f) || relocate_vertex(f, allow_lattice)) ++fixed;
      }
      repairs += fixed;
      if (bad == 0) break;
      if (fixed == 0) {
        if (allow_lattice) break;
        allow_lattice = true;
      }
    }
    return repairs;
  }

  void compact() {
    std::vector<int32_t> remap(m_.vertices.size(), -1);
    std::vector<MergedVertex> vertices;
    for (auto v : mesh_.vertices()) {
      if (mesh_.status(v).deleted() || mesh_.is_isolated(v)) continue;
      remap[static_cast<size_t>(v.idx())] = static_cast<int32_t>(vertices.size());
      vertices.push_back(mv(v));
    }
    std::vector<std::array<int32_t, 3>> faces;
    for (auto f : mesh_.faces()) {
      if (mesh_.status(f).deleted()) continue;
      std::array<int32_t, 3> t{};
      int k = 0;
      for (auto v : mesh_.fv_range(f)) t[static_cast<size_t>(k++)] = remap[static_cast<size_t>(v.idx())];
      faces.push_back(t);
    }
    m_.vertices = std::move(vertices);
    m_.faces = std::move(faces);
    m_.face_relief.assign(m_.faces.size(), -1);
  }

  MergedMesh& m_;
  const std::vector<Vec3>& normals_;
  const AabbTree& tree_;
  double cos_max_;
  double min_norm_;
  OMesh mesh_;
};

}  // namespace

SeamStats optimize_seams(MergedMesh& mesh, const std::vector<Vec3>& input_normals, const AabbTree& input_tree,
                         const SeamOptions& options) {
  return SeamOptimizer(mesh, input_normals, input_tree, options).run();
}

}  // namespace prm::remesh
