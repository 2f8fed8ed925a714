// prm_gltf_make_scene OUT.glb|.gltf [--quantized] [--no-lines]: a test scene built from the shared meshes: a node hierarchy with
// TRS and matrix transforms, a camera, extras, three materials (one textured, with an embedded PNG), a mesh of two
// primitives with normals (spot, rabbit), a textured primitive with UVs (rabbit), a LINES primitive; --quantized
// adds a mesh whose POSITION is normalized unsigned short (KHR_mesh_quantization), dequantized by its node;
// --no-lines leaves the LINES primitive and the camera out (draco_transcoder refuses the one and drops the other).
// prm_gltf_make_scene OUT --meshes MESH...: a plain scene for bench/gltf: each mesh (POSITION, NORMAL by the
// extension's rule, indices) its own glTF mesh with its own material, placed side by side under a root node.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "prm/gltf/accessors.h"
#include "prm/gltf/document.h"
#include "prm/gltf/prm_extension.h"
#include "prm/mesh_io.h"

using nlohmann::json;
using namespace prm;
using namespace prm::gltf;

namespace {

// A 1x1 RGBA PNG, written out byte by byte so the test needs no image library.
const std::vector<uint8_t> kPng = {
    0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00, 0x00,
    0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1F, 0x15, 0xC4, 0x89, 0x00, 0x00, 0x00, 0x0D, 0x49,
    0x44, 0x41, 0x54, 0x78, 0x9C, 0x63, 0xF8, 0xCF, 0xC0, 0xF0, 0x1F, 0x00, 0x05, 0x00, 0x01, 0xFF, 0x56, 0xC7, 0x2F,
    0x0D, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82};

std::vector<double> flat_positions(const Mesh& m) {
  std::vector<double> out;
  for (const Vec3& p : m.positions)
    for (double c : p) out.push_back(c);
  return out;
}

std::vector<double> flat_indices(const Mesh& m) {
  std::vector<double> out;
  for (const Tri& t : m.triangles)
    for (uint32_t c : t) out.push_back(c);
  return out;
}

std::vector<uint32_t> index_list(const Mesh& m) {
  std::vector<uint32_t> out;
  for (const Tri& t : m.triangles)
    for (uint32_t c : t) out.push_back(c);
  return out;
}

}  // namespace

