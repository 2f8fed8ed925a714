// prm_gltf: the document layer (GLB / .gltf, compact), accessors, the extension's rules (normals, field checks),
// which primitives pack_scene keeps and why, and hostile containers. The end-to-end cases through the prm tool and
// the Khronos validator are the prm_gltf_cli_* tests (gltf_cli_test.cmake).
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "prm/error.h"
#include "prm/gltf/accessors.h"
#include "prm/gltf/decompress.h"
#include "prm/gltf/document.h"
#include "prm/gltf/pack_scene.h"
#include "prm/gltf/prm_extension.h"
#include "prm/mesh_io.h"

namespace prm::gltf {
namespace {

using nlohmann::json;

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("prm_gltf_test_" + name)).string();
}

void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::vector<uint8_t> glb(const std::string& text, const std::vector<uint8_t>& bin) {
  std::vector<uint8_t> out;
  auto u32 = [&](uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
  };
  std::string t = text;
  t.resize((t.size() + 3) / 4 * 4, ' ');
  u32(0x46546C67);
  u32(2);
  u32(static_cast<uint32_t>(12 + 8 + t.size() + (bin.empty() ? 0 : 8 + bin.size())));
  u32(static_cast<uint32_t>(t.size()));
  u32(0x4E4F534A);
  out.insert(out.end(), t.begin(), t.end());
  if (!bin.empty()) {
    u32(static_cast<uint32_t>(bin.size()));
    u32(0x004E4942);
    out.insert(out.end(), bin.begin(), bin.end());
  }
  return out;
}

void expect_input_error(const std::string& path, const std::string& fragment) {
  try {
    read_document(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// A unit cube, 8 vertices, 12 outward triangles.
Mesh cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

TEST(GltfNormals, AreaWeightedSumOfTheTrianglesNormalized) {
  // Two triangles in z = 0 and one standing triangle sharing vertex 0.
  const std::vector<double> p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 2, 5, 5, 5};
  const std::vector<uint32_t> t = {0, 1, 2, 0, 3, 1};
  const std::vector<double> n = regenerate_normals(p, t);
  // Vertex 0: (0,0,1) (area 0.5 x 2) + (0,2,0)x... = (0, 2, 0) from triangle (0,3,1): sum (0, 2, 1) / sqrt(5).
  EXPECT_NEAR(n[0], 0, 1e-15);
  EXPECT_NEAR(n[1], 2 / std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(n[2], 1 / std::sqrt(5.0), 1e-15);
  EXPECT_DOUBLE_EQ(n[6 + 2], 1.0);  // vertex 2: only the flat triangle
  // Vertex 4 is in no triangle: (0, 0, 1) by the rule.
  EXPECT_EQ(n[12], 0);
  EXPECT_EQ(n[13], 0);
  EXPECT_EQ(n[14], 1);
}

TEST(GltfDocument, GltfAndGlbRoundTripKeepJsonAndBytes) {
  Document doc = document_from_mesh(cube(), "cube");
  doc.json["extras"] = {{"k", "v"}};
  doc.json["cameras"] = json::array({{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"zfar", 10}, {"znear", 0.1}}}}});
  for (const char* ext : {".gltf", ".glb"}) {
    Document copy = doc;
    const std::string path = temp_path(std::string("rt") + ext);
    write_document(copy, path);
    const Document back = read_document(path);
    EXPECT_EQ(back.json["extras"], doc.json["extras"]);
    EXPECT_EQ(back.json["cameras"], doc.json["cameras"]);
    const AccessorData pos = read_accessor(back, 0, "test");
    ASSERT_EQ(pos.count, 8u);
    EXPECT_EQ(pos.values[3 * 7], 1.0);
    EXPECT_EQ(back.json["accessors"][0]["min"], json::array({0.0, 0.0, 0.0}));
    const AccessorData idx = read_accessor(back, 1, "test");
    EXPECT_EQ(idx.values[2], 1.0);
  }
}

