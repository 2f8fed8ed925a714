// Metro-style sampling: counts per kind, budgets, determinism, and samples on the surface.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "metro_test_meshes.h"
#include "prm/aabb_tree.h"
#include "prm/error.h"
#include "prm/surface_sampler.h"

namespace prm {
namespace {

TEST(SurfaceSampler, AreaAndEdgeLength) {
  const Mesh patch = test::grid_patch(4, 2, 2.0, 1.0);
  SamplingOptions o;
  o.samples = 1000;
  const SurfaceSamples s = sample_surface(patch, o);
  EXPECT_NEAR(s.area, 2.0, 1e-14);
  EXPECT_NEAR(surface_area(patch), 2.0, 1e-14);
  // 5×3 grid lines: 3 horizontal lines of length 2, 5 vertical of length 1, 8 diagonals of length sqrt(0.5² + 0.5²).
  EXPECT_NEAR(s.edge_length, 3 * 2.0 + 5 * 1.0 + 8 * std::sqrt(0.5), 1e-12);
  EXPECT_EQ(s.vertex_samples, 15u);
}

TEST(SurfaceSampler, MetroBudget) {
  const Mesh sphere = test::icosphere(3);  // 642 vertices, 1280 faces
  SamplingOptions o;
  o.samples = 50000;
  const SurfaceSamples s = sample_surface(sphere, o);
  EXPECT_EQ(s.vertex_samples, 642u);
  // Edges: sqrt(remaining / area) per unit length, rounded by error diffusion (within one of the exact total).
  const double left = 50000.0 - 642.0;
  const double expected_edges = std::sqrt(left / s.area) * s.edge_length;
  EXPECT_NEAR(static_cast<double>(s.edge_samples), expected_edges, 1.0);
  // Faces: what is left.
  EXPECT_NEAR(static_cast<double>(s.face_samples), left - static_cast<double>(s.edge_samples), 1.0);
  EXPECT_EQ(s.points.size(), s.vertex_samples + s.edge_samples + s.face_samples);
}

TEST(SurfaceSampler, MetroBudgetIsNeverExceededByTheEdges) {
  const Mesh sphere = test::icosphere(4);  // 2562 vertices, 5120 faces: 5000 samples is under one per face
  SamplingOptions o;
  o.samples = 5000;
  const SurfaceSamples s = sample_surface(sphere, o);
  EXPECT_EQ(s.vertex_samples, 2562u);
  EXPECT_NEAR(static_cast<double>(s.edge_samples), 5000.0 - 2562.0, 1.0);
  EXPECT_LE(s.face_samples, 1u);
  // More vertices than samples: every vertex all the same, nothing else.
  o.samples = 1000;
  const SurfaceSamples t = sample_surface(sphere, o);
  EXPECT_EQ(t.points.size(), 2562u);
}

TEST(SurfaceSampler, PerKindBudget) {
  const Mesh sphere = test::icosphere(3);
  SamplingOptions o;
  o.samples = 20000;
  o.budget = SampleBudget::PerKind;
  const SurfaceSamples s = sample_surface(sphere, o);
  EXPECT_EQ(s.vertex_samples, 642u);
  EXPECT_NEAR(static_cast<double>(s.edge_samples), 20000.0, 1.0);
  EXPECT_NEAR(static_cast<double>(s.face_samples), 20000.0, 1.0);
}

TEST(SurfaceSampler, KindsCanBeSwitchedOff) {
  const Mesh sphere = test::icosphere(2);
  SamplingOptions o;
  o.samples = 10000;
  o.vertices = false;
  o.edges = false;
  SurfaceSamples s = sample_surface(sphere, o);
  EXPECT_EQ(s.vertex_samples, 0u);
  EXPECT_EQ(s.edge_samples, 0u);
  EXPECT_NEAR(static_cast<double>(s.face_samples), 10000.0, 1.0);
  o.faces = false;
  o.edges = true;
  s = sample_surface(sphere, o);  // edges only: the whole budget along the edges
  EXPECT_EQ(s.face_samples, 0u);
  EXPECT_NEAR(static_cast<double>(s.edge_samples), 10000.0, 1.0);
}

TEST(SurfaceSampler, OnlyReferencedVerticesAreSampled) {
  Mesh m = test::grid_patch(2, 2, 1.0, 1.0);
  m.positions.push_back({5, 5, 5});  // unreferenced
  SamplingOptions o;
  o.samples = 100;
  const SurfaceSamples s = sample_surface(m, o);
  EXPECT_EQ(s.vertex_samples, 9u);
  for (const Vec3& p : s.points) EXPECT_LE(p[2], 0.0);
}

TEST(SurfaceSampler, SamplesLieOnTheSurface) {
  const Mesh sphere = test::icosphere(3, 3.0, {1, 2, 3});
  const AabbTree tree(sphere);
  SamplingOptions o;
  o.samples = 20000;
  const SurfaceSamples s = sample_surface(sphere, o);
  for (const Vec3& p : s.points) ASSERT_LT(std::sqrt(tree.closest(p).distance2), 1e-13);
}

TEST(SurfaceSampler, DeterministicAndIndependentOfThreads) {
  const Mesh sphere = test::icosphere(3);
  SamplingOptions o;
  o.samples = 30000;
  o.seed = 42;
  const SurfaceSamples a = sample_surface(sphere, o);
  SurfaceSamples b;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    b = sample_surface(sphere, o);
  }
  EXPECT_EQ(a.points, b.points);
  o.seed = 43;
  const SurfaceSamples c = sample_surface(sphere, o);
  ASSERT_EQ(a.points.size(), c.points.size());  // the counts do not depend on the seed...
  EXPECT_NE(a.points, c.points);               // ...the face samples' positions do
  const size_t fixed = a.vertex_samples + a.edge_samples;
  EXPECT_TRUE(std::equal(a.points.begin(), a.points.begin() + static_cast<long>(fixed), c.points.begin()));
}

// SamplePlan computes each chunk of 1024 samples on its own, starting inside an edge's or a face's run: with the
// PerKind budget the edge and face counts do not depend on the vertex samples, so dropping the 642 vertex samples
// moves every chunk boundary to another place inside those runs, and the samples must not change.
TEST(SurfaceSampler, ChunksStartingInsideAnEdgeOrAFaceGiveTheSameSamples) {
  const Mesh sphere = test::icosphere(3);  // 642 vertices
  SamplingOptions o;
  o.samples = 9000;
  o.budget = SampleBudget::PerKind;
  o.seed = 7;
  const SurfaceSamples with = sample_surface(sphere, o);
  o.vertices = false;
  const SurfaceSamples without = sample_surface(sphere, o);
  ASSERT_EQ(with.vertex_samples, 642u);
  ASSERT_GT(without.points.size(), 8 * SamplePlan::kSampleChunk);
  ASSERT_EQ(with.points.size(), without.points.size() + 642);
  EXPECT_TRUE(std::equal(without.points.begin(), without.points.end(), with.points.begin() + 642));
  // The plan's chunks are the stored samples.
  const SamplePlan plan(sphere, o);
  std::vector<Vec3> chunk;
  plan.chunk(3, chunk);
  ASSERT_EQ(chunk.size(), SamplePlan::kSampleChunk);
  EXPECT_TRUE(std::equal(chunk.begin(), chunk.end(), without.points.begin() + 3 * SamplePlan::kSampleChunk));
}

TEST(SurfaceSampler, BadIndexThrows) {
  Mesh m;
  m.positions = {{0, 0, 0}};
  m.triangles = {{0, 0, 1}};
  EXPECT_THROW(sample_surface(m, SamplingOptions{}), InputError);
}

}  // namespace
}  // namespace prm
