// Metro distance: known answers on generated meshes, symmetry, determinism, errors.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "metro_test_meshes.h"
#include "prm/error.h"
#include "prm/metro_distance.h"
#include "prm/point_triangle_distance.h"

namespace prm {
namespace {

void expect_same(const OneSidedDistance& x, const OneSidedDistance& y) {
  EXPECT_EQ(x.mean, y.mean);
  EXPECT_EQ(x.rms, y.rms);
  EXPECT_EQ(x.max, y.max);
  EXPECT_EQ(x.samples, y.samples);
  EXPECT_EQ(x.vertex_samples, y.vertex_samples);
  EXPECT_EQ(x.edge_samples, y.edge_samples);
  EXPECT_EQ(x.face_samples, y.face_samples);
}

TEST(MetroDistance, MeshAgainstItselfIsZero) {
  const Mesh sphere = test::icosphere(4, 2.5, {1, -2, 0.5});
  MetroOptions o;
  o.samples = 100000;
  const DistanceReport r = metro_distance(sphere, sphere, o);
  EXPECT_LT(r.max, 1e-14 * r.diagonal);
  EXPECT_LT(r.rms, 1e-15 * r.diagonal);
  EXPECT_EQ(r.a_to_b.samples, r.b_to_a.samples);
  EXPECT_NEAR(static_cast<double>(r.a_to_b.samples), 100000.0, 2.0);
  EXPECT_NEAR(r.diagonal, 2.5 * 2 * std::sqrt(3.0), 0.1);  // the icosphere's box is nearly the sphere's cube
}

TEST(MetroDistance, ConcentricSpheres) {
  const double r1 = 1.0, r2 = 1.1;
  const Mesh inner = test::icosphere(5, r1), outer = test::icosphere(4, r2);
  // The polyhedra lie in the shells [rho_i, r_i] where rho_i is their distance to the centre, so every sample's
  // distance to the other surface lies in [rho2 - r1, r2 - rho1] (the tessellation's share of the answer).
  const double rho1 = std::sqrt(AabbTree(inner).closest({0, 0, 0}).distance2);
  const double rho2 = std::sqrt(AabbTree(outer).closest({0, 0, 0}).distance2);
  ASSERT_GT(rho1, 0.999 * r1);
  ASSERT_GT(rho2, 0.998 * r2);
  const double lo = rho2 - r1, hi = r2 - rho1;

  MetroOptions o;
  o.samples = 200000;
  const DistanceReport r = metro_distance(inner, outer, o);
  for (const OneSidedDistance* d : {&r.a_to_b, &r.b_to_a}) {
    EXPECT_GE(d->mean, lo);
    EXPECT_LE(d->mean, hi);
    EXPECT_GE(d->rms, lo);
    EXPECT_LE(d->rms, hi);
    EXPECT_LE(d->max, hi);
    EXPECT_NEAR(d->mean, r2 - r1, 0.01 * (r2 - r1));  // within 1% of |r1 - r2|
  }
  EXPECT_NEAR(r.max, r2 - r1, 0.03 * (r2 - r1));

  // Every sample, not only the averages.
  SamplingOptions so;
  so.samples = 50000;
  std::vector<double> d;
  distance_to_surface(sample_surface(outer, so), AabbTree(inner), &d);
  ASSERT_EQ(d.size(), sample_surface(outer, so).points.size());
  for (double x : d) {
    ASSERT_GE(x, lo - 1e-12);
    ASSERT_LE(x, hi + 1e-12);
  }
}

TEST(MetroDistance, PlanePatchAndItsOffsetCopy) {
  const double h = 0.05;
  // Different tessellations of the same square, one above the other: every point is exactly h from the other.
  const Mesh a = test::grid_patch(10, 10, 1.0, 1.0, 0.0), b = test::grid_patch(7, 13, 1.0, 1.0, h);
  MetroOptions o;
  o.samples = 50000;
  const DistanceReport r = metro_distance(a, b, o);
  for (const OneSidedDistance* d : {&r.a_to_b, &r.b_to_a}) {
    EXPECT_NEAR(d->mean, h, 1e-14);
    EXPECT_NEAR(d->rms, h, 1e-14);
    EXPECT_NEAR(d->max, h, 1e-14);
  }
  EXPECT_NEAR(r.rel(r.rms), h / std::sqrt(2.0), 1e-13);  // A's box is the unit square (diagonal sqrt 2)
}

TEST(MetroDistance, TranslatedCopy) {
  const Mesh a = test::icosphere(3, 1.0);
  // Along an axis: each point x of A has x + t on B (so no distance exceeds |t|), and B's extreme vertex in the
  // direction of t is |t| away from all of A (and it is a vertex sample): the Hausdorff distance is exactly |t|.
  {
    const Mesh b = test::translated(a, {0.3, 0, 0});
    const DistanceReport r = metro_distance(a, b, MetroOptions{});
    EXPECT_NEAR(r.max, 0.3, 1e-12);
    EXPECT_LE(r.a_to_b.max, 0.3 + 1e-12);
    EXPECT_LE(r.b_to_a.max, 0.3 + 1e-12);
    EXPECT_GT(r.mean, 0.0);
    EXPECT_LT(r.mean, 0.3);
    EXPECT_LE(r.rms, 0.3);
    EXPECT_GE(r.rms, r.mean);
  }
  // Any direction: the Hausdorff distance lies between the largest coordinate shift and |t|.
  {
    const Vec3 t{0.1, -0.2, 0.05};
    const Mesh b = test::translated(a, t);
    const DistanceReport r = metro_distance(a, b, MetroOptions{});
    EXPECT_LE(r.max, norm(t) + 1e-12);
    EXPECT_GE(r.max, 0.2 - 1e-12);
    EXPECT_LE(r.mean, norm(t));
  }
}

TEST(MetroDistance, SwappingTheMeshesSwapsTheDirections) {
  const Mesh a = test::icosphere(3, 1.0), b = test::jittered(test::icosphere(2, 1.05), 0.02, 5);
  MetroOptions o;
  o.samples = 40000;
  const DistanceReport ab = metro_distance(a, b, o), ba = metro_distance(b, a, o);
  expect_same(ab.a_to_b, ba.b_to_a);
  expect_same(ab.b_to_a, ba.a_to_b);
  EXPECT_EQ(ab.mean, ba.mean);
  EXPECT_EQ(ab.rms, ba.rms);
  EXPECT_EQ(ab.max, ba.max);
  EXPECT_NE(ab.a_to_b.rms, ab.b_to_a.rms);  // the one-sided figures do differ
}

TEST(MetroDistance, AgreesWithBruteForce) {
  const Mesh a = test::jittered(test::icosphere(2, 1.0), 0.05, 1), b = test::random_soup(200, 9, 0.3);
  SamplingOptions so;
  so.samples = 3000;
  const SurfaceSamples s = sample_surface(a, so);
  std::vector<double> d;
  const OneSidedDistance r = distance_to_surface(s, AabbTree(b), &d);
  double sum = 0, sum2 = 0, mx = 0;
  for (size_t i = 0; i < s.points.size(); ++i) {
    double best = HUGE_VAL;
    for (const Tri& t : b.triangles)
      best = std::min(best, point_triangle_distance2(s.points[i], b.positions[t[0]], b.positions[t[1]],
                                                     b.positions[t[2]]));
    ASSERT_EQ(d[i], std::sqrt(best));
    sum += d[i];
    sum2 += d[i] * d[i];
    mx = std::max(mx, d[i]);
  }
  const double n = static_cast<double>(s.points.size());
  EXPECT_NEAR(r.mean, sum / n, 1e-12);
  EXPECT_NEAR(r.rms, std::sqrt(sum2 / n), 1e-12);
  EXPECT_EQ(r.max, mx);
}

TEST(MetroDistance, DefaultIsTenSamplesPerFaceOfTheLargerMesh) {
  const Mesh a = test::icosphere(2), b = test::icosphere(3, 1.01);  // 320 and 1280 faces
  const DistanceReport r = metro_distance(a, b);
  EXPECT_NEAR(static_cast<double>(r.a_to_b.samples), 12800.0, 2.0);
  EXPECT_NEAR(static_cast<double>(r.b_to_a.samples), 12800.0, 2.0);
}

// MetroOptions::max_samples caps samples_per_face x faces (pack's search estimates on large inputs), and only that:
// below the cap, and with an explicit sample count, the counts are as without it.
TEST(MetroDistance, MaxSamplesCapsThePerFaceCount) {
  const Mesh a = test::icosphere(2), b = test::icosphere(3, 1.01);  // 320 and 1280 faces
  MetroOptions o;
  o.max_samples = 5000;
  const DistanceReport capped = metro_distance(a, b, o);
  EXPECT_NEAR(static_cast<double>(capped.a_to_b.samples), 5000.0, 2.0);
  EXPECT_NEAR(static_cast<double>(capped.b_to_a.samples), 5000.0, 2.0);
  EXPECT_NEAR(capped.rms, metro_distance(a, b).rms, 0.05 * capped.rms);
  o.max_samples = 20000;
  EXPECT_NEAR(static_cast<double>(metro_distance(a, b, o).a_to_b.samples), 12800.0, 2.0);
  o.max_samples = 5000;
  o.samples = 8000;
  EXPECT_NEAR(static_cast<double>(metro_distance(a, b, o).a_to_b.samples), 8000.0, 2.0);
}

TEST(MetroDistance, MeshLabBudget) {
  const Mesh a = test::icosphere(3), b = test::icosphere(3, 1.02);
  MetroOptions o;
  o.samples = 10000;
  o.budget = SampleBudget::PerKind;
  const DistanceReport r = metro_distance(a, b, o);
  EXPECT_EQ(r.a_to_b.vertex_samples, 642u);
  EXPECT_NEAR(static_cast<double>(r.a_to_b.edge_samples), 10000.0, 1.0);
  EXPECT_NEAR(static_cast<double>(r.a_to_b.face_samples), 10000.0, 1.0);
}

TEST(MetroDistance, IndependentOfThreadCount) {
  const Mesh a = test::icosphere(4), b = test::jittered(test::icosphere(3), 0.01, 2);
  MetroOptions o;
  o.samples = 100000;
  const DistanceReport many = metro_distance(a, b, o);
  DistanceReport one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = metro_distance(a, b, o);
  }
  expect_same(many.a_to_b, one.a_to_b);
  expect_same(many.b_to_a, one.b_to_a);
}

TEST(MetroDistance, ReferenceMatchesTheOneShotFunction) {
  const Mesh a = test::icosphere(3), b = test::jittered(test::icosphere(3), 0.01, 3),
             c = test::jittered(test::icosphere(2), 0.02, 4);
  MetroOptions o;
  o.samples = 20000;
  const MetroReference ref(a, o);
  for (const Mesh* m : {&b, &c, &b}) {
    const DistanceReport x = ref.compare(*m), y = metro_distance(a, *m, o);
    expect_same(x.a_to_b, y.a_to_b);
    expect_same(x.b_to_a, y.b_to_a);
    EXPECT_EQ(x.diagonal, y.diagonal);
  }
  // With the default count (which depends on the candidate) too.
  const MetroReference ref_default(a);
  const DistanceReport x = ref_default.compare(c), y = metro_distance(a, c);
  expect_same(x.a_to_b, y.a_to_b);
  expect_same(x.b_to_a, y.b_to_a);
}

TEST(MetroDistance, MeshesWithoutSurfaceAreRejected) {
  const Mesh sphere = test::icosphere(1);
  Mesh points;
  points.positions = {{0, 0, 0}, {1, 1, 1}};
  EXPECT_THROW(metro_distance(sphere, points), InputError);
  EXPECT_THROW(metro_distance(points, sphere), InputError);
  EXPECT_THROW(MetroReference{points}, InputError);
  Mesh bad = sphere;
  bad.triangles.push_back({0, 1, 100000});
  EXPECT_THROW(metro_distance(sphere, bad), InputError);
}

}  // namespace
}  // namespace prm

