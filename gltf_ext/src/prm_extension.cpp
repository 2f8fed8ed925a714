// PRM_mesh_compression: reading, checking, decoding and writing a primitive's extension object
// (spec/PRM_mesh_compression/README.md; the stream itself: spec/prm-format.md).
#include "prm/gltf/prm_extension.h"

#include <cmath>

#include "prm/error.h"
#include "prm/gltf/accessors.h"

namespace prm::gltf {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const Document& doc, const std::string& what) { throw InputError(doc.path + ": " + what); }

const json& primitive_json(const Document& doc, size_t mesh, size_t primitive) {
  return doc.json.at("meshes").at(mesh).at("primitives").at(primitive);
}

json& primitive_json(Document& doc, size_t mesh, size_t primitive) {
  return doc.json.at("meshes").at(mesh).at("primitives").at(primitive);
}

}  // namespace

bool has_prm_extension(const json& primitive) {
  const auto e = primitive.find("extensions");
  return e != primitive.end() && e->is_object() && e->contains(kExtensionName);
}

PrmPrimitive parse_prm_extension(const Document& doc, size_t mesh, size_t primitive) {
  const json& prim = primitive_json(doc, mesh, primitive);
  const std::string where = primitive_name(mesh, primitive) + ".extensions." + kExtensionName;
  const json& ext = prim["extensions"][kExtensionName];
  if (!ext.is_object()) fail(doc, where + " is not an object");
  for (const auto& [key, value] : ext.items())
    if (key != "bufferView" && key != "attributes" && key != "version" && key != "extensions" && key != "extras")
      fail(doc, where + " has an unknown property '" + key + "'");
  PrmPrimitive out;
  // version first: a loader must not interpret the rest of an object of a version it does not know.
  if (!ext.contains("version")) fail(doc, where + ".version is missing");
  if (!ext["version"].is_number_integer()) fail(doc, where + ".version must be an integer");
  const int64_t version = ext["version"].get<int64_t>();
  if (version != kExtensionVersion)
    fail(doc, where + ".version " + std::to_string(version) + " is not supported (this decoder implements version " +
                  std::to_string(kExtensionVersion) + ")");
  out.version = static_cast<int>(version);
  if (!ext.contains("bufferView")) fail(doc, where + ".bufferView is missing");
  if (!ext["bufferView"].is_number_integer() || ext["bufferView"].get<int64_t>() < 0)
    fail(doc, where + ".bufferView must be a non-negative integer");
  out.buffer_view = ext["bufferView"].get<int64_t>();
  buffer_view_bytes(doc, out.buffer_view, where + ".bufferView");
  if (!ext.contains("attributes")) fail(doc, where + ".attributes is missing");
  if (!ext["attributes"].is_object()) fail(doc, where + ".attributes must be an object");
  for (const auto& [key, value] : ext["attributes"].items())
    if (key != "POSITION")
      fail(doc, where + ".attributes." + key + ": version 1 streams carry POSITION only");
  if (!ext["attributes"].contains("POSITION")) fail(doc, where + ".attributes.POSITION is missing");
  if (!ext["attributes"]["POSITION"].is_number_integer() || ext["attributes"]["POSITION"].get<int64_t>() != 0)
    fail(doc, where + ".attributes.POSITION must be 0 (the stream's positions)");
  // The primitive around it ("Constraints on the primitive").
  const std::string pw = primitive_name(mesh, primitive);
  if (prim.value("mode", kModeTriangles) != kModeTriangles) fail(doc, pw + ".mode must be 4 (TRIANGLES) with " + kExtensionName);
  if (!prim.contains("indices")) fail(doc, pw + ".indices is missing (required with " + std::string(kExtensionName) + ")");
  if (prim.contains("targets")) fail(doc, pw + ".targets: morph targets cannot go with " + std::string(kExtensionName));
  if (!prim.contains("attributes") || !prim["attributes"].contains("POSITION"))
    fail(doc, pw + ".attributes.POSITION is missing");
  for (const auto& [key, value] : prim["attributes"].items())
    if (key != "POSITION" && key != "NORMAL")
      fail(doc, pw + ".attributes." + key + ": only POSITION and NORMAL may go with " + kExtensionName);
  return out;
}