int meshes_scene(const std::string& out, const std::vector<std::string>& files) {
  Document doc;
  doc.json = {{"asset", {{"version", "2.0"}, {"generator", "prm_gltf_make_scene"}}}, {"scene", 0}};
  json root = {{"name", "root"}, {"children", json::array()}};
  doc.json["nodes"] = json::array({root});
  doc.json["meshes"] = json::array();
  doc.json["materials"] = json::array();
  double x = 0;
  for (const std::string& f : files) {
    const Mesh m = read_mesh(f);
    const std::vector<double> p = flat_positions(m);
    Vec3 lo = m.positions[0], hi = lo;
    for (const Vec3& q : m.positions)
      for (size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], q[k]);
        hi[k] = std::max(hi[k], q[k]);
      }
    const int pos = add_accessor(doc, p, kFloat, "VEC3", kArrayBuffer, true);
    const int nrm = add_accessor(doc, regenerate_normals(p, index_list(m)), kFloat, "VEC3", kArrayBuffer, false);
    const int idx = add_accessor(doc, flat_indices(m), m.num_vertices() <= 65535 ? kUnsignedShort : kUnsignedInt,
                                 "SCALAR", kElementArrayBuffer, false);
    const size_t k = doc.json["meshes"].size();
    const std::string name = f.substr(f.find_last_of('/') + 1);
    doc.json["materials"].push_back({{"name", name}, {"pbrMetallicRoughness", {{"metallicFactor", 0.1 * static_cast<double>(k)}}}});
    doc.json["meshes"].push_back({{"name", name},
                                  {"primitives", json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", idx}, {"material", k}}})}});
    // Scaled to a unit diagonal and placed side by side.
    const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    doc.json["nodes"].push_back({{"name", name}, {"mesh", k}, {"scale", {1 / diag, 1 / diag, 1 / diag}},
                                 {"translation", {x - lo[0] / diag, -lo[1] / diag, -lo[2] / diag}}});
    doc.json["nodes"][0]["children"].push_back(doc.json["nodes"].size() - 1);
    x += 1.2;
  }
  doc.json["scenes"] = json::array({{{"nodes", {0}}}});
  write_document(doc, out);
  return 0;
}

int main(int argc, char** argv) {
  if (argc > 2 && std::string(argv[2]) == "--meshes") return meshes_scene(argv[1], std::vector<std::string>(argv + 3, argv + argc));
  if (argc < 2) {
    std::fprintf(stderr, "usage: prm_gltf_make_scene OUT.glb [--quantized] [--no-lines]\n");
    return 1;
  }
  bool quantized = false, lines_mesh = true;
  for (int i = 2; i < argc; ++i) {
    quantized = quantized || std::string(argv[i]) == "--quantized";
    lines_mesh = lines_mesh && std::string(argv[i]) != "--no-lines";
  }
  const std::string shared = PRM_SHARED_MESHES;
  const Mesh spot = read_mesh(shared + "/spot.obj");
  const Mesh rabbit = read_mesh(shared + "/rabbit_1k_decimated.off");

  Document doc;
  doc.json = {{"asset", {{"version", "2.0"}, {"generator", "prm_gltf_make_scene"}}}, {"scene", 0}};
  // spot with normals, rabbit without: mesh 0, two primitives, two materials.
  const std::vector<double> sp = flat_positions(spot), rp = flat_positions(rabbit);
  const int spot_pos = add_accessor(doc, sp, kFloat, "VEC3", kArrayBuffer, true);
  const int spot_nrm = add_accessor(doc, regenerate_normals(sp, index_list(spot)), kFloat, "VEC3", kArrayBuffer, false);
  const int spot_idx = add_accessor(doc, flat_indices(spot), kUnsignedShort, "SCALAR", kElementArrayBuffer, false);
  const int rab_pos = add_accessor(doc, rp, kFloat, "VEC3", kArrayBuffer, true);
  const int rab_idx = add_accessor(doc, flat_indices(rabbit), kUnsignedShort, "SCALAR", kElementArrayBuffer, false);
  // The textured rabbit: spherical UVs around its centre.
  std::vector<double> uv;
  for (const Vec3& p : rabbit.positions) {
    const double x = p[0] - 0.0, y = p[1], z = p[2];
    const double r = std::sqrt(x * x + y * y + z * z) + 1e-12;
    uv.push_back(0.5 + std::atan2(z, x) / (2 * M_PI));
    uv.push_back(std::acos(std::max(-1.0, std::min(1.0, y / r))) / M_PI);
  }
  const int rab_uv = add_accessor(doc, uv, kFloat, "VEC2", kArrayBuffer, false);
  // A LINES primitive: the first 30 edges of the rabbit.
  std::vector<double> lines;
  for (size_t t = 0; t < 30; ++t) {
    lines.push_back(rabbit.triangles[t][0]);
    lines.push_back(rabbit.triangles[t][1]);
  }
  const int line_idx = add_accessor(doc, lines, kUnsignedShort, "SCALAR", kElementArrayBuffer, false);
  const int image_view = add_buffer_view(doc, kPng);

  doc.json["meshes"] = json::array({
      {{"name", "animals"},
       {"primitives", json::array({{{"attributes", {{"POSITION", spot_pos}, {"NORMAL", spot_nrm}}}, {"indices", spot_idx}, {"material", 0}},
                                   {{"attributes", {{"POSITION", rab_pos}}}, {"indices", rab_idx}, {"material", 1}, {"extras", {{"note", "plain rabbit"}}}}})}},
      {{"name", "textured"},
       {"primitives", json::array({{{"attributes", {{"POSITION", rab_pos}, {"TEXCOORD_0", rab_uv}}}, {"indices", rab_idx}, {"material", 2}}})}},
      {{"name", "wire"},
       {"primitives", json::array({{{"attributes", {{"POSITION", rab_pos}}}, {"indices", line_idx}, {"mode", 1}}})}},
  });
  doc.json["materials"] = json::array({
      {{"name", "hide"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.7, 0.6, 1.0}}, {"metallicFactor", 0.0}}}},
      {{"name", "fur"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.9, 0.9, 1.0}}, {"roughnessFactor", 0.4}}}, {"doubleSided", true}},
      {{"name", "painted"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
  });
  doc.json["textures"] = json::array({{{"sampler", 0}, {"source", 0}}});
  doc.json["samplers"] = json::array({{{"magFilter", 9729}, {"minFilter", 9987}}});
  doc.json["images"] = json::array({{{"bufferView", image_view}, {"mimeType", "image/png"}, {"name", "dot"}}});
  doc.json["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.01}, {"aspectRatio", 1.5}}}}});
  doc.json["nodes"] = json::array({
      {{"name", "root"}, {"children", {1, 2, 3, 5}}, {"extras", {{"author", "prm tests"}}}},
      {{"name", "cow"}, {"mesh", 0}, {"translation", {1.5, 0, 0}}, {"rotation", {0, 0.38268343, 0, 0.92387953}}},
      {{"name", "bunny"}, {"mesh", 1}, {"scale", {2, 2, 2}}, {"translation", {-1, 0, 0}}},
      {{"name", "frame"}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0.5, 0, 1}}, {"children", {4}}},
      {{"name", "wire"}, {"mesh", 2}},
      {{"name", "eye"}, {"camera", 0}, {"translation", {0, 0.5, 4}}},
  });
  if (quantized) {
    // rabbit positions as normalized unsigned shorts in [0, 1]^3; the node maps them back.
    Vec3 lo = rabbit.positions[0], hi = lo;
    for (const Vec3& p : rabbit.positions)
      for (size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    std::vector<double> q;
    for (const Vec3& p : rabbit.positions)
      for (size_t k = 0; k < 3; ++k) q.push_back(std::round((p[k] - lo[k]) / (hi[k] - lo[k]) * 65535.0));
    const int qpos = add_accessor(doc, q, kUnsignedShort, "VEC3", kArrayBuffer, true);
    doc.json["accessors"][static_cast<size_t>(qpos)]["normalized"] = true;
    doc.json["meshes"].push_back({{"name", "quantized"},
                                  {"primitives", json::array({{{"attributes", {{"POSITION", qpos}}}, {"indices", rab_idx}, {"material", 1}}})}});
    doc.json["nodes"].push_back({{"name", "quantized bunny"}, {"mesh", 3}, {"translation", {lo[0], lo[1] + 1, lo[2]}},
                                 {"scale", {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}}});
    doc.json["nodes"][0]["children"].push_back(6);
    declare_extension(doc, "KHR_mesh_quantization", true);
  }
  if (!lines_mesh) {  // mesh 2 goes; node 4 shows mesh 0 a second time; no camera (draco_transcoder drops cameras)
    doc.json["meshes"].erase(2);
    doc.json["nodes"][4]["mesh"] = 0;
    doc.json["nodes"][5].erase("camera");
    doc.json["nodes"][5]["mesh"] = 1;
    doc.json.erase("cameras");
    if (quantized) doc.json["nodes"][6]["mesh"] = 2;
  }
  doc.json["scenes"] = json::array({{{"name", "test scene"}, {"nodes", {0}}}});
  write_document(doc, argv[1]);
  return 0;
}
