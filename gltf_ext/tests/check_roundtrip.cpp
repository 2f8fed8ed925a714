// prm_gltf_check IN PACKED PLAIN [--fallback]: what `prm pack IN -o PACKED` and `prm unpack PACKED -o PLAIN` must
// keep. The scene graph (scenes, nodes, cameras), materials, textures, samplers, images (with their bytes) and the
// meshes' names, extras and primitive order are equal in all three; every primitive PACKED left uncompressed has the
// same accessor data as IN (IN's Draco/meshopt data decoded); every PRM primitive of PACKED decodes exactly to
// PLAIN's accessors (positions, regenerated normals, indices), its accessors' counts and min/max describe the
// decoded mesh, and with --fallback its accessors hold exactly that decoded mesh. Prints what differs; exit 1.
#include <algorithm>
#include <cstdio>
#include <string>

#include "prm/gltf/accessors.h"
#include "prm/gltf/decompress.h"
#include "prm/gltf/document.h"
#include "prm/gltf/prm_extension.h"

using nlohmann::json;
using namespace prm::gltf;

namespace {

int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    ++failures;
    std::printf("FAIL: %s\n", what.c_str());
  }
}

json field(const json& j, const char* key) { return j.contains(key) ? j[key] : json(); }

std::vector<double> as_float(const std::vector<double>& v) {
  std::vector<double> out;
  for (double x : v) out.push_back(static_cast<double>(static_cast<float>(x)));
  return out;
}

std::vector<double> values(const Document& doc, const json& index, const std::string& where) {
  return read_accessor(doc, index.get<int64_t>(), where).values;
}

std::vector<uint8_t> image_bytes(const Document& doc, const json& image) {
  if (!image.contains("bufferView")) return {};
  const ByteSpan s = buffer_view_bytes(doc, image["bufferView"].get<int64_t>(), "image");
  return {s.data, s.data + s.size};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: prm_gltf_check IN PACKED PLAIN [--fallback]\n");
    return 2;
  }
  const bool fallback = argc > 4 && std::string(argv[4]) == "--fallback";
  Document in = read_document(argv[1]);
  decompress(in);
  const Document packed = read_document(argv[2]);
  const Document plain = read_document(argv[3]);
  const json &a = in.json, &b = packed.json, &c = plain.json;

  for (const char* key : {"scene", "scenes", "nodes", "cameras", "materials", "textures", "samplers", "extras",
                          "animations", "skins"}) {
    check(field(a, key) == field(b, key), std::string(key) + " differ between input and packed");
    check(field(a, key) == field(c, key), std::string(key) + " differ between input and unpacked");
  }
  const size_t num_images = a.contains("images") ? a["images"].size() : 0;
  check(num_images == (b.contains("images") ? b["images"].size() : 0), "image count differs");
  for (size_t i = 0; i < num_images && i < b["images"].size(); ++i) {
    json ia = a["images"][i], ib = b["images"][i], ic = c["images"][i];
    check(image_bytes(in, ia) == image_bytes(packed, ib) && image_bytes(in, ia) == image_bytes(plain, ic),
          "images[" + std::to_string(i) + "] bytes differ");
    for (json* j : {&ia, &ib, &ic}) j->erase("bufferView");
    check(ia == ib && ia == ic, "images[" + std::to_string(i) + "] properties differ");
  }
  check(!c.contains("extensionsUsed") || std::find(c["extensionsUsed"].begin(), c["extensionsUsed"].end(),
                                                   kExtensionName) == c["extensionsUsed"].end(),
        "the unpacked asset still declares the extension");
  const bool required = b.contains("extensionsRequired") &&
                        std::find(b["extensionsRequired"].begin(), b["extensionsRequired"].end(), kExtensionName) !=
                            b["extensionsRequired"].end();
  size_t compressed = 0;
  check(a["meshes"].size() == b["meshes"].size() && a["meshes"].size() == c["meshes"].size(), "mesh count differs");
  for (size_t m = 0; m < a["meshes"].size(); ++m) {
    const json &ma = a["meshes"][m], &mb = b["meshes"][m], &mc = c["meshes"][m];
    check(field(ma, "name") == field(mb, "name") && field(ma, "name") == field(mc, "name"), "mesh names differ");
    check(field(ma, "extras") == field(mb, "extras"), "mesh extras differ");
    check(ma["primitives"].size() == mb["primitives"].size() && ma["primitives"].size() == mc["primitives"].size(),
          "primitive count differs in meshes[" + std::to_string(m) + "]");
    for (size_t p = 0; p < ma["primitives"].size(); ++p) {
      const json &pa = ma["primitives"][p], &pb = mb["primitives"][p], &pc = mc["primitives"][p];
      const std::string name = primitive_name(m, p);
      for (const char* key : {"material", "extras"})
        check(field(pa, key) == field(pb, key) && field(pa, key) == field(pc, key), name + "." + key + " differs");
      if (!has_prm_extension(pb)) {
        // Untouched: same accessor data everywhere.
        for (const auto& [k, v] : pa["attributes"].items())
          check(values(in, v, name) == values(packed, pb["attributes"][k], name) &&
                    values(in, v, name) == values(plain, pc["attributes"][k], name),
                name + ".attributes." + k + " data differ");
        if (pa.contains("indices"))
          check(values(in, pa["indices"], name) == values(packed, pb["indices"], name), name + ".indices differ");
        check(field(pa, "mode") == field(pb, "mode"), name + ".mode differs");
        continue;
      }
      ++compressed;
      const prm::codec::DecodedMesh d = decode_prm_primitive(packed, m, p);
      const std::vector<double> pos = as_float(d.positions_f64);
      const std::vector<double> idx(d.triangles.begin(), d.triangles.end());
      check(values(plain, pc["attributes"]["POSITION"], name) == pos, name + ": unpacked POSITION differs from the decoded stream");
      check(values(plain, pc["indices"], name) == idx, name + ": unpacked indices differ from the decoded stream");
      check(pa["attributes"].contains("NORMAL") == pb["attributes"].contains("NORMAL"), name + ": NORMAL kept / dropped");
      if (pb["attributes"].contains("NORMAL"))
        check(values(plain, pc["attributes"]["NORMAL"], name) == as_float(regenerate_normals(d.positions_f64, d.triangles)),
              name + ": unpacked NORMAL differs from the extension's rule");
      const json& acc = b["accessors"][pb["attributes"]["POSITION"].get<size_t>()];
      json expect;
      set_min_max(expect, d.positions_f64, 3, kFloat);
      check(acc["count"] == d.num_vertices() && acc["min"] == expect["min"] && acc["max"] == expect["max"],
            name + ": POSITION accessor count/min/max do not describe the decoded mesh");
      check(acc.contains("bufferView") == fallback, name + ": POSITION accessor data present iff --fallback");
      if (fallback) {
        check(values(packed, pb["attributes"]["POSITION"], name) == pos, name + ": fallback POSITION differs from the decoded stream");
        check(values(packed, pb["indices"], name) == idx, name + ": fallback indices differ from the decoded stream");
      }
    }
  }
  check(compressed > 0, "no primitive was compressed");
  check(required != fallback, "extensionsRequired must list the extension exactly when there is no fallback");
  std::printf("%s: %zu PRM primitive(s) checked, %d failure(s)\n", argv[2], compressed, failures);
  return failures ? 1 : 0;
}
