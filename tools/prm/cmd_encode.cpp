// prm encode IN -o OUT.prm [--bits B] [--json]: any mesh file -> PRM stream (general path: Edgebreaker
// connectivity, parallelogram-predicted positions; spec/prm-format.md §6, §10).
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "codec_cli_util.h"
#include "json_report.h"
#include "commands.h"
#include "prm/error.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/codec_bridge.h"

namespace prm::cli {
namespace {

// §9.4 / §9.7 How the heights were coded, in words.
std::string height_coding(const codec::EncodeReport& rep) {
  if (rep.height_depth == 7)
    return "linear prediction in " + std::to_string(rep.predicted_patches) + " patches, difference depth " +
           std::to_string(rep.overlap_depth) + " in the others";
  return "difference patches, depth " + std::to_string(rep.height_depth);
}

}  // namespace

void add_encode_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("encode", "Compress a triangle mesh (OBJ/PLY/OFF/STL/glTF) into a .prm stream");
  cmd->footer(
      "A stream holds triangles and the vertices they use (spec §6.1): faces with a repeated vertex and vertices no\n"
      "face uses are dropped, and the report counts them (--json: \"dropped\"), with the vertices welded (STL, glTF)\n"
      "and the polygons triangulated on reading. A mesh that is not manifold is refused (exit 2).");
  struct Options {
    std::string input, output;
    int bits = 12;
    std::string max_version = "1.5";
    bool json = false;
  };
  auto opt = std::make_shared<Options>();
  cmd->add_option("input", opt->input, "Mesh file to compress")->required();
  cmd->add_option("-o,--output", opt->output, "Output .prm file")->required();
  cmd->add_option("--bits", opt->bits, "Quantization bits per coordinate (8..20)")->check(CLI::Range(8, 20));
  cmd->add_option("--max-version", opt->max_version,
                  "Newest format the stream may need, for older decoders: 1.5 (default), 1.4 (one grid size for every "
                  "patch, spec §8.4.2), 1.3 (no patch contexts either, "
                  "§8.4.1), 1.2 (no CLERS seam context either, §6.5.2; a general-path stream is then 1.0)")
      ->check(CLI::IsMember({"1.2", "1.3", "1.4", "1.5"}));
  cmd->add_flag("--json", opt->json, kJsonFlagHelp);
  cmd->callback([opt] {
    ReadReport rr;
    const Mesh mesh = read_mesh(opt->input, {}, &rr);
    codec::EncodeReport rep;
    bool was_prm = false;
    const auto t0 = std::chrono::steady_clock::now();
    // A PRM file (`prm remesh` output: prm-frame comment, lattice labels) is encoded in its own frame, so that its
    // grid vertices are lattice points; any other mesh takes the general path at --bits.
    const int max_minor = opt->max_version[2] - '0';
    const auto enc = pipeline::encode_any_mesh(mesh, opt->bits, &rep, &was_prm, max_minor);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!enc.ok()) throw InputError("'" + opt->input + "' cannot be encoded: " + describe(enc.status));
    write_file_bytes(opt->output, enc.value);
    const auto header = codec::inspect(enc.value.data(), enc.value.size());
    const int bits = header.ok() ? header.value.frame.bits : opt->bits;  // a PRM keeps its own frame
    const double v = rep.vertices ? rep.vertices : 1;
    // What reading and encoding left out of the stream (nothing is dropped silently).
    const size_t degenerate = rr.degenerate_dropped, unreferenced = rr.unreferenced_dropped + rep.unreferenced_dropped;
    if (opt->json) {
      JsonReport j("encode");
      j.input(opt->input).output(opt->output).mesh_size(rep.vertices, rep.triangles);
      j.bytes(rep.total_bytes, rep.vertices,
              {{"header", rep.header_bytes},
               {"connectivity", rep.connectivity_bytes},
               {"positions", rep.position_bytes},
               {"irregular_triangles", rep.irregular_bytes},
               {"patches", rep.patch_bytes},
               {"framing", rep.framing_bytes}});
      j.seconds(ms / 1000);
      j["bits"] = bits;
      j["piecewise_regular"] = was_prm;
      j["components"] = rep.components;
      j["holes"] = rep.holes;
      j["genus_total"] = rep.handles;
      j["unreferenced_dropped"] = unreferenced;
      j["dropped"] = {{"faces_with_repeated_vertex", degenerate}, {"unreferenced_vertices", unreferenced}};
      j["read"] = {{"file_vertices", rr.file_vertices},
                   {"file_faces", rr.file_faces},
                   {"polygons_triangulated", rr.polygons_triangulated},
                   {"strip_triangles", rr.strip_triangles},
                   {"vertices_welded", rr.vertices_welded}};
      if (was_prm)
        j["prm"] = {{"regular_triangles", rep.regular_triangles},
                    {"regular_patches", rep.regular_patches},
                    {"patch_vertices", rep.patch_vertices},
                    {"height_depth", rep.height_depth},
                    {"height_coding", rep.height_depth == 7 ? "linear prediction" : "difference patches"},
                    {"overlap_depth", rep.overlap_depth},
                    {"predicted_patches", rep.predicted_patches}};
      j.print();
    } else {
      std::printf("%s -> %s: %zu bytes (%.3f bits/vertex)\n", opt->input.c_str(), opt->output.c_str(),
                  rep.total_bytes, 8.0 * rep.total_bytes / v);
      std::printf("  %u vertices, %u triangles, %u component(s), %u hole(s), total genus %u", rep.vertices,
                  rep.triangles, rep.components, rep.holes, rep.handles);
      std::printf("\n  dropped: faces with a repeated vertex %zu, unreferenced vertices %zu", degenerate, unreferenced);
      if (rr.vertices_welded) std::printf("; %zu vertices welded", rr.vertices_welded);
      if (rr.polygons_triangulated) std::printf("; %zu polygons triangulated", rr.polygons_triangulated);
      if (was_prm)
        std::printf("\n  piecewise regular: %u of %u triangles regular in %u patches (heights: %s); irregular "
                    "triangles %zu B (%.3f bpv), patches %zu B (%.3f bpv)",
                    rep.regular_triangles, rep.triangles, rep.regular_patches, height_coding(rep).c_str(),
                    rep.irregular_bytes, 8.0 * rep.irregular_bytes / v, rep.patch_bytes, 8.0 * rep.patch_bytes / v);
      std::printf("\n  connectivity %zu B (%.3f bpv), positions %zu B (%.3f bpv, %d bits), header %zu B, "
                  "framing %zu B; %.1f ms\n",
                  rep.connectivity_bytes, 8.0 * rep.connectivity_bytes / v, rep.position_bytes,
                  8.0 * rep.position_bytes / v, bits, rep.header_bytes, rep.framing_bytes, ms);
    }
  });
}

}  // namespace prm::cli
