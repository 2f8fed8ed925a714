// simplify_boundary (issue 22): a 1-D simplification of an open surface's boundary loops before remeshing. The loops
// stay loops (as many, the mesh an oriented 2-manifold), every input boundary vertex stays within the tolerance of
// the simplified loop, no interior vertex moves, and a boundary wigglier than the tolerance is kept.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "grid_sheet.h"
#include "prm/boundary_deviation.h"
#include "prm/mesh_validate.h"
#include "prm/pipeline/boundary_simplification.h"

namespace {

using prm::Mesh;

// An n x n grid of the unit square, z = 0, its border rippled by `ripple` (in y on the side y = 0).
Mesh sheet(int n, double ripple) {
  return prm::test::grid_sheet(n, [ripple](int i, int j, double x, double y) {
    return prm::Vec3{x, y + (j == 0 ? ripple * ((i % 2) ? 1 : -1) : 0.0), 0.0};
  });
}

TEST(BoundarySimplification, StraightSidesLoseTheirMiddleVertices) {
  const Mesh in = sheet(20, 0);
  Mesh out = in;
  const prm::pipeline::BoundarySimplification st = prm::pipeline::simplify_boundary(out, 1e-3);
  EXPECT_EQ(st.boundary_vertices_before, 80u);
  EXPECT_GT(st.removed, 40u);  // most of the 76 side vertices
  EXPECT_LE(st.max_distance, 1e-3);
  const prm::MeshReport r = prm::validate_mesh(out);
  EXPECT_TRUE(r.manifold() && r.oriented());
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_EQ(r.boundary_edges, 80u - st.removed);
  // Every input boundary vertex lies on the simplified loop (within the tolerance), and every vertex left is one of
  // the input's, where it was.
  EXPECT_LE(prm::boundary_deviation(out, in).max, 1e-3);
  std::set<std::array<double, 3>> original;
  for (const prm::Vec3& p : in.positions) original.insert({p[0], p[1], p[2]});
  for (const prm::Vec3& p : out.positions) EXPECT_TRUE(original.count({p[0], p[1], p[2]}));
  EXPECT_EQ(out.positions.size(), in.positions.size() - st.removed);
}

TEST(BoundarySimplification, ARippleAboveTheToleranceStays) {
  const Mesh in = sheet(20, 0.01);
  Mesh out = in;
  prm::pipeline::simplify_boundary(out, 1e-3);
  // The rippled side (y = 0) keeps all its 21 vertices: each is 0.01 off the line through its neighbours.
  size_t low = 0;
  for (const prm::Vec3& p : out.positions) low += std::abs(p[1]) <= 0.01 + 1e-12;
  EXPECT_EQ(low, 21u);
  EXPECT_LE(prm::boundary_deviation(out, in).max, 1e-3);
  EXPECT_EQ(prm::validate_mesh(out).boundary_loops, 1u);
}

}  // namespace
