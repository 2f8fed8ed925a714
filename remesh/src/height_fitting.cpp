// Least-squares heights (height_fitting.h). Point sampling puts every lattice vertex on the input surface, so each
// triangle's chord cuts the curved surface on one side: the distance has a mean that a small vertical shift
// removes. Each iteration samples every triangle at seven points, finds the input's closest point to each, and
// moves each lattice vertex by the hat-weighted mean of the vertical offsets that would close the gap along the
// triangle normals (a Jacobi step of the least-squares problem; a constant offset is removed in one step).
// Measured on the venus at one grid size (g = 0.0042 of the diagonal, 52,120 vertices): RMS error 1.237e-4
// interpolated, 0.884e-4 after one iteration, 0.845e-4 after two, 0.837e-4 after three; each iteration also adds
// detail the heights' coder pays for (+4.7%, +7.1%, +8.5% bytes), so two iterations are the default: at the same
// target error the grid is coarser and the stream smaller (venus at 1.3e-4: 16,308 / 16,050 / 16,249 bytes).
#include "height_fitting.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <vector>

#include "prm/surface_facing.h"
#include "prm/vec3.h"
#include "triangle_samples.h"

namespace prm::remesh {
namespace {

// Seven points per triangle (triangle_samples.h), equal weights.
constexpr auto& kSamples = kTriangleSamples;
// A triangle tilted further than this from a vertex's axis (cosine) says little about that vertex's height.
constexpr double kMinFacing = 0.3;
// Faces per parallel task of the fit, in order (one closest-point hint carried through each).
constexpr size_t kFaceChunk = 256;

}  // namespace

HeightFitStats fit_heights(PrmMesh& prm, const Mesh& input, const AabbTree& tree, const HeightFitOptions& options) {
  HeightFitStats stats;
  Mesh& m = prm.mesh;
  const size_t nv = m.positions.size(), nf = m.triangles.size();
  if (nv == 0 || tree.empty()) return stats;
  // The largest move, a fraction of the vertex's own relief's grid length (spec §8.4.2: a grid size per relief).
  auto max_shift_of = [&](size_t v) {
    return options.max_shift * static_cast<double>(prm.grid_of(static_cast<size_t>(prm.vertex_relief[v]))) *
           prm.frame.step;
  };
  std::vector<int> axis(nv, -1);
  for (size_t v = 0; v < nv; ++v)
    if (prm.vertex_relief[v] >= 0) axis[v] = prm.relief_axis[static_cast<size_t>(prm.vertex_relief[v])];
  // Reference normals: no triangle may turn against its orientation before the fit.
  std::vector<Vec3> normal0(nf);
  for (size_t f = 0; f < nf; ++f) {
    const Tri& t = m.triangles[f];
    normal0[f] = normalized(triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  }
  // A triangle is flipped when its normal is 90 degrees or more from the normal of the input face nearest to its
  // centroid (the remesher's own test): the fit must not flip a triangle that was not. The input face it finds is
  // kept (HeightFitOptions::centroid_faces) until a corner moves.
  std::vector<uint32_t>* nearest = options.centroid_faces;
  if (nearest) nearest->assign(nf, AabbTree::kNoFace);
  // Per face and sample, the input triangle of its closest point in the last iteration (kNoFace: none yet). The
  // sample has moved by the heights' change only since: that triangle's distance is the next search's start bound
  // (the venus at 1.3e-4: the second iteration's searches 0.28 -> 0.21 s), or with HeightFitOptions::reuse_faces
  // the answer when the sample projects well inside it.
  std::vector<uint32_t> sample_face(std::size(kSamples) * nf, AabbTree::kNoFace);
  auto flipped = [&](uint32_t f) {
    const Tri& t = m.triangles[f];
    const Vec3 n2 = triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
    if (!(norm2(n2) > 0)) return true;
    const Vec3 centroid = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) * (1.0 / 3.0);
    // HeightFitOptions::reuse_faces: the triangle of the face's centroid sample (kSamples[0]) when the centroid
    // projects well inside it, as the samples take it.
    const uint32_t known = options.reuse_faces ? sample_face[std::size(kSamples) * f] : AabbTree::kNoFace;
    if (known != AabbTree::kNoFace && tree.well_inside(centroid, known)) {
      if (nearest) (*nearest)[f] = known;
      return !faces_surface_face(n2, input, known);
    }
    return !faces_surface(n2, centroid, input, tree, nearest ? &(*nearest)[f] : nullptr);
  };
  auto forget_nearest = [&](uint32_t f) {
    if (nearest) (*nearest)[f] = AabbTree::kNoFace;
  };
  // With reuse_faces, after the first iteration's samples (at these positions still), whose centroids' triangles it
  // takes.
  std::vector<uint8_t> was_flipped(nf);
  const auto find_flipped = [&] {
    tbb::parallel_for(size_t{0}, nf, [&](size_t f) { was_flipped[f] = flipped(static_cast<uint32_t>(f)); });
  };
  if (!options.reuse_faces) find_flipped();
  const std::vector<std::vector<uint32_t>> vertex_faces = faces_around_vertices(m);
  const std::vector<Vec3> start = m.positions;
  std::vector<double> shift(nv, 0.0);  // total move along the vertex's axis so far
  std::vector<std::array<double, 6>> face_terms(nf);  // per corner: weighted offset sum, weight sum
  std::vector<uint8_t> moved(nv, 0);
  // flipped() of a face at the current positions, while they last (kFlipUnknown: not evaluated or a corner moved).
  enum : uint8_t { kFlipUnknown, kFlipUnknownMark, kFlipNo, kFlipYes };
  std::vector<uint8_t> flip_state(nf, kFlipUnknown);
  // HeightFitOptions::closest_faces: the first iteration's answers where known (the venus at 1.3e-4: its searches
  // 0.285 -> 0.039 s at the first grid, 0.19 -> 0.026 s at the second).
  const bool answers =
      !options.reuse_faces && options.closest_faces && options.closest_faces->size() == sample_face.size();
  if (answers) sample_face = *options.closest_faces;
  for (int it = 0; it < options.iterations; ++it) {
    // Consecutive faces are neighbours (each relief's faces come in lattice order): the last sample's answer bounds
    // the next face's first query (AabbTree's hint) as it bounds the face's other six. Only the point is used, which
    // a tie between triangles (a shared vertex or edge) does not change.
    auto fit_face = [&](size_t f, AabbTree::Hit& hint) {
      const Tri& t = m.triangles[f];
      const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
      const Vec3 n2 = triangle_normal_area2(a, b, c);
      const double area2 = norm(n2);
      auto& out = face_terms[f];
      out.fill(0.0);
      if (!(area2 > 0)) return;
      const Vec3 n = n2 * (1.0 / area2);
      double facing[3];
      bool any = false;
      for (int k = 0; k < 3; ++k) {
        facing[k] = axis[t[k]] >= 0 ? dot(n, axis_vector(axis[t[k]])) : 0.0;
        any = any || facing[k] > kMinFacing;
      }
      if (!any) return;
      for (size_t si = 0; si < std::size(kSamples); ++si) {
        const auto& s = kSamples[si];
        const Vec3 p = a * s[0] + b * s[1] + c * s[2];
        // This sample's triangle of the last iteration, else the previous sample's.
        uint32_t& known = sample_face[std::size(kSamples) * f + si];
        if (!options.reuse_faces) {
          if (answers && it == 0 && known != AabbTree::kNoFace) {
            hint = tree.on_face(p, known);  // the answer for p: no search
          } else {
            if (known != AabbTree::kNoFace) hint.face = known;
            tree.closest(p, hint);
          }
        } else if (known != AabbTree::kNoFace && tree.well_inside(p, known)) {
          hint = tree.on_face(p, known);
        } else {
          tree.closest_reusing(p, hint);
        }
        known = hint.face;
        if (!hint.found()) continue;
        const double offset = dot(hint.point - p, n);  // along the normal, to the input
        for (int k = 0; k < 3; ++k) {
          if (facing[k] <= kMinFacing) continue;
          out[static_cast<size_t>(2 * k)] += s[k] * area2 * offset / facing[k];
          out[static_cast<size_t>(2 * k + 1)] += s[k] * area2;
        }
      }
    };
    // Fixed chunks, each with its own hint: the answers do not depend on the scheduling.
    tbb::parallel_for(size_t{0}, (nf + kFaceChunk - 1) / kFaceChunk, [&](size_t c) {
      AabbTree::Hit hint;
      for (size_t f = c * kFaceChunk, end = std::min(nf, f + kFaceChunk); f < end; ++f) fit_face(f, hint);
    });
    if (it == 0 && options.reuse_faces) find_flipped();
    std::vector<double> num(nv, 0.0), den(nv, 0.0);
    for (size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = m.triangles[f][static_cast<size_t>(k)];
        num[v] += face_terms[f][static_cast<size_t>(2 * k)];
        den[v] += face_terms[f][static_cast<size_t>(2 * k + 1)];
      }
    const std::vector<Vec3> before = m.positions;
    std::vector<uint32_t> touched;
    for (uint32_t v = 0; v < nv; ++v) {
      if (axis[v] < 0 || !(den[v] > 0)) continue;
      const double max_shift = max_shift_of(v);
      const double target = std::clamp(shift[v] + num[v] / den[v], -max_shift, max_shift);
      if (target == shift[v]) continue;
      m.positions[v] = start[v] + axis_vector(axis[v]) * target;
      shift[v] = target;
      touched.push_back(v);
    }
    // Undo moves that fold a triangle (its normal turning by more than 90 degrees from its original one), flip it
    // against the input or make it degenerate, until none does. The flip test (a closest-point query) of each face
    // around a moved vertex is evaluated once, in parallel, and again only when one of its corners is reverted.
    std::vector<uint32_t> check_faces;
    for (uint32_t v : touched)
      if (m.positions[v] != before[v])
        for (uint32_t f : vertex_faces[v]) {
          forget_nearest(f);
          if (!was_flipped[f] && flip_state[f] != kFlipUnknownMark) {
            flip_state[f] = kFlipUnknownMark;
            check_faces.push_back(f);
          }
        }
    tbb::parallel_for(size_t{0}, check_faces.size(), [&](size_t k) {
      flip_state[check_faces[k]] = flipped(check_faces[k]) ? kFlipYes : kFlipNo;
    });
    auto flipped_now = [&](uint32_t f) {
      if (flip_state[f] < kFlipNo) flip_state[f] = flipped(f) ? kFlipYes : kFlipNo;
      return flip_state[f] == kFlipYes;
    };
    for (bool again = true; again;) {
      again = false;
      for (uint32_t v : touched) {
        if (m.positions[v] == before[v]) continue;
        for (uint32_t f : vertex_faces[v]) {
          const Tri& t = m.triangles[f];
          const Vec3 n2 = triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
          if (dot(n2, normal0[f]) > 1e-3 * norm(n2) && norm2(n2) > 0 && (was_flipped[f] || !flipped_now(f))) continue;
          for (uint32_t u : t)
            if (m.positions[u] != before[u]) {
              m.positions[u] = before[u];
              for (uint32_t g : vertex_faces[u]) {
                flip_state[g] = kFlipUnknown;
                forget_nearest(g);
              }
              shift[u] = dot(before[u] - start[u], axis_vector(axis[u]));
              ++stats.reverted;
              again = true;
            }
        }
      }
    }
    std::fill(flip_state.begin(), flip_state.end(), kFlipUnknown);
    for (uint32_t v : touched) moved[v] = moved[v] || m.positions[v] != start[v];
  }
  for (uint8_t x : moved) stats.moved += x;
  return stats;
}

}  // namespace prm::remesh
