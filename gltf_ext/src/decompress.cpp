// decompress(): every compression extension of an input asset decoded into ordinary accessors.
#include "prm/gltf/decompress.h"

#include "prm/gltf/prm_extension.h"

namespace prm::gltf {

size_t decode_prm_primitives(Document& doc, DecompressReport* report) {
  if (!doc.json.contains("meshes")) return 0;
  size_t decoded = 0;
  for (size_t m = 0; m < doc.json["meshes"].size(); ++m) {
    const nlohmann::json& mesh = doc.json["meshes"][m];
    if (!mesh.contains("primitives")) continue;
    for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
      if (!has_prm_extension(mesh["primitives"][p])) continue;
      const codec::DecodedMesh decoded_mesh = decode_prm_primitive(doc, m, p);
      if (report) {
        const int64_t view = mesh["primitives"][p]["extensions"][kExtensionName]["bufferView"].get<int64_t>();
        report->compressed_bytes[{m, p}] = buffer_view_bytes(doc, view, "").size;
        report->codec[{m, p}] = kExtensionName;
      }
      expand_prm_primitive(doc, m, p, decoded_mesh);
      ++decoded;
    }
  }
  if (decoded) remove_extension_declaration(doc, kExtensionName);
  if (report) report->prm_primitives = decoded;
  return decoded;
}

DecompressReport decompress(Document& doc) {
  DecompressReport report;
  report.meshopt_views = decode_meshopt_views(doc);
  decode_draco_primitives(doc, &report);
  decode_prm_primitives(doc, &report);
  return report;
}

}  // namespace prm::gltf
