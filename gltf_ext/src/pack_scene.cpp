// pack_scene(): which primitives PRM can carry, remeshing each in its own frame, attaching the streams
// (spec/PRM_mesh_compression/README.md, "Overview": POSITION and NORMAL only, TRIANGLES, no morph targets or skin).
#include "prm/gltf/pack_scene.h"

#include <map>
#include <set>
#include <tuple>

#include "prm/error.h"
#include "prm/gltf/accessors.h"
#include "prm/gltf/prm_extension.h"
#include "prm/metro_distance.h"
#include "prm/remesh/remesh.h"

namespace prm::gltf {
namespace {

using nlohmann::json;

// The input bytes of every primitive's geometry, before decompression: an EXT_meshopt bufferView counts for its
// compressed share, a Draco or PRM primitive for its compressed data (filled in later from DecompressReport).
std::map<std::pair<size_t, size_t>, std::pair<size_t, std::string>> input_bytes(const Document& doc) {
  std::map<std::pair<size_t, size_t>, std::pair<size_t, std::string>> out;
  if (!doc.json.contains("meshes")) return out;
  const json& accessors = doc.json.contains("accessors") ? doc.json["accessors"] : json::array();
  const json& views = doc.json.contains("bufferViews") ? doc.json["bufferViews"] : json::array();
  auto bytes_of = [&](const json& index, std::string& codec) -> double {
    if (!index.is_number_integer() || index.get<int64_t>() < 0 || index.get<size_t>() >= accessors.size()) return 0;
    const json& a = accessors[index.get<size_t>()];
    const double raw = a.value("count", 0.0) * component_size(a.value("componentType", 0)) *
                       component_count(a.value("type", std::string()));
    if (!a.contains("bufferView") || !a["bufferView"].is_number_integer() || a["bufferView"].get<int64_t>() < 0 ||
        a["bufferView"].get<size_t>() >= views.size())
      return raw;
    const json& v = views[a["bufferView"].get<size_t>()];
    if (v.contains("extensions") && v["extensions"].contains("EXT_meshopt_compression") && v.value("byteLength", 0.0) > 0) {
      codec = "EXT_meshopt_compression";
      return raw * v["extensions"]["EXT_meshopt_compression"].value("byteLength", 0.0) / v["byteLength"].get<double>();
    }
    return raw;
  };
  for (size_t m = 0; m < doc.json["meshes"].size(); ++m) {
    const json& mesh = doc.json["meshes"][m];
    if (!mesh.contains("primitives")) continue;
    for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const json& prim = mesh["primitives"][p];
      std::string codec;
      double total = 0;
      if (prim.contains("attributes") && prim["attributes"].is_object())
        for (const auto& [k, v] : prim["attributes"].items()) total += bytes_of(v, codec);
      if (prim.contains("indices")) total += bytes_of(prim["indices"], codec);
      out[{m, p}] = {static_cast<size_t>(total + 0.5), codec};
    }
  }
  return out;
}

// Why the primitive cannot be carried, or "".
std::string unsupported_reason(const json& prim, bool skinned) {
  const int mode = prim.value("mode", kModeTriangles);
  if (mode != kModeTriangles)
    return "mode " + std::to_string(mode) + " is not TRIANGLES (PRM streams hold triangle lists)";
  if (prim.contains("targets")) return "it has morph targets (the remeshed vertices would not match them)";
  if (skinned) return "its mesh is skinned (JOINTS/WEIGHTS do not survive remeshing)";
  if (!prim.contains("attributes") || !prim["attributes"].contains("POSITION")) return "it has no POSITION";
  std::string others;
  for (const auto& [k, v] : prim["attributes"].items())
    if (k != "POSITION" && k != "NORMAL") others += (others.empty() ? "" : ", ") + k;
  if (!others.empty())
    return "it has " + others + " (a PRM stream carries positions only; NORMAL is regenerated, other attributes "
           "would lose their place on the remeshed surface)";
  return {};
}

}  // namespace

