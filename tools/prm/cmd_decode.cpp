// prm decode IN.prm -o OUT.(ply|obj|off|glb) [--json]: PRM stream -> mesh file (spec/prm-format.md).
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "codec_cli_util.h"
#include "json_report.h"
#include "commands.h"
#include "prm/error.h"
#include "prm/mesh_io.h"

namespace prm::cli {

void add_decode_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("decode", "Decompress a .prm stream into a mesh file (PLY/OBJ/OFF/glTF/GLB)");
  struct Options {
    std::string input, output;
    bool json = false, double_positions = false;
  };
  auto opt = std::make_shared<Options>();
  cmd->add_option("input", opt->input, ".prm stream")->required();
  cmd->add_option("-o,--output", opt->output, "Output mesh file; the format follows the extension")->required();
  cmd->add_flag("--double", opt->double_positions,
                "PLY: write the dequantized positions as double (exact); default float, as glTF and other tools read");
  cmd->add_flag("--json", opt->json, kJsonFlagHelp);
  cmd->callback([opt] {
    const std::vector<uint8_t> bytes = read_file_bytes(opt->input);
    codec::DecodeOptions dopt;
    dopt.positions = codec::PositionOutput::float64;
    const auto t0 = std::chrono::steady_clock::now();
    auto dec = codec::decode(bytes.data(), bytes.size(), dopt);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!dec.ok()) throw InputError("'" + opt->input + "' is not a valid PRM stream: " + describe(dec.status));
    const codec::DecodedMesh& d = dec.value;
    Mesh mesh;
    mesh.positions.resize(d.num_vertices());
    for (size_t v = 0; v < d.num_vertices(); ++v)
      mesh.positions[v] = {d.positions_f64[3 * v], d.positions_f64[3 * v + 1], d.positions_f64[3 * v + 2]};
    mesh.triangles.resize(d.num_triangles());
    for (size_t t = 0; t < d.num_triangles(); ++t)
      mesh.triangles[t] = {d.triangles[3 * t], d.triangles[3 * t + 1], d.triangles[3 * t + 2]};
    WriteOptions wo;
    wo.double_positions = opt->double_positions;  // PLY only
    write_mesh(mesh, opt->output, wo);
    if (opt->json) {
      JsonReport j("decode");
      j.input(opt->input).output(opt->output).mesh_size(d.num_vertices(), d.num_triangles());
      j.bytes(bytes.size(), d.num_vertices()).seconds(ms / 1000);
      j["bits"] = d.frame.bits;
      j["double_positions"] = opt->double_positions;
      j.print();
    } else {
      std::printf("%s -> %s: %zu vertices, %zu triangles (%d-bit positions); decoded in %.1f ms\n",
                  opt->input.c_str(), opt->output.c_str(), d.num_vertices(), d.num_triangles(), d.frame.bits, ms);
    }
  });
}

}  // namespace prm::cli
