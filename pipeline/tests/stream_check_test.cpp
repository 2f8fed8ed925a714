// The stream check's turned triangles (stream_check.h): with a known mesh of the same triangles, the triangles whose
// corners did not move take the known answer and the others are tested again (pack's lambda streams), the same list
// as testing every triangle.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/mesh.h"
#include "prm/pipeline/stream_check.h"
#include "prm/vec3.h"
#include "test_meshes.h"

namespace prm::pipeline {
namespace {

TEST(StreamCheck, TurnedTrianglesTestAgainOnlyTheMovedOnes) {
  const Mesh sphere = prm::test::icosphere(3, 1.0);
  const AabbTree tree(sphere);
  // known: vertex 0 pulled through the centre, its fan turned away from the sphere.
  TurnedTriangles known{sphere, {}};
  known.mesh.positions[0] = known.mesh.positions[0] * -0.5;
  known.turned = turned_triangles(known.mesh, sphere, tree);
  ASSERT_FALSE(known.turned.empty());
  // m: vertex 0 back in place (its fan faces the sphere again), vertex 5 pulled through instead.
  Mesh m = known.mesh;
  m.positions[0] = sphere.positions[0];
  m.positions[5] = m.positions[5] * -0.5;
  const std::vector<size_t> every = turned_triangles(m, sphere, tree);
  ASSERT_FALSE(every.empty());
  EXPECT_NE(every, known.turned);
  EXPECT_EQ(turned_triangles(m, sphere, tree, &known), every);
  // Other triangles: nothing is taken from `known`.
  Mesh flipped = m;
  for (Tri& t : flipped.triangles) std::swap(t[1], t[2]);
  EXPECT_EQ(turned_triangles(flipped, sphere, tree, &known), turned_triangles(flipped, sphere, tree));
}

}  // namespace
}  // namespace prm::pipeline
