// prm reliefs IN -o OUT.ply [--tau T] [--naive] [--geodesic fmm|dijkstra] [--json]: the relief layout of paper §2.1,
// written as a binary PLY with a "relief" face property and face colours (render it with `prm render`).
#include <array>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "json_report.h"
#include "prm/mesh_io.h"
#include "prm/mesh_repair.h"
#include "prm/mesh_validate.h"
#include "prm/remesh/reliefs.h"

namespace prm::cli {

void add_reliefs_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("reliefs", "Split a mesh into reliefs with smooth boundaries (paper §2.1)");
  struct Options {
    std::string input, output;
    double tau = 0.2;
    bool naive = false, json = false;
    std::string geodesic = "fmm";
    double snap = 0.05, min_relief = remesh::ReliefOptions{}.min_relief_triangles,
           merge_facing = remesh::ReliefOptions{}.merge_facing;
  };
  auto opt = std::make_shared<Options>();
  cmd->add_option("input", opt->input,
                  "Mesh file (a 2-manifold; holes are closed and pinched vertices split first, as prm repair does)")
      ->required();
  cmd->add_option("-o,--output", opt->output, "Output PLY: the refined mesh, face property 'relief', face colours");
  cmd->add_option("--tau", opt->tau, "Smoothing parameter in (0, 0.577); smaller is smoother (paper: 0.1-0.3)")
      ->check(CLI::Range(1e-9, 0.57735));
  cmd->add_flag("--naive", opt->naive, "Each triangle to the axis closest to its normal (no smoothing)");
  cmd->add_option("--geodesic", opt->geodesic, "Distance fields: fmm (fast marching, default) or dijkstra (the paper's)")
      ->check(CLI::IsMember({"fmm", "dijkstra"}));
  cmd->add_option("--snap", opt->snap, "Drop boundary pieces shorter than this fraction of an edge (default 0.05)")
      ->check(CLI::Range(0.0, 0.24));
  cmd->add_option("--min-relief", opt->min_relief,
                  "Reliefs smaller than this many mean triangles join a neighbour (default 256; 0: keep all)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--merge-facing", opt->merge_facing,
                  "A small relief joins a neighbour only if all its faces face that axis by at least this (n.v; "
                  "default 0.02; --tau if smaller)")
      ->check(CLI::Range(1e-9, 0.57735));
  cmd->add_flag("--json", opt->json, kJsonFlagHelp);
  cmd->callback([opt] {
    Mesh mesh = read_mesh(opt->input);
    RepairReport rep;
    const MeshReport check = validate_mesh(mesh);
    const bool repaired = !check.closed() || !check.manifold();
    if (repaired) mesh = repair_mesh(mesh, &rep);
    remesh::ReliefOptions ro;
    ro.tau = opt->tau;
    ro.naive = opt->naive;
    ro.snap = opt->snap;
    ro.min_relief_triangles = opt->min_relief;
    ro.merge_facing = opt->merge_facing;
    ro.geodesic = opt->geodesic == "dijkstra" ? remesh::GeodesicMethod::Dijkstra : remesh::GeodesicMethod::FastMarching;
    const auto t0 = std::chrono::steady_clock::now();
    const remesh::ReliefLayout layout = remesh::build_reliefs(mesh, ro);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!opt->output.empty()) write_mesh(layout.mesh, opt->output);

    double total = 0;
    std::array<double, 6> per_axis{};
    std::array<int, 6> count_axis{};
    for (const auto& r : layout.reliefs) {
      total += r.area;
      per_axis[static_cast<size_t>(r.axis)] += r.area;
      ++count_axis[static_cast<size_t>(r.axis)];
    }
    auto share = [&](double a) { return total > 0 ? a / total : 0.0; };
    static const char* names[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    if (opt->json) {
      nlohmann::json reliefs = nlohmann::json::array(), axes = nlohmann::json::object();
      for (size_t i = 0; i < layout.reliefs.size(); ++i)
        reliefs.push_back({{"id", i},
                           {"axis", names[layout.reliefs[i].axis]},
                           {"faces", layout.reliefs[i].faces},
                           {"area_share", share(layout.reliefs[i].area)}});
      for (size_t a = 0; a < 6; ++a)
        axes[names[a]] = {{"reliefs", count_axis[a]}, {"area_share", share(per_axis[a])}};
      JsonReport report("reliefs");
      report.input(opt->input).output(opt->output);
      report.mesh_size(layout.mesh.positions.size(), layout.mesh.triangles.size()).seconds(ms / 1000);
      report.json().update(nlohmann::json{{"tau", opt->tau},
                                {"naive", opt->naive},
                                {"geodesic", opt->geodesic},
                                {"repair",
                                 {{"holes_closed", rep.holes_filled},
                                  {"pinched_vertices_split", rep.pinched_vertices_split}}},
                                {"input_triangles", mesh.triangles.size()},
                                {"split_faces", layout.split_faces},
                                {"inner_points", layout.inner_points},
                                {"merged_reliefs", layout.merged_reliefs},
                                {"reliefs", layout.reliefs.size()},
                                {"boundary_length", layout.boundary_length},
                                {"per_axis", axes},
                                {"relief_list", reliefs}});
      report.print();
      return;
    }
    std::printf("%s: %zu reliefs (tau %g%s), boundary length %.6g; %zu of %zu faces split, %zu small reliefs merged; "
                "%.0f ms\n",
                opt->input.c_str(), layout.reliefs.size(), opt->tau, opt->naive ? ", naive" : "",
                layout.boundary_length, layout.split_faces, mesh.triangles.size(), layout.merged_reliefs, ms);
    if (rep.holes_filled) std::printf("  closed %zu hole(s) first\n", rep.holes_filled);
    if (rep.pinched_vertices_split) std::printf("  split %zu pinched vertex copies first\n", rep.pinched_vertices_split);
    for (size_t a = 0; a < 6; ++a)
      std::printf("  %s: %d relief(s), %.1f%% of the area\n", names[a], count_axis[a], 100.0 * share(per_axis[a]));
  });
}

}  // namespace prm::cli