codec::DecodedMesh decode_prm_primitive(const Document& doc, size_t mesh, size_t primitive) {
  const PrmPrimitive ext = parse_prm_extension(doc, mesh, primitive);
  const std::string where = primitive_name(mesh, primitive) + ".extensions." + kExtensionName;
  const ByteSpan bytes = buffer_view_bytes(doc, ext.buffer_view, where + ".bufferView");
  codec::DecodeOptions options;
  options.positions = codec::PositionOutput::float64;
  auto result = codec::decode(bytes.data, bytes.size, options);
  if (!result.ok()) {
    const codec::Status& s = result.status;
    fail(doc, where + ": the PRM stream in bufferViews[" + std::to_string(ext.buffer_view) + "] (" +
                  std::to_string(bytes.size) + " bytes) does not decode: " + codec::error_name(s.error) + ": " +
                  s.message + " (byte " + std::to_string(s.byte_offset) +
                  (*s.spec_section ? std::string(", spec §") + s.spec_section : std::string()) + ")");
  }
  if (bytes.size < 5 || bytes.data[4] != ext.version)
    fail(doc, where + ": the stream's Version_Major differs from version " + std::to_string(ext.version));
  // The primitive's accessors must agree with the decoded counts ("Loader behaviour" item 4).
  const json& prim = primitive_json(doc, mesh, primitive);
  const json& accessors = doc.json.contains("accessors") ? doc.json["accessors"] : json::array();
  auto count_of = [&](const json& index, const std::string& what) -> uint64_t {
    if (!index.is_number_integer() || index.get<int64_t>() < 0 ||
        static_cast<uint64_t>(index.get<int64_t>()) >= accessors.size())
      fail(doc, primitive_name(mesh, primitive) + "." + what + " is not an accessor");
    return accessors[index.get<size_t>()].value("count", uint64_t{0});
  };
  const uint64_t nv = result.value.num_vertices(), nt = result.value.num_triangles();
  for (const auto& [key, value] : prim["attributes"].items())
    if (count_of(value, "attributes." + key) != nv)
      fail(doc, primitive_name(mesh, primitive) + ".attributes." + key + ": accessor count " +
                    std::to_string(count_of(value, "attributes." + key)) + " differs from the " + std::to_string(nv) +
                    " vertices the stream decodes to");
  if (count_of(prim["indices"], "indices") != 3 * nt)
    fail(doc, primitive_name(mesh, primitive) + ".indices: accessor count " +
                  std::to_string(count_of(prim["indices"], "indices")) + " differs from 3 x " + std::to_string(nt) +
                  " decoded triangles");
  return std::move(result.value);
}

std::vector<double> regenerate_normals(const std::vector<double>& p, const std::vector<uint32_t>& triangles) {
  std::vector<double> s(p.size(), 0.0);
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const size_t a = 3 * size_t{triangles[t]}, b = 3 * size_t{triangles[t + 1]}, c = 3 * size_t{triangles[t + 2]};
    const double u[3] = {p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]};
    const double v[3] = {p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (size_t corner : {a, b, c})
      for (size_t k = 0; k < 3; ++k) s[corner + k] += n[k];
  }
  for (size_t i = 0; i < s.size(); i += 3) {
    const double len = std::sqrt(s[i] * s[i] + s[i + 1] * s[i + 1] + s[i + 2] * s[i + 2]);
    if (len > 0) {
      for (size_t k = 0; k < 3; ++k) s[i + k] /= len;
    } else {
      s[i] = 0;
      s[i + 1] = 0;
      s[i + 2] = 1;
    }
  }
  return s;
}

namespace {

// Sets the primitive's POSITION / NORMAL / indices to new accessors for `decoded`, holding data when `with_data`.
void set_decoded_accessors(Document& doc, json& prim, const codec::DecodedMesh& decoded, bool with_data) {
  const std::vector<double>& positions = decoded.positions_f64;
  const bool normals = prim.contains("attributes") && prim["attributes"].contains("NORMAL");
  const int index_type = decoded.num_vertices() <= 65535 ? kUnsignedShort : kUnsignedInt;
  const std::vector<double> indices(decoded.triangles.begin(), decoded.triangles.end());
  int pos, nrm = -1, idx;
  if (with_data) {
    pos = add_accessor(doc, positions, kFloat, "VEC3", kArrayBuffer, true);
    if (normals) nrm = add_accessor(doc, regenerate_normals(positions, decoded.triangles), kFloat, "VEC3", kArrayBuffer, false);
    idx = add_accessor(doc, indices, index_type, "SCALAR", kElementArrayBuffer, false);
  } else {
    pos = add_empty_accessor(doc, decoded.num_vertices(), kFloat, "VEC3", &positions);
    if (normals) nrm = add_empty_accessor(doc, decoded.num_vertices(), kFloat, "VEC3");
    idx = add_empty_accessor(doc, indices.size(), index_type, "SCALAR");
  }
  prim["attributes"]["POSITION"] = pos;
  if (normals) prim["attributes"]["NORMAL"] = nrm;
  prim["indices"] = idx;
  prim.erase("mode");  // TRIANGLES, the default
}

}  // namespace

size_t attach_prm_stream(Document& doc, size_t mesh, size_t primitive, std::vector<uint8_t> stream,
                         const codec::DecodedMesh& decoded, bool fallback) {
  const size_t before = [&] {
    size_t n = 0;
    for (const auto& b : doc.buffers) n += b.size();
    return n;
  }();
  const int view = add_buffer_view(doc, std::move(stream));
  json& prim = primitive_json(doc, mesh, primitive);
  set_decoded_accessors(doc, prim, decoded, fallback);
  prim["extensions"][kExtensionName] = {
      {"bufferView", view}, {"attributes", {{"POSITION", 0}}}, {"version", kExtensionVersion}};
  declare_extension(doc, kExtensionName, !fallback);
  size_t after = 0;
  for (const auto& b : doc.buffers) after += b.size();
  return after - before;
}

void expand_prm_primitive(Document& doc, size_t mesh, size_t primitive, const codec::DecodedMesh& decoded) {
  json& prim = primitive_json(doc, mesh, primitive);
  set_decoded_accessors(doc, prim, decoded, true);
  prim["extensions"].erase(kExtensionName);
  if (prim["extensions"].empty()) prim.erase("extensions");
}

}  // namespace prm::gltf