TEST(GltfDocument, CompactDropsUnusedAccessorsAndViewsAndRenumbers) {
  Document doc = document_from_mesh(cube(), "cube");
  // An accessor and a view nobody uses, placed before the used ones' next additions.
  add_accessor(doc, {1, 2, 3}, kFloat, "VEC3", kArrayBuffer, true);
  const int used = add_accessor(doc, {4, 5, 6}, kFloat, "VEC3", kArrayBuffer, true);
  doc.json["meshes"][0]["primitives"][0]["targets"] = json::array({{{"POSITION", used}}});
  compact(doc);
  EXPECT_EQ(doc.json["accessors"].size(), 3u);
  EXPECT_EQ(doc.json["bufferViews"].size(), 3u);
  EXPECT_EQ(doc.json["meshes"][0]["primitives"][0]["targets"][0]["POSITION"], 2);
  EXPECT_EQ(read_accessor(doc, 2, "t").values, (std::vector<double>{4, 5, 6}));
  EXPECT_EQ(doc.buffers.size(), 1u);
  for (const json& v : doc.json["bufferViews"]) EXPECT_EQ(v.value("byteOffset", 0) % 4, 0);
}

TEST(GltfAccessors, NormalizedStridedAndSparse) {
  Document doc;
  doc.path = "mem";
  doc.json = {{"asset", {{"version", "2.0"}}}};
  // Three VEC2 normalized shorts at stride 8 (4 bytes of padding each).
  std::vector<uint8_t> bytes(24, 0);
  const int16_t v[6] = {32767, -32768, 0, 16384, -1, 1};
  for (int i = 0; i < 3; ++i) std::memcpy(bytes.data() + 8 * i, v + 2 * i, 4);
  const int view = add_buffer_view(doc, bytes, kArrayBuffer, 8);
  const int sparse_idx = add_buffer_view(doc, {2, 0, 0, 0});
  std::vector<uint8_t> sv(4);
  const int16_t s[2] = {0, 32767};
  std::memcpy(sv.data(), s, 4);
  const int sparse_val = add_buffer_view(doc, sv);
  doc.json["accessors"] = json::array(
      {{{"bufferView", view}, {"componentType", kShort}, {"normalized", true}, {"count", 3}, {"type", "VEC2"},
        {"sparse", {{"count", 1}, {"indices", {{"bufferView", sparse_idx}, {"componentType", kUnsignedByte}}},
                    {"values", {{"bufferView", sparse_val}}}}}}});
  const AccessorData a = read_accessor(doc, 0, "t");
  EXPECT_EQ(a.values, (std::vector<double>{1.0, -1.0, 0.0, 16384 / 32767.0, 0.0, 1.0}));
  doc.json["accessors"][0]["count"] = 4;  // now past the end of the view
  EXPECT_THROW(read_accessor(doc, 0, "t"), InputError);
}

TEST(GltfDocument, HostileContainersAreRefusedByName) {
  const std::string p = temp_path("hostile.glb");
  write_bytes(p, {'g', 'l', 'T', 'F', 2, 0, 0, 0});
  expect_input_error(p, "shorter than its 12-byte header");
  std::vector<uint8_t> g = glb(R"({"asset":{"version":"2.0"}})", {});
  g[8] = 0xFF;  // total length beyond the file
  write_bytes(p, g);
  expect_input_error(p, "GLB header says");
  write_bytes(p, glb(R"({"asset":{"version":"2.0"},)", {}));
  expect_input_error(p, "does not parse");
  write_bytes(p, glb(R"({"asset":{"version":"1.0"}})", {}));
  expect_input_error(p, "asset.version");
  write_bytes(p, glb(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":8}]})", {1, 2, 3, 4}));
  expect_input_error(p, "buffers[0].byteLength is 8 but its data has 4 bytes");
  write_bytes(p, glb(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4}],
                         "bufferViews":[{"buffer":0,"byteOffset":2,"byteLength":4}]})", {1, 2, 3, 4}));
  expect_input_error(p, "bufferViews[0] (byteOffset 2, byteLength 4) reaches past the end of buffers[0]");
  write_bytes(p, glb(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"../../etc/passwd"}]})", {}));
  expect_input_error(p, "is not a relative path inside the asset's folder");
  write_bytes(p, glb(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"data:application/octet-stream;base64,A$=="}]})", {}));
  expect_input_error(p, "not base64");
}

