// Error flips (ours, after the valence flips): edges that no regular face may use, flipped where that brings
// the surface closer to the input.
#include "prm/vec3.h"
#include "seam_optimizer.h"
#include "triangle_samples.h"

namespace prm::remesh {

namespace {

// Error flips (ours, after the paper's area flips and the valence flips): the area-reducing diagonal of a
// seam quad is the one that cuts deeper into a convex surface, and the seam triangles are the PRM's largest
// (their longest edge is 1.5-2 grid lengths against 1.16 inside a patch). Measured on the feline at a fixed
// grid and 14 bits, before these flips: the seam triangles are 16.5% of the surface and carry 48.5% of the
// squared distance to the input. An edge of the seams or of the irregular triangles inside a relief (no face
// of it may be regular) is flipped when that lowers the two triangles' squared distance to the input by
// kErrorFlipGain of it and, if it moves the four valences away from 6 (the sum of (valence - 6)^2 grows by D
// > 0; irregular valences cost the connectivity coder, spec §6.5.2), the drop is at least error_flip_weight *
// D mean triangle errors.
constexpr double kErrorFlipGain = 0.1;

}  // namespace

// Squared distance to the input integrated over a triangle: seven samples (the first SeamOptions::error_samples of
// them), each weighted by its share of twice the area. The hint only bounds the searches (the distance is the
// smallest over the input's triangles whatever it is): the callers carry one through neighbouring triangles. With
// `stop` finite, returns as soon as base + (the error so far) >= stop, with the error so far: every sample adds a
// distance >= 0 and rounding is monotone, so then base + (the full error) >= stop as well.
double SeamOptimizer::triangle_error(const Vec3& a, const Vec3& b, const Vec3& c, AabbTree::Hit& hint,
                                     double base, double stop, uint32_t* faces) const {
  const double area = norm(cross(b - a, c - a));
  double sum = 0;
  const double n = static_cast<double>(error_samples_);
  for (int si = 0; si < error_samples_; ++si) {
    const auto& w = kTriangleSamples[si];
    tree_.closest(a * w[0] + b * w[1] + c * w[2], hint);
    if (hint.found()) sum += hint.distance2;
    if (faces) faces[si] = hint.face;
    if (base + sum * area / n >= stop) break;
  }
  return sum * area / n;
}

// `q`: on success, the quad whose diagonal was flipped.
bool SeamOptimizer::try_error_flip(EH e, double error_unit, Quad& q) {
  if (!flippable(e, q)) return false;
  const int va = valence(mesh_, q.a), vb = valence(mesh_, q.b);
  if (va <= 3 || vb <= 3) return false;
  AabbTree::Hit hint;  // through the quad's four triangles
  const double before =
      triangle_error(pos(q.a), pos(q.b), pos(q.c), hint) + triangle_error(pos(q.b), pos(q.a), pos(q.d), hint);
  // The flip needs after < limit. The sum after stops once it reaches the limit (triangle_error's `stop`): the
  // full sum would reach it too, so the answer is the one of the full sums.
  const double limit = before * (1.0 - kErrorFlipGain);
  const double after_1 = triangle_error(pos(q.c), pos(q.a), pos(q.d), hint, 0, limit);
  if (!(after_1 < limit)) return false;
  const double after = after_1 + triangle_error(pos(q.d), pos(q.b), pos(q.c), hint, after_1, limit);
  if (!(after < limit)) return false;
  auto dev = [](int v) { return (v - 6) * (v - 6); };
  const int vc = valence(mesh_, q.c), vd = valence(mesh_, q.d);
  const int grow =
      dev(va - 1) + dev(vb - 1) + dev(vc + 1) + dev(vd + 1) - (dev(va) + dev(vb) + dev(vc) + dev(vd));
  if (grow > 0 && !(before - after >= error_flip_weight_ * grow * error_unit)) return false;
  if (!flip_is_valid(q)) return false;
  mesh_.flip(e);
  return true;
}

// A face that may be regular: three grid vertices of one relief, pairwise lattice neighbours (the orientation
// is not looked at). The error flips leave such faces alone.
bool SeamOptimizer::grid_face(HH h) const {
  if (!h.is_valid() || mesh_.is_boundary(h)) return false;
  const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
  const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
  const MergedVertex &x = mv(a), &y = mv(b), &z = mv(c);
  if (!x.lattice || !y.lattice || !z.lattice || x.relief != y.relief || y.relief != z.relief) return false;
  return lattice_neighbours(y.i - x.i, y.j - x.j) && lattice_neighbours(z.i - y.i, z.j - y.j) &&
         lattice_neighbours(x.i - z.i, x.j - z.j);
}

bool SeamOptimizer::touches_grid_face(EH e) const {
  return grid_face(mesh_.halfedge_handle(e, 0)) || grid_face(mesh_.halfedge_handle(e, 1));
}

size_t SeamOptimizer::reduce_error_by_flips() {
  double sum = 0;
  size_t faces = 0, seen = 0;
  AabbTree::Hit hint;
  // The input faces found for each face's samples, with its corners in that order (MergedMesh::sample_face).
  unit_faces_.assign(kTriangleErrorSamples * mesh_.n_faces(), AabbTree::kNoFace);
  unit_corners_.assign(mesh_.n_faces(), {-1, -1, -1});
  for (auto f : mesh_.faces()) {
    if (mesh_.status(f).deleted()) continue;
    if (seen++ % error_unit_stride_ != 0) continue;  // SeamOptions::error_unit_stride
    auto it = mesh_.cfv_iter(f);
    const VH a = *it, b = *++it, c = *++it;
    const size_t i = static_cast<size_t>(f.idx());
    sum += triangle_error(pos(a), pos(b), pos(c), hint, 0, HUGE_VAL, &unit_faces_[kTriangleErrorSamples * i]);
    unit_corners_[i] = {a.idx(), b.idx(), c.idx()};
    ++faces;
  }
  const double error_unit = faces ? sum / static_cast<double>(faces) : 0;
  // Each round visits the edges in index order, as a full sweep would, but looks again only at the edges
  // whose test may have changed since it last failed: an edge's test reads its two faces, the valences of
  // their four vertices and the edges around those (OpenMesh's is_flip_ok), all within the faces around the
  // four vertices of a flipped quad, whose edges a flip marks again. Positions do not move, so the flips are
  // those of full sweeps.
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

}  // namespace prm::remesh