// A flat patch and a copy with one vertex lifted by 0.3 (a spike) and another by 0.1: the worst site is the spike's
// tip, sampled on the copy (B -> A), at the Hausdorff distance; the second, farther than the separation (0.4) from it, is the smaller bump.
TEST(MetroDistance, WorstDeviationsFindTheSpikes) {
  using namespace prm;
  const Mesh a = prm::test::grid_patch(10, 10, 1.0, 1.0);
  Mesh b = a;
  size_t spike = 0, bump = 0;
  for (size_t v = 0; v < b.positions.size(); ++v) {
    if (std::abs(b.positions[v][0] - 0.3) < 1e-9 && std::abs(b.positions[v][1] - 0.3) < 1e-9) spike = v;
    if (std::abs(b.positions[v][0] - 0.7) < 1e-9 && std::abs(b.positions[v][1] - 0.7) < 1e-9) bump = v;
  }
  b.positions[spike][2] = 0.3;
  b.positions[bump][2] = 0.1;
  const DistanceReport d = metro_distance(a, b);
  const std::vector<DeviationSite> sites = worst_deviations(a, b, 2, 0.4);
  ASSERT_EQ(sites.size(), 2u);
  EXPECT_FALSE(sites[0].a_to_b);
  EXPECT_DOUBLE_EQ(sites[0].distance, d.max);
  EXPECT_NEAR(sites[0].distance, 0.3, 1e-12);
  EXPECT_NEAR(norm(sites[0].sample - b.positions[spike]), 0, 1e-12);
  EXPECT_NEAR(norm(sites[0].closest - Vec3{0.3, 0.3, 0}), 0, 1e-12);
  EXPECT_NEAR(sites[1].distance, 0.1, 1e-12);
  EXPECT_NEAR(norm(sites[1].sample - b.positions[bump]), 0, 1e-12);
}