// Members of the wrong JSON type were left to nlohmann's type_error inside `prm info`, `prm unpack` and `prm pack`
// (exit 70, "internal error"; found by hand, with crafted assets, while writing gltf_ext/fuzz/gltf_ext_fuzzer.cpp):
// read_document names them.
TEST(GltfDocument, MembersOfTheWrongTypeAreRefusedByName) {
  const std::string p = temp_path("wrong_type.glb");
  const auto with = [&](const std::string& members) {
    write_bytes(p, glb(R"({"asset":{"version":"2.0"},)" + members + "}", {}));
  };
  with(R"("meshes":[{"primitives":[{"attributes":{},"mode":"x"}]}])");
  expect_input_error(p, "meshes[0].primitives[0].mode is not an integer");
  with(R"("meshes":[{"name":5,"primitives":[]}])");
  expect_input_error(p, "meshes[0].name is not a string");
  with(R"("extensionsUsed":[1])");
  expect_input_error(p, "extensionsUsed[0] is not a string");
  with(R"("extensionsRequired":{})");
  expect_input_error(p, "extensionsRequired is not an array");
  with(R"("meshes":[7])");
  expect_input_error(p, "meshes[0] is not an object");
  with(R"("meshes":[{"primitives":{}}])");
  expect_input_error(p, "meshes[0].primitives is not an array");
  with(R"("meshes":[{"primitives":[{"attributes":[]}]}])");
  expect_input_error(p, "meshes[0].primitives[0].attributes is not an object");
  with(R"("meshes":[{"primitives":[{"attributes":{},"extensions":3}]}])");
  expect_input_error(p, "meshes[0].primitives[0].extensions is not an object");
  // Read as integers by the Draco input (`prm unpack`).
  with(R"("meshes":[{"primitives":[{"attributes":{"POSITION":"0"}}]}])");
  expect_input_error(p, "meshes[0].primitives[0].attributes.POSITION is not an integer");
  with(R"("meshes":[{"primitives":[{"attributes":{},"indices":[1]}]}])");
  expect_input_error(p, "meshes[0].primitives[0].indices is not an integer");
  // Read by read_accessor (`prm pack` of a .glb, Draco primitives in `prm unpack`).
  with(R"("accessors":[{"componentType":"x","count":1,"type":"VEC3"}])");
  expect_input_error(p, "accessors[0].componentType is not an integer");
  with(R"("accessors":[{"componentType":5126,"count":1,"type":"VEC3","normalized":1}])");
  expect_input_error(p, "accessors[0].normalized is not a boolean");
  with(R"("accessors":[{"componentType":5126,"count":1,"type":3}])");
  expect_input_error(p, "accessors[0].type is not a string");
  with(R"("accessors":[{"componentType":5126,"count":1,"type":"VEC3","sparse":{"count":1,"indices":{"bufferView":"0"}}}])");
  expect_input_error(p, "accessors[0].sparse.indices.bufferView is not an integer");
  with(R"("buffers":[{"byteLength":4,"uri":"data:application/octet-stream;base64,AAAAAA=="}],
          "bufferViews":[{"buffer":0,"byteLength":4,"byteStride":"x"}])");
  expect_input_error(p, "bufferViews[0].byteStride is not an integer");
  with(R"("meshes":[{"name":"ok","primitives":[{"attributes":{},"mode":4}]}],"extensionsUsed":["X"])");
  EXPECT_NO_THROW(read_document(p));
}

