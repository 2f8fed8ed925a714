// prm_bench_remesh: speed of relief construction (paper §2.1) and of the whole remesh (§2.2-2.4: slicing,
// constrained collapses, merging) on the ~50k-vertex meshes of ../shared/meshes: horse.ply, venus.off, feline.off
// and bunny_zipper.ply (its 5 holes closed first, outside the timed region).
//
// The remesh runs at a fixed grid size per mesh (the one `prm remesh --target-error 2e-4` finds, bench/README.md),
// so that a run measures resampling and merging, not the grid search. Both run with the parallel loops on (the
// reliefs are independent: TBB) and off (/parallel:0), to show what the second core buys.
//
//   build/bench/prm_bench_remesh [--benchmark_filter=...] [--benchmark_min_time=...]
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include "prm/mesh_io.h"
#include "prm/mesh_repair.h"
#include "prm/mesh_validate.h"
#include "prm/remesh/reliefs.h"
#include "prm/remesh/remesh.h"

namespace {

struct Case {
  const char* file;
  double grid_fraction;  // of the bounding-box diagonal
};

// Grid fractions found by `prm remesh FILE --target-error 2e-4 --json` (field grid_fraction).
const Case kCases[] = {
    {"horse.ply", 0.00690},
    {"venus.off", 0.00713},
    {"feline.off", 0.00519},
    {"bunny_zipper.ply", 0.00744},
};

const prm::Mesh& closed_mesh(const std::string& name) {
  static std::map<std::string, prm::Mesh> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    prm::Mesh m = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/" + name);
    if (!prm::validate_mesh(m).closed()) m = prm::repair_mesh(m);
    it = cache.emplace(name, std::move(m)).first;
  }
  return it->second;
}

void BM_Reliefs(benchmark::State& state, const Case& c) {
  const prm::Mesh& mesh = closed_mesh(c.file);
  prm::remesh::ReliefOptions options;
  options.parallel = state.range(0) != 0;
  size_t reliefs = 0;
  for (auto _ : state) {
    prm::remesh::ReliefLayout layout = prm::remesh::build_reliefs(mesh, options);
    reliefs = layout.reliefs.size();
    benchmark::DoNotOptimize(layout.face_relief.data());
  }
  state.counters["input_vertices"] = static_cast<double>(mesh.positions.size());
  state.counters["reliefs"] = static_cast<double>(reliefs);
  state.counters["Mverts/s"] = benchmark::Counter(static_cast<double>(mesh.positions.size()) * 1e-6,
                                                  benchmark::Counter::kIsIterationInvariantRate);
}

void BM_Remesh(benchmark::State& state, const Case& c) {
  const prm::Mesh& mesh = closed_mesh(c.file);
  prm::remesh::RemeshOptions options;
  options.grid_fraction = c.grid_fraction;
  options.parallel = state.range(0) != 0;
  options.reliefs.parallel = options.parallel;
  size_t n_r = 0;
  for (auto _ : state) {
    prm::remesh::RemeshResult r = prm::remesh::remesh(mesh, options);
    n_r = r.prm.mesh.positions.size();
    benchmark::DoNotOptimize(r.prm.mesh.triangles.data());
  }
  state.counters["n_o"] = static_cast<double>(mesh.positions.size());
  state.counters["n_r"] = static_cast<double>(n_r);
}

const bool registered = [] {
  for (const Case& c : kCases) {
    benchmark::RegisterBenchmark((std::string("Reliefs/") + c.file).c_str(), BM_Reliefs, c)
        ->ArgName("parallel")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark((std::string("Remesh/") + c.file).c_str(), BM_Remesh, c)
        ->ArgName("parallel")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
