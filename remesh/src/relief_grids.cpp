#include "prm/remesh/relief_grids.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

#include <tbb/parallel_for.h>

#include "prm/dihedral_edges.h"
#include "prm/remesh/resample.h"
#include "prm/vec3.h"

namespace prm::remesh {

ReliefDetail measure_relief_detail(const Mesh& input, const ReliefLayout& layout) {
  // Each interior edge once: dihedral^2 x length / centroid distance, half to each side (an integral of the
  // squared curvature over the strip between the centroids).
  const FaceFrames frames = face_frames(input);
  std::vector<double> integrated(input.triangles.size(), 0.0);
  for_each_dihedral_edge(input, frames, [&](uint32_t f, uint32_t g, double angle, double length, double d) {
    const double k2 = 0.5 * angle * angle * length / d;
    integrated[f] += k2;
    integrated[g] += k2;
  });
  ReliefDetail out;
  out.area.assign(layout.reliefs.size(), 0.0);
  out.curvature2.assign(layout.reliefs.size(), 0.0);
  const Mesh& refined = layout.mesh;
  for (size_t f = 0; f < refined.triangles.size(); ++f) {
    const Tri& t = refined.triangles[f];
    const double a = triangle_area(refined.positions[t[0]], refined.positions[t[1]], refined.positions[t[2]]);
    const size_t s = layout.source_face.empty() ? f : static_cast<size_t>(layout.source_face[f]);
    const size_t r = static_cast<size_t>(layout.face_relief[f]);
    out.area[r] += a;
    if (frames.area[s] > 0) out.curvature2[r] += a * integrated[s] / frames.area[s];
  }
  for (size_t r = 0; r < out.area.size(); ++r)
    if (out.area[r] > 0) out.curvature2[r] /= out.area[r];
  return out;
}

namespace {

void check_levels(const ReliefGridOptions& options) {
  if (options.coarsest_level - options.finest_level + 1 > static_cast<int>(kMaxReliefGrids) ||
      options.finest_level > 0 || options.coarsest_level < 0 || options.levels_per_octave < 1 || !(options.exponent > 0))
    throw std::invalid_argument("relief grid levels: at most " + std::to_string(kMaxReliefGrids) + ", around 0");
}

// A scale rounded to 2^(k / levels_per_octave), k within the options' levels.
double round_to_level(double s, const ReliefGridOptions& options) {
  const int k = std::clamp(static_cast<int>(std::lround(std::log2(s) * options.levels_per_octave)),
                           options.finest_level, options.coarsest_level);
  return std::exp2(static_cast<double>(k) / options.levels_per_octave);
}

}  // namespace

std::vector<double> allocate_relief_grid_scales(const ReliefDetail& detail, const ReliefGridOptions& options) {
  check_levels(options);
  const size_t n = detail.curvature2.size();
  double top = 0, total = 0, log_sum = 0;
  for (double c : detail.curvature2) top = std::max(top, c);
  // A flat relief's curvature is floored, so that it gets the coarsest level rather than an infinite grid.
  const double floor = std::max(top * 1e-9, 1e-300);
  for (size_t r = 0; r < n; ++r) {
    total += detail.area[r];
    log_sum += detail.area[r] * std::log(std::max(detail.curvature2[r], floor));
  }
  const double reference = total > 0 ? std::exp(log_sum / total) : 1.0;
  std::vector<double> scale(n, 1.0);
  for (size_t r = 0; r < n; ++r) {
    const double s = std::pow(std::max(detail.curvature2[r], floor) / reference, -options.exponent);
    scale[r] = round_to_level(s, options);
  }
  return scale;
}

FaceErrors measure_face_error(const PrmMesh& prm, const AabbTree& input_tree, size_t reliefs) {
  const Mesh& m = prm.mesh;
  const size_t nf = m.triangles.size();
  FaceErrors e;
  e.area.assign(nf, 0.0);
  e.msq.assign(nf, 0.0);
  e.sum.assign(nf, 0.0);
  e.relief.assign(nf, -1);
  e.input_face.assign(nf, AabbTree::kNoFace);
  // Barycentric weights of the seven points, the centroid first.
  static constexpr double kPoints[7][3] = {{1 / 3.0, 1 / 3.0, 1 / 3.0}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5},
                                           {2 / 3.0, 1 / 6.0, 1 / 6.0}, {1 / 6.0, 2 / 3.0, 1 / 6.0},
                                           {1 / 6.0, 1 / 6.0, 2 / 3.0}};
  tbb::parallel_for(size_t{0}, nf, [&](size_t f) {
    const Tri& t = m.triangles[f];
    for (int c = 0; c < 3 && e.relief[f] < 0; ++c)
      if (t[c] < prm.vertex_relief.size() && prm.vertex_relief[t[c]] >= 0 &&
          static_cast<size_t>(prm.vertex_relief[t[c]]) < reliefs)
        e.relief[f] = prm.vertex_relief[t[c]];
    if (e.relief[f] < 0) return;
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    e.area[f] = triangle_area(a, b, c);
    AabbTree::Hit hint = input_tree.closest(a);
    double sum = 0;
    for (const auto& w : kPoints) {
      input_tree.closest(a * w[0] + b * w[1] + c * w[2], hint);
      if (&w == &kPoints[0]) e.input_face[f] = hint.face;
      sum += hint.distance2;
    }
    e.sum[f] = sum;
    e.msq[f] = sum / 7.0;
  });
  return e;
}