// KHR_draco_mesh_compression's attribute ids are Draco's 32-bit unique ids: 2^32 was read as id 0 (the positions),
// with no error (found by hfuzz4's review of gltf_ext/src/draco_input.cpp). It is refused by name; 0 decodes.
TEST(GltfDraco, AnAttributeIdBeyond32BitsIsRefusedNotTruncated) {
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(1);
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  builder.SetAttributeValuesForFace(pos, draco::FaceIndex(0), draco::Vector3f(0, 0, 0).data(),
                                    draco::Vector3f(1, 0, 0).data(), draco::Vector3f(0, 1, 0).data());
  const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  ASSERT_TRUE(mesh);
  ASSERT_EQ(mesh->attribute(pos)->unique_id(), 0u);
  draco::EncoderBuffer encoded;
  draco::Encoder encoder;
  ASSERT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());
  const auto document_with_id = [&](uint64_t id) {
    Document doc;
    doc.path = "draco.glb";
    doc.json = {{"asset", {{"version", "2.0"}}}};
    const int view = add_buffer_view(doc, std::vector<uint8_t>(encoded.data(), encoded.data() + encoded.size()));
    const int acc = add_empty_accessor(doc, 3, kFloat, "VEC3");
    doc.json["meshes"] = json::array({{{"primitives", json::array({{
        {"attributes", {{"POSITION", acc}}},
        {"extensions", {{"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", {{"POSITION", id}}}}}}}}})}}});
    return doc;
  };
  Document ok = document_with_id(0);
  EXPECT_EQ(decode_draco_primitives(ok, nullptr), 1u);
  EXPECT_EQ(read_accessor(ok, 0, "t").count, 3u);
  Document hostile = document_with_id(uint64_t{1} << 32);
  try {
    decode_draco_primitives(hostile, nullptr);
    ADD_FAILURE() << "an attribute id of 2^32 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("attributes.POSITION is not a Draco attribute id: 4294967296"), std::string::npos)
        << e.what();
  }
}

