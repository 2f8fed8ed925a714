// Issue 21, h21fast9 (bench/README.md, "Twelfth round"): cheap statistics of an input surface that might predict the
// grid at which `prm pack` meets a target RMS error, so that effort 0's first grid (today kGridPerTargetError x target
// x diagonal, pipeline/src/pack.cpp) could be predicted per mesh. Prints one JSON object; bench/first_grid_study.py
// sets them beside the grid each mesh needs. Per interior edge of the input (faces f, g; dihedral angle theta, length
// l, centroid distance d), prm::pipeline::surface_grid_statistics (first_grid.h): kappa_rms, kappa_abs, edge_mean,
// model_grid; and predicted, the grid effort 0 would start from when it is finer than the constant's (pack.cpp),
// both grids / (target x diagonal).
// Usage: prm_bench_first_grid MESH TARGET_ERROR
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "prm/mesh_io.h"
#include "prm/metro_distance.h"
#include "prm/pipeline/first_grid.h"
#include "prm/pipeline/pack.h"

int main(int argc, char** argv) {
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
    const prm::pipeline::SurfaceGridStatistics s = prm::pipeline::surface_grid_statistics(in, unit, diagonal);
    std::printf(
        "{\"mesh\":\"%s\",\"target\":%.9g,\"diagonal\":%.9g,\"faces\":%zu,\"edges\":%zu,\"kappa_rms\":%.9g,"
        "\"kappa_abs\":%.9g,\"edge_mean\":%.9g,\"model_grid\":%.9g,\"predicted\":%.9g,\"constant\":%.9g}\n",
        argv[1], target, diagonal, in.triangles.size(), s.edges, s.kappa_rms, s.kappa_abs, s.edge_mean, s.model_grid,
        prm::pipeline::predict_first_grid(s, unit) / unit, prm::pipeline::kGridPerTargetError);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prm_bench_first_grid: %s\n", e.what());
    return 1;
  }
}
