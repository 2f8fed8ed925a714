// prm repair IN -o OUT [--json]: removes faces with a repeated vertex and duplicate faces, splits pinched
// vertices, flips away zero-area slivers, closes every hole (the triangulation that folds least, or a fan around its
// centroid: paper §4, the bunny). Refuses edges with three or more faces and inconsistent orientation
// (common/include/prm/mesh_repair.h).
#include <cstdio>
#include <nlohmann/json.hpp>

#include <chrono>

#include "commands.h"
#include "json_report.h"
#include "prm/error.h"
#include "prm/mesh_io.h"
#include "prm/mesh_repair.h"
#include "prm/mesh_validate.h"

namespace prm::cli {

void add_repair_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "repair",
      "Make a closed manifold: drop degenerate and duplicate faces, split pinched vertices, "
      "close every hole by the triangulation of its loop that folds least (a fan around its centroid for a loop over "
      "400 vertices); refuses edges with 3+ faces and inconsistent orientation");
  struct Options {
    std::string input, output;
    bool json = false;
  };
  auto opt = std::make_shared<Options>();
  cmd->add_option("input", opt->input, "Mesh file")->required();
  cmd->add_option("-o,--output", opt->output, "Repaired mesh file (.ply, .obj, .off, .glb)")->required();
  cmd->add_flag("--json", opt->json, kJsonFlagHelp);
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    ReadReport rr;
    const Mesh in = read_mesh(opt->input, {}, &rr);
    RepairReport rep;
    Mesh out;
    try {
      out = repair_mesh(in, &rep);
    } catch (const InputError& e) {
      throw InputError(opt->input + ": " + e.what());
    }
    write_mesh(out, opt->output);
    const MeshReport after = validate_mesh(out);
    if (opt->json) {
      JsonReport report("repair");
      report.input(opt->input).output(opt->output).mesh_size(after.vertices, after.faces).seconds(seconds_since(t0));
      report.json().update(nlohmann::json{
          {"unreferenced_dropped_on_read", rr.unreferenced_dropped},
          {"repeated_index_removed", rep.repeated_index_removed},
          {"duplicate_removed", rep.duplicate_removed},
          {"pinched_vertices_split", rep.pinched_vertices_split},
          {"zero_area_flipped", rep.zero_area_flipped},
          {"holes_filled", rep.holes_filled},
          {"fill_triangles", rep.fill_triangles},
          {"notes", rep.notes},
          {"result",
           {{"closed", after.closed()},
            {"manifold", after.manifold()},
            {"oriented", after.oriented()},
            {"genus", after.genus_sum() < 0 ? nlohmann::json(nullptr) : nlohmann::json(after.genus_sum())}}}});
      report.print();
      return;
    }
    std::printf("%s -> %s\n", opt->input.c_str(), opt->output.c_str());
    if (rr.unreferenced_dropped)
      std::printf("  %zu unreferenced vertices dropped on reading\n", rr.unreferenced_dropped);
    std::printf(
        "  removed %zu faces with a repeated vertex and %zu duplicate faces; flipped away %zu zero-area "
        "faces\n",
        rep.repeated_index_removed, rep.duplicate_removed, rep.zero_area_flipped);
    if (rep.pinched_vertices_split) std::printf("  split %zu pinched vertices\n", rep.pinched_vertices_split);
    std::printf("  closed %zu hole(s) with %zu triangles\n", rep.holes_filled, rep.fill_triangles);
    for (const std::string& n : rep.notes) std::printf("  note: %s\n", n.c_str());
    std::printf("  result: %zu vertices, %zu faces, %s, %s", after.vertices, after.faces,
                after.closed() ? "closed" : "open", after.manifold() ? "manifold" : "not manifold");
    if (after.genus_sum() >= 0) std::printf(", genus %d", after.genus_sum());
    std::printf("\n");
  });
}

}  // namespace prm::cli