// EXT_meshopt_compression claims (found by hand while writing gltf_ext/fuzz/gltf_ext_fuzzer.cpp): a 16-byte view
// that claims 2^28 x 256 decoded bytes was allocated before decoding (`prm unpack`: out of memory, exit 3), and a mode or
// filter that is not a string threw nlohmann's type_error (exit 70). Both are refused by name.
TEST(GltfMeshopt, ClaimsBeyondTheDataAndMistypedFieldsAreRefusedByName) {
  const auto expect_refused = [](const std::string& ext, const std::string& fragment) {
    Document doc;
    doc.path = "meshopt.glb";
    doc.json = json::parse(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":16}],
        "bufferViews":[{"buffer":0,"byteLength":16,"extensions":{"EXT_meshopt_compression":)" + ext + "}}]}");
    doc.buffers = {std::vector<uint8_t>(16, 0)};
    try {
      decode_meshopt_views(doc);
      ADD_FAILURE() << "no error for " << ext;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_refused(R"({"buffer":0,"byteLength":16,"byteStride":256,"count":268435456,"mode":"ATTRIBUTES"})",
                 "count x byteStride = 68719476736 bytes from 16 compressed bytes, more than meshopt's codecs expand to");
  expect_refused(R"({"buffer":0,"byteLength":16,"byteStride":4,"count":3,"mode":5})", ".mode is not a string");
  expect_refused(R"({"buffer":0,"byteLength":16,"byteStride":4,"count":3,"mode":"TRIANGLES","filter":[]})",
                 ".filter is not a string");
  expect_refused(R"({"buffer":0,"byteOffset":"0","byteLength":16,"byteStride":4,"count":3,"mode":"TRIANGLES"})",
                 ".byteOffset is not a non-negative integer");
}

TEST(GltfPackScene, KeepsWhatPrmCannotCarryAndSaysWhy) {
  // Five primitives over the cube: TEXCOORD_0, COLOR_0, morph target, strip mode, skinned mesh; one plain one.
  Document doc = document_from_mesh(cube(), "cube");
  std::vector<double> uv(16, 0.5), colour(32, 1.0);
  const int uv_acc = add_accessor(doc, uv, kFloat, "VEC2", kArrayBuffer, false);
  const int col_acc = add_accessor(doc, colour, kFloat, "VEC4", kArrayBuffer, false);
  const json base = doc.json["meshes"][0]["primitives"][0];
  json prims = json::array();
  json p = base;
  p["attributes"]["TEXCOORD_0"] = uv_acc;
  prims.push_back(p);
  p = base;
  p["attributes"]["COLOR_0"] = col_acc;
  prims.push_back(p);
  p = base;
  p["targets"] = json::array({{{"POSITION", 0}}});
  prims.push_back(p);
  p = base;
  p["mode"] = 5;
  prims.push_back(p);
  doc.json["meshes"][0]["primitives"] = prims;
  doc.json["meshes"].push_back({{"primitives", json::array({base})}});
  doc.json["nodes"].push_back({{"mesh", 1}, {"skin", 0}});
  doc.json["skins"] = json::array({{{"joints", {0}}}});
  ScenePackOptions o;
  o.pack.grid_fraction = 0.2;
  o.pack.bits = 10;
  const json before = doc.json["meshes"];
  const ScenePackReport r = pack_scene(doc, o);
  ASSERT_EQ(r.primitives.size(), 5u);
  EXPECT_NE(r.primitives[0].reason.find("TEXCOORD_0"), std::string::npos);
  EXPECT_NE(r.primitives[1].reason.find("COLOR_0"), std::string::npos);
  EXPECT_NE(r.primitives[2].reason.find("morph targets"), std::string::npos);
  EXPECT_NE(r.primitives[3].reason.find("mode 5"), std::string::npos);
  EXPECT_NE(r.primitives[4].reason.find("skinned"), std::string::npos);
  for (const auto& pr : r.primitives) EXPECT_FALSE(pr.compressed);
  EXPECT_EQ(doc.json["meshes"], before);  // untouched
  EXPECT_FALSE(doc.json.contains("extensionsUsed"));
}

// PackOptions::mode applies per primitive (issue 22): a 12-triangle cube at a target error is kept as it is, coded
// through the general path, and decodes to its 8 vertices.
TEST(GltfPackScene, ACubeIsCodedAsItIs) {
  Mesh cube;
  for (int i = 0; i < 8; ++i) cube.positions.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  cube.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  Document doc = document_from_mesh(cube, "cube");
  ScenePackOptions o;
  o.pack.target_error = 1e-3;
  const ScenePackReport r = pack_scene(doc, o);
  ASSERT_EQ(r.primitives.size(), 1u);
  ASSERT_TRUE(r.primitives[0].compressed) << r.primitives[0].reason;
  EXPECT_EQ(r.primitives[0].mode, "general") << r.primitives[0].mode_reason;
  EXPECT_EQ(r.primitives[0].vertices_out, 8u);
  EXPECT_EQ(decode_prm_primitive(doc, 0, 0).num_vertices(), 8u);
}

// An open primitive keeps its boundary loop, and the per-primitive report says so as `prm pack` does (issue 22);
// with fill_holes the loop is filled and reported filled.
TEST(GltfPackScene, AnOpenPrimitiveReportsItsBoundaryLoops) {
  Mesh sheet;  // a 9 x 9 height field: one boundary loop
  const int n = 8;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) sheet.positions.push_back({i / double(n), j / double(n), 0.1 * std::sin(3.0 * i / n)});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      sheet.triangles.push_back({a, b, d});
      sheet.triangles.push_back({a, d, c});
    }
  for (bool fill : {false, true}) {
    Document doc = document_from_mesh(sheet, "sheet");
    ScenePackOptions o;
    o.pack.grid_fraction = 0.05;
    o.pack.bits = 12;
    o.pack.fill_holes = fill;
    const ScenePackReport r = pack_scene(doc, o);
    ASSERT_EQ(r.primitives.size(), 1u);
    const PrimitiveReport& p = r.primitives[0];
    ASSERT_TRUE(p.compressed) << p.reason;
    EXPECT_EQ(p.boundary_loops_in, 1u);
    EXPECT_EQ(p.boundary_loops_out, fill ? 0u : 1u);
    EXPECT_EQ(p.holes_filled, fill ? 1u : 0u);
    EXPECT_FALSE(p.boundary_fallback);
  }
}

