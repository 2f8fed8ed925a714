// Issue 21, h21fast9 (bench/README.md, "Twelfth round"): cheap statistics of an input surface that might predict the
// grid at which `prm pack` meets a target RMS error, so that effort 0's first grid (today kGridPerTargetError x target
// x diagonal, pipeline/src/pack.cpp) could be predicted per mesh. Prints one JSON object; bench/first_grid_study.py
// sets them beside the grid each mesh needs. Per interior edge of the input (faces f, g; dihedral angle theta, length
// l, centroid distance d):
//   kappa_rms  sqrt(sum theta^2 l / d / area): the RMS curvature (as remesh::measure_relief_detail), x diagonal
//   kappa_abs  sum theta l / area: the mean absolute curvature, x diagonal
//   edge_mean  the mean edge length, / (target x diagonal)
//   model_grid the grid g (/ (target x diagonal)) at which sqrt(sum theta^2 l g^3 min(g / d, 1) / area) equals
//              target x diagonal: the interpolation error of a smooth patch (g^4 kappa^2 where d < g) and of a crease
//              (g^3 theta^2 per length where d > g), up to one constant factor
// Usage: prm_bench_first_grid MESH TARGET_ERROR
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <unordered_map>
#include <utility>
#include <vector>

#include "prm/mesh_io.h"
#include "prm/metro_distance.h"
#include "prm/vec3.h"

int main(int argc, char** argv) {
  using namespace prm;  // the Vec3 operators
  if (argc != 3) {
    std::fprintf(stderr, "usage: prm_bench_first_grid MESH TARGET_ERROR\n");
    return 2;
  }
  try {
    const prm::Mesh in = prm::read_mesh(argv[1]);
    const double target = std::atof(argv[2]);
    const double diagonal = prm::bbox_diagonal(in);
    const double unit = target * diagonal;
    if (!(unit > 0)) {
      std::fprintf(stderr, "prm_bench_first_grid: the target and the diagonal must be positive\n");
      return 2;
    }
    const size_t nf = in.triangles.size();
    std::vector<prm::Vec3> normal(nf), centroid(nf);
    std::vector<double> area(nf);
    double total_area = 0;
    for (size_t f = 0; f < nf; ++f) {
      const prm::Tri& t = in.triangles[f];
      const prm::Vec3 n2 = prm::triangle_normal_area2(in.positions[t[0]], in.positions[t[1]], in.positions[t[2]]);
      area[f] = 0.5 * prm::norm(n2);
      total_area += area[f];
      normal[f] = area[f] > 0 ? n2 * (0.5 / area[f]) : prm::Vec3{0, 0, 0};
      centroid[f] = (in.positions[t[0]] + in.positions[t[1]] + in.positions[t[2]]) * (1.0 / 3.0);
    }
    std::unordered_map<uint64_t, uint32_t> first;  // undirected edge -> the first face seen
    first.reserve(3 * nf);
    std::vector<std::pair<double, double>> edges;  // theta^2 l, d
    double k2 = 0, kabs = 0, length = 0;
    size_t counted = 0;
    for (uint32_t f = 0; f < nf; ++f)
      for (size_t k = 0; k < 3; ++k) {
        const uint32_t a = in.triangles[f][k], b = in.triangles[f][(k + 1) % 3];
        const uint64_t key = uint64_t{std::min(a, b)} << 32 | std::max(a, b);
        const auto [it, inserted] = first.emplace(key, f);
        if (inserted) continue;
        const uint32_t g = it->second;
        const double d = prm::norm(centroid[f] - centroid[g]);
        if (!(d > 0) || !(area[f] > 0) || !(area[g] > 0)) continue;
        const double theta = std::acos(std::clamp(prm::dot(normal[f], normal[g]), -1.0, 1.0));
        const double l = prm::norm(in.positions[a] - in.positions[b]);
        edges.push_back({theta * theta * l, d});
        k2 += theta * theta * l / d;
        kabs += theta * l;
        length += l;
        ++counted;
      }
    auto model_error = [&](double g) {
      double s = 0;
      for (const auto& [t2l, d] : edges) s += t2l * g * g * g * std::min(g / d, 1.0);
      return std::sqrt(s / total_area);
    };
    double lo = unit, hi = 1e4 * unit;  // bisection on log g: model_error grows with g
    for (int i = 0; i < 60; ++i) {
      const double mid = std::sqrt(lo * hi);
      (model_error(mid) < unit ? lo : hi) = mid;
    }
    std::printf(
        "{\"mesh\":\"%s\",\"target\":%.9g,\"diagonal\":%.9g,\"faces\":%zu,\"edges\":%zu,\"kappa_rms\":%.9g,"
        "\"kappa_abs\":%.9g,\"edge_mean\":%.9g,\"model_grid\":%.9g}\n",
        argv[1], target, diagonal, nf, counted, std::sqrt(k2 / total_area) * diagonal, kabs / total_area * diagonal,
        counted ? length / static_cast<double>(counted) / unit : 0.0, lo / unit);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prm_bench_first_grid: %s\n", e.what());
    return 1;
  }
}
