// Every reader on small hand-made files (common/tests/data, written by generate.py), and write -> read round
// trips.
#include "prm/mesh_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "mesh_io_test_util.h"
#include "prm/error.h"
#include "prm/mesh_validate.h"

namespace prm {
namespace {

using test::data_path;

// The tetrahedron of generate.py, read from any format: 4 vertices, 4 faces, closed, outward.
void expect_tetrahedron(const Mesh& m, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(m.num_vertices(), 4u);
  ASSERT_EQ(m.num_faces(), 4u);
  const MeshReport r = validate_mesh(m);
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.manifold());
  EXPECT_TRUE(r.oriented());
  EXPECT_EQ(r.per_component.at(0).genus, 0);
  EXPECT_NEAR(test::signed_volume(m), 1.0 / 6, 1e-12);
}

TEST(MeshIoPly, AsciiWithPropertiesCommentsAndUnknownElement) {
  ReadReport rep;
  const Mesh m = read_mesh(data_path("tet_ascii.ply"), {}, &rep);
  expect_tetrahedron(m, "tet_ascii.ply");
  EXPECT_EQ(rep.format, MeshFormat::Ply);
  EXPECT_EQ(rep.file_vertices, 4u);
  EXPECT_EQ(rep.file_faces, 4u);
  ASSERT_EQ(m.comments.size(), 2u);
  EXPECT_EQ(m.comments[0], "made by generate.py");
  EXPECT_EQ(m.comments[1], "  two leading blanks kept");
  const Property* conf = m.find_vertex_property("confidence");
  ASSERT_NE(conf, nullptr);
  EXPECT_EQ(conf->type, ScalarType::Float32);
  EXPECT_EQ(conf->values, (std::vector<double>{0, 0.25, 0.5, 0.75}));
  const Property* red = m.find_vertex_property("red");
  ASSERT_NE(red, nullptr);
  EXPECT_EQ(red->type, ScalarType::UInt8);
  EXPECT_EQ(red->values, (std::vector<double>{0, 10, 20, 30}));
  const Property* relief = m.find_face_property("relief");
  ASSERT_NE(relief, nullptr);
  EXPECT_EQ(relief->type, ScalarType::Int32);
  EXPECT_EQ(relief->values, (std::vector<double>{-1, 0, 1, 2}));
  EXPECT_EQ(m.find_vertex_property("shine"), nullptr);  // the unknown element is skipped
}

TEST(MeshIoPly, PropertiesCanBeLeftOut) {
  ReadOptions o;
  o.keep_properties = false;
  const Mesh m = read_mesh(data_path("tet_ascii.ply"), o);
  EXPECT_TRUE(m.vertex_properties.empty());
  EXPECT_TRUE(m.face_properties.empty());
}

TEST(MeshIoPly, BinaryLittleEndianDoublePositionsAndSkippedElement) {
  const Mesh m = read_mesh(data_path("tet_binary_le.ply"));
  expect_tetrahedron(m, "tet_binary_le.ply");
  const Property* label = m.find_vertex_property("label");
  ASSERT_NE(label, nullptr);
  EXPECT_EQ(label->type, ScalarType::Int16);
  EXPECT_EQ(label->values, (std::vector<double>{0, -1, -2, -3}));
  EXPECT_EQ(m.comments, std::vector<std::string>{"little endian"});
}

TEST(MeshIoPly, BinaryBigEndianVertexIndexWithUintCount) {
  expect_tetrahedron(read_mesh(data_path("tet_binary_be.ply")), "tet_binary_be.ply");
}

TEST(MeshIoPly, TriangleStripsWithRestartsAndParity) {
  ReadReport rep;
  const Mesh m = read_mesh(data_path("strips.ply"), {}, &rep);
  // Run 0 4 1 5 2 6 gives 4 triangles, run 2 6 3 7 7 gives 2 (its last one repeats 7 and is skipped).
  EXPECT_EQ(rep.strip_triangles, 6u);
  EXPECT_EQ(rep.file_faces, 1u);
  ASSERT_EQ(m.num_faces(), 6u);
  EXPECT_EQ(m.triangles[0], (Tri{0, 4, 1}));
  EXPECT_EQ(m.triangles[1], (Tri{1, 4, 5}));  // odd: (s[k+1], s[k], s[k+2])
  EXPECT_EQ(m.triangles[4], (Tri{2, 6, 3}));  // parity restarts after -1
  EXPECT_EQ(m.triangles[5], (Tri{3, 6, 7}));
  const MeshReport r = validate_mesh(m);
  EXPECT_TRUE(r.oriented());  // strips alternate, the decoded faces agree
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_EQ(r.per_component.at(0).genus, 0);
  ASSERT_FALSE(rep.notes.empty());
  EXPECT_NE(rep.notes[0].find("1 strip triangles"), std::string::npos);
}

TEST(MeshIoPly, PolygonsAreTriangulated) {
  ReadReport rep;
  const Mesh m = read_mesh(data_path("polygons.ply"), {}, &rep);
  EXPECT_EQ(rep.polygons_triangulated, 2u);
  EXPECT_EQ(m.num_faces(), 2u + 3u);             // a quad and a pentagon
  EXPECT_NEAR(test::area(m), 1.0 + 2.5, 1e-12);  // the pentagon (1,0) (2,0) (3,1) (2,2) (1,1) has area 2.5
}

TEST(MeshIoObj, QuadsCommentsAndTriangulation) {
  ReadReport rep;
  const Mesh m = read_mesh(data_path("cube_quads.obj"), {}, &rep);
  EXPECT_EQ(rep.format, MeshFormat::Obj);
  EXPECT_EQ(rep.file_faces, 6u);
  EXPECT_EQ(rep.polygons_triangulated, 6u);
  ASSERT_EQ(m.num_faces(), 12u);
  const MeshReport r = validate_mesh(m);
  EXPECT_TRUE(r.closed() && r.manifold() && r.oriented());
  EXPECT_NEAR(std::fabs(test::signed_volume(m)), 1.0, 1e-12);
  EXPECT_EQ(m.comments, (std::vector<std::string>{"a unit cube of quads", "second comment"}));
}

TEST(MeshIoObj, NegativeIndices) {
  expect_tetrahedron(read_mesh(data_path("negative_indices.obj")), "negative_indices.obj");
}

TEST(MeshIoObj, CornerFormsGroupsAndMaterials) {
  ReadReport rep;
  const Mesh m = read_mesh(data_path("corner_forms.obj"), {}, &rep);
  expect_tetrahedron(m, "corner_forms.obj");
  EXPECT_EQ(m.comments, std::vector<std::string>{"apex"});
}

TEST(MeshIoObj, ConcavePolygonIsEarClipped) {
  const Mesh m = read_mesh(data_path("concave.obj"));
  ASSERT_EQ(m.num_faces(), 4u);
  EXPECT_NEAR(test::area(m), 3.0, 1e-12);  // a fan from the first corner would overlap and not sum to 3
  for (const Tri& t : m.triangles) {  // every triangle keeps the polygon's (counter-clockwise) orientation
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    EXPECT_GT((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]), 0);
  }
}