Mesh primitive_mesh(const Document& doc, size_t mesh, size_t primitive) {
  const json& prim = doc.json["meshes"][mesh]["primitives"][primitive];
  const std::string where = primitive_name(mesh, primitive);
  const AccessorData pos = read_accessor(doc, prim["attributes"]["POSITION"].get<int64_t>(), where + ".attributes.POSITION");
  if (pos.components != 3) throw InputError(doc.path + ": " + where + ".attributes.POSITION is not VEC3");
  std::vector<uint32_t> corners;
  if (prim.contains("indices")) {
    const AccessorData idx = read_accessor(doc, prim["indices"].get<int64_t>(), where + ".indices");
    if (idx.components != 1) throw InputError(doc.path + ": " + where + ".indices is not SCALAR");
    for (double v : idx.values) {
      if (v < 0 || v >= static_cast<double>(pos.count))
        throw InputError(doc.path + ": " + where + ".indices: index " + std::to_string(static_cast<long long>(v)) +
                         " is out of range (" + std::to_string(pos.count) + " vertices)");
      corners.push_back(static_cast<uint32_t>(v));
    }
  } else {
    for (size_t i = 0; i < pos.count; ++i) corners.push_back(static_cast<uint32_t>(i));
  }
  // Weld coincident positions: glTF splits vertices at UV seams and creases; the remesher needs the surface.
  Mesh out;
  std::map<std::tuple<double, double, double>, uint32_t> seen;
  std::vector<uint32_t> remap(pos.count);
  for (size_t i = 0; i < pos.count; ++i) {
    const auto key = std::make_tuple(pos.values[3 * i], pos.values[3 * i + 1], pos.values[3 * i + 2]);
    const auto it = seen.find(key);
    if (it != seen.end()) {
      remap[i] = it->second;
    } else {
      remap[i] = static_cast<uint32_t>(out.positions.size());
      seen.emplace(key, remap[i]);
      out.positions.push_back({pos.values[3 * i], pos.values[3 * i + 1], pos.values[3 * i + 2]});
    }
  }
  for (size_t t = 0; t + 2 < corners.size(); t += 3) {
    const uint32_t a = remap[corners[t]], b = remap[corners[t + 1]], c = remap[corners[t + 2]];
    if (a != b && b != c && a != c) out.triangles.push_back({a, b, c});
  }
  return out;
}

