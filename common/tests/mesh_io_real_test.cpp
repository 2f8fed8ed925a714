// The real meshes: every file of ../shared/meshes loads with the counts MANIFEST.md gives, bunny_zipper
// repairs to a closed genus-0 manifold, and every file of CGAL's data/meshes is either read or refused with
// an InputError. The data must be there (CI always has it): a missing file fails the test.
#include <dirent.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mesh_io_test_util.h"
#include "prm/error.h"
#include "prm/mesh_io.h"
#include "prm/mesh_repair.h"
#include "prm/mesh_validate.h"
#include "prm/vec3.h"

namespace prm {
namespace {

struct SharedMesh {
  const char* file;
  size_t file_vertices, vertices, faces, boundary_loops;
  int genus;  // -1: none (non-manifold)
};

void PrintTo(const SharedMesh& m, std::ostream* os) {
  *os << m.file;
}

class MeshIoShared : public testing::TestWithParam<SharedMesh> {};

TEST_P(MeshIoShared, LoadWithManifestCounts) {
  const SharedMesh& e = GetParam();
  ReadReport rep;
  const Mesh m = read_mesh(test::shared_mesh(e.file), {}, &rep);
  EXPECT_EQ(rep.file_vertices, e.file_vertices);
  EXPECT_EQ(rep.unreferenced_dropped, e.file_vertices - e.vertices);
  EXPECT_EQ(rep.vertices_welded, 0u);
  EXPECT_EQ(rep.degenerate_dropped, 0u);
  EXPECT_EQ(rep.polygons_triangulated, 0u);
  EXPECT_EQ(m.num_vertices(), e.vertices);
  EXPECT_EQ(m.num_faces(), e.faces);
  const MeshReport r = validate_mesh(m);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.boundary_loops, e.boundary_loops);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.inconsistent_edges, 0u);
  EXPECT_TRUE(r.clean());
  EXPECT_EQ(r.genus_sum(), e.genus);
  EXPECT_GT(r.diagonal, 0);
}

// MANIFEST.md: vertices in the file, referenced vertices, faces, boundary loops, genus.
INSTANTIATE_TEST_SUITE_P(Manifest, MeshIoShared,
                         testing::Values(SharedMesh{"horse.ply", 48485, 48485, 96966, 0, 0},
                                         SharedMesh{"venus.off", 50002, 50002, 100000, 0, 0},
                                         SharedMesh{"feline.off", 49864, 49864, 99732, 0, 2},
                                         SharedMesh{"bunny_zipper.ply", 35947, 34834, 69451, 5, 0},
                                         SharedMesh{"igea.ply", 134345, 134345, 268686, 0, 0},
                                         SharedMesh{"rocker-arm.off", 10044, 10044, 20088, 0, 1},
                                         SharedMesh{"fandisk.obj", 6475, 6475, 12946, 0, 0},
                                         SharedMesh{"feline_5k.obj", 4998, 4998, 10000, 0, 2},
                                         SharedMesh{"spot.obj", 2930, 2930, 5856, 0, 0},
                                         SharedMesh{"rabbit_1k_decimated.off", 1001, 1001, 2000, 0, -1}));

TEST(MeshIoSharedDetails, BunnyZipper) {
  ReadReport rep;
  const Mesh m = read_mesh(test::shared_mesh("bunny_zipper.ply"), {}, &rep);
  EXPECT_EQ(rep.unreferenced_dropped, 1113u);
  const MeshReport r = validate_mesh(m);
  EXPECT_EQ(r.boundary_edges, 223u);
  EXPECT_EQ(r.boundary_loops, 5u);
  EXPECT_TRUE(r.manifold());
  // Its extra vertex properties survive, for the kept vertices.
  const Property* conf = m.find_vertex_property("confidence");
  ASSERT_NE(conf, nullptr);
  EXPECT_EQ(conf->values.size(), m.num_vertices());
  EXPECT_NE(m.find_vertex_property("intensity"), nullptr);
}

TEST(MeshIoSharedDetails, IgeaFacesComeFromStrips) {
  ReadReport rep;
  const Mesh m = read_mesh(test::shared_mesh("igea.ply"), {}, &rep);
  EXPECT_EQ(rep.strip_triangles, 268686u);
  EXPECT_EQ(rep.file_faces, 1u);  // one tristrips record
  const MeshReport r = validate_mesh(m);
  EXPECT_TRUE(r.closed() && r.manifold() && r.oriented());
}

