// validate_mesh on generated meshes with known answers.
#include "prm/mesh_validate.h"

#include <gtest/gtest.h>

#include "mesh_io_test_util.h"

namespace prm {
namespace {

TEST(MeshValidate, Tetrahedron) {
  const MeshReport r = validate_mesh(test::tetrahedron());
  EXPECT_EQ(r.vertices, 4u);
  EXPECT_EQ(r.faces, 4u);
  EXPECT_EQ(r.edges, 6u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.euler, 2);
  EXPECT_TRUE(r.closed() && r.manifold() && r.oriented() && r.clean());
  EXPECT_EQ(r.genus_sum(), 0);
  EXPECT_EQ(r.bbox_min, (Vec3{0, 0, 0}));
  EXPECT_EQ(r.bbox_max, (Vec3{1, 1, 1}));
  EXPECT_DOUBLE_EQ(r.diagonal, std::sqrt(3.0));
  EXPECT_TRUE(r.examples.empty());
}

TEST(MeshValidate, TorusHasGenusOne) {
  const Mesh t = test::torus();
  EXPECT_GT(test::signed_volume(t), 0);  // outward, as generated
  const MeshReport r = validate_mesh(t);
  EXPECT_EQ(r.euler, 0);
  EXPECT_TRUE(r.closed() && r.manifold() && r.oriented());
  ASSERT_EQ(r.per_component.size(), 1u);
  EXPECT_EQ(r.per_component[0].genus, 1);
  EXPECT_EQ(r.genus_sum(), 1);
  EXPECT_EQ(r.edges, 3 * t.num_faces() / 2);
}

TEST(MeshValidate, TwoComponentsAreCountedSeparately) {
  Mesh m = test::torus(10, 6);
  test::append(m, test::tetrahedron(10));
  const MeshReport r = validate_mesh(m);
  EXPECT_EQ(r.components, 2u);
  ASSERT_EQ(r.per_component.size(), 2u);
  EXPECT_EQ(r.per_component[0].faces, 120u);  // largest first
  EXPECT_EQ(r.per_component[0].genus, 1);
  EXPECT_EQ(r.per_component[1].faces, 4u);
  EXPECT_EQ(r.per_component[1].vertices, 4u);
  EXPECT_EQ(r.per_component[1].euler, 2);
  EXPECT_EQ(r.per_component[1].genus, 0);
  EXPECT_EQ(r.euler, 2);
  EXPECT_EQ(r.genus_sum(), 1);
}

TEST(MeshValidate, HolesAreBoundaryLoops) {
  const Mesh c = test::open_cylinder(16, 4);
  const MeshReport r = validate_mesh(c);
  EXPECT_FALSE(r.closed());
  EXPECT_EQ(r.boundary_edges, 32u);
  EXPECT_EQ(r.boundary_loops, 2u);
  EXPECT_EQ(r.per_component.at(0).boundary_loops, 2u);
  EXPECT_EQ(r.euler, 0);
  EXPECT_EQ(r.per_component.at(0).genus, 0);  // a sphere with two holes
  EXPECT_TRUE(r.manifold() && r.oriented());

  // A torus with two faces removed far apart: two holes, genus still 1.
  Mesh t = test::torus(12, 8);
  t.triangles.erase(t.triangles.begin() + 50);
  t.triangles.erase(t.triangles.begin() + 3);
  const MeshReport rt = validate_mesh(t);
  EXPECT_EQ(rt.boundary_loops, 2u);
  EXPECT_EQ(rt.boundary_edges, 6u);
  EXPECT_EQ(rt.per_component.at(0).genus, 1);
}

TEST(MeshValidate, NonManifoldEdge) {
  // Three triangles on one edge (0, 1).
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const MeshReport r = validate_mesh(m);
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_EQ(r.first_non_manifold_edge, (std::array<uint32_t, 2>{0, 1}));
  EXPECT_EQ(r.non_manifold_vertices, 0u);  // the faces at 0 and 1 meet at the edge: one fan each
  EXPECT_FALSE(r.manifold());
  EXPECT_EQ(r.per_component.at(0).genus, -1);
  EXPECT_EQ(r.genus_sum(), -1);
  bool named = false;
  for (const std::string& e : r.examples) named |= e == "edge (0, 1) has 3 faces";
  EXPECT_TRUE(named);
}

TEST(MeshValidate, PinchedVertex) {
  // Two tetrahedra sharing vertex 0 only.
  Mesh m = test::tetrahedron();
  Mesh b = test::tetrahedron();
  for (Vec3& p : b.positions) p = {-p[0], -p[1], -p[2]};
  for (Tri& t : b.triangles) std::swap(t[1], t[2]);
  test::append(m, b);
  for (Tri& t : m.triangles)
    for (uint32_t& v : t)
      if (v == 4) v = 0;
  m.positions.erase(m.positions.begin() + 4);
  for (Tri& t : m.triangles)
    for (uint32_t& v : t)
      if (v > 4) --v;
  const MeshReport r = validate_mesh(m);
  EXPECT_EQ(r.vertices, 7u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.non_manifold_vertices, 1u);
  EXPECT_EQ(r.first_non_manifold_vertex, 0u);
  EXPECT_EQ(r.components, 2u);  // components are joined through edges, and the two share none
  ASSERT_EQ(r.per_component.size(), 2u);
  for (const ComponentReport& c : r.per_component) {  // each is a tetrahedron on its own
    EXPECT_EQ(c.vertices, 4u);
    EXPECT_EQ(c.euler, 2);
    EXPECT_TRUE(c.manifold);
    EXPECT_EQ(c.genus, 0);
  }
  EXPECT_EQ(r.euler, 7 - 12 + 8);
  EXPECT_FALSE(r.manifold());
}

TEST(MeshValidate, InconsistentOrientationAndDegenerateAndDuplicateFaces) {
  Mesh m = test::tetrahedron();
  std::swap(m.triangles[3][1],
            m.triangles[3][2]);  // one face flipped: its three edges are traversed twice the same way
  MeshReport r = validate_mesh(m);
  EXPECT_EQ(r.inconsistent_edges, 3u);
  EXPECT_FALSE(r.oriented());
  EXPECT_EQ(r.per_component.at(0).genus, -1);

  m = test::tetrahedron();
  m.positions.push_back({0.5, 0, 0});  // 4: on edge (0, 1)
  m.positions.push_back({0, 0, 0});    // 5: coincides with 0
  m.triangles.push_back({0, 1, 4});    // zero area, collinear
  m.triangles.push_back({0, 5, 2});    // zero area, coincident corners
  m.triangles.push_back({1, 1, 2});    // repeated index
  m.triangles.push_back({1, 3, 0});    // duplicate of {0, 1, 3} (same orientation)
  m.triangles.push_back({0, 3, 1});    // duplicate, reversed
  r = validate_mesh(m);
  EXPECT_EQ(r.zero_area_faces, 2u);
  EXPECT_EQ(r.repeated_index_faces, 1u);
  EXPECT_EQ(r.duplicate_faces, 2u);
  EXPECT_FALSE(r.clean());
}

TEST(MeshValidate, UnreferencedVerticesAreCountedNotComponents) {
  Mesh m = test::tetrahedron();
  m.positions.push_back({9, 9, 9});
  const MeshReport r = validate_mesh(m);
  EXPECT_EQ(r.unreferenced_vertices, 1u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.euler, 2);
  EXPECT_EQ(r.bbox_max, (Vec3{9, 9, 9}));
}

TEST(MeshValidate, EmptyMeshAndBadIndex) {
  const MeshReport r = validate_mesh(Mesh{});
  EXPECT_EQ(r.components, 0u);
  EXPECT_EQ(r.diagonal, 0);
  Mesh bad = test::tetrahedron();
  bad.triangles[0][2] = 4;
  EXPECT_THROW(validate_mesh(bad), std::invalid_argument);
}

}  // namespace
}  // namespace prm
