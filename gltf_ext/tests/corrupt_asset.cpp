// prm_gltf_corrupt IN OUT CASE: IN (an asset with PRM_mesh_compression) with one defect, for the bad-input tests:
//   no-bufferview     the first extension object without bufferView
//   wrong-attributes  its attributes {"POSITION": 1}
//   bufferview-index  its bufferView 99 (no such bufferView)
//   view-past-buffer  its bufferView's byteLength beyond the end of the buffer
//   corrupt-stream    a byte in the middle of its PRM stream flipped (the GLB itself stays valid)
//   version           its version 2
#include <cstdio>
#include <string>

#include "prm/gltf/document.h"
#include "prm/gltf/prm_extension.h"

using namespace prm::gltf;

int main(int argc, char** argv) {
  if (argc != 4) return std::fprintf(stderr, "usage: prm_gltf_corrupt IN OUT CASE\n"), 2;
  Document doc = read_document(argv[1]);
  const std::string what = argv[3];
  nlohmann::json* ext = nullptr;
  for (auto& mesh : doc.json["meshes"])
    for (auto& prim : mesh["primitives"])
      if (!ext && has_prm_extension(prim)) ext = &prim["extensions"][kExtensionName];
  if (!ext) return std::fprintf(stderr, "%s has no %s primitive\n", argv[1], kExtensionName), 2;
  const int64_t view = (*ext)["bufferView"].get<int64_t>();
  if (what == "no-bufferview") {
    ext->erase("bufferView");
  } else if (what == "wrong-attributes") {
    (*ext)["attributes"]["POSITION"] = 1;
  } else if (what == "bufferview-index") {
    (*ext)["bufferView"] = 99;
  } else if (what == "view-past-buffer") {
    doc.json["bufferViews"][static_cast<size_t>(view)]["byteLength"] = doc.buffers[0].size() + 16;
  } else if (what == "corrupt-stream") {
    const auto& v = doc.json["bufferViews"][static_cast<size_t>(view)];
    const size_t at = v.value("byteOffset", size_t{0}) + v["byteLength"].get<size_t>() / 2;
    doc.buffers[0][at] ^= 0x5A;
  } else if (what == "version") {
    (*ext)["version"] = 2;
  } else {
    return std::fprintf(stderr, "unknown case '%s'\n", what.c_str()), 2;
  }
  write_document(doc, argv[2], false);
  return 0;
}