TEST(MeshIoSharedDetails, RabbitHasOnePinchedVertex) {
  const MeshReport r = validate_mesh(read_mesh(test::shared_mesh("rabbit_1k_decimated.off")));
  EXPECT_EQ(r.non_manifold_vertices, 1u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_EQ(r.euler, 1);
}

TEST(MeshIoSharedDetails, BunnyZipperRepairsToClosedGenusZero) {
  const Mesh in = read_mesh(test::shared_mesh("bunny_zipper.ply"));
  RepairReport rep;
  const Mesh m = repair_mesh(in, &rep);
  EXPECT_EQ(rep.holes_filled, 5u);
  EXPECT_EQ(rep.holes_fanned, 0u);
  EXPECT_EQ(rep.fill_triangles, 213u);  // loops of 39, 22, 42, 80 and 40 vertices, n - 2 triangles each
  EXPECT_EQ(rep.repeated_index_removed + rep.duplicate_removed + rep.pinched_vertices_split, 0u);
  EXPECT_EQ(m.num_vertices(), 34834u);
  EXPECT_EQ(m.num_faces(), 69451u + 213u);
  const MeshReport r = validate_mesh(m);
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.manifold());
  EXPECT_TRUE(r.oriented());
  EXPECT_TRUE(r.clean());
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.genus_sum(), 0);
  EXPECT_EQ(r.euler, 2);
  // No fill folds back over the scan: the largest angle between the normals of a new face and a face it shares an
  // edge with is 69.0 degrees (the bottom's 39-vertex loop). The paper's centroid fans met the rim there at up to
  // 163.5 degrees, and the remeshed bunny then missed that rim by 11.6x the 2e-4 target (bench/README.md
  // "Worst-case error", "Holes closed without folds").
  std::vector<std::vector<uint32_t>> faces_of = faces_around_vertices(m);
  const auto unit_normal = [&](uint32_t f) {
    const Tri& t = m.triangles[f];
    const Vec3 n = triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
    return n * (1.0 / norm(n));
  };
  double worst = 1;
  for (uint32_t f = 69451; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
      for (uint32_t g : faces_of[a])
        if (g != f && std::count(m.triangles[g].begin(), m.triangles[g].end(), b))
          worst = std::min(worst, dot(unit_normal(f), unit_normal(g)));
    }
  EXPECT_GT(worst, std::cos(70.0 * 3.14159265358979 / 180.0));
}

TEST(MeshIoSharedDetails, RabbitRepairsBySplittingThePinch) {
  RepairReport rep;
  const Mesh m = repair_mesh(read_mesh(test::shared_mesh("rabbit_1k_decimated.off")), &rep);
  EXPECT_EQ(rep.pinched_vertices_split, 1u);
  const MeshReport r = validate_mesh(m);
  EXPECT_TRUE(r.closed() && r.manifold() && r.oriented());
  EXPECT_EQ(r.genus_sum(), 0);
}

std::vector<std::string> list_dir(const std::string& dir) {
  std::vector<std::string> names;
  if (DIR* d = opendir(dir.c_str())) {
    while (dirent* e = readdir(d)) {
      const std::string n = e->d_name;
      if (n != "." && n != "..") names.push_back(n);
    }
    closedir(d);
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(MeshIoCgal, EveryFileIsReadOrRefusedCleanly) {
  const std::vector<std::string> names = list_dir(PRM_CGAL_MESHES);
  ASSERT_GT(names.size(), 100u) << "CGAL's data/meshes is missing from " << PRM_CGAL_MESHES
                                << " (libcgal-demo, extracted at configure time)";
  size_t read = 0;
  for (const std::string& n : names) {
    const std::string path = std::string(PRM_CGAL_MESHES) + "/" + n;
    try {
      ReadReport rep;
      const Mesh m = read_mesh(path, {}, &rep);
      const MeshReport r = validate_mesh(m);
      EXPECT_GT(r.faces, 0u) << n;
      ++read;
    } catch (const InputError& e) {
      // Only the point cloud is expected here; anything else is a reader bug or a new odd file to look at.
      EXPECT_EQ(n, "b9.ply") << e.what();
      EXPECT_NE(std::string(e.what()).find("point cloud"), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << n << ": " << e.what();
    }
  }
  EXPECT_EQ(read, names.size() - 1);
}

TEST(MeshIoCgal, EveryMeshRepairsToAClosedManifoldOrIsRefused) {
  for (const std::string& n : list_dir(PRM_CGAL_MESHES)) {
    if (n == "b9.ply") continue;  // a point cloud
    const Mesh in = read_mesh(std::string(PRM_CGAL_MESHES) + "/" + n);
    try {
      RepairReport rep;
      const MeshReport r = validate_mesh(repair_mesh(in, &rep));
      EXPECT_TRUE(r.closed() && r.manifold() && r.oriented()) << n;
    } catch (const InputError& e) {
      // Only the files whose faces were shuffled to random orientations (CGAL's orientation tests) are
      // refused.
      EXPECT_NE(n.find("shuffled"), std::string::npos) << n << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find("not consistently oriented"), std::string::npos) << e.what();
    }
  }
}

TEST(MeshIoCgal, OddOnes) {
  const std::string dir = std::string(PRM_CGAL_MESHES) + "/";
  {  // The header announces 7 faces; 8 follow. The extra one is ignored and reported.
    ReadReport rep;
    const Mesh m = read_mesh(dir + "prim.off", {}, &rep);
    ASSERT_EQ(rep.notes.size(), 1u);
    EXPECT_NE(rep.notes[0].find("after the last of the 7 faces"), std::string::npos) << rep.notes[0];
  }
  {  // Faces in random orientation.
    const MeshReport r = validate_mesh(read_mesh(dir + "cube-shuffled.off"));
    EXPECT_GT(r.inconsistent_edges, 0u);
    EXPECT_EQ(r.genus_sum(), -1);
  }
  {  // A binary STL: 3 corners per triangle, welded.
    ReadReport rep;
    const Mesh m = read_mesh(dir + "sphere.stl", {}, &rep);
    EXPECT_EQ(rep.vertices_welded, 3 * m.num_faces() - m.num_vertices());
    const MeshReport r = validate_mesh(m);
    EXPECT_TRUE(r.closed() && r.manifold() && r.oriented());
    EXPECT_EQ(r.genus_sum(), 0);
  }
  {  // Polygons with collinear corners and quads: triangulated, genus 3.
    ReadReport rep;
    const MeshReport r = validate_mesh(read_mesh(dir + "3torus.off", {}, &rep));
    EXPECT_GT(rep.polygons_triangulated, 0u);
    EXPECT_EQ(r.genus_sum(), 3);
  }
}

}  // namespace
}  // namespace prm
