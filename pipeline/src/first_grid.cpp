// Issue 21: effort 0's first grid from the input surface (first_grid.h).
#include "prm/pipeline/first_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "prm/vec3.h"

namespace prm::pipeline {

SurfaceGridStatistics surface_grid_statistics(const Mesh& input, double unit, double diagonal) {
  SurfaceGridStatistics out;
  const size_t nf = input.triangles.size();
  if (!(unit > 0) || nf == 0) return out;
  std::vector<Vec3> normal(nf), centroid(nf);
  std::vector<double> area(nf);
  double total_area = 0;
  for (size_t f = 0; f < nf; ++f) {
    const Tri& t = input.triangles[f];
    const Vec3 n2 = triangle_normal_area2(input.positions[t[0]], input.positions[t[1]], input.positions[t[2]]);
    area[f] = 0.5 * norm(n2);
    total_area += area[f];
    normal[f] = area[f] > 0 ? n2 * (0.5 / area[f]) : Vec3{0, 0, 0};
    centroid[f] = (input.positions[t[0]] + input.positions[t[1]] + input.positions[t[2]]) * (1.0 / 3.0);
  }
  std::unordered_map<uint64_t, uint32_t> first;  // undirected edge -> the first face seen
  first.reserve(3 * nf);
  std::vector<std::pair<double, double>> edges;  // theta^2 l, d
  double k2 = 0, kabs = 0, length = 0;
  for (uint32_t f = 0; f < nf; ++f)
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t a = input.triangles[f][k], b = input.triangles[f][(k + 1) % 3];
      const uint64_t key = uint64_t{std::min(a, b)} << 32 | std::max(a, b);
      const auto [it, inserted] = first.emplace(key, f);
      if (inserted) continue;
      const uint32_t g = it->second;
      const double d = norm(centroid[f] - centroid[g]);
      if (!(d > 0) || !(area[f] > 0) || !(area[g] > 0)) continue;
      const double theta = std::acos(std::clamp(dot(normal[f], normal[g]), -1.0, 1.0));
      const double l = norm(input.positions[a] - input.positions[b]);
      edges.push_back({theta * theta * l, d});
      k2 += theta * theta * l / d;
      kabs += theta * l;
      length += l;
    }
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