ScenePackReport pack_scene(Document& doc, const ScenePackOptions& options) {
  ScenePackReport report;
  const auto before = input_bytes(doc);
  report.input = decompress(doc);
  std::set<size_t> skinned;
  if (doc.json.contains("nodes"))
    for (const json& n : doc.json["nodes"])
      if (n.contains("skin") && n.contains("mesh") && n["mesh"].is_number_integer() && n["mesh"].get<int64_t>() >= 0) skinned.insert(n["mesh"].get<size_t>());
  if (!doc.json.contains("meshes")) return report;
  for (size_t m = 0; m < doc.json["meshes"].size(); ++m) {
    if (!doc.json["meshes"][m].contains("primitives")) continue;
    for (size_t p = 0; p < doc.json["meshes"][m]["primitives"].size(); ++p) {
      const json prim = doc.json["meshes"][m]["primitives"][p];
      PrimitiveReport r;
      r.mesh = m;
      r.primitive = p;
      r.mesh_name = doc.json["meshes"][m].value("name", std::string());
      const auto b = before.find({m, p});
      if (b != before.end()) {
        r.bytes_in = b->second.first;
        r.input_codec = b->second.second;
      }
      const auto c = report.input.compressed_bytes.find({m, p});
      if (c != report.input.compressed_bytes.end()) {
        r.bytes_in = c->second;
        r.input_codec = report.input.codec[{m, p}];
      }
      r.reason = unsupported_reason(prim, skinned.count(m) > 0);
      if (prim.contains("attributes") && prim["attributes"].contains("POSITION")) {
        const AccessorData pos = read_accessor(doc, prim["attributes"]["POSITION"].get<int64_t>(),
                                               primitive_name(m, p) + ".attributes.POSITION");
        r.vertices_in = pos.count;
        r.triangles_in = prim.contains("indices")
                             ? read_accessor(doc, prim["indices"].get<int64_t>(), primitive_name(m, p) + ".indices").count / 3
                             : pos.count / 3;
      }
      if (r.reason.empty()) {
        const Mesh input = primitive_mesh(doc, m, p);
        try {
          if (input.triangles.empty()) throw InputError("it has no triangle with three distinct vertices");
          const pipeline::PackResult packed = pipeline::pack(input, options.pack);
          codec::DecodeOptions dopt;
          dopt.positions = codec::PositionOutput::float64;
          auto decoded = codec::decode(packed.stream.data(), packed.stream.size(), dopt);
          if (!decoded.ok()) throw InputError("its stream does not decode (a bug): " + decoded.status.message);
          Mesh out;
          for (size_t i = 0; i < decoded.value.num_vertices(); ++i)
            out.positions.push_back({decoded.value.positions_f64[3 * i], decoded.value.positions_f64[3 * i + 1],
                                     decoded.value.positions_f64[3 * i + 2]});
          for (size_t t = 0; t < decoded.value.num_triangles(); ++t)
            out.triangles.push_back({decoded.value.triangles[3 * t], decoded.value.triangles[3 * t + 1],
                                     decoded.value.triangles[3 * t + 2]});
          MetroOptions mo;
          mo.samples = options.pack.metro_samples;
          const DistanceReport d = metro_distance(input, out, mo);
          r.rms = d.rel(d.rms);
          r.max = d.rel(d.max);
          r.diagonal = d.diagonal;
          r.bits = packed.bits;
          r.repaired = packed.repaired;
          r.boundary_loops_in = packed.boundary_loops_in;
          r.boundary_loops_out = packed.boundary_loops_out;
          r.holes_filled = packed.repair.holes_filled;
          r.boundary_fallback = packed.boundary_fallback;
          r.mode = pipeline::pack_mode_name(packed.mode);
          r.mode_reason = packed.mode_reason;
          r.stream_bytes = packed.stream.size();
          r.vertices_out = decoded.value.num_vertices();
          r.triangles_out = decoded.value.num_triangles();
          r.bytes_out = attach_prm_stream(doc, m, p, packed.stream, decoded.value, options.fallback);
          r.compressed = true;
        } catch (const InputError& e) {
          r.reason = std::string("the pipeline cannot remesh it: ") + e.what();
        } catch (const remesh::TargetNotReached& e) {
          r.reason = std::string("no grid size meets the target error: ") + e.what();
        }
      }
      if (!r.compressed) {
        r.vertices_out = r.vertices_in;
        r.triangles_out = r.triangles_in;
        r.bytes_out = r.bytes_in;
        if (!r.input_codec.empty()) {  // it was decoded on input and is now stored as plain accessors
          size_t plain = 0;
          for (const auto& [k, v] : prim["attributes"].items()) {
            const json& a = doc.json["accessors"][v.get<size_t>()];
            plain += a.value("count", size_t{0}) * static_cast<size_t>(component_size(a.value("componentType", 0)) *
                                                                      component_count(a.value("type", std::string())));
          }
          if (prim.contains("indices")) {
            const json& a = doc.json["accessors"][prim["indices"].get<size_t>()];
            plain += a.value("count", size_t{0}) * static_cast<size_t>(component_size(a.value("componentType", 0)));
          }
          r.bytes_out = plain;
          r.reason += " (stored uncompressed: its " + r.input_codec + " data was decoded)";
        }
      }
      report.primitives.push_back(std::move(r));
    }
  }
  return report;
}

Document document_from_mesh(const Mesh& mesh, const std::string& name) {
  Document doc;
  doc.path = name;
  doc.json = {{"asset", {{"version", "2.0"}, {"generator", "prm"}}},
              {"scene", 0},
              {"scenes", json::array({{{"nodes", {0}}}})},
              {"nodes", json::array({{{"mesh", 0}}})}};
  std::vector<double> positions, indices;
  for (const Vec3& p : mesh.positions)
    for (int k = 0; k < 3; ++k) positions.push_back(p[static_cast<size_t>(k)]);
  for (const Tri& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) indices.push_back(t[static_cast<size_t>(k)]);
  const int pos = add_accessor(doc, positions, kFloat, "VEC3", kArrayBuffer, true);
  const int idx = add_accessor(doc, indices, kUnsignedInt, "SCALAR", kElementArrayBuffer, false);
  doc.json["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}})}}});
  return doc;
}

}  // namespace prm::gltf
