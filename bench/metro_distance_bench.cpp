// prm_bench_metro: speed of the Metro-style distance (common/include/prm/metro_distance.h) on two ~50k-vertex
// meshes: ../shared/meshes/horse.ply (48,485 vertices, 96,966 faces) against a copy whose vertices are moved along
// their normals (uniform in ±0.02% of the bounding-box diagonal, the paper's error scale), and venus.off
// (50,002 vertices) against a bumped copy likewise. Timed parts: tree build, sampling, a full metro_distance() at
// Metro's default density (ten samples per face, about 2 × 1M queries) and at 100k samples per surface (a search-loop
// setting), and MetroReference::compare() (the reference's tree and samples prepared once). Each is run on one
// thread and on all threads (the /threads argument).
//
//   build/bench/prm_bench_metro [--benchmark_filter=...] [--benchmark_min_time=...]
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <cstdio>
#include <map>
#include <random>
#include <string>

#include "prm/aabb_tree.h"
#include "prm/mesh_io.h"
#include "prm/metro_distance.h"
#include "prm/surface_sampler.h"
#include "prm/vec3.h"

namespace {

using namespace prm;  // Vec3 operators (prm/vec3.h) are found by ordinary lookup, not ADL

// Every vertex moved along its area-weighted normal by a uniform amount in [-amplitude, amplitude].
Mesh bumped(const Mesh& m, double amplitude, uint64_t seed) {
  std::vector<prm::Vec3> normal(m.positions.size(), prm::Vec3{0, 0, 0});
  for (const prm::Tri& t : m.triangles) {
    const prm::Vec3 n = prm::triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
    for (uint32_t v : t) normal[v] += n;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Mesh out = m;
  for (size_t v = 0; v < out.positions.size(); ++v) out.positions[v] += prm::normalized(normal[v]) * u(rng);
  return out;
}

struct Pair {
  Mesh a, b;
};

const Pair& pair(const std::string& name) {
  static std::map<std::string, Pair> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    Pair p;
    p.a = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/" + name);
    p.b = bumped(p.a, 2e-4 * prm::bbox_diagonal(p.a), 1);
    it = cache.emplace(name, std::move(p)).first;
  }
  return it->second;
}

const char* kMeshes[] = {"horse.ply", "venus.off"};

// state.range(0): mesh index; state.range(1): threads (0 = all).
std::unique_ptr<tbb::global_control> threads(const benchmark::State& state) {
  const int n = static_cast<int>(state.range(1));
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               n > 0 ? n : tbb::info::default_concurrency());
}

void BM_TreeBuild(benchmark::State& state) {
  const Pair& p = pair(kMeshes[state.range(0)]);
  const auto control = threads(state);
  for (auto _ : state) {
    prm::AabbTree tree(p.b);
    benchmark::DoNotOptimize(tree.num_nodes());
  }
  state.counters["faces"] = static_cast<double>(p.b.num_faces());
  state.counters["Mfaces/s"] = benchmark::Counter(static_cast<double>(p.b.num_faces()) * 1e-6,
                                                  benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(kMeshes[state.range(0)]);
}

void BM_Sample(benchmark::State& state) {
  const Pair& p = pair(kMeshes[state.range(0)]);
  const auto control = threads(state);
  prm::SamplingOptions o;
  o.samples = 10 * p.a.num_faces();
  size_t n = 0;
  for (auto _ : state) {
    const prm::SurfaceSamples s = prm::sample_surface(p.a, o);
    n = s.points.size();
    benchmark::DoNotOptimize(s.points.data());
  }
  state.counters["Msamples/s"] =
      benchmark::Counter(static_cast<double>(n) * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(kMeshes[state.range(0)]);
}

// state.range(2): samples per surface (0 = Metro's default, ten per face).
void BM_MetroDistance(benchmark::State& state) {
  const Pair& p = pair(kMeshes[state.range(0)]);
  const auto control = threads(state);
  prm::MetroOptions o;
  o.samples = static_cast<size_t>(state.range(2));
  prm::DistanceReport r;
  for (auto _ : state) {
    r = prm::metro_distance(p.a, p.b, o);
    benchmark::ClobberMemory();  // (not DoNotOptimize(double&): with GCC 12 and benchmark 1.7.1 it garbles the value)
  }
  const double queries = static_cast<double>(r.a_to_b.samples + r.b_to_a.samples);
  state.counters["queries"] = queries;
  state.counters["Mqueries/s"] = benchmark::Counter(queries * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["rms/diag"] = r.rel(r.rms);
  state.SetLabel(kMeshes[state.range(0)]);
}

void BM_MetroReferenceCompare(benchmark::State& state) {
  const Pair& p = pair(kMeshes[state.range(0)]);
  const auto control = threads(state);
  prm::MetroOptions o;
  o.samples = static_cast<size_t>(state.range(2));
  const prm::MetroReference ref(p.a, o);
  prm::DistanceReport r = ref.compare(p.b);  // prepares the reference's samples
  for (auto _ : state) {
    r = ref.compare(p.b);
    benchmark::ClobberMemory();  // (not DoNotOptimize(double&): with GCC 12 and benchmark 1.7.1 it garbles the value)
  }
  const double queries = static_cast<double>(r.a_to_b.samples + r.b_to_a.samples);
  state.counters["Mqueries/s"] = benchmark::Counter(queries * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(kMeshes[state.range(0)]);
}

BENCHMARK(BM_TreeBuild)->ArgsProduct({{0, 1}, {1, 0}})->ArgNames({"mesh", "threads"})->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Sample)->ArgsProduct({{0, 1}, {1, 0}})->ArgNames({"mesh", "threads"})->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_MetroDistance)
    ->ArgsProduct({{0, 1}, {1, 0}, {0, 100000}})
    ->ArgNames({"mesh", "threads", "samples"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_MetroReferenceCompare)
    ->ArgsProduct({{0, 1}, {1, 0}, {0, 100000}})
    ->ArgNames({"mesh", "threads", "samples"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
