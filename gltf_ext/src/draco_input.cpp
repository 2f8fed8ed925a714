// KHR_draco_mesh_compression primitives (KhronosGroup/glTF extensions/2.0/Khronos/KHR_draco_mesh_compression)
// decoded with Draco's own decoder (Debian libdraco-dev). Only Draco's core codec is used, never its glTF reader, so
// its internal copy of tinygltf cannot meet ours (../shared/guide/ECOSYSTEM.md §2.3).
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include <cstdint>
#include <cstring>

#include "prm/error.h"
#include "prm/gltf/accessors.h"
#include "prm/gltf/decompress.h"

namespace prm::gltf {
namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

using nlohmann::json;

[[noreturn]] void fail(const Document& doc, const std::string& what) { throw InputError(doc.path + ": " + what); }

template <typename T>
bool convert(const draco::PointAttribute& att, const draco::Mesh& mesh, int ncomp, std::vector<uint8_t>& bytes,
             size_t stride, std::vector<double>& raw) {
  std::vector<T> value(static_cast<size_t>(ncomp));
  for (uint32_t i = 0; i < mesh.num_points(); ++i) {
    if (!att.ConvertValue<T>(att.mapped_index(draco::PointIndex(i)), static_cast<int8_t>(ncomp), value.data()))
      return false;
    std::memcpy(bytes.data() + i * stride, value.data(), sizeof(T) * static_cast<size_t>(ncomp));
    for (const T& v : value) raw.push_back(static_cast<double>(v));
  }
  return true;
}

// Fills accessor `acc` (an attribute of the primitive) from Draco attribute `att`.
void fill_attribute(Document& doc, int64_t acc, const draco::PointAttribute& att, const draco::Mesh& mesh,
                    const std::string& where) {
  json& a = doc.json["accessors"][static_cast<size_t>(acc)];
  const int ctype = a.value("componentType", 0), ncomp = component_count(a.value("type", std::string()));
  const int csize = component_size(ctype);
  if (!csize || !ncomp) fail(doc, where + ": accessor " + std::to_string(acc) + " has an unknown type");
  const size_t elem = static_cast<size_t>(csize * ncomp), stride = (elem + 3) / 4 * 4;
  std::vector<uint8_t> bytes(mesh.num_points() * stride, 0);
  std::vector<double> raw;
  bool ok = false;
  switch (ctype) {
    case kFloat: ok = convert<float>(att, mesh, ncomp, bytes, stride, raw); break;
    case kUnsignedByte: ok = convert<uint8_t>(att, mesh, ncomp, bytes, stride, raw); break;
    case kByte: ok = convert<int8_t>(att, mesh, ncomp, bytes, stride, raw); break;
    case kUnsignedShort: ok = convert<uint16_t>(att, mesh, ncomp, bytes, stride, raw); break;
    case kShort: ok = convert<int16_t>(att, mesh, ncomp, bytes, stride, raw); break;
    case kUnsignedInt: ok = convert<uint32_t>(att, mesh, ncomp, bytes, stride, raw); break;
  }
  if (!ok) fail(doc, where + ": the Draco attribute does not convert to the accessor's type");
  a["bufferView"] = add_buffer_view(doc, std::move(bytes), kArrayBuffer, stride != elem ? static_cast<int>(stride) : 0);
  a.erase("byteOffset");
  a["count"] = mesh.num_points();
  if (a.contains("min") || a.contains("max")) set_min_max(a, raw, ncomp, ctype);
}

}  // namespace

