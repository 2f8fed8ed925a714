// prm unpack IN.prm -o OUT.(ply|obj|off|glb) [--json]: the inverse of `prm pack`: decode a stream (spec
// §2) and write the mesh, reporting what the stream spent where.
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "codec_cli_util.h"
#include "commands.h"
#include "gltf_commands.h"
#include "json_report.h"
#include "prm/error.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm_stream_info.h"

namespace prm::cli {

void add_unpack_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("unpack", "Decompress a .prm stream made by `prm pack` (or `prm encode`) into a mesh file");
  struct Options {
    std::string input, output;
    bool json = false, double_positions = false;
  };
  auto opt = std::make_shared<Options>();
  cmd->add_option("input", opt->input, ".prm stream, or a .glb/.gltf asset (its PRM, Draco and meshopt primitives are decoded into a plain .glb/.gltf)")->required();
  cmd->add_option("-o,--output", opt->output, "Output mesh file (PLY, OBJ, OFF, GLB); the format follows the extension")
      ->required();
  cmd->add_flag("--double", opt->double_positions,
                "PLY: write the dequantized positions as double (exact); default float, as glTF and other tools read");
  cmd->add_flag("--json", opt->json, kJsonFlagHelp);
  cmd->callback([opt] {
    if (is_gltf_file_path(opt->input)) return run_gltf_unpack(opt->input, opt->output, opt->json);
    const std::vector<uint8_t> bytes = read_file_bytes(opt->input);
    const auto t0 = std::chrono::steady_clock::now();
    codec::DecodeOptions dopt;
    dopt.positions = codec::PositionOutput::quantized_only;
    const auto dec = codec::decode(bytes.data(), bytes.size(), dopt);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!dec.ok()) throw InputError("'" + opt->input + "' is not a valid PRM stream: " + describe(dec.status));
    const Mesh mesh = pipeline::to_mesh(dec.value);
    WriteOptions wo;
    wo.double_positions = opt->double_positions;  // PLY only
    write_mesh(mesh, opt->output, wo);
    const nlohmann::json split = stream_byte_split(bytes);
    if (opt->json) {
      JsonReport j("unpack");
      j.input(opt->input).output(opt->output).mesh_size(dec.value.num_vertices(), dec.value.num_triangles());
      j.bytes(split.at("total").get<size_t>(), dec.value.num_vertices(), split).seconds(ms / 1000);
      j["bits"] = dec.value.frame.bits;
      j["double_positions"] = opt->double_positions;
      j.print();
    } else {
      std::printf("%s -> %s: %zu vertices, %zu triangles (%d-bit positions), decoded in %.1f ms\n", opt->input.c_str(),
                  opt->output.c_str(), dec.value.num_vertices(), dec.value.num_triangles(), dec.value.frame.bits, ms);
      std::printf("  %s\n", describe_byte_split(split, dec.value.num_vertices()).c_str());
    }
  });
}

}  // namespace prm::cli