TEST(MeshIoOff, Variants) {
  for (const char* name : {"tet.off", "tet_counts_on_keyword_line.off", "tet_noff.off", "tet_coff.off"}) {
    ReadReport rep;
    expect_tetrahedron(read_mesh(data_path(name), {}, &rep), name);
    EXPECT_EQ(rep.format, MeshFormat::Off);
  }
  const Mesh m = read_mesh(data_path("tet_counts_on_keyword_line.off"));
  EXPECT_EQ(m.comments, (std::vector<std::string>{"comment before", "vertices"}));
}

TEST(MeshIoOff, UnreferencedVerticesAndRepeatedIndexFacesAreDroppedAndCounted) {
  ReadReport rep;
  const Mesh m = read_mesh(data_path("unreferenced.off"), {}, &rep);
  EXPECT_EQ(rep.file_vertices, 6u);
  EXPECT_EQ(rep.file_faces, 6u);
  EXPECT_EQ(rep.unreferenced_dropped, 2u);
  EXPECT_EQ(rep.polygons_triangulated, 1u);
  EXPECT_EQ(rep.degenerate_dropped, 2u);  // "3 0 0 1" and half of "4 0 1 2 2"
  EXPECT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(m.num_faces(), 5u);
  EXPECT_EQ(validate_mesh(m).duplicate_faces, 1u);  // what is left of the quad repeats a face

  ReadOptions keep;
  keep.drop_unreferenced = false;
  EXPECT_EQ(read_mesh(data_path("unreferenced.off"), keep).num_vertices(), 6u);
}

