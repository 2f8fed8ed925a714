// Hostile input: one small file per failure class and format (common/tests/data/hostile_*, written by
// generate.py). Each must throw prm::InputError (prm::IoError for a missing file) whose message names the
// file and the problem, without allocating for counts the file cannot hold.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "mesh_io_test_util.h"
#include "prm/error.h"
#include "prm/mesh_io.h"

namespace prm {
namespace {

struct HostileCase {
  const char* file;
  std::vector<const char*> message;  // substrings the message must contain (besides the file name)
};

void PrintTo(const HostileCase& c, std::ostream* os) {
  *os << c.file;
}

class MeshIoHostile : public testing::TestWithParam<HostileCase> {};

TEST_P(MeshIoHostile, ThrowsInputErrorNamingFileAndProblem) {
  const HostileCase& c = GetParam();
  const std::string path = test::data_path(c.file);
  ASSERT_TRUE(std::ifstream(path).good()) << "missing test file " << path;
  try {
    read_mesh(path);
    FAIL() << c.file << " was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    for (const char* m : c.message)
      EXPECT_NE(what.find(m), std::string::npos) << "'" << m << "' not in: " << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Truncated, MeshIoHostile,
    testing::Values(HostileCase{"hostile_truncated_binary.ply", {"face 3", "beyond the end of the file"}},
                    HostileCase{"hostile_truncated_ascii.ply",
                                {"unexpected end of file", "line 17", "counts do not match"}},
                    HostileCase{"hostile_no_end_header.ply", {"no end_header"}},
                    HostileCase{"hostile_truncated.off", {"only 49 bytes follow"}},
                    HostileCase{"hostile_truncated_binary.stl", {"264 bytes", "4 triangles (284 bytes)"}},
                    HostileCase{"hostile_truncated_solid_header.stl",
                                {"264 bytes", "4 triangles (284 bytes)"}},
                    HostileCase{"hostile_truncated_ascii.stl", {"no endsolid"}},
                    HostileCase{"hostile_truncated.glb", {"malformed glTF"}}));

INSTANTIATE_TEST_SUITE_P(
    CountsDoNotMatchContent, MeshIoHostile,
    testing::Values(HostileCase{"hostile_count_mismatch.ply", {"ends inside", "counts do not match"}},
                    HostileCase{"hostile_count_mismatch.off", {"claims 5 vertices and 4 faces"}},
                    HostileCase{"hostile_count_mismatch.stl", {"284 bytes", "5 triangles"}},
                    HostileCase{"hostile_list_count.ply", {"face 0", "list of 200 entries"}}));

INSTANTIATE_TEST_SUITE_P(
    NonFinite, MeshIoHostile,
    testing::Values(HostileCase{"hostile_nan.ply", {"vertex 0", "non-finite"}},
                    HostileCase{"hostile_nan.obj", {"line 1", "non-finite"}},
                    HostileCase{"hostile_inf.obj", {"line 2", "1e999", "does not fit a double"}},
                    HostileCase{"hostile_inf.off", {"vertex 1", "non-finite"}},
                    HostileCase{"hostile_nan.stl", {"vertex 1", "non-finite"}},
                    HostileCase{"hostile_nan.glb", {"vertex 0", "non-finite"}},
                    HostileCase{"hostile_not_a_number.obj", {"line 2", "'zero' is not a number"}},
                    HostileCase{"hostile_two_coordinates.obj", {"line 1", "2 coordinates"}}));

INSTANTIATE_TEST_SUITE_P(
    IndexOutOfRange, MeshIoHostile,
    testing::Values(HostileCase{"hostile_index.ply", {"face 3 uses vertex 9", "only 4 vertices"}},
                    HostileCase{"hostile_negative_index.ply", {"face 3", "vertex index -2"}},
                    HostileCase{"hostile_index.obj", {"uses vertex 4", "only 3 vertices"}},
                    HostileCase{"hostile_index_zero.obj", {"line 4", "vertex index 0"}},
                    HostileCase{"hostile_index_overflow.obj", {"line 4", "4294967297", "out of range"}},
                    HostileCase{"hostile_relative_index.obj", {"line 4", "-4", "before the first vertex"}},
                    HostileCase{"hostile_two_corners.obj", {"line 4", "2 corners"}},
                    HostileCase{"hostile_index.off", {"line 10", "face 3 uses vertex 7"}},
                    HostileCase{"hostile_four_vertices.stl", {"line 8", "4 vertices"}},
                    HostileCase{"hostile_index.glb", {"index 9 is out of range"}}));

INSTANTIATE_TEST_SUITE_P(
    NegativeOrHugeCounts, MeshIoHostile,
    testing::Values(HostileCase{"hostile_negative_count.ply", {"'vertex'", "negative"}},
                    HostileCase{"hostile_negative_count.off", {"line 2", "negative"}},
                    HostileCase{"hostile_billions.ply", {"4000000000", "at most 2^31"}},
                    HostileCase{"hostile_billions_fits.ply", {"2000000000", "only 52 bytes follow"}},
                    HostileCase{"hostile_billions.off", {"2000000000 vertices", "bytes follow"}},
                    HostileCase{"hostile_billions.stl", {"4294967295 triangles"}},
                    HostileCase{"hostile_billions.glb", {"1099511627776 elements", "past the end"}}));

INSTANTIATE_TEST_SUITE_P(
    GarbageAndEmpty, MeshIoHostile,
    testing::Values(HostileCase{"hostile_garbage.ply", {"not a PLY file"}},
                    HostileCase{"hostile_garbage.obj", {"no vertices and no faces"}},
                    HostileCase{"hostile_garbage.off", {"not an OFF file"}},
                    HostileCase{"hostile_garbage.stl", {"binary STL size is 1000 bytes"}},
                    HostileCase{"hostile_garbage.glb", {"malformed glTF"}},
                    HostileCase{"hostile_not_json.gltf", {"malformed glTF"}},
                    HostileCase{"hostile_device_buffer.gltf", {"dev/zero", "not a regular file"}},
                    HostileCase{"hostile_not_off.off", {"not an OFF file"}},
                    HostileCase{"hostile_no_faces.obj", {"no faces", "3 vertices"}},
                    HostileCase{"hostile_empty.ply", {"no end_header"}},
                    HostileCase{"hostile_empty.obj", {"empty"}}, HostileCase{"hostile_empty.off", {"empty"}},
                    HostileCase{"hostile_empty.stl", {"empty"}},
                    HostileCase{"hostile_empty.glb", {"empty"}}));

TEST(MeshIoHostileMisc, MissingFileIsAnIoError) {
  for (const char* ext : {".ply", ".obj", ".off", ".stl", ".glb", ".gltf", ""}) {
    const std::string path = test::data_path(std::string("does_not_exist") + ext);
    try {
      read_mesh(path);
      FAIL() << path;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
    }
  }
}

TEST(MeshIoHostileMisc, UnknownFormat) {
  const std::string path = test::temp_path("unknown.xyz");
  {
    std::ofstream f(path);
    f << "\x01\x02 nothing a mesh reader knows\n";
  }
  try {
    read_mesh(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown mesh format"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

// Every truncation of valid binary and text files is refused cleanly (or, at a record boundary where the file
// still parses, accepted): never a crash, never another exception type. Run under ASan in CI.
TEST(MeshIoHostileMisc, EveryTruncationOfValidFiles) {
  for (const char* name :
       {"tet_binary_le.ply", "tet_binary_be.ply", "tet_ascii.ply", "strips.ply", "tet_binary.stl",
        "tet_ascii.stl", "tet.off", "tet_coff.off", "cube_quads.obj", "tet.glb", "tet_transformed.gltf"}) {
    std::ifstream in(test::data_path(name), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string ext = std::string(name).substr(std::string(name).find_last_of('.'));
    const std::string path = test::temp_path(std::string("trunc") + ext);
    for (size_t n = 0; n < bytes.size(); ++n) {
      {
        std::ofstream out(path, std::ios::binary);
        out.write(bytes.data(), static_cast<std::streamsize>(n));
      }
      try {
        read_mesh(path);
      } catch (const InputError&) {
      } catch (const std::exception& e) {
        ADD_FAILURE() << name << " cut at " << n << ": " << e.what();
      }
    }
    std::remove(path.c_str());
  }
}

// Every byte of valid files flipped to a few values: never a crash, only InputError.
TEST(MeshIoHostileMisc, EveryByteFlipped) {
  for (const char* name : {"tet_binary_le.ply", "tet_ascii.ply", "strips.ply", "tet_binary.stl", "tet.off",
                           "tet.glb", "cube_quads.obj"}) {
    std::ifstream in(test::data_path(name), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string ext = std::string(name).substr(std::string(name).find_last_of('.'));
    const std::string path = test::temp_path(std::string("flip") + ext);
    for (size_t i = 0; i < bytes.size(); ++i) {
      const char orig = bytes[i];
      for (char v : {'\0', '\xff', '\x7f', '9', '-'}) {
        bytes[i] = v;
        {
          std::ofstream out(path, std::ios::binary);
          out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        }
        try {
          read_mesh(path);
        } catch (const InputError&) {
        } catch (const std::exception& e) {
          ADD_FAILURE() << name << " byte " << i << " = " << static_cast<int>(v) << ": " << e.what();
        }
      }
      bytes[i] = orig;
    }
    std::remove(path.c_str());
  }
}

TEST(MeshIoHostileMisc, HugePolygonIsFanTriangulatedQuickly) {
  // One face with 200000 corners on a circle: ear clipping would be quadratic or worse, the reader falls back
  // to a fan.
  const size_t n = 200000;
  std::string s = "OFF\n" + std::to_string(n) + " 1 0\n";
  for (size_t i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * static_cast<double>(i) / static_cast<double>(n);
    s += std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
  }
  s += std::to_string(n);
  for (size_t i = 0; i < n; ++i) s += " " + std::to_string(i);
  s += "\n";
  const std::string path = test::temp_path("huge_polygon.off");
  {
    std::ofstream f(path, std::ios::binary);
    f << s;
  }
  ReadReport rep;
  ReadOptions o;
  o.weld = ReadOptions::Weld::Never;  // std::to_string keeps 6 decimals: neighbouring corners may coincide
  const Mesh m = read_mesh(path, o, &rep);
  EXPECT_EQ(m.num_faces() + rep.degenerate_dropped, n - 2);
  EXPECT_EQ(rep.polygons_triangulated, 1u);
  ASSERT_FALSE(rep.notes.empty());
  EXPECT_NE(rep.notes.back().find("fans"), std::string::npos);
  std::remove(path.c_str());
}

// Welding within a tolerance on coordinates beyond 4e18 tolerances: they once shared one clamped grid cell (a
// binary STL of distinct coordinates near 1e17 with --weld-tolerance 1e-3: 3.5 s for 1 MB, quadratic). There the
// tolerance is below the spacing of doubles, so only equal coordinates weld; the cell is the value itself.
TEST(MeshIoHostileMisc, WeldingWithinAToleranceOnHugeCoordinatesWeldsEqualOnesOnly) {
  const double big = 1e17, next = std::nextafter(big, 2e17), tiny = 1e-4;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "OFF\n8 3 0\n%.17g %.17g %.17g\n%.17g %.17g %.17g\n%.17g %.17g %.17g\n%.17g %.17g %.17g\n"
                "%.17g %.17g %.17g\n0 0 0\n%.17g 0 0\n0 1 0\n3 0 2 3\n3 1 4 3\n",
                big, big, big,      // 0
                big, big, -big,     // 1
                next, big, big,     // 2: one ulp (16) from vertex 0 in x: not within 1e-3
                big, big, big,      // 3: vertex 0 again: welds
                big, big, -big,     // 4: vertex 1 again: welds
                tiny);              // 6: 1e-4 from vertex 5: welds
  const std::string path = test::temp_path("huge_coordinates_weld.off");
  {
    std::ofstream f(path, std::ios::binary);
    f << buf << "3 5 6 7\n";
  }
  ReadOptions o;
  o.weld = ReadOptions::Weld::Always;
  o.weld_tolerance = 1e-3;
  ReadReport rep;
  const Mesh m = read_mesh(path, o, &rep);
  EXPECT_EQ(rep.vertices_welded, 3u);  // 3 into 0, 4 into 1, 6 into 5
  std::remove(path.c_str());
}

// A second 'face' (or 'vertex') element, or 'face' with 'tristrips', gave the polygons properties of another length:
// finish_mesh read past them (ASan heap-buffer-overflow; found by common/fuzz/mesh_read_fuzzer.cpp). Refused by name.
TEST(MeshIoHostileMisc, PlyWithARepeatedVertexOrFaceElementIsRefused) {
  const std::string path = test::temp_path("repeated_element.ply");
  const auto expect = [&](const std::string& elements, const std::string& body, const std::string& fragment) {
    {
      std::ofstream f(path, std::ios::binary);
      f << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        << elements << "end_header\n0 0 0\n1 0 0\n0 1 0\n" << body;
    }
    try {
      read_mesh(path);
      ADD_FAILURE() << "no error for " << elements;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect("element face 0\nproperty list uchar int vertex_indices\nproperty int t\n"
         "element face 1\nproperty list uchar int vertex_indices\n",
         "3 0 1 2\n", "element 'face' appears twice in the header");
  expect("element face 1\nproperty list uchar int vertex_indices\nproperty int t\n"
         "element tristrips 1\nproperty list int int vertex_indices\n",
         "3 0 1 2 7\n3 0 1 2\n", "elements 'face' and 'tristrips' together");
  expect("element vertex 0\nproperty float x\nproperty float y\nproperty float z\nproperty float c\n"
         "element face 1\nproperty list uchar int vertex_indices\n",
         "3 0 1 2\n", "element 'vertex' appears twice in the header");
  std::remove(path.c_str());
}

}  // namespace
}  // namespace prm