TEST(GltfPackScene, PacksAMeshAndTheStreamDecodesToTheAccessorCounts) {
  const Mesh spot = read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  Document doc = document_from_mesh(spot, "spot");
  ScenePackOptions o;
  o.pack.grid_fraction = 0.03;
  o.pack.bits = 10;
  const ScenePackReport r = pack_scene(doc, o);
  ASSERT_EQ(r.primitives.size(), 1u);
  ASSERT_TRUE(r.primitives[0].compressed) << r.primitives[0].reason;
  EXPECT_GT(r.primitives[0].rms, 0);
  EXPECT_LT(r.primitives[0].rms, 0.01);
  EXPECT_EQ(r.primitives[0].bytes_out, r.primitives[0].stream_bytes);
  const std::string path = temp_path("spot.glb");
  write_document(doc, path);
  Document back = read_document(path);
  EXPECT_EQ(back.json["extensionsRequired"], json::array({kExtensionName}));
  const codec::DecodedMesh d = decode_prm_primitive(back, 0, 0);
  EXPECT_EQ(d.num_vertices(), r.primitives[0].vertices_out);
  // A loader fills the accessors; afterwards the asset is plain.
  EXPECT_EQ(decode_prm_primitives(back, nullptr), 1u);
  EXPECT_FALSE(back.json.contains("extensionsUsed"));
  EXPECT_EQ(read_accessor(back, back.json["meshes"][0]["primitives"][0]["indices"].get<int64_t>(), "t").count,
            3 * d.num_triangles());
}

TEST(GltfExtension, MisplacedPrimitiveFieldsAreNamed) {
  const Mesh spot = read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  Document doc = document_from_mesh(spot, "spot");
  ScenePackOptions o;
  o.pack.grid_fraction = 0.05;
  o.pack.bits = 10;
  pack_scene(doc, o);
  auto expect = [&](const std::function<void(json&)>& edit, const std::string& fragment) {
    Document bad = doc;
    edit(bad.json["meshes"][0]["primitives"][0]);
    try {
      decode_prm_primitive(bad, 0, 0);
      ADD_FAILURE() << "no error, expected " << fragment;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect([](json& p) { p["extensions"][kExtensionName]["extra_field"] = 1; }, "unknown property 'extra_field'");
  expect([](json& p) { p["extensions"][kExtensionName]["version"] = "1"; }, "version must be an integer");
  expect([](json& p) { p["extensions"][kExtensionName]["attributes"]["NORMAL"] = 1; }, "attributes.NORMAL: version 1 streams carry POSITION only");
  expect([](json& p) { p["extensions"][kExtensionName].erase("attributes"); }, "attributes is missing");
  expect([](json& p) { p.erase("indices"); }, "indices is missing");
  expect([](json& p) { p["mode"] = 0; }, "mode must be 4");
  expect([](json& p) { p["attributes"]["TEXCOORD_0"] = 0; }, "attributes.TEXCOORD_0: only POSITION and NORMAL");
  expect([&](json& p) { p["indices"] = p["attributes"]["POSITION"]; }, "indices: accessor count");
}

}  // namespace
}  // namespace prm::gltf
