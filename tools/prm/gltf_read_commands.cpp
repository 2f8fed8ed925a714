// prm unpack / info on glTF assets with PRM_mesh_compression (spec/PRM_mesh_compression/README.md): the reading
// side, apart from `prm pack`'s (gltf_commands.cpp) so that it builds without the remesher (the glTF extension's
// fuzzer, gltf_ext/fuzz/gltf_ext_fuzzer.cpp, runs exactly this code).
#include <sys/stat.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "gltf_commands.h"
#include "json_report.h"
#include "prm/error.h"
#include "prm/gltf/decompress.h"
#include "prm/gltf/document.h"
#include "prm/gltf/prm_extension.h"
#include "prm_stream_info.h"

namespace prm::cli {

using nlohmann::json;

size_t file_size(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 ? static_cast<size_t>(st.st_size) : 0;
}

void run_gltf_unpack(const std::string& input, const std::string& output, bool as_json) {
  if (!gltf::is_gltf_path(output))
    throw CLI::ValidationError("unpack", "a glTF input unpacks to a .glb or .gltf output, not '" + output + "'");
  const auto t0 = std::chrono::steady_clock::now();
  gltf::Document doc = gltf::read_document(input);
  const gltf::DecompressReport report = gltf::decompress(doc);
  gltf::write_document(doc, output);
  const double seconds = seconds_since(t0);
  if (as_json) {
    json prims = json::array();
    for (const auto& [key, bytes] : report.compressed_bytes)
      prims.push_back({{"mesh", key.first}, {"primitive", key.second}, {"codec", report.codec.at(key)}, {"bytes", bytes}});
    JsonReport j("unpack");
    j.input(input).output(output).bytes(file_size(input), 0, {{"output", file_size(output)}});
    j.seconds(seconds);
    j["primitives"] = prims;
    j["meshopt_views"] = report.meshopt_views;
    j["file_bytes_in"] = file_size(input);
    j["file_bytes_out"] = file_size(output);
    j.print();
    return;
  }
  std::printf("%s -> %s: %zu PRM, %zu Draco primitive(s) and %zu meshopt bufferView(s) decoded, file %zu -> %zu bytes\n",
              input.c_str(), output.c_str(), report.prm_primitives, report.draco_primitives, report.meshopt_views,
              file_size(input), file_size(output));
}

bool print_gltf_prm_info(const std::string& path, bool as_json) {
  const gltf::Document doc = gltf::read_document(path);
  const json& j = doc.json;
  bool any = false;
  if (j.contains("meshes"))
    for (const json& m : j["meshes"])
      if (m.contains("primitives"))
        for (const json& p : m["primitives"]) any = any || gltf::has_prm_extension(p);
  if (!any) return false;
  const auto list = [&](const char* key) {
    std::string s;
    if (j.contains(key))
      for (const json& e : j[key]) s += (s.empty() ? "" : ", ") + e.get<std::string>();
    return s.empty() ? std::string("none") : s;
  };
  json prims = json::array();
  size_t stream_total = 0;
  for (size_t mi = 0; mi < j["meshes"].size(); ++mi) {
    const json& m = j["meshes"][mi];
    if (!m.contains("primitives")) continue;
    for (size_t pi = 0; pi < m["primitives"].size(); ++pi) {
      const json& p = m["primitives"][pi];
      json entry = {{"mesh", mi}, {"primitive", pi}, {"name", m.value("name", std::string())}};
      entry["attributes"] = json::array();
      if (p.contains("attributes"))
        for (const auto& [k, v] : p["attributes"].items()) entry["attributes"].push_back(k);
      if (gltf::has_prm_extension(p)) {
        const gltf::PrmPrimitive ext = gltf::parse_prm_extension(doc, mi, pi);
        const codec::DecodedMesh decoded = gltf::decode_prm_primitive(doc, mi, pi);  // checks the stream and counts
        const gltf::ByteSpan span = gltf::buffer_view_bytes(doc, ext.buffer_view, "");
        const std::vector<uint8_t> bytes(span.data, span.data + span.size);
        entry["prm"] = {{"bufferView", ext.buffer_view},
                        {"version", std::to_string(bytes[4]) + "." + std::to_string(bytes[5])},
                        {"vertices", decoded.num_vertices()},
                        {"triangles", decoded.num_triangles()},
                        {"bits", decoded.frame.bits},
                        {"bytes", stream_byte_split(bytes)}};
        const json& a = j["accessors"][p["attributes"]["POSITION"].get<size_t>()];
        entry["fallback"] = a.contains("bufferView");
        stream_total += bytes.size();
      }
      prims.push_back(std::move(entry));
    }
  }
  const size_t total = file_size(path);
  if (as_json) {
    JsonReport out("info");
    out.input(path).bytes(total, 0,
                          {{"file", total}, {"prm_streams", stream_total}, {"other", total - std::min(total, stream_total)}});
    out["format"] = "gltf";
    out["extensionsUsed"] = j.value("extensionsUsed", json::array());
    out["extensionsRequired"] = j.value("extensionsRequired", json::array());
    out["primitives"] = prims;
    out.print();
    return true;
  }
  std::printf("%s: glTF asset, %zu meshes, %zu nodes; extensions used: %s; required: %s\n", path.c_str(),
              j["meshes"].size(), j.contains("nodes") ? j["nodes"].size() : size_t{0}, list("extensionsUsed").c_str(),
              list("extensionsRequired").c_str());
  for (const json& e : prims) {
    std::string attrs;
    for (const json& a : e["attributes"]) attrs += (attrs.empty() ? "" : " ") + a.get<std::string>();
    std::printf("  %s%s [%s]: ", gltf::primitive_name(e["mesh"], e["primitive"]).c_str(),
                e["name"].get<std::string>().empty() ? "" : (" (" + e["name"].get<std::string>() + ")").c_str(),
                attrs.c_str());
    if (e.contains("prm")) {
      const json& s = e["prm"];
      std::printf("PRM stream %s in bufferViews[%lld], %zu bytes, %zu vertices, %zu triangles, %d bits%s\n    %s\n",
                  s["version"].get<std::string>().c_str(), s["bufferView"].get<long long>(),
                  s["bytes"]["total"].get<size_t>(), s["vertices"].get<size_t>(), s["triangles"].get<size_t>(),
                  s["bits"].get<int>(), e["fallback"].get<bool>() ? ", with fallback accessors" : "",
                  describe_byte_split(s["bytes"], s["vertices"].get<size_t>()).c_str());
    } else {
      std::printf("uncompressed\n");
    }
  }
  std::printf("  bytes: file %zu, PRM streams %zu, everything else %zu\n", total, stream_total,
              total - std::min(total, stream_total));
  return true;
}

}  // namespace prm::cli
