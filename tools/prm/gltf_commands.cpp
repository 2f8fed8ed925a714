// prm pack / unpack / info on glTF assets with PRM_mesh_compression (spec/PRM_mesh_compression/README.md).
#include "gltf_commands.h"

#include <sys/stat.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <chrono>
#include <nlohmann/json.hpp>

#include "json_report.h"

#include "prm/error.h"
#include "prm/gltf/decompress.h"
#include "prm/gltf/document.h"
#include "prm/gltf/pack_scene.h"
#include "prm/gltf/prm_extension.h"
#include "prm/mesh_io.h"
#include "codec_cli_util.h"
#include "prm_stream_info.h"

namespace prm::cli {
namespace {

using nlohmann::json;

std::string lower_extension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return {};
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string label(const gltf::PrimitiveReport& r) {
  std::string s = gltf::primitive_name(r.mesh, r.primitive);
  if (!r.mesh_name.empty()) s += " (" + r.mesh_name + ")";
  return s;
}

}  // namespace

bool is_gltf_file_path(const std::string& path) { return gltf::is_gltf_path(path); }

void check_pack_output(const std::string& output, bool fallback) {
  const std::string ext = lower_extension(output);
  if (ext == "ply" || ext == "obj" || ext == "off" || ext == "stl")
    throw CLI::ValidationError("pack", "the output '" + output + "' is named like a mesh file, but pack writes a .prm "
                               "stream or a .glb/.gltf asset (for the remeshed mesh use --keep-prm or `prm remesh`)");
  if (fallback && !gltf::is_gltf_path(output))
    throw CLI::ValidationError("pack", "--fallback applies to a .glb/.gltf output only");
}

void run_gltf_pack(const std::string& input, const std::string& output, const pipeline::PackOptions& options,
                   bool fallback, bool as_json) {
  gltf::Document doc;
  if (gltf::is_gltf_path(input)) {
    doc = gltf::read_document(input);
  } else {
    const size_t slash = input.find_last_of('/');
    doc = gltf::document_from_mesh(read_mesh(input), slash == std::string::npos ? input : input.substr(slash + 1));
  }
  gltf::ScenePackOptions so;
  so.pack = options;
  so.fallback = fallback;
  const gltf::ScenePackReport report = gltf::pack_scene(doc, so);
  gltf::write_document(doc, output);

  size_t bytes_in = 0, bytes_out = 0, compressed = 0;
  for (const auto& r : report.primitives) {
    bytes_in += r.bytes_in;
    bytes_out += r.bytes_out;
    compressed += r.compressed;
  }
  const size_t file_in = file_size(input), file_out = file_size(output);
  if (as_json) {
    json prims = json::array();
    for (const auto& r : report.primitives) {
      json p = {{"mesh", r.mesh},
                {"primitive", r.primitive},
                {"name", r.mesh_name},
                {"compressed", r.compressed},
                {"input_codec", r.input_codec},
                {"vertices_in", r.vertices_in},
                {"vertices_out", r.vertices_out},
                {"triangles_in", r.triangles_in},
                {"triangles_out", r.triangles_out},
                {"bytes_in", r.bytes_in},
                {"bytes_out", r.bytes_out}};
      if (r.compressed) {
        p["stream_bytes"] = r.stream_bytes;
        p["bits"] = r.bits;
        p["distance"] = {{"rms_rel", r.rms}, {"max_rel", r.max}, {"rms", r.rms * r.diagonal},
                         {"max", r.max * r.diagonal}, {"diagonal", r.diagonal}};  // docs/cli-json.md "distance"
        p["repaired"] = r.repaired;
        p["boundary_loops_in"] = r.boundary_loops_in;
        p["boundary_loops_out"] = r.boundary_loops_out;
        p["holes_closed"] = r.holes_filled;
        p["boundary_fallback"] = r.boundary_fallback;
        p["mode"] = r.mode;
        p["mode_reason"] = r.mode_reason;
      } else {
        p["reason"] = r.reason;
      }
      prims.push_back(std::move(p));
    }
    JsonReport j("pack");  // the shared schema (docs/cli-json.md): the asset's bytes; per primitive below
    j.input(input).output(output).bytes(file_out, 0, {{"input", file_in}});
    j["extension"] = gltf::kExtensionName;
    j["fallback"] = fallback;
    j["decoded_input"] = {{"draco_primitives", report.input.draco_primitives},
                          {"meshopt_views", report.input.meshopt_views},
                          {"prm_primitives", report.input.prm_primitives}};
    j["primitives"] = prims;
    j["totals"] = {{"primitives", report.primitives.size()},
                   {"compressed", compressed},
                   {"kept", report.primitives.size() - compressed},
                   {"bytes_in", bytes_in},
                   {"bytes_out", bytes_out},
                   {"file_bytes_in", file_in},
                   {"file_bytes_out", file_out}};
    j.print();
    return;
  }
  std::printf("%s -> %s: %zu of %zu primitives compressed with %s (%s), file %zu -> %zu bytes\n", input.c_str(),
              output.c_str(), compressed, report.primitives.size(), gltf::kExtensionName,
              fallback ? "with uncompressed fallback" : "required", file_in, file_out);
  if (report.input.draco_primitives || report.input.meshopt_views || report.input.prm_primitives)
    std::printf("  decoded on input: %zu Draco primitive(s), %zu meshopt bufferView(s), %zu PRM primitive(s)\n",
                report.input.draco_primitives, report.input.meshopt_views, report.input.prm_primitives);
  for (const auto& r : report.primitives) {
    if (r.compressed) {
      std::printf("  %s: %zu -> %zu vertices, %zu -> %zu triangles, %zu -> %zu bytes%s%s, RMS %.3e max %.3e of the "
                  "diagonal, %d bits%s, boundary loops %zu in, %zu out%s, mode %s (%s)\n",
                  label(r).c_str(), r.vertices_in, r.vertices_out, r.triangles_in, r.triangles_out, r.bytes_in,
                  r.bytes_out, r.input_codec.empty() ? "" : " (input ", r.input_codec.empty() ? "" : (r.input_codec + ")").c_str(),
                  r.rms, r.max, r.bits, r.repaired ? ", repaired first" : "", r.boundary_loops_in,
                  r.boundary_loops_out,
                  r.holes_filled ? (" (" + std::to_string(r.holes_filled) +
                                    (r.boundary_fallback ? " filled: the remesher could not keep them)" : " filled: --fill-holes)"))
                                       .c_str()
                                 : "",
                  r.mode.c_str(), r.mode_reason.c_str());
    } else {
      std::printf("  %s: kept as it was (%zu vertices, %zu bytes): %s\n", label(r).c_str(), r.vertices_in, r.bytes_out,
                  r.reason.c_str());
    }
  }
  std::printf("  total: primitives' geometry %zu -> %zu bytes\n", bytes_in, bytes_out);
}

void wrap_prm_stream(const std::string& input, const std::string& output, bool fallback, bool as_json) {
  const std::vector<uint8_t> stream = read_file_bytes(input);
  codec::DecodeOptions dopt;
  dopt.positions = codec::PositionOutput::float64;
  const auto decoded = codec::decode(stream.data(), stream.size(), dopt);
  if (!decoded.ok()) throw InputError("'" + input + "' is not a valid PRM stream: " + describe(decoded.status));
  gltf::Document doc;
  doc.path = output;
  doc.json = {{"asset", {{"version", "2.0"}, {"generator", "prm"}}},
              {"scene", 0},
              {"scenes", json::array({{{"nodes", {0}}}})},
              {"nodes", json::array({{{"mesh", 0}}})},
              {"meshes", json::array({{{"primitives", json::array({{{"attributes", json::object()}}})}}})}};
  const size_t bytes_out = gltf::attach_prm_stream(doc, 0, 0, stream, decoded.value, fallback);
  gltf::write_document(doc, output);
  if (as_json) {
    JsonReport j("pack");
    j.input(input).output(output).mesh_size(decoded.value.num_vertices(), decoded.value.num_triangles());
    j.bytes(file_size(output), 0, {{"stream", stream.size()}, {"primitive", bytes_out}});
    j["extension"] = gltf::kExtensionName;
    j["fallback"] = fallback;
    j["stream_bytes"] = stream.size();
    j["bytes_out"] = bytes_out;
    j["file_bytes_out"] = file_size(output);
    j.print();
  } else {
    std::printf("%s -> %s: the stream (%zu bytes, %zu vertices, %zu triangles) as it is in one %s primitive%s, file "
                "%zu bytes\n",
                input.c_str(), output.c_str(), stream.size(), decoded.value.num_vertices(),
                decoded.value.num_triangles(), gltf::kExtensionName, fallback ? " with fallback" : "", file_size(output));
  }
}

void note_gltf_to_prm(const std::string& input) {
  if (!gltf::is_gltf_path(input)) return;
  std::fprintf(stderr,
               "note: '%s' is a glTF asset: every triangle primitive is placed by its nodes and merged into one mesh; "
               "a .prm stream holds no normals, UVs, colours, materials or scene (pack to a .glb/.gltf to keep them)\n",
               input.c_str());
}

}  // namespace prm::cli
