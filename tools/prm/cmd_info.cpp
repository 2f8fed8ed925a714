// prm info FILE [--json]: what a mesh file holds and what is wrong with it; on a .prm stream, its header and
// the bytes of every section (prm_stream_info.cpp).
#include <cstdio>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "gltf_commands.h"
#include "json_report.h"
#include "prm/mesh_io.h"
#include "prm/mesh_validate.h"
#include "prm_stream_info.h"

namespace prm::cli {

void add_info_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("info", "Validate a mesh file (or a .prm stream) and report on it");
  cmd->footer(
      "A .prm stream is decoded in full: one that does not decode (framing, CRC or any section) is invalid input,\n"
      "exit 2, with the error's name, byte offset and spec section (--json: \"error\"), after what could be read.");
  struct Options {
    std::string input;
    bool json = false;
    double weld = 0;
    bool weld_all = false, no_weld = false;
  };
  auto opt = std::make_shared<Options>();
  cmd->add_option("input", opt->input, "Mesh file (OBJ, PLY, OFF, STL, glTF, GLB) or .prm stream")
      ->required();
  cmd->add_flag("--json", opt->json, kJsonFlagHelp);
  cmd->add_option("--weld-tolerance", opt->weld,
                  "Weld vertices closer than this (model units; default: exact)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--weld", opt->weld_all,
                "Weld coincident vertices in every format (default: STL and glTF only)");
  cmd->add_flag("--no-weld", opt->no_weld, "Never weld");
  cmd->callback([opt] {
    if (is_gltf_file_path(opt->input) && print_gltf_prm_info(opt->input, opt->json)) return;
    if (is_prm_stream_path(opt->input)) {
      print_prm_stream_info(opt->input, opt->json);
      return;
    }
    ReadOptions ro;
    ro.weld_tolerance = opt->weld;
    if (opt->weld_all || opt->weld > 0) ro.weld = ReadOptions::Weld::Always;
    if (opt->no_weld) ro.weld = ReadOptions::Weld::Never;
    ReadReport rr;
    const Mesh mesh = read_mesh(opt->input, ro, &rr);
    const MeshReport r = validate_mesh(mesh);
    if (opt->json) {
      nlohmann::json comps = nlohmann::json::array();
      for (const ComponentReport& c : r.per_component)
        comps.push_back({{"vertices", c.vertices},
                         {"triangles", c.faces},
                         {"edges", c.edges},
                         {"boundary_loops", c.boundary_loops},
                         {"euler", c.euler},
                         {"manifold", c.manifold},
                         {"genus", c.genus < 0 ? nlohmann::json(nullptr) : nlohmann::json(c.genus)}});
      JsonReport report("info");
      report.input(opt->input).mesh_size(r.vertices, r.faces);
      nlohmann::json& j = report.json();
      j.update(nlohmann::json{
          {"format", format_name(rr.format)},
          {"read",
           {{"file_vertices", rr.file_vertices},
            {"file_faces", rr.file_faces},
            {"polygons_triangulated", rr.polygons_triangulated},
            {"strip_triangles", rr.strip_triangles},
            {"vertices_welded", rr.vertices_welded},
            {"unreferenced_dropped", rr.unreferenced_dropped},
            {"degenerate_dropped", rr.degenerate_dropped},
            {"notes", rr.notes}}},
          {"edges", r.edges},
          {"components", r.components},
          {"boundary_edges", r.boundary_edges},
          {"boundary_loops", r.boundary_loops},
          {"non_manifold_edges", r.non_manifold_edges},
          {"non_manifold_vertices", r.non_manifold_vertices},
          {"repeated_index_faces", r.repeated_index_faces},
          {"zero_area_faces", r.zero_area_faces},
          {"duplicate_faces", r.duplicate_faces},
          {"inconsistent_edges", r.inconsistent_edges},
          {"oriented", r.oriented()},
          {"manifold", r.manifold()},
          {"closed", r.closed()},
          {"euler", r.euler},
          {"genus", r.genus_sum() < 0 ? nlohmann::json(nullptr) : nlohmann::json(r.genus_sum())},
          {"per_component", comps},
          {"bbox", {{"min", r.bbox_min}, {"max", r.bbox_max}}},
          {"diagonal", r.diagonal},
          {"problems", r.examples}});
      report.print();
      return;
    }
    std::printf("%s (%s)\n", opt->input.c_str(), format_name(rr.format));
    std::printf("  file: %zu vertices, %zu faces", rr.file_vertices, rr.file_faces);
    if (rr.polygons_triangulated) std::printf(", %zu polygons triangulated", rr.polygons_triangulated);
    if (rr.strip_triangles) std::printf(", %zu triangles from strips", rr.strip_triangles);
    if (rr.vertices_welded) std::printf(", %zu vertices welded", rr.vertices_welded);
    if (rr.unreferenced_dropped) std::printf(", %zu unreferenced vertices dropped", rr.unreferenced_dropped);
    if (rr.degenerate_dropped)
      std::printf(", %zu faces with a repeated vertex dropped", rr.degenerate_dropped);
    std::printf("\n");
    for (const std::string& n : rr.notes) std::printf("  note: %s\n", n.c_str());
    std::printf("  mesh: %zu vertices, %zu faces, %zu edges, %zu component(s), Euler characteristic %ld\n",
                r.vertices, r.faces, r.edges, r.components, r.euler);
    std::printf("  %s, %s, %s", r.closed() ? "closed" : "open", r.manifold() ? "manifold" : "NOT manifold",
                r.oriented() ? "consistently oriented" : "NOT consistently oriented");
    if (r.genus_sum() >= 0) std::printf(", genus %d", r.genus_sum());
    std::printf("\n");
    std::printf("  boundary: %zu edges in %zu loop(s); non-manifold: %zu edges, %zu vertices\n",
                r.boundary_edges, r.boundary_loops, r.non_manifold_edges, r.non_manifold_vertices);
    std::printf("  faces: %zu with a repeated vertex, %zu with zero area, %zu duplicates\n",
                r.repeated_index_faces, r.zero_area_faces, r.duplicate_faces);
    if (r.components > 1) {
      std::printf("  components (largest first):\n");
      for (size_t c = 0; c < r.per_component.size() && c < 10; ++c) {
        const ComponentReport& k = r.per_component[c];
        std::printf("    %zu: %zu vertices, %zu faces, %zu boundary loop(s), Euler %ld", c, k.vertices,
                    k.faces, k.boundary_loops, k.euler);
        if (k.genus >= 0) std::printf(", genus %d", k.genus);
        std::printf("\n");
      }
      if (r.per_component.size() > 10) std::printf("    ... %zu more\n", r.per_component.size() - 10);
    }
    std::printf("  bounding box: (%g, %g, %g) - (%g, %g, %g), diagonal %g\n", r.bbox_min[0], r.bbox_min[1],
                r.bbox_min[2], r.bbox_max[0], r.bbox_max[1], r.bbox_max[2], r.diagonal);
    for (const std::string& e : r.examples) std::printf("  problem: %s\n", e.c_str());
  });
}

}  // namespace prm::cli
