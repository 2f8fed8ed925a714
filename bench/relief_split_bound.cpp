// Issue 23's bound on splitting reliefs along their detail, without ranking noise (bench/README.md "The bound
// (h23bound)", bench/relief_bound.py). Packs MESH at fixed grids (one grid for every relief; the bits, step scale and
// height lambda given): the CLASS grid (default 1.2 x GRID) cuts each relief's faces, sorted by their own squared
// error, into four classes of equal area; at GRID and at 1.44 x GRID (the measured grids) each face takes the class
// of the class grid's face closest to its centroid. So the classes come from a third remesh, and their errors at the two measured grids carry no
// selection of that grid's noise. Prints JSON: per measured grid its size, bytes, and per relief the patch bits
// (pipeline::relief_costs), lattice vertices and per class the area and mean squared distance; the area left
// unclassified (faces whose closest class-grid face belongs to no relief).
// Usage: prm_bench_relief_split MESH GRID BITS STEP_SCALE LAMBDA [CLASS_FACTOR 1.2] [MEASURE_FACTOR 1.44]
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/pack.h"
#include "prm/pipeline/relief_costs.h"
#include "prm/remesh/relief_grids.h"

namespace {

constexpr int kClasses = prm::remesh::ReliefErrorSample::kErrorQuarters;

prm::pipeline::PackResult pack_at(const prm::Mesh& input, double grid, int bits, double scale, double lambda) {
  prm::pipeline::PackOptions o;
  o.grid_size = grid;
  o.bits = bits;
  o.step_scale = scale;
  o.height_lambda = lambda;
  o.mode = prm::pipeline::PackMode::prm;
  return prm::pipeline::pack(input, o);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: %s MESH GRID BITS STEP_SCALE LAMBDA [CLASS_FACTOR] [MEASURE_FACTOR]\n", argv[0]);
    return 1;
  }
  const prm::Mesh input = prm::read_mesh(argv[1]);
  const double grid = std::atof(argv[2]), scale = std::atof(argv[4]), lambda = std::atof(argv[5]);
  const int bits = std::atoi(argv[3]);
  const double class_factor = argc > 6 ? std::atof(argv[6]) : 1.2, measure_factor = argc > 7 ? std::atof(argv[7]) : 1.44;

  // The classes, from the class grid.
  const prm::pipeline::PackResult c = pack_at(input, grid * class_factor, bits, scale, lambda);
  const prm::Mesh& remeshed_input = c.repaired ? c.repaired_input : input;
  const prm::AabbTree tree(remeshed_input);
  const size_t reliefs = c.remesh.prm.relief_axis.size();
  const prm::remesh::FaceErrors ce = prm::remesh::measure_face_error(c.remesh.prm, tree, reliefs);
  std::vector<std::vector<uint32_t>> faces(reliefs);
  std::vector<double> relief_area(reliefs, 0.0);
  for (size_t f = 0; f < ce.area.size(); ++f)
    if (ce.relief[f] >= 0 && ce.area[f] > 0) {
      faces[static_cast<size_t>(ce.relief[f])].push_back(static_cast<uint32_t>(f));
      relief_area[static_cast<size_t>(ce.relief[f])] += ce.area[f];
    }
  std::vector<int8_t> face_class(ce.area.size(), -1);
  for (size_t r = 0; r < reliefs; ++r) {
    std::sort(faces[r].begin(), faces[r].end(), [&](uint32_t x, uint32_t y) { return ce.msq[x] < ce.msq[y]; });
    double done = 0;
    for (uint32_t f : faces[r]) {
      const int k = std::min(kClasses - 1, static_cast<int>(kClasses * (done + ce.area[f] / 2) / relief_area[r]));
      done += ce.area[f];
      face_class[f] = static_cast<int8_t>(k);
    }
  }

  const prm::AabbTree class_tree(c.remesh.prm.mesh);
  std::printf("{\"class_grid\": %.9g, \"runs\": [", c.remesh.prm.lattice.A * c.remesh.prm.frame.step);
  const double factors[2] = {1.0, measure_factor};
  for (int run = 0; run < 2; ++run) {
    const prm::pipeline::PackResult m = pack_at(input, grid * factors[run], bits, scale, lambda);
    const prm::pipeline::ReliefCosts costs = prm::pipeline::relief_costs(m.remesh.prm, m.report, tree);
    const prm::remesh::FaceErrors e = prm::remesh::measure_face_error(m.remesh.prm, tree, reliefs);
    std::vector<std::array<double, kClasses>> area(reliefs), sum(reliefs);
    double unclassified = 0, total = 0;
    for (size_t f = 0; f < e.area.size(); ++f) {
      if (e.relief[f] < 0 || static_cast<size_t>(e.relief[f]) >= reliefs) continue;
      total += e.area[f];
      const prm::Tri& t = m.remesh.prm.mesh.triangles[f];
      const std::vector<prm::Vec3>& p = m.remesh.prm.mesh.positions;
      prm::Vec3 centroid;
      for (int a = 0; a < 3; ++a) centroid[a] = (p[t[0]][a] + p[t[1]][a] + p[t[2]][a]) / 3;
      const prm::AabbTree::Hit hit = class_tree.closest(centroid);
      const int k = hit.found() ? face_class[hit.face] : -1;
      if (k < 0) {
        unclassified += e.area[f];
        continue;
      }
      area[static_cast<size_t>(e.relief[f])][static_cast<size_t>(k)] += e.area[f];
      sum[static_cast<size_t>(e.relief[f])][static_cast<size_t>(k)] += e.area[f] * e.msq[f];
    }
    double patch_bits = 0;
    for (const auto& rc : costs.reliefs) patch_bits += rc.bits;
    std::printf("%s{\"grid_size\": %.9g, \"bytes\": %zu, \"patch_bits\": %.3f, \"unclassified_area\": %.9g, "
                "\"area\": %.9g, \"reliefs\": [",
                run ? ", " : "", m.remesh.prm.lattice.A * m.remesh.prm.frame.step, m.stream.size(), patch_bits,
                unclassified, total);
    for (size_t r = 0; r < reliefs; ++r) {
      const prm::pipeline::ReliefCost& rc = costs.reliefs[r];
      std::printf("%s{\"bits\": %.3f, \"lattice_vertices\": %u, \"area\": [", r ? ", " : "", rc.bits,
                  rc.lattice_vertices);
      for (int k = 0; k < kClasses; ++k) std::printf("%s%.9g", k ? ", " : "", area[r][static_cast<size_t>(k)]);
      std::printf("], \"msq\": [");
      for (int k = 0; k < kClasses; ++k) {
        const double a = area[r][static_cast<size_t>(k)];
        std::printf("%s%.9g", k ? ", " : "", a > 0 ? sum[r][static_cast<size_t>(k)] / a : 0.0);
      }
      std::printf("]}");
    }
    std::printf("]}");
  }
  std::printf("]}\n");
  return 0;
}