size_t decode_draco_primitives(Document& doc, DecompressReport* report) {
  if (!doc.json.contains("meshes")) return 0;
  size_t decoded = 0;
  for (size_t m = 0; m < doc.json["meshes"].size(); ++m) {
    json& mesh_json = doc.json["meshes"][m];
    if (!mesh_json.contains("primitives")) continue;
    for (size_t p = 0; p < mesh_json["primitives"].size(); ++p) {
      json& prim = mesh_json["primitives"][p];
      if (!prim.contains("extensions") || !prim["extensions"].contains(kDraco)) continue;
      const std::string where = primitive_name(m, p) + ".extensions." + kDraco;
      const json ext = prim["extensions"][kDraco];
      if (!ext.is_object() || !ext.contains("bufferView") || !ext["bufferView"].is_number_integer())
        fail(doc, where + ".bufferView is missing or not an integer");
      if (!ext.contains("attributes") || !ext["attributes"].is_object())
        fail(doc, where + ".attributes is missing or not an object");
      const ByteSpan bytes = buffer_view_bytes(doc, ext["bufferView"].get<int64_t>(), where + ".bufferView");
      draco::DecoderBuffer buffer;
      buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
      draco::Decoder decoder;
      auto result = decoder.DecodeMeshFromBuffer(&buffer);
      if (!result.ok()) fail(doc, where + ": the Draco data does not decode: " + result.status().error_msg_string());
      const std::unique_ptr<draco::Mesh> mesh = std::move(result).value();
      if (report) {
        report->compressed_bytes[{m, p}] = bytes.size;
        report->codec[{m, p}] = kDraco;
      }
      for (const auto& [semantic, id] : ext["attributes"].items()) {
        // Draco's attribute ids are 32-bit (its unique_id): a larger number is refused, not truncated to another id.
        if (!id.is_number_unsigned() || id.get<uint64_t>() > UINT32_MAX)
          fail(doc, where + ".attributes." + semantic + " is not a Draco attribute id: " + id.dump());
        const draco::PointAttribute* att = mesh->GetAttributeByUniqueId(id.get<uint32_t>());
        if (!att) fail(doc, where + ".attributes." + semantic + ": the Draco data has no attribute " + id.dump());
        if (!prim.contains("attributes") || !prim["attributes"].contains(semantic))
          fail(doc, where + ".attributes." + semantic + " is not an attribute of the primitive");
        const int64_t acc = prim["attributes"][semantic].get<int64_t>();
        if (acc < 0 || static_cast<size_t>(acc) >= doc.json["accessors"].size())
          fail(doc, primitive_name(m, p) + ".attributes." + semantic + " is not an accessor");
        fill_attribute(doc, acc, *att, *mesh, where + ".attributes." + semantic);
      }
      if (prim.contains("indices")) {
        const int64_t acc = prim["indices"].get<int64_t>();
        if (acc < 0 || static_cast<size_t>(acc) >= doc.json["accessors"].size())
          fail(doc, primitive_name(m, p) + ".indices is not an accessor");
        json& a = doc.json["accessors"][static_cast<size_t>(acc)];
        int ctype = a.value("componentType", kUnsignedInt);
        if (ctype == kUnsignedByte && mesh->num_points() > 255) ctype = kUnsignedShort;
        if (ctype != kUnsignedInt && mesh->num_points() > 65535) ctype = kUnsignedInt;
        std::vector<double> idx;
        idx.reserve(3 * mesh->num_faces());
        for (uint32_t f = 0; f < mesh->num_faces(); ++f)
          for (int c = 0; c < 3; ++c) idx.push_back(mesh->face(draco::FaceIndex(f))[c].value());
        const int tmp = add_accessor(doc, idx, ctype, "SCALAR", kElementArrayBuffer, false);
        json made = doc.json["accessors"][static_cast<size_t>(tmp)];
        doc.json["accessors"].erase(static_cast<size_t>(tmp));
        json& target = doc.json["accessors"][static_cast<size_t>(acc)];
        target["bufferView"] = made["bufferView"];
        target["componentType"] = ctype;
        target["count"] = idx.size();
        target.erase("byteOffset");
      }
      prim["extensions"].erase(kDraco);
      if (prim["extensions"].empty()) prim.erase("extensions");
      ++decoded;
    }
  }
  if (decoded) remove_extension_declaration(doc, kDraco);
  if (report) report->draco_primitives = decoded;
  return decoded;
}

}  // namespace prm::gltf
