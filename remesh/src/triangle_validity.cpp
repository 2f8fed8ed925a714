// Paper §2.4: the test every pass of the merge stage keeps: a triangle is not zero-area and not flipped (its
// normal within the allowed angle of the input's nearby normal).
#include <cmath>
#include <cstring>

#include "prm/point_triangle_distance.h"
#include "prm/vec3.h"
#include "seam_optimizer.h"

namespace prm::remesh {

// Not zero-area, and not flipped: within the allowed angle of the normal of the input face nearest to its
// centroid (issue 4's definition; where the input folds, as a centroid fan over a non-planar hole does, the
// input faces at its corners may face both ways, and only the nearest one says which way is out).
bool SeamOptimizer::triangle_ok(VH a, VH b, VH c, const Vec3& pa, const Vec3& pb, const Vec3& pc) const {
  const Vec3 n = cross(pb - pa, pc - pa);
  const double n2 = norm2(n);
  if (n2 <= min_norm_ * min_norm_) return false;
  const double limit = cos_max_ * std::sqrt(n2);
  // A corner that lies on the input (on its source face) bounds the search: the nearest such corner is the
  // hint.
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
  // Where the nearest input point lies on an edge or a corner of its face (a crease, the fold of a hole's
  // fan), several input faces are nearest: the triangle must face the way of every one of them, so that the
  // answer does not depend on which of them a search returns.
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
      if (point_triangle_distance2(centroid, input_.positions[u[0]], input_.positions[u[1]],
                                   input_.positions[u[2]]) <= tie2 &&
          !(dot(n, normals_[g]) > limit))
        return false;
    }
  }
  return true;
}

bool SeamOptimizer::face_ok(FH f) {
  auto it = mesh_.cfv_iter(f);
  const VH v[3] = {*it, *++it, *++it};
  const size_t i = static_cast<size_t>(f.idx());
  if (i >= face_ok_memo_.size()) face_ok_memo_.resize(mesh_.n_faces());
  FaceOkMemo& memo = face_ok_memo_[i];
  // Bitwise equal inputs (a moved vertex may keep its index), so that the remembered answer is the one
  // triangle_ok would give.
  auto same = [&](int k) {
    const MergedVertex& now = mv(v[k]);
    const FaceOkMemo::Read& then = memo.read[k];
    return memo.v[k] == v[k] && std::memcmp(&now.position, &then.position, sizeof now.position) == 0 &&
           now.source_face == then.source_face && now.on_input == then.on_input;
  };
  if (memo.known && same(0) && same(1) && same(2)) return memo.ok;
  for (int k = 0; k < 3; ++k) {
    memo.v[k] = v[k];
    memo.read[k] = {mv(v[k]).position, mv(v[k]).source_face, mv(v[k]).on_input};
  }
  memo.ok = triangle_ok(v[0], v[1], v[2], pos(v[0]), pos(v[1]), pos(v[2]));
  memo.known = true;
  return memo.ok;
}

}  // namespace prm::remesh