TEST(MeshIoStl, AsciiBinaryAndSolidHeaderBinaryAreWelded) {
  for (const char* name : {"tet_ascii.stl", "tet_binary.stl", "tet_binary_solid_header.stl"}) {
    ReadReport rep;
    expect_tetrahedron(read_mesh(data_path(name), {}, &rep), name);
    EXPECT_EQ(rep.format, MeshFormat::Stl);
    EXPECT_EQ(rep.file_vertices, 12u);
    EXPECT_EQ(rep.vertices_welded, 8u);
  }
  ReadOptions never;
  never.weld = ReadOptions::Weld::Never;
  const Mesh soup = read_mesh(data_path("tet_binary.stl"), never);
  EXPECT_EQ(soup.num_vertices(), 12u);
  EXPECT_EQ(validate_mesh(soup).components, 4u);
}

TEST(MeshIoStl, WeldTolerance) {
  ReadReport exact;
  const Mesh a = read_mesh(data_path("near_coincident.stl"), {}, &exact);
  EXPECT_EQ(a.num_vertices(), 6u);  // corners 1e-6 apart stay apart by default
  EXPECT_EQ(validate_mesh(a).components, 2u);
  ReadOptions o;
  o.weld_tolerance = 1e-5;
  o.weld = ReadOptions::Weld::Always;
  ReadReport rep;
  const Mesh b = read_mesh(data_path("near_coincident.stl"), o, &rep);
  EXPECT_EQ(rep.vertices_welded, 2u);
  EXPECT_EQ(b.num_vertices(), 4u);
  EXPECT_EQ(validate_mesh(b).components, 1u);
  EXPECT_EQ(b.positions[1], (Vec3{1, 0, 0}));  // the first of the coincident vertices is kept
}

TEST(MeshIoWeld, HashGridMatchesBruteForce) {
  // Random points on a coarse lattice plus jitter: the grid must find every pair within the tolerance that
  // the first-come rule would join.
  Mesh m;
  uint32_t seed = 12345;
  auto rnd = [&] {
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) / 16777216.0;
  };
  for (int i = 0; i < 600; ++i)
    m.positions.push_back(
        {std::floor(rnd() * 8) + rnd() * 1e-3, std::floor(rnd() * 8), std::floor(rnd() * 8)});
  for (uint32_t i = 0; i + 2 < m.positions.size(); i += 3) m.triangles.push_back({i, i + 1, i + 2});
  const std::string path = test::temp_path("weld.ply");
  WriteOptions w;
  w.double_positions = true;
  write_mesh(m, path, w);
  ReadOptions o;
  o.weld = ReadOptions::Weld::Always;
  o.weld_tolerance = 2e-3;
  o.drop_unreferenced = false;
  ReadReport rep;
  const Mesh welded = read_mesh(path, o, &rep);
  // Brute force with the same rule: each vertex joins the first earlier representative within the tolerance.
  std::vector<uint32_t> reps;
  size_t merged = 0;
  for (uint32_t v = 0; v < m.positions.size(); ++v) {
    bool joined = false;
    for (uint32_t r : reps) {
      const Vec3 &a = m.positions[v], &b = m.positions[r];
      if (std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) <= o.weld_tolerance) {
        joined = true;
        break;
      }
    }
    if (joined)
      ++merged;
    else
      reps.push_back(v);
  }
  EXPECT_EQ(rep.vertices_welded, merged);
  EXPECT_EQ(welded.num_vertices(), reps.size());
  std::remove(path.c_str());
}

TEST(MeshIoGltf, NodeTransformsAreApplied) {
  ReadReport rep;
  const Mesh m = read_mesh(data_path("tet_transformed.gltf"), {}, &rep);
  EXPECT_EQ(rep.format, MeshFormat::Gltf);
  ASSERT_EQ(m.num_vertices(), 4u);
  // Parent translation (10, 0, 0) applied after the child's scale 2.
  EXPECT_EQ(m.positions[0], (Vec3{10, 0, 0}));
  EXPECT_EQ(m.positions[1], (Vec3{12, 0, 0}));
  EXPECT_EQ(m.positions[3], (Vec3{10, 0, 2}));
  EXPECT_NEAR(test::signed_volume(m), 8.0 / 6, 1e-12);
  ASSERT_FALSE(rep.notes.empty());  // the LINES primitive was skipped, and said so
  EXPECT_NE(rep.notes[0].find("not made of triangles"), std::string::npos);
}

TEST(MeshIoGltf, GlbAndInstancedMirroredMeshKeepOutwardFaces) {
  expect_tetrahedron(read_mesh(data_path("tet.glb")), "tet.glb");
  expect_tetrahedron(read_mesh(data_path("tet_external.gltf")),
                     "tet_external.gltf");  // buffer in a .bin beside it
  const Mesh m = read_mesh(data_path("tet_instanced.glb"));
  EXPECT_EQ(m.num_vertices(), 8u);
  EXPECT_EQ(m.num_faces(), 8u);
  const MeshReport r = validate_mesh(m);
  EXPECT_EQ(r.components, 2u);
  EXPECT_TRUE(r.oriented() && r.closed());
  EXPECT_NEAR(test::signed_volume(m), 2.0 / 6, 1e-12);  // the mirrored copy was flipped back outward
}

