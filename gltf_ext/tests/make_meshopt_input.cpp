// prm_gltf_make_meshopt IN.glb OUT.glb: IN with every vertex-attribute and index bufferView compressed by
// meshoptimizer's encoders into EXT_meshopt_compression (ATTRIBUTES, TRIANGLES or INDICES mode, no filter), the
// uncompressed data left out (a fallback buffer without data, so the extension is required), as gltfpack -c writes.
#include <meshoptimizer.h>

#include <cstdio>
#include <map>

#include "prm/gltf/accessors.h"
#include "prm/gltf/document.h"

using nlohmann::json;
using namespace prm::gltf;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: prm_gltf_make_meshopt IN.glb OUT.glb\n");
    return 1;
  }
  Document doc = read_document(argv[1]);
  compact(doc);
  json& j = doc.json;
  // How each bufferView is used: mode and element count.
  std::map<size_t, std::pair<std::string, size_t>> use;
  for (const json& mesh : j["meshes"])
    for (const json& prim : mesh["primitives"]) {
      for (const auto& [k, a] : prim["attributes"].items()) {
        const json& acc = j["accessors"][a.get<size_t>()];
        use[acc["bufferView"].get<size_t>()] = {"ATTRIBUTES", acc["count"].get<size_t>()};
      }
      if (prim.contains("indices")) {
        const json& acc = j["accessors"][prim["indices"].get<size_t>()];
        use[acc["bufferView"].get<size_t>()] = {prim.value("mode", 4) == 4 ? "TRIANGLES" : "INDICES",
                                                acc["count"].get<size_t>()};
      }
    }
  std::vector<uint8_t> bin;
  size_t fallback = 0;
  for (size_t i = 0; i < j["bufferViews"].size(); ++i) {
    json& view = j["bufferViews"][i];
    const ByteSpan bytes = buffer_view_bytes(doc, static_cast<int64_t>(i), "bufferViews[" + std::to_string(i) + "]");
    const auto u = use.find(i);
    const size_t count = u == use.end() ? 0 : u->second.second;
    const size_t stride = count ? bytes.size / count : 0;
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    if (u == use.end() || stride * count != bytes.size || stride % (u->second.first == "ATTRIBUTES" ? 4 : 2) ||
        (u->second.first != "ATTRIBUTES" && stride != 2 && stride != 4)) {
      view["buffer"] = 0;
      view["byteOffset"] = bin.size();
      bin.insert(bin.end(), bytes.data, bytes.data + bytes.size);
      continue;
    }
    std::vector<uint8_t> out;
    if (u->second.first == "ATTRIBUTES") {
      out.resize(meshopt_encodeVertexBufferBound(count, stride));
      out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), bytes.data, count, stride));
    } else {
      std::vector<unsigned int> idx(count);
      for (size_t k = 0; k < count; ++k)
        idx[k] = stride == 2 ? reinterpret_cast<const uint16_t*>(bytes.data)[k] : reinterpret_cast<const uint32_t*>(bytes.data)[k];
      if (u->second.first == "TRIANGLES") {
        out.resize(meshopt_encodeIndexBufferBound(count, 1 << 20));
        out.resize(meshopt_encodeIndexBuffer(out.data(), out.size(), idx.data(), count));
      } else {
        out.resize(meshopt_encodeIndexSequenceBound(count, 1 << 20));
        out.resize(meshopt_encodeIndexSequence(out.data(), out.size(), idx.data(), count));
      }
    }
    if (out.empty()) return std::fprintf(stderr, "meshopt encoder failed on bufferViews[%zu]\n", i), 1;
    view["extensions"]["EXT_meshopt_compression"] = {{"buffer", 0},       {"byteOffset", bin.size()},
                                                     {"byteLength", out.size()}, {"byteStride", stride},
                                                     {"count", count},    {"mode", u->second.first}};
    bin.insert(bin.end(), out.begin(), out.end());
    fallback = (fallback + 3) / 4 * 4;
    view["buffer"] = 1;
    view["byteOffset"] = fallback;
    fallback += bytes.size;
  }
  bin.resize((bin.size() + 3) / 4 * 4, 0);
  j["buffers"] = json::array({{{"byteLength", bin.size()}},
                              {{"byteLength", fallback}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
  doc.buffers = {bin, {}};
  declare_extension(doc, "EXT_meshopt_compression", true);
  write_document(doc, argv[2], false);
  return 0;
}
