// The stream check's turned triangles (stream_check.h): with a known mesh of the same triangles, the triangles whose
// corners did not move take the known answer and the others are tested again (pack's lambda streams), the same list
// as testing every triangle. vertex_distance_max: Metro's distance of the mesh's vertex samples, bit for bit.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/mesh.h"
#include "prm/metro_distance.h"
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

// pack's heights refuse a lambda whose vertices pass the aim without its Metro run: that needs vertex_distance_max to
// be at most Metro's max, and it is Metro's own figure where the farthest sample is a vertex.
TEST(StreamCheck, VertexDistanceMaxIsMetrosFarthestVertexSample) {
  const Mesh sphere = prm::test::icosphere(3, 1.0);
  MetroOptions o;
  o.samples_per_face = 4;
  const MetroReference reference(sphere, o);
  Mesh m = sphere;
  m.positions[7] = m.positions[7] * 1.02;  // the farthest sample of m from the sphere
  m.positions[9] = m.positions[9] * 0.995;
  const double v = vertex_distance_max(m, reference.tree());
  const DistanceReport d = reference.compare(m);
  EXPECT_GT(v, 0.015);
  EXPECT_EQ(v, d.b_to_a.max);
  // A vertex no triangle uses is no sample.
  m.positions.push_back(Vec3{5, 5, 5});
  EXPECT_EQ(vertex_distance_max(m, reference.tree()), v);
  // With vertex 7 back in place, at most Metro's max.
  m.positions[7] = sphere.positions[7];
  const DistanceReport inward = reference.compare(m);
  EXPECT_LE(vertex_distance_max(m, reference.tree()), inward.b_to_a.max);
}

}  // namespace
}  // namespace prm::pipeline
