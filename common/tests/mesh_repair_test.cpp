// repair_mesh on generated meshes: hole triangulations and fans, face removals, pinch splitting, sliver flips, refusals.
#include "prm/mesh_repair.h"

#include <gtest/gtest.h>

#include "mesh_io_test_util.h"
#include "prm/error.h"
#include "prm/mesh_validate.h"

namespace prm {
namespace {

void expect_closed_manifold(const Mesh& m, int genus) {
  const MeshReport r = validate_mesh(m);
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.manifold());
  EXPECT_TRUE(r.oriented());
  EXPECT_TRUE(r.clean()) << (r.examples.empty() ? "" : r.examples[0]);
  EXPECT_EQ(r.unreferenced_vertices, 0u);
  EXPECT_EQ(r.genus_sum(), genus);
}

TEST(MeshRepair, OpenCylinderGetsTwoFlatCaps) {
  const Mesh c = test::open_cylinder(16, 4);
  RepairReport rep;
  const Mesh m = repair_mesh(c, &rep);
  EXPECT_EQ(rep.holes_filled, 2u);
  EXPECT_EQ(rep.holes_fanned, 0u);
  EXPECT_EQ(rep.fill_triangles, 28u);  // n - 2 a loop of n
  EXPECT_EQ(m.num_vertices(), c.num_vertices());
  EXPECT_EQ(m.num_faces(), c.num_faces() + 28);
  expect_closed_manifold(m, 0);
  // Each cap is a triangulation of its planar loop: every new triangle lies in z = 0 or z = 4.
  for (size_t f = c.num_faces(); f < m.num_faces(); ++f) {
    const Tri& t = m.triangles[f];
    const double z = m.positions[t[0]][2];
    EXPECT_TRUE(z == 0 || z == 4) << z;
    EXPECT_EQ(m.positions[t[1]][2], z);
    EXPECT_EQ(m.positions[t[2]][2], z);
  }
}

TEST(MeshRepair, LongLoopsGetFansAroundTheirCentroids) {
  // Loops longer than the triangulation takes (O(n^3)) are closed by the paper's fans.
  const Mesh c = test::open_cylinder(500, 4);
  RepairReport rep;
  const Mesh m = repair_mesh(c, &rep);
  EXPECT_EQ(rep.holes_filled, 2u);
  EXPECT_EQ(rep.holes_fanned, 2u);
  EXPECT_EQ(rep.fill_triangles, 1000u);
  EXPECT_EQ(m.num_vertices(), c.num_vertices() + 2);
  expect_closed_manifold(m, 0);
  // The fan centres are the loops' centroids: (0, 0, 0) and (0, 0, 4).
  const Vec3& a = m.positions[m.num_vertices() - 2];
  const Vec3& b = m.positions[m.num_vertices() - 1];
  EXPECT_NEAR(std::fabs(a[0]) + std::fabs(a[1]) + std::fabs(b[0]) + std::fabs(b[1]), 0, 1e-12);
  EXPECT_NEAR(std::fabs(a[2] - b[2]), 4, 1e-12);
}

TEST(MeshRepair, TorusWithHolesKeepsItsGenus) {
  Mesh t = test::torus(12, 8);
  t.triangles.erase(t.triangles.begin() + 50);
  t.triangles.erase(t.triangles.begin() + 3);
  RepairReport rep;
  const Mesh m = repair_mesh(t, &rep);
  EXPECT_EQ(rep.holes_filled, 2u);
  EXPECT_EQ(rep.fill_triangles, 2u);  // each hole a triangle again
  expect_closed_manifold(m, 1);
}

TEST(MeshRepair, ClosedCleanMeshIsUnchanged) {
  const Mesh t = test::torus();
  RepairReport rep;
  const Mesh m = repair_mesh(t, &rep);
  EXPECT_EQ(m.positions, t.positions);
  EXPECT_EQ(m.triangles, t.triangles);
  EXPECT_EQ(rep.holes_filled + rep.duplicate_removed + rep.repeated_index_removed + rep.unreferenced_removed,
            0u);
}

TEST(MeshRepair, RepeatedIndexAndDuplicateFacesAreRemoved) {
  Mesh m = test::tetrahedron();
  m.triangles.push_back({1, 1, 2});
  m.triangles.push_back({1, 3, 0});  // repeats {0, 1, 3}
  m.triangles.push_back({0, 3, 1});  // repeats it reversed
  m.positions.push_back({7, 7, 7});  // unreferenced
  RepairReport rep;
  const Mesh out = repair_mesh(m, &rep);
  EXPECT_EQ(rep.repeated_index_removed, 1u);
  EXPECT_EQ(rep.duplicate_removed, 2u);
  EXPECT_EQ(rep.unreferenced_removed, 1u);
  EXPECT_EQ(rep.holes_filled, 0u);
  EXPECT_EQ(out.triangles, test::tetrahedron().triangles);  // the first of each set stays
  expect_closed_manifold(out, 0);
}

TEST(MeshRepair, PinchedVertexIsSplit) {
  // Two tetrahedra sharing vertex 0.
  Mesh m = test::tetrahedron();
  m.positions.push_back({-1, 0, 0});
  m.positions.push_back({0, -1, 0});
  m.positions.push_back({0, 0, -1});
  m.triangles.push_back({0, 4, 5});
  m.triangles.push_back({0, 6, 4});
  m.triangles.push_back({0, 5, 6});
  m.triangles.push_back({4, 6, 5});
  ASSERT_EQ(validate_mesh(m).non_manifold_vertices, 1u);
  RepairReport rep;
  const Mesh out = repair_mesh(m, &rep);
  EXPECT_EQ(rep.pinched_vertices_split, 1u);
  EXPECT_EQ(out.num_vertices(), 8u);
  EXPECT_EQ(out.positions[7], out.positions[0]);  // the copy sits where the vertex was
  const MeshReport r = validate_mesh(out);
  EXPECT_EQ(r.components, 2u);
  expect_closed_manifold(out, 0);
}

TEST(MeshRepair, PinchedBoundaryVertexIsSplitBeforeHolesAreFilled) {
  // A bow tie: two triangles sharing vertex 0; its boundary passes through 0 twice.
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  m.triangles = {{0, 1, 2}, {0, 3, 4}};
  RepairReport rep;
  const Mesh out = repair_mesh(m, &rep);
  EXPECT_EQ(rep.pinched_vertices_split, 1u);
  EXPECT_EQ(rep.holes_filled, 2u);
  EXPECT_EQ(rep.fill_triangles, 6u);
  EXPECT_EQ(out.num_vertices(), 6u + 2u);
  const MeshReport r = validate_mesh(out);
  EXPECT_EQ(r.components, 2u);
  EXPECT_TRUE(r.closed() && r.manifold() && r.oriented());
  EXPECT_EQ(r.genus_sum(), 0);
}

TEST(MeshRepair, ZeroAreaSliverIsFlippedAway) {
  // A tetrahedron whose face (0, 1, 3) is split at the midpoint 4 of edge (0, 1); the T-junction is closed by
  // the zero-area face (0, 1, 4).
  Mesh m = test::tetrahedron();
  m.positions.push_back({0.5, 0, 0});
  m.triangles = {{0, 2, 1}, {0, 4, 3}, {4, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 1, 4}};
  const MeshReport before = validate_mesh(m);
  ASSERT_TRUE(before.closed() && before.manifold() && before.oriented());
  ASSERT_EQ(before.zero_area_faces, 1u);
  RepairReport rep;
  const Mesh out = repair_mesh(m, &rep);
  EXPECT_EQ(rep.zero_area_flipped, 1u);
  EXPECT_EQ(out.num_faces(), 6u);
  expect_closed_manifold(out, 0);
  EXPECT_NEAR(test::signed_volume(out), 1.0 / 6, 1e-12);
}

TEST(MeshRepair, NonManifoldEdgeIsRefusedNamingTheEdge) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  try {
    repair_mesh(m);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("edge (0, 1)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("three or more faces"), std::string::npos) << e.what();
  }
}

TEST(MeshRepair, InconsistentOrientationIsRefusedNamingTheEdge) {
  Mesh m = test::tetrahedron();
  std::swap(m.triangles[3][1], m.triangles[3][2]);
  try {
    repair_mesh(m);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not consistently oriented"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("edge ("), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace prm
