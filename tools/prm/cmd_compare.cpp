// prm compare A B [--json] [--samples N] [--seed S]: Metro-style surface distances between two meshes
// (common/include/prm/metro_distance.h): one-sided and symmetric mean, RMS and maximum, absolute and as fractions of
// A's bounding-box diagonal.
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "prm/mesh_io.h"
#include "prm/metro_distance.h"

namespace prm::cli {

void add_compare_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("compare", "Measure the surface distance between two meshes, as Metro does");
  struct Options {
    std::string a, b;
    bool json = false;
    size_t samples = 100000;
    uint64_t seed = 1;
  };
  auto opt = std::make_shared<Options>();
  cmd->add_option("a", opt->a, "Reference mesh (its diagonal is the unit of the relative figures)")->required();
  cmd->add_option("b", opt->b, "Mesh to compare with it")->required();
  cmd->add_flag("--json", opt->json, "Print the report as one JSON object");
  cmd->add_option("--samples", opt->samples, "Edge and face samples per direction (each; vertices are all sampled)")
      ->check(CLI::Range(size_t{1}, size_t{1} << 28));
  cmd->add_option("--seed", opt->seed, "Random seed of the face samples");
  cmd->callback([opt] {
    const Mesh a = read_mesh(opt->a), b = read_mesh(opt->b);
    MetroOptions mo;
    mo.samples = opt->samples;
    mo.seed = opt->seed;
    const auto t0 = std::chrono::steady_clock::now();
    const DistanceReport r = metro_distance(a, b, mo);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    auto side = [&](const OneSidedDistance& d) {
      return nlohmann::json{{"samples", d.samples},
                            {"mean", d.mean}, {"rms", d.rms}, {"max", d.max},
                            {"mean_rel", r.rel(d.mean)}, {"rms_rel", r.rel(d.rms)}, {"max_rel", r.rel(d.max)}};
    };
    if (opt->json) {
      nlohmann::json j = {{"a", opt->a},
                          {"b", opt->b},
                          {"diagonal", r.diagonal},
                          {"a_to_b", side(r.a_to_b)},
                          {"b_to_a", side(r.b_to_a)},
                          {"symmetric",
                           {{"mean", r.mean}, {"rms", r.rms}, {"max", r.max},
                            {"mean_rel", r.rel(r.mean)}, {"rms_rel", r.rel(r.rms)}, {"max_rel", r.rel(r.max)}}},
                          {"seconds", secs}};
      std::printf("%s\n", j.dump().c_str());
      return;
    }
    std::printf("A = %s\nB = %s\nbounding-box diagonal of A: %g\n", opt->a.c_str(), opt->b.c_str(), r.diagonal);
    std::printf("%-10s %9s %13s %13s %13s   %11s %11s %11s\n", "", "samples", "mean", "RMS", "max", "mean/diag",
                "RMS/diag", "max/diag");
    auto row = [&](const char* name, size_t n, double mean, double rms, double max) {
      std::printf("%-10s %9zu %13.6g %13.6g %13.6g   %11.4e %11.4e %11.4e\n", name, n, mean, rms, max, r.rel(mean),
                  r.rel(rms), r.rel(max));
    };
    row("A -> B", r.a_to_b.samples, r.a_to_b.mean, r.a_to_b.rms, r.a_to_b.max);
    row("B -> A", r.b_to_a.samples, r.b_to_a.mean, r.b_to_a.rms, r.b_to_a.max);
    row("symmetric", r.a_to_b.samples + r.b_to_a.samples, r.mean, r.rms, r.max);
    std::printf("(max = Hausdorff distance; %.2f s)\n", secs);
  });
}

}  // namespace prm::cli
