// The merge stage's passes over the merged mesh (seam_optimization.h), as one object: the mesh as OpenMesh
// half-edges, the triangle test every pass keeps, and the passes, each defined in the file named for the step
// it implements. run() (seam_optimization.cpp) calls them in order.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "openmesh_queries.h"
#include "seam_optimization.h"
#include "triangle_answer_memo.h"

namespace prm::remesh {

class SeamOptimizer {
 public:
  using VH = OMesh::VertexHandle;
  using HH = OMesh::HalfedgeHandle;
  using EH = OMesh::EdgeHandle;
  using FH = OMesh::FaceHandle;

  SeamOptimizer(MergedMesh& m, const Mesh& input, const std::vector<Vec3>& normals, const AabbTree& tree,
                const SeamOptions& o);
  // The passes in order, then the mesh written back without deleted elements.
  SeamStats run();

 private:
  const MergedVertex& mv(VH v) const { return m_.vertices[static_cast<size_t>(v.idx())]; }
  Vec3 pos(VH v) const { return mv(v).position; }
  double face_area2(VH a, VH b, VH c) const { return norm(cross(pos(b) - pos(a), pos(c) - pos(a))); }

  // triangle_validity.cpp: paper §2.4's test, kept by every pass: not zero-area, not flipped.
  bool triangle_ok(VH a, VH b, VH c, const Vec3& pa, const Vec3& pb, const Vec3& pc) const;
  // triangle_ok of a face's vertices in OpenMesh's order, remembered per face with what it read: those
  // vertices, their positions, source_face and on_input. The scans of remove_bad_triangles() and the final
  // count compute it again only for the faces where any of these changed (the answer is a function of them).
  bool face_ok(FH f);

  // seam_optimization.cpp: the moves several passes try.
  bool collapse_ok(HH h);
  // triangle_ok(y, a, b) at the vertices' data, remembered in collapse_memo_ while remember_collapses_ is on:
  // during collapse_seam_vertices(), where no vertex's position, source_face or on_input changes.
  bool collapsed_triangle_ok(VH y, VH a, VH b);
  // An open surface keeps its boundary where it is: no collapse removes a vertex of the mesh boundary (the input's
  // boundary, refined by the grid crossings; every other edge has two faces after the loop fill).
  bool moves_boundary(HH h) const { return mesh_.is_boundary(mesh_.from_vertex_handle(h)); }
  bool joins_reliefs(EH e) const;

  // The quad of a flippable edge: faces (a, b, c) and (b, a, d), which a flip turns into (c, a, d) and (d, b,
  // c).
  struct Quad {
    VH a, b, c, d;
    double area_before, area_after;  // twice the two faces' areas, before and after the flip
  };
  bool flippable(EH e, Quad& q) const;
  bool flip_is_valid(const Quad& q) const;
  void compact();

  // seam_collapses.cpp, paper §2.3: loop breaking, then seam vertices collapsed onto grid vertices.
  double collapse_cost(VH x, VH y) const;
  size_t merge_coincident();
  bool best_lattice_target(VH x, HH& best, double& best_cost);
  size_t collapse_seam_vertices();

  // area_reducing_flips.cpp, paper §2.3 (last paragraph): edges between reliefs flipped while that reduces
  // the area.
  bool try_area_flip(EH e);
  size_t reduce_area_by_flips();

  // flipped_triangle_removal.cpp, paper §2.4: flipped and zero-area triangles removed by local collapses,
  // flips, moves and splits; region_retriangulation.cpp: what those cannot fix, retriangulated (ours).
  size_t remove_bad_triangles();
  bool repair_face(FH f);
  bool collapse_improves(HH h);
  bool relocate_vertex(FH f, bool allow_lattice);
  bool split_edge_on_surface(FH f);
  bool collapse_face(FH f);
  bool split_face_on_surface(FH f);
  bool retriangulate_region(const std::vector<VH>& S);
  bool retriangulate_around(FH f);

  // valence_flips.cpp (ours): seam edges flipped towards valence 6.
  bool try_valence_flip(EH e);
  size_t regularize_valences();

  // error_flips.cpp (ours): irregular edges flipped where that brings the surface closer to the input.
  // `hint`: the last answer of a nearby query (AabbTree's hint), updated; the result does not depend on it.
  // With `stop` finite, returns early, a value whose sum with `base` is >= stop, once the full error's would be.
  // `faces`: when given, set to the input triangle closest to each sample taken (kTriangleSamples order).
  double triangle_error(const Vec3& a, const Vec3& b, const Vec3& c, AabbTree::Hit& hint, double base = 0,
                        double stop = HUGE_VAL, uint32_t* faces = nullptr) const;
  bool try_error_flip(EH e, double error_unit, Quad& q);
  bool grid_face(HH h) const;
  bool touches_grid_face(EH e) const;
  size_t reduce_error_by_flips();

  MergedMesh& m_;
  const Mesh& input_;
  std::vector<uint32_t> star_offset_, star_faces_;
  const std::vector<Vec3>& normals_;
  const AabbTree& tree_;
  double cos_max_;
  double error_flip_weight_;
  size_t error_unit_stride_;  // SeamOptions::error_unit_stride
  int error_samples_;         // SeamOptions::error_samples
  double min_norm_;
  OMesh mesh_;
  struct FaceOkMemo {
    bool known = false, ok = false;
    VH v[3];
    struct Read {
      Vec3 position;
      int32_t source_face;
      bool on_input;
    } read[3];
  };
  std::vector<FaceOkMemo> face_ok_memo_;
  bool remember_collapses_ = false;
  TriangleAnswerMemo collapse_memo_;
  // The error flips' mean triangle error: per face index, the closest input faces of its samples
  // (kTriangleErrorSamples a face) and its corners in the order sampled; compact() keeps those of the faces the
  // flips left as they were (MergedMesh::sample_face).
  std::vector<uint32_t> unit_faces_;
  std::vector<std::array<int, 3>> unit_corners_;
};

}  // namespace prm::remesh
