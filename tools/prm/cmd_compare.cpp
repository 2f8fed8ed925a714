// prm compare A B [--json] [--samples N] [--seed S] [--sampling metro|meshlab]: Metro-style surface distances
// between two meshes (common/include/prm/metro_distance.h): one-sided and symmetric mean, RMS and maximum
// (Hausdorff), absolute and as fractions of A's bounding-box diagonal.
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.h"
#include "json_report.h"
#include "read_any_mesh.h"
#include "prm/metro_distance.h"
#include "prm/progress.h"

namespace prm::cli {
namespace {

struct CompareOptions {
  std::string a, b;
  bool json = false;
  size_t samples = 0;
  uint64_t seed = 1;
  SampleBudget budget = SampleBudget::Metro;
  bool no_vertices = false, no_edges = false, no_faces = false;
};

nlohmann::json side_json(const OneSidedDistance& d, const DistanceReport& r) {
  return {{"mean", d.mean},
          {"rms", d.rms},
          {"max", d.max},
          {"mean_rel", r.rel(d.mean)},
          {"rms_rel", r.rel(d.rms)},
          {"max_rel", r.rel(d.max)},
          {"samples", d.samples},
          {"vertex_samples", d.vertex_samples},
          {"edge_samples", d.edge_samples},
          {"face_samples", d.face_samples},
          {"area", d.area}};
}

void run(const CompareOptions& o) {
  if (o.json) Progress::set_enabled(false);
  const Mesh a = read_any_mesh(o.a);
  const Mesh b = read_any_mesh(o.b);
  MetroOptions mo;
  mo.samples = o.samples;
  mo.seed = o.seed;
  mo.budget = o.budget;
  mo.sample_vertices = !o.no_vertices;
  mo.sample_edges = !o.no_edges;
  mo.sample_faces = !o.no_faces;
  mo.progress = !o.json;
  const auto t0 = std::chrono::steady_clock::now();
  const DistanceReport r = metro_distance(a, b, mo);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const char* budget = o.budget == SampleBudget::Metro ? "metro" : "meshlab";

  if (o.json) {
    JsonReport report("compare");
    report.distance(r.rel(r.rms), r.rel(r.max), r.diagonal).seconds(seconds);
    report["distance"]["mean"] = r.mean;
    report["distance"]["mean_rel"] = r.rel(r.mean);
    report.json().update(nlohmann::json{
        {"a", {{"file", o.a}, {"vertices", a.num_vertices()}, {"faces", a.num_faces()}}},
        {"b", {{"file", o.b}, {"vertices", b.num_vertices()}, {"faces", b.num_faces()}}},
        {"sampling", {{"budget", budget}, {"samples", o.samples}, {"seed", o.seed}}},
        {"diagonal", r.diagonal},
        {"a_to_b", side_json(r.a_to_b, r)},
        {"b_to_a", side_json(r.b_to_a, r)},
        {"symmetric",
         {{"mean", r.mean},
          {"rms", r.rms},
          {"max", r.max},
          {"mean_rel", r.rel(r.mean)},
          {"rms_rel", r.rel(r.rms)},
          {"max_rel", r.rel(r.max)}}}});
    report.print();
    return;
  }
  std::printf("A: %s (%zu vertices, %zu faces, area %.6g)\n", o.a.c_str(), a.num_vertices(), a.num_faces(),
              r.a_to_b.area);
  std::printf("B: %s (%zu vertices, %zu faces, area %.6g)\n", o.b.c_str(), b.num_vertices(), b.num_faces(),
              r.b_to_a.area);
  std::printf("bounding-box diagonal of A: %.9g (the unit of the relative figures)\n", r.diagonal);
  std::printf("sampling: %s budget, seed %llu\n", budget, static_cast<unsigned long long>(o.seed));
  auto samples_line = [](const char* name, const OneSidedDistance& d) {
    std::printf("  %s %zu samples: %zu vertices, %zu on edges, %zu on faces\n", name, d.samples, d.vertex_samples,
                d.edge_samples, d.face_samples);
  };
  samples_line("A -> B", r.a_to_b);
  samples_line("B -> A", r.b_to_a);
  std::printf("\n%-10s %14s %14s %14s   %11s %11s %11s\n", "", "mean", "RMS", "max", "mean/diag", "RMS/diag",
              "max/diag");
  auto row = [&](const char* name, double mean, double rms, double max) {
    std::printf("%-10s %14.7g %14.7g %14.7g   %11.4e %11.4e %11.4e\n", name, mean, rms, max, r.rel(mean), r.rel(rms),
                r.rel(max));
  };
  row("A -> B", r.a_to_b.mean, r.a_to_b.rms, r.a_to_b.max);
  row("B -> A", r.b_to_a.mean, r.b_to_a.rms, r.b_to_a.max);
  row("symmetric", r.mean, r.rms, r.max);
  std::printf("\nsymmetric = the larger direction; symmetric max = Hausdorff distance (%.2f s)\n", seconds);
}

}  // namespace

void add_compare_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "compare",
      "Measure the distance between two surfaces as the Metro tool does: mean, RMS and maximum (Hausdorff)\n"
      "distance from A's samples to B, from B's samples to A, and the larger of the two, absolute and as\n"
      "fractions of A's bounding-box diagonal.");
  auto o = std::make_shared<CompareOptions>();
  // (Missing files are reported by the reader, as I/O errors: exit code 4.)
  cmd->add_option("A", o->a, "First mesh, .prm stream or glTF asset (its bounding-box diagonal is the unit of the relative figures)")->required();
  cmd->add_option("B", o->b, "Second mesh, .prm stream or glTF asset")->required();
  cmd->add_flag("--json", o->json, kJsonFlagHelp);
  cmd->add_option("--samples", o->samples,
                  "Samples per surface (0: ten per face of the larger mesh, Metro's default). With --sampling\n"
                  "meshlab: samples on the edges and again on the faces, besides every vertex")
      ->check(CLI::Range(size_t{0}, size_t{1} << 30));
  cmd->add_option("--seed", o->seed, "Seed of the random face samples")->capture_default_str();
  cmd->add_option("--sampling", o->budget,
                  "How samples are split: 'metro' (vertices, then edges at the square root of the area\n"
                  "density, then faces: Metro's rule) or 'meshlab' (vertices, N on edges, N on faces: MeshLab's\n"
                  "Hausdorff Distance filter)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, SampleBudget>{{"metro", SampleBudget::Metro}, {"meshlab", SampleBudget::PerKind}},
          CLI::ignore_case))
      ->option_text("metro|meshlab (default: metro)");
  cmd->add_flag("--no-vertex-samples", o->no_vertices, "Do not sample the vertices");
  cmd->add_flag("--no-edge-samples", o->no_edges, "Do not sample the edges");
  cmd->add_flag("--no-face-samples", o->no_faces, "Do not sample the faces");
  cmd->callback([o] { run(*o); });
}

}  // namespace prm::cli
