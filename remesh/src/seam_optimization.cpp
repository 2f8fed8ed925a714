// Paper §2.3-2.4, the merge stage after the loop fill: SeamOptimizer (seam_optimizer.h) runs its passes in
// order; here are the pass sequence and the moves several passes try (collapse, flip, the relief test of an
// edge).
#include "seam_optimization.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "prm/vec3.h"
#include "openmesh_edits.h"
#include "seam_optimizer.h"

namespace prm::remesh {

SeamOptimizer::SeamOptimizer(MergedMesh& m, const Mesh& input, const std::vector<Vec3>& normals,
                             const AabbTree& tree, const SeamOptions& o)
    : m_(m),
      input_(input),
      normals_(normals),
      tree_(tree),
      cos_max_(std::cos(o.max_normal_angle_deg * M_PI / 180.0)),
      error_flip_weight_(o.error_flip_weight),
      error_unit_stride_(o.error_unit_stride > 1 ? static_cast<size_t>(o.error_unit_stride) : 1),
      error_samples_(std::clamp(o.error_samples, 1, kTriangleErrorSamples)) {
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
  for (const MergedVertex& v : m.vertices)
    mesh_.add_vertex(OMesh::Point(v.position[0], v.position[1], v.position[2]));
  for (size_t f = 0; f < m.faces.size(); ++f) {
    const auto& t = m.faces[f];
    const FH fh = add_triangle(mesh_, VH(t[0]), VH(t[1]), VH(t[2]));
    if (!fh.is_valid()) throw std::logic_error("merge_reliefs: the merged mesh is not a manifold");
  }
}

SeamStats SeamOptimizer::run() {
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

// Collapse x -> y leaves every surviving triangle around x valid?
bool SeamOptimizer::collapse_ok(HH h) {
  if (!is_collapse_ok(mesh_, h) || moves_boundary(h)) return false;
  const VH x = mesh_.from_vertex_handle(h), y = mesh_.to_vertex_handle(h);
  for (auto oh : mesh_.voh_range(x)) {
    if (mesh_.is_boundary(oh)) continue;
    const VH a = mesh_.to_vertex_handle(oh), b = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(oh));
    if (a == y || b == y) continue;
    if (!collapsed_triangle_ok(y, a, b)) return false;
  }
  return true;
}

bool SeamOptimizer::collapsed_triangle_ok(VH y, VH a, VH b) {
  if (!remember_collapses_) return triangle_ok(y, a, b, pos(y), pos(a), pos(b));
  const int known = collapse_memo_.find(y.idx(), a.idx(), b.idx());
  if (known >= 0) return known == 1;
  const bool ok = triangle_ok(y, a, b, pos(y), pos(a), pos(b));
  collapse_memo_.add(y.idx(), a.idx(), b.idx(), ok);
  return ok;
}

bool SeamOptimizer::joins_reliefs(EH e) const {
  const HH h = mesh_.halfedge_handle(e, 0);
  const MergedVertex& a = mv(mesh_.from_vertex_handle(h));
  const MergedVertex& b = mv(mesh_.to_vertex_handle(h));
  return a.relief < 0 || b.relief < 0 || a.relief != b.relief;
}

bool SeamOptimizer::flippable(EH e, Quad& q) const {
  if (mesh_.status(e).deleted() || mesh_.is_boundary(e) || !is_flip_ok(mesh_, e)) return false;
  const HH h = mesh_.halfedge_handle(e, 0), o = mesh_.halfedge_handle(e, 1);
  q.a = mesh_.from_vertex_handle(h);
  q.b = mesh_.to_vertex_handle(h);
  q.c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
  q.d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
  q.area_before = face_area2(q.a, q.b, q.c) + face_area2(q.b, q.a, q.d);
  q.area_after = face_area2(q.c, q.a, q.d) + face_area2(q.d, q.b, q.c);
  return true;
}

bool SeamOptimizer::flip_is_valid(const Quad& q) const {
  return triangle_ok(q.c, q.a, q.d, pos(q.c), pos(q.a), pos(q.d)) &&
         triangle_ok(q.d, q.b, q.c, pos(q.d), pos(q.b), pos(q.c));
}

void SeamOptimizer::compact() {
  std::vector<int32_t> remap(m_.vertices.size(), -1);
  std::vector<MergedVertex> vertices;
  for (auto v : mesh_.vertices()) {
    if (mesh_.status(v).deleted() || mesh_.is_isolated(v)) continue;
    remap[static_cast<size_t>(v.idx())] = static_cast<int32_t>(vertices.size());
    vertices.push_back(mv(v));
  }
  std::vector<std::array<int32_t, 3>> faces;
  std::vector<uint32_t> sample_face;
  for (auto f : mesh_.faces()) {
    if (mesh_.status(f).deleted()) continue;
    std::array<int32_t, 3> t{};
    std::array<int, 3> corners{};
    int k = 0;
    for (auto v : mesh_.fv_range(f)) {
      corners[static_cast<size_t>(k)] = v.idx();
      t[static_cast<size_t>(k++)] = remap[static_cast<size_t>(v.idx())];
    }
    faces.push_back(t);
    if (unit_faces_.empty()) continue;
    // The same corners in the same order: the same sample points (the flips move no vertex).
    const size_t i = static_cast<size_t>(f.idx());
    const bool same = unit_corners_[i] == corners;
    for (size_t s = 0; s < static_cast<size_t>(kTriangleErrorSamples); ++s)
      sample_face.push_back(same ? unit_faces_[kTriangleErrorSamples * i + s] : AabbTree::kNoFace);
  }
  m_.vertices = std::move(vertices);
  m_.faces = std::move(faces);
  m_.sample_face = std::move(sample_face);
  m_.face_relief.assign(m_.faces.size(), -1);
}

SeamStats optimize_seams(MergedMesh& mesh, const Mesh& input, const std::vector<Vec3>& input_normals,
                         const AabbTree& input_tree, const SeamOptions& options) {
  return SeamOptimizer(mesh, input, input_normals, input_tree, options).run();
}

}  // namespace prm::remesh