TEST(MeshIoFormat, ByExtensionAndByContent) {
  EXPECT_EQ(format_from_path("a/b.PLY"), MeshFormat::Ply);
  EXPECT_EQ(format_from_path("x.obj"), MeshFormat::Obj);
  EXPECT_EQ(format_from_path("x.glb"), MeshFormat::Glb);
  EXPECT_EQ(format_from_path("dir.ply/mesh"), MeshFormat::Auto);
  // Files without a known extension are recognised from their first bytes (binary STL from its size).
  for (const char* name :
       {"tet_ascii.ply", "tet.off", "tet_binary.stl", "tet_ascii.stl", "cube_quads.obj", "tet.glb"}) {
    const std::string src = data_path(name), dst = test::temp_path(std::string(name) + ".mesh");
    {
      std::ifstream in(src, std::ios::binary);
      std::ofstream out(dst, std::ios::binary);
      out << in.rdbuf();
    }
    ReadReport rep;
    EXPECT_NO_THROW(read_mesh(dst, {}, &rep)) << name;
    EXPECT_EQ(rep.format, format_from_path(src)) << name;
    std::remove(dst.c_str());
  }
}

// ------------------------------------------------------------------------------------------------ round
// trips

Mesh labelled_mesh() {
  Mesh m = test::torus(6, 5);
  for (Vec3& p : m.positions)
    for (double& c : p) c = c * 0.7310585786300049 + 1e-9;  // values that need all 17 digits
  std::vector<double> relief(m.num_vertices()), li(m.num_vertices()), conf(m.num_vertices());
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    relief[v] = static_cast<double>(v % 7) - 1;
    li[v] = -1000000.0 + static_cast<double>(v);
    conf[v] = static_cast<float>(0.1 * static_cast<double>(v));
  }
  m.set_vertex_property("relief", ScalarType::Int32, relief);
  m.set_vertex_property("lattice_i", ScalarType::Int32, li);
  m.set_vertex_property("confidence", ScalarType::Float32, conf);
  std::vector<double> fr(m.num_faces()), reg(m.num_faces()), w(m.num_faces());
  for (size_t f = 0; f < m.num_faces(); ++f) {
    fr[f] = static_cast<double>(f % 5) - 1;
    reg[f] = f % 2;
    w[f] = 1.0 / (1.0 + static_cast<double>(f));
  }
  m.set_face_property("relief", ScalarType::Int32, fr);
  m.set_face_property("regular", ScalarType::UInt8, reg);
  m.set_face_property("weight", ScalarType::Float64, w);
  m.set_face_property("tag", ScalarType::Int8, std::vector<double>(m.num_faces(), -128));
  m.set_face_property("code", ScalarType::UInt16, std::vector<double>(m.num_faces(), 65535));
  m.set_face_property("big", ScalarType::UInt32, std::vector<double>(m.num_faces(), 4294967295.0));
  m.set_face_property("small", ScalarType::Int16, std::vector<double>(m.num_faces(), -32768));
  m.comments = {"prm-frame bits 12 origin 0.10000000000000001 -2 3 step 0.001 grid 7", "prm-relief 0 axis 4",
                ""};
  return m;
}

void expect_same(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.comments, b.comments);
  ASSERT_EQ(a.vertex_properties.size(), b.vertex_properties.size());
  for (size_t i = 0; i < a.vertex_properties.size(); ++i) {
    EXPECT_EQ(a.vertex_properties[i].name, b.vertex_properties[i].name);
    EXPECT_EQ(a.vertex_properties[i].type, b.vertex_properties[i].type);
    EXPECT_EQ(a.vertex_properties[i].values, b.vertex_properties[i].values) << a.vertex_properties[i].name;
  }
  ASSERT_EQ(a.face_properties.size(), b.face_properties.size());
  for (size_t i = 0; i < a.face_properties.size(); ++i) {
    EXPECT_EQ(a.face_properties[i].name, b.face_properties[i].name);
    EXPECT_EQ(a.face_properties[i].type, b.face_properties[i].type);
    EXPECT_EQ(a.face_properties[i].values, b.face_properties[i].values) << a.face_properties[i].name;
  }
}

