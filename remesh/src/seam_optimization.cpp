#include "seam_optimization.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <queue>
#include <stdexcept>

#include "openmesh_types.h"
#include "prm/point_triangle_distance.h"
#include "prm/vec3.h"

namespace prm::remesh {
namespace {

using VH = OMesh::VertexHandle;
using HH = OMesh::HalfedgeHandle;
using EH = OMesh::EdgeHandle;
using FH = OMesh::FaceHandle;

class SeamOptimizer {
 public:
  SeamOptimizer(MergedMesh& m, const Mesh& input, const std::vector<Vec3>& normals, const AabbTree& tree,
                const SeamOptions& o)
      : m_(m), input_(input), normals_(normals), tree_(tree),
        cos_max_(std::cos(o.max_normal_angle_deg * M_PI / 180.0)), error_flip_weight_(o.error_flip_weight) {
    // The input's faces around each vertex, for the faces tied for nearest at an edge or a corner.
    star_offset_.assign(input.positions.size() + 1, 0);
    for (const Tri& t : input.triangles)
      for (uint32_t v : t) ++star_offset_[v + 1];
    for (size_t v = 0; v < input.positions.size(); ++v) star_offset_[v + 1] += star_offset_[v];
    star_faces_.resize(star_offset_.back());
    std::vector<uint32_t> fill(star_offset_.begin(), star_offset_.end() - 1);
    for (uint32_t f = 0; f < input.triangles.size(); ++f)
      for (uint32_t v : input.triangles[f]) star_faces_[fill[v]++] = f;
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
    s.valence_flips = regularize_valences();
    if (error_flip_weight_ >= 0) s.error_flips = reduce_error_by_flips();
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
    // A corner that lies on the input (on its source face) bounds the search: the nearest such corner is the hint.
    const Vec3 centroid = (pa + pb + pc) * (1.0 / 3.0);
    AabbTree::Hit hit;
    for (VH v : {a, b, c}) {
      const Vec3& p = v == a ? pa : v == b ? pb : pc;
      if (!mv(v).on_input || p != mv(v).position) continue;  // a tentative or repaired position
      const double d2 = norm2(p - centroid);
      if (d2 < hit.distance2 && mv(v).source_face >= 0) {
        hit.distance2 = d2 * (1 + 1e-12);
        hit.point = p;
        hit.face = static_cast<uint32_t>(mv(v).source_face);
      }
    }
    tree_.closest(centroid, hit);
    if (!hit.found() || !(dot(n, normals_[hit.face]) > limit)) return false;
    // Where the nearest input point lies on an edge or a corner of its face (a crease, the fold of a hole's fan),
    // several input faces are nearest: the triangle must face the way of every one of them, so that the answer
    // does not depend on which of them a search returns.
    const Tri& s = input_.triangles[hit.face];
    const Vec3 &sa = input_.positions[s[0]], &sb = input_.positions[s[1]], &sc = input_.positions[s[2]];
    const Vec3 sn = cross(sb - sa, sc - sa);
    const double A = norm2(sn);
    if (!(A > 0)) return true;
    const double bu = dot(cross(sc - hit.point, sa - hit.point), sn) / A;
    const double bv = dot(cross(sa - hit.point, sb - hit.point), sn) / A;
    const double bary[3] = {1 - bu - bv, bu, bv};
    constexpr double kOnSide = 1e-7;
    if (bary[0] > kOnSide && bary[1] > kOnSide && bary[2] > kOnSide) return true;
    const double tie2 = hit.distance2 * (1 + 1e-7) + 1e-14 * std::sqrt(A);
    for (size_t k = 0; k < 3; ++k) {
      if (bary[k] <= kOnSide) continue;  // the nearest point is on the side opposite this corner, or the corner
      for (uint32_t i = star_offset_[s[k]]; i < star_offset_[s[k] + 1]; ++i) {
        const uint32_t g = star_faces_[i];
        if (g == hit.face) continue;
        const Tri& u = input_.triangles[g];
        if (point_triangle_distance2(centroid, input_.positions[u[0]], input_.positions[u[1]], input_.positions[u[2]]) <=
                tie2 &&
            !(dot(n, normals_[g]) > limit))
          return false;
      }
    }
    return true;
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

  // The quad of a flippable edge: faces (a, b, c) and (b, a, d), which a flip turns into (c, a, d) and (d, b, c).
  struct Quad {
    VH a, b, c, d;
    double area_before, area_after;  // twice the two faces' areas, before and after the flip
  };
  bool flippable(EH e, Quad& q) const {
    if (mesh_.status(e).deleted() || mesh_.is_boundary(e) || !mesh_.is_flip_ok(e)) return false;
    const HH h = mesh_.halfedge_handle(e, 0), o = mesh_.halfedge_handle(e, 1);
    q.a = mesh_.from_vertex_handle(h);
    q.b = mesh_.to_vertex_handle(h);
    q.c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
    q.d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
    q.area_before = face_area2(q.a, q.b, q.c) + face_area2(q.b, q.a, q.d);
    q.area_after = face_area2(q.c, q.a, q.d) + face_area2(q.d, q.b, q.c);
    return true;
  }
  bool flip_is_valid(const Quad& q) const {
    return triangle_ok(q.c, q.a, q.d, pos(q.c), pos(q.a), pos(q.d)) &&
           triangle_ok(q.d, q.b, q.c, pos(q.d), pos(q.b), pos(q.c));
  }

  // Flip e if both new triangles are valid and the area shrinks.
  bool try_area_flip(EH e) {
    Quad q;
    if (!flippable(e, q) || !(q.area_after < q.area_before * (1.0 - 1e-9)) || !flip_is_valid(q)) return false;
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

  // Valence flips on the seams (ours): flip an edge between two reliefs when that brings the valences of its four
  // vertices closer to 6 (the sum of (valence - 6)^2 falls by at least 2), both new triangles are valid and the
  // quad's area grows by at most kValenceFlipArea. Regular vertices cost the connectivity coder almost nothing
  // (spec §6.5.2) and the seams are where the irregular valences are; such an edge never borders a regular
  // triangle (it joins two reliefs).
  static constexpr double kValenceFlipArea = 0.2;
  bool try_valence_flip(EH e) {
    Quad q;
    if (!flippable(e, q)) return false;
    auto dev = [](int v) { return (v - 6) * (v - 6); };
    const int va = static_cast<int>(mesh_.valence(q.a)), vb = static_cast<int>(mesh_.valence(q.b));
    const int vc = static_cast<int>(mesh_.valence(q.c)), vd = static_cast<int>(mesh_.valence(q.d));
    const int before = dev(va) + dev(vb) + dev(vc) + dev(vd);
    const int after = dev(va - 1) + dev(vb - 1) + dev(vc + 1) + dev(vd + 1);
    if (after > before - 2 || va <= 3 || vb <= 3) return false;
    if (!(q.area_after <= q.area_before * (1.0 + kValenceFlipArea)) || !flip_is_valid(q)) return false;
    mesh_.flip(e);
    return true;
  }

  // Error flips (ours, after the paper's area flips and the valence flips): the area-reducing diagonal of a seam
  // quad is the one that cuts deeper into a convex surface, and the seam triangles are the PRM's largest (their
  // longest edge is 1.5-2 grid lengths against 1.16 inside a patch). Measured on the feline at a fixed grid and 14
  // bits, before these flips: the seam triangles are 16.5% of the surface and carry 48.5% of the squared distance
  // to the input. An edge of the seams or of the irregular triangles inside a relief (no face of it may be regular)
  // is flipped when that lowers the two triangles' squared distance to the input by kErrorFlipGain of it and, if it
  // moves the four valences away from 6 (the sum of (valence - 6)^2 grows by D > 0; irregular valences cost the
  // connectivity coder, spec §6.5.2), the drop is at least error_flip_weight * D mean triangle errors.
  static constexpr double kErrorFlipGain = 0.1;
  // Squared distance to the input integrated over a triangle: seven samples, each weighted by a seventh of twice
  // the area.
  double triangle_error(const Vec3& a, const Vec3& b, const Vec3& c) const {
    static constexpr double kSamples[7][3] = {
        {1.0 / 3, 1.0 / 3, 1.0 / 3},   {2.0 / 3, 1.0 / 6, 1.0 / 6},   {1.0 / 6, 2.0 / 3, 1.0 / 6},
        {1.0 / 6, 1.0 / 6, 2.0 / 3},   {1.0 / 6, 5.0 / 12, 5.0 / 12}, {5.0 / 12, 1.0 / 6, 5.0 / 12},
        {5.0 / 12, 5.0 / 12, 1.0 / 6}};
    double sum = 0;
    AabbTree::Hit hint;
    for (const auto& w : kSamples) {
      tree_.closest(a * w[0] + b * w[1] + c * w[2], hint);
      if (hint.found()) sum += hint.distance2;
    }
    return sum * norm(cross(b - a, c - a)) / 7.0;
  }
  // `q`: on success, the quad whose diagonal was flipped.
  bool try_error_flip(EH e, double error_unit, Quad& q) {
    if (!flippable(e, q)) return false;
    const int va = static_cast<int>(mesh_.valence(q.a)), vb = static_cast<int>(mesh_.valence(q.b));
    if (va <= 3 || vb <= 3) return false;
    const double before = triangle_error(pos(q.a), pos(q.b), pos(q.c)) + triangle_error(pos(q.b), pos(q.a), pos(q.d));
    const double after = triangle_error(pos(q.c), pos(q.a), pos(q.d)) + triangle_error(pos(q.d), pos(q.b), pos(q.c));
    if (!(after < before * (1.0 - kErrorFlipGain))) return false;
    auto dev = [](int v) { return (v - 6) * (v - 6); };
    const int vc = static_cast<int>(mesh_.valence(q.c)), vd = static_cast<int>(mesh_.valence(q.d));
    const int grow = dev(va - 1) + dev(vb - 1) + dev(vc + 1) + dev(vd + 1) - (dev(va) + dev(vb) + dev(vc) + dev(vd));
    if (grow > 0 && !(before - after >= error_flip_weight_ * grow * error_unit)) return false;
    if (!flip_is_valid(q)) return false;
    mesh_.flip(e);
    return true;
  }
  // A face that may be regular: three grid vertices of one relief, pairwise lattice neighbours (the orientation is
  // not looked at). The error flips leave such faces alone.
  bool grid_face(HH h) const {
    if (!h.is_valid() || mesh_.is_boundary(h)) return false;
    const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
    const MergedVertex &x = mv(a), &y = mv(b), &z = mv(c);
    if (!x.lattice || !y.lattice || !z.lattice || x.relief != y.relief || y.relief != z.relief) return false;
    return lattice_neighbours(y.i - x.i, y.j - x.j) && lattice_neighbours(z.i - y.i, z.j - y.j) &&
           lattice_neighbours(x.i - z.i, x.j - z.j);
  }
  bool touches_grid_face(EH e) const {
    return grid_face(mesh_.halfedge_handle(e, 0)) || grid_face(mesh_.halfedge_handle(e, 1));
  }
  size_t reduce_error_by_flips() {
    double sum = 0;
    size_t faces = 0;
    for (auto f : mesh_.faces()) {
      if (mesh_.status(f).deleted()) continue;
      auto it = mesh_.cfv_iter(f);
      const VH a = *it, b = *++it, c = *++it;
      sum += triangle_error(pos(a), pos(b), pos(c));
      ++faces;
    }
    const double error_unit = faces ? sum / static_cast<double>(faces) : 0;
    // Each round visits the edges in index order, as a full sweep would, but looks again only at the edges whose
    // test may have changed since it last failed: an edge's test reads its two faces, the valences of their four
    // vertices and the edges around those (OpenMesh's is_flip_ok), all within the faces around the four vertices of a
    // flipped quad, whose edges a flip marks again. Positions do not move, so the flips are those of full sweeps.
    std::vector<uint8_t> again(mesh_.n_edges(), 1);
    auto mark_around = [&](VH v) {
      for (auto f : mesh_.vf_range(v))
        for (auto e : mesh_.fe_range(f)) again[static_cast<size_t>(e.idx())] = 1;
    };
    size_t flips = 0;
    for (int round = 0; round < 6; ++round) {
      size_t now = 0;
      for (auto e : mesh_.edges()) {
        uint8_t& look = again[static_cast<size_t>(e.idx())];
        if (!look) continue;
        look = 0;
        Quad q;
        if (mesh_.status(e).deleted() || touches_grid_face(e) || !try_error_flip(e, error_unit, q)) continue;
        ++now;
        for (VH v : {q.a, q.b, q.c, q.d}) mark_around(v);
      }
      flips += now;
      if (now == 0) break;
    }
    return flips;
  }

  size_t regularize_valences() {
    size_t flips = 0;
    for (int round = 0; round < 4; ++round) {
      size_t now = 0;
      for (auto e : mesh_.edges())
        if (!mesh_.status(e).deleted() && joins_reliefs(e) && try_valence_flip(e)) ++now;
      flips += now;
      if (now == 0) break;
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

  // Where the grid is too coarse for the surface (a thin part, a sharp tip), a bad triangle's edge is split at the
  // input point nearest to its midpoint, when the four new triangles are all valid: a vertex that follows the
  // surface where the grid cannot.
  bool split_edge_on_surface(FH f) {
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
    if (static_cast<size_t>(m.idx()) + 1 != m_.vertices.size()) throw std::logic_error("seam repair: vertex ids out of step");
    mesh_.split(mesh_.edge_handle(best), m);
    return true;
  }

  // A small bad triangle at a sharp spot: collapse all three corners into one of them, when every triangle left
  // around them is valid (two collapses; the first alone may not be an improvement).
  bool collapse_face(FH f) {
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
          int in = (p == corner[0] || p == corner[1] || p == corner[2]) + (q == corner[0] || q == corner[1] || q == corner[2]);
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
      if (!h1.is_valid() || !mesh_.is_collapse_ok(h1)) continue;
      mesh_.collapse(h1);
      const HH h2 = mesh_.find_halfedge(x2, y);
      if (h2.is_valid() && mesh_.is_collapse_ok(h2)) mesh_.collapse(h2);
      return true;
    }
    return false;
  }

  // A bad triangle whose edges cannot be split usefully: split the face at the input point nearest to its
  // centroid, when the three new triangles are valid.
  bool split_face_on_surface(FH f) {
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
    if (static_cast<size_t>(m.idx()) + 1 != m_.vertices.size()) throw std::logic_error("seam repair: vertex ids out of step");
    mesh_.split(f, m);
    return true;
  }

  // Last resort for a bad face: remove the vertices in S (the face's corners, then with their neighbours) and
  // triangulate the hole their stars leave afresh: the triangulation of the hole's polygon whose worst triangle is
  // best shaped among those whose every triangle is valid and makes no edge that exists already (dynamic
  // programming over the polygon's diagonals). The region must be a disk, so the topology does not change.
  bool retriangulate_region(const std::vector<VH>& S) {
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
      if (o.is_valid() && !mesh_.is_boundary(o) && mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o)) == ring[2])
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
    for (FH f : F) mesh_.delete_face(f, true);
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
      const FH f = mesh_.add_face(ring[(*it)[0]], ring[(*it)[1]], ring[(*it)[2]]);
      if (!f.is_valid()) throw std::logic_error("seam repair: a retriangulated region did not close");
    }
    return true;
  }

  bool retriangulate_around(FH f) {
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

  // The loops below add and delete faces as they go, so they walk the face indices that exist when a round starts.
  // (Not OpenMesh's skipping iterators: when the face at the range's end index is deleted, they step over the end
  // and run off the face array.)
  size_t remove_bad_triangles() {
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
        if (repair_face(f) || relocate_vertex(f, allow_lattice) || (allow_lattice && (collapse_face(f) || split_edge_on_surface(f) || split_face_on_surface(f)))) ++fixed;
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
  const Mesh& input_;
  std::vector<uint32_t> star_offset_, star_faces_;
  const std::vector<Vec3>& normals_;
  const AabbTree& tree_;
  double cos_max_;
  double error_flip_weight_;
  double min_norm_;
  OMesh mesh_;
};

}  // namespace

SeamStats optimize_seams(MergedMesh& mesh, const Mesh& input, const std::vector<Vec3>& input_normals,
                         const AabbTree& input_tree, const SeamOptions& options) {
  return SeamOptimizer(mesh, input, input_normals, input_tree, options).run();
}

}  // namespace prm::remesh