ReliefErrorSample measure_relief_error(const PrmMesh& prm, const AabbTree& input_tree, size_t reliefs, double grid) {
  const FaceErrors e = measure_face_error(prm, input_tree, reliefs);
  const size_t nf = e.area.size();
  const std::vector<double>& face_area = e.area;
  const std::vector<int32_t>& face_relief = e.relief;
  ReliefErrorSample out;
  out.grid = grid;
  out.area.assign(reliefs, 0.0);
  out.msq.assign(reliefs, 0.0);
  for (size_t f = 0; f < nf; ++f) {
    if (face_relief[f] < 0) continue;
    const size_t r = static_cast<size_t>(face_relief[f]);
    out.area[r] += face_area[f];
    out.msq[r] += face_area[f] * e.sum[f] / 7.0;  // as before measure_face_error (the --adaptive model's rounding)
  }
  for (size_t r = 0; r < reliefs; ++r)
    if (out.area[r] > 0) out.msq[r] /= out.area[r];
  // The quarters: each relief's faces by their own msq, cut at every quarter of the relief's area.
  constexpr int kQ = ReliefErrorSample::kErrorQuarters;
  std::vector<std::vector<uint32_t>> faces(reliefs);
  for (size_t f = 0; f < nf; ++f)
    if (face_relief[f] >= 0 && face_area[f] > 0) faces[static_cast<size_t>(face_relief[f])].push_back(static_cast<uint32_t>(f));
  out.msq_quarters.assign(reliefs, std::array<double, kQ>{});
  for (size_t r = 0; r < reliefs; ++r) {
    std::sort(faces[r].begin(), faces[r].end(),
              [&](uint32_t x, uint32_t y) { return e.msq[x] < e.msq[y]; });
    std::array<double, kQ> area{}, sum{};
    double done = 0;
    for (uint32_t f : faces[r]) {
      const int k = std::min(kQ - 1, static_cast<int>(kQ * (done + face_area[f] / 2) / out.area[r]));
      area[static_cast<size_t>(k)] += face_area[f];
      sum[static_cast<size_t>(k)] += face_area[f] * e.msq[f];
      done += face_area[f];
    }
    for (int k = 0; k < kQ; ++k)
      if (area[static_cast<size_t>(k)] > 0) out.msq_quarters[r][static_cast<size_t>(k)] = sum[static_cast<size_t>(k)] / area[static_cast<size_t>(k)];
  }
  return out;
}

std::vector<double> allocate_relief_grid_scales_measured(const ReliefErrorSample& a, const ReliefErrorSample& b,
                                                         const ReliefGridOptions& options) {
  check_levels(options);
  if (!(a.grid > 0) || !(b.grid > a.grid) || a.msq.size() != b.msq.size() || a.area.size() != a.msq.size())
    throw std::invalid_argument("relief error samples: two grids, the second coarser, of the same reliefs");
  const size_t n = a.msq.size();
  // log(p_r msq_r(g_a)) / (p_r + 2) and 1 / (p_r + 2), for the reliefs measured in both.
  std::vector<double> log_m(n, 0.0), inv(n, 0.0);
  std::vector<bool> known(n, false);
  double weight = 0, weighted = 0;
  const double log_ratio = std::log(b.grid / a.grid);
  for (size_t r = 0; r < n; ++r) {
    if (!(a.area[r] > 0) || !(b.area[r] > 0) || !(a.msq[r] > 0) || !(b.msq[r] > 0)) continue;
    const double p =
        std::clamp(std::log(b.msq[r] / a.msq[r]) / log_ratio, kMinErrorExponent, kMaxErrorExponent);
    known[r] = true;
    inv[r] = 1.0 / (p + 2);
    log_m[r] = std::log(p * a.msq[r]);
    weight += a.area[r] * inv[r];
    weighted += a.area[r] * inv[r] * log_m[r];
  }
  std::vector<double> scale(n, 1.0);
  if (!(weight > 0)) return scale;
  const double log_q = weighted / weight;  // the area-weighted mean of log s_r is then 0
  for (size_t r = 0; r < n; ++r)
    if (known[r]) scale[r] = round_to_level(std::exp((log_q - log_m[r]) * inv[r]), options);
  return scale;
}

}  // namespace prm::remesh