TEST(MeshIoRoundTrip, PlyBinaryAndAsciiWithDoublePositionsPropertiesAndCommentsIsExact) {
  const Mesh m = labelled_mesh();
  for (bool binary : {true, false}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const std::string path = test::temp_path(binary ? "rt_bin.ply" : "rt_ascii.ply");
    WriteOptions w;
    w.binary = binary;
    w.double_positions = true;
    write_mesh(m, path, w);
    ReadReport rep;
    expect_same(m, read_mesh(path, {}, &rep));
    EXPECT_TRUE(rep.notes.empty());
    std::remove(path.c_str());
  }
}

TEST(MeshIoRoundTrip, PlyFloatPositionsRoundToFloat) {
  Mesh m = labelled_mesh();
  for (bool binary : {true, false}) {
    const std::string path = test::temp_path("rt_float.ply");
    WriteOptions w;
    w.binary = binary;
    write_mesh(m, path, w);
    const Mesh back = read_mesh(path);
    for (size_t v = 0; v < m.num_vertices(); ++v)
      for (size_t a = 0; a < 3; ++a)
        EXPECT_EQ(back.positions[v][a], static_cast<double>(static_cast<float>(m.positions[v][a])));
    // Float positions read back and written again are exact.
    write_mesh(back, path, w);
    EXPECT_EQ(read_mesh(path).positions, back.positions);
    std::remove(path.c_str());
  }
}

TEST(MeshIoRoundTrip, PlyWithoutProperties) {
  Mesh m = labelled_mesh();
  const std::string path = test::temp_path("rt_noprops.ply");
  WriteOptions w;
  w.write_properties = false;
  write_mesh(m, path, w);
  const Mesh back = read_mesh(path);
  EXPECT_TRUE(back.vertex_properties.empty());
  EXPECT_TRUE(back.face_properties.empty());
  std::remove(path.c_str());
}

TEST(MeshIoRoundTrip, PlyRefusesAValueItsTypeCannotHold) {
  Mesh m = test::tetrahedron();
  m.set_face_property("regular", ScalarType::UInt8, {0, 1, 256, 0});
  EXPECT_THROW(write_mesh(m, test::temp_path("bad.ply")), std::invalid_argument);
}

TEST(MeshIoRoundTrip, ObjAndOffAreExact) {
  Mesh m = labelled_mesh();
  m.vertex_properties.clear();
  m.face_properties.clear();
  for (const char* name : {"rt.obj", "rt.off"}) {
    SCOPED_TRACE(name);
    const std::string path = test::temp_path(name);
    write_mesh(m, path);
    const Mesh back = read_mesh(path);
    EXPECT_EQ(back.positions, m.positions);
    EXPECT_EQ(back.triangles, m.triangles);
    EXPECT_EQ(back.comments, m.comments);
    std::remove(path.c_str());
  }
}

TEST(MeshIoRoundTrip, GlbAndGltf) {
  const Mesh m = test::torus(9, 7);
  for (const char* name : {"rt.glb", "rt.gltf"}) {
    SCOPED_TRACE(name);
    const std::string path = test::temp_path(name);
    write_mesh(m, path);
    ReadReport rep;
    const Mesh back = read_mesh(path, {}, &rep);
    EXPECT_EQ(rep.vertices_welded, 0u);
    EXPECT_EQ(back.triangles, m.triangles);
    ASSERT_EQ(back.num_vertices(), m.num_vertices());
    for (size_t v = 0; v < m.num_vertices(); ++v)
      for (size_t a = 0; a < 3; ++a)
        EXPECT_EQ(back.positions[v][a], static_cast<double>(static_cast<float>(m.positions[v][a])));
    if (std::string(name) == "rt.glb") {
      std::ifstream f(path, std::ios::binary);
      char magic[4] = {0};
      f.read(magic, 4);
      EXPECT_EQ(std::string(magic, 4), "glTF");
    }
    std::remove(path.c_str());
  }
}

TEST(MeshIoWrite, UnknownFormatAndBadIndicesAreRefused) {
  const Mesh m = test::tetrahedron();
  EXPECT_THROW(write_mesh(m, test::temp_path("x.stl")), InputError);
  EXPECT_THROW(write_mesh(m, test::temp_path("x.unknown")), InputError);
  Mesh bad = m;
  bad.triangles[0][0] = 99;
  EXPECT_THROW(write_mesh(bad, test::temp_path("x.ply")), std::invalid_argument);
  EXPECT_THROW(write_mesh(m, "/nonexistent-dir/x.ply"), IoError);
}

}  // namespace
}  // namespace prm
