// Issue 21: effort 0's first grid from the input surface (first_grid.h).
#include "prm/pipeline/first_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "prm/dihedral_edges.h"

namespace prm::pipeline {

SurfaceGridStatistics surface_grid_statistics(const Mesh& input, double unit, double diagonal) {
  SurfaceGridStatistics out;
  const size_t nf = input.triangles.size();
  if (!(unit > 0) || nf == 0) return out;
  const FaceFrames frames = face_frames(input);
  double total_area = 0;
  for (size_t f = 0; f < nf; ++f) total_area += frames.area[f];
  std::vector<std::pair<double, double>> edges;  // theta^2 l, d
  double k2 = 0, kabs = 0, length = 0;
  for_each_dihedral_edge(input, frames, [&](uint32_t, uint32_t, double theta, double l, double d) {
    edges.push_back({theta * theta * l, d});
    k2 += theta * theta * l / d;
    kabs += theta * l;
    length += l;
  });
  if (edges.empty() || !(total_area > 0)) return out;
  auto model_error = [&](double g) {
    double s = 0;
    for (const auto& [t2l, d] : edges) s += t2l * g * g * g * std::min(g / d, 1.0);
    return std::sqrt(s / total_area);
  };
  double lo = unit, hi = 1e4 * unit;  // bisection on log g: the model error grows with g
  for (int i = 0; i < 60; ++i) {
    const double mid = std::sqrt(lo * hi);
    (model_error(mid) < unit ? lo : hi) = mid;
  }
  out.edges = edges.size();
  out.kappa_rms = std::sqrt(k2 / total_area) * diagonal;
  out.kappa_abs = kabs / total_area * diagonal;
  out.edge_mean = length / static_cast<double>(edges.size()) / unit;
  out.model_grid = lo / unit;
  return out;
}

double predict_first_grid(const SurfaceGridStatistics& s, double unit) {
  if (!(s.model_grid > 0) || !(s.edge_mean > 0)) return 0;
  return std::exp(kFirstGridFit[0]) * std::pow(s.model_grid, kFirstGridFit[1]) * std::pow(s.edge_mean, kFirstGridFit[2]) *
         unit;
}

}  // namespace prm::pipeline
