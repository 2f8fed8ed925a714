// Paper §2.1 in pieces: the upper envelope of the six fields along an edge (where the relief boundary crosses it)
// and the geodesic distance fields (Dijkstra against fast marching, with known answers).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "../src/geodesic_distance.h"
#include "../src/relief_envelope.h"
#include "../src/relief_topology.h"
#include "prm/vec3.h"
#include "test_meshes.h"

namespace prm::remesh {
namespace {

AxisValues values(std::initializer_list<double> v) {
  AxisValues a{};
  size_t i = 0;
  for (double x : v) a[i++] = x;
  return a;
}

TEST(UpperEnvelope, OneFieldAboveTheOthers) {
  const EdgeEnvelope e = upper_envelope(values({0.1, 1.0, 0.2}), values({0.3, 2.0, 0.1}), 0.05);
  ASSERT_EQ(e.count, 1);
  EXPECT_EQ(e.axis[0], 1);
  EXPECT_EQ(e.start[0], 0.0);
  EXPECT_EQ(e.start[1], 1.0);
}

TEST(UpperEnvelope, SplitsAtTheZeroOfTheDifference) {
  // d0 = 0.3 - 0.2 t, d1 = 0.1 + 0.4 t: equal at t = 1/3.
  const EdgeEnvelope e = upper_envelope(values({0.3, 0.1}), values({0.1, 0.5}), 0.05);
  ASSERT_EQ(e.count, 2);
  EXPECT_EQ(e.axis[0], 0);
  EXPECT_EQ(e.axis[1], 1);
  EXPECT_NEAR(e.start[1], 1.0 / 3.0, 1e-15);
}

TEST(UpperEnvelope, TiesGoToTheGrowingFieldThenToTheLowerAxis) {
  // Every field 0 at a (the vertex touches every A_v): the field that grows fastest takes the edge.
  EdgeEnvelope e = upper_envelope(values({0, 0, 0, 0, 0, 0}), values({0, 0, 0.2, 0.1, 0, 0}), 0.05);
  ASSERT_EQ(e.count, 1);
  EXPECT_EQ(e.axis[0], 2);
  // Equal at a, d3 grows faster.
  e = upper_envelope(values({0, 0, 0, 0.5, 0.5}), values({0, 0, 0, 0.7, 0.6}), 0.05);
  ASSERT_EQ(e.count, 1);
  EXPECT_EQ(e.axis[0], 3);
  // Identical along the whole edge: the lower axis.
  e = upper_envelope(values({0, 0.2, 0, 0, 0.2}), values({0, 0.4, 0, 0, 0.4}), 0.05);
  ASSERT_EQ(e.count, 1);
  EXPECT_EQ(e.axis[0], 1);
}

TEST(UpperEnvelope, AllZeroEdgeSaysNothing) {
  EXPECT_EQ(upper_envelope(values({}), values({}), 0.05).count, 0);
}

TEST(UpperEnvelope, ShortPiecesSnap) {
  // Crossing at t = 0.03: the first piece is dropped, the edge is d1's.
  EdgeEnvelope e = upper_envelope(values({0.03, 0}), values({0, 0.97}), 0.05);
  ASSERT_EQ(e.count, 1);
  EXPECT_EQ(e.axis[0], 1);
  // Crossing at t = 0.97: the last piece is dropped.
  e = upper_envelope(values({0.97, 0}), values({0, 0.03}), 0.05);
  ASSERT_EQ(e.count, 1);
  EXPECT_EQ(e.axis[0], 0);
  // d0 = 1 - t, d1 = t, d2 = 0.51: d2 leads on [0.49, 0.51] only; d0 and d1 meet at its middle.
  e = upper_envelope(values({1, 0, 0.51}), values({0, 1, 0.51}), 0.05);
  ASSERT_EQ(e.count, 2);
  EXPECT_EQ(e.axis[0], 0);
  EXPECT_EQ(e.axis[1], 1);
  EXPECT_NEAR(e.start[1], 0.5, 1e-15);
  // Without snapping all three pieces stay.
  e = upper_envelope(values({1, 0, 0.51}), values({0, 1, 0.51}), 0);
  ASSERT_EQ(e.count, 3);
  EXPECT_EQ(e.axis[1], 2);
  EXPECT_NEAR(e.start[1], 0.49, 1e-15);
  EXPECT_NEAR(e.start[2], 0.51, 1e-15);
}

TEST(UpperEnvelope, RandomEdgesLabelTheLargestPositiveField) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 20000; ++trial) {
    AxisValues a{}, b{};
    for (size_t k = 0; k < kReliefAxes; ++k) {
      // Many zeros and many ties, as near the rims of the A_v sets.
      a[k] = u(rng) < 0.4 ? 0 : std::round(u(rng) * 8) / 8;
      b[k] = u(rng) < 0.4 ? 0 : std::round(u(rng) * 8) / 8;
    }
    const EdgeEnvelope e = upper_envelope(a, b, 0);
    const bool zero = *std::max_element(a.begin(), a.end()) == 0 && *std::max_element(b.begin(), b.end()) == 0;
    if (zero) {
      EXPECT_EQ(e.count, 0);
      continue;
    }
    ASSERT_GE(e.count, 1);
    ASSERT_LE(e.count, kReliefAxes);
    EXPECT_EQ(e.start[0], 0.0);
    EXPECT_EQ(e.start[static_cast<size_t>(e.count)], 1.0);
    for (int i = 0; i < e.count; ++i) {
      const size_t s = static_cast<size_t>(i);
      ASSERT_LT(e.start[s], e.start[s + 1]) << trial;
      if (i > 0) {
        EXPECT_NE(e.axis[s], e.axis[s - 1]);
      }
      // In the middle of its piece the label's field is the largest, and positive (so a face of A_v, where
      // d_v = 0, never takes label v from an edge).
      const double t = 0.5 * (e.start[s] + e.start[s + 1]);
      double top = 0;
      for (size_t k = 0; k < kReliefAxes; ++k) top = std::max(top, a[k] + t * (b[k] - a[k]));
      const size_t l = static_cast<size_t>(e.axis[s]);
      const double mine = a[l] + t * (b[l] - a[l]);
      EXPECT_GE(mine, top - 1e-12) << trial;
      EXPECT_GT(mine, 0) << trial;
    }
    // Snapping leaves pieces of at least the snap length and only labels the exact envelope had.
    const EdgeEnvelope s = upper_envelope(a, b, 0.05);
    ASSERT_GE(s.count, 1);
    for (int i = 0; i < s.count; ++i) {
      if (s.count > 1) {
        EXPECT_GE(s.start[static_cast<size_t>(i + 1)] - s.start[static_cast<size_t>(i)], 0.05 - 1e-15);
      }
      bool known = false;
      for (int j = 0; j < e.count; ++j) known = known || e.axis[static_cast<size_t>(j)] == s.axis[static_cast<size_t>(i)];
      EXPECT_TRUE(known) << trial;
    }
  }
}

// A flat, jittered grid in the plane z = 0 over [-1, 1] x [0, 1]; the faces left of x = 0 are the source.
Mesh jittered_plane(int n, double jitter) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  Mesh m;
  const double h = 1.0 / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= 2 * n; ++i) {
      // The column x = 0 stays straight so that the source's rim is the line x = 0 exactly.
      const bool inner = i > 0 && i < 2 * n && i != n && j > 0 && j < n;
      m.positions.push_back({-1 + i * h + (inner ? u(rng) * h : 0), j * h + (inner ? u(rng) * h : 0), 0});
    }
  auto id = [&](int i, int j) { return static_cast<uint32_t>(j * (2 * n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < 2 * n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

struct FieldError {
  double mean = 0, max = 0;
};

FieldError plane_error(GeodesicMethod method) {
  const Mesh m = jittered_plane(40, 0.3);
  std::vector<uint8_t> source(m.triangles.size());
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    double x = 0;
    for (uint32_t v : m.triangles[f]) x += m.positions[v][0];
    source[f] = x < 0;
  }
  std::vector<double> d;
  geodesic_distance(m, vertex_star(m, true), source, method, d);
  FieldError e;
  size_t n = 0;
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const double truth = std::max(0.0, m.positions[v][0]);
    const double err = std::abs(d[v] - truth);
    e.mean += err;
    e.max = std::max(e.max, err);
    ++n;
  }
  e.mean /= static_cast<double>(n);
  return e;
}

TEST(GeodesicDistance, FastMarchingFollowsAStraightFront) {
  // Distance from the half plane x < 0 is x: edge paths zigzag over the jittered grid, fronts do not.
  const FieldError dijkstra = plane_error(GeodesicMethod::Dijkstra);
  const FieldError fmm = plane_error(GeodesicMethod::FastMarching);
  std::printf("plane: fmm %.5f/%.5f dijkstra %.5f/%.5f\n", fmm.mean, fmm.max, dijkstra.mean, dijkstra.max);
  EXPECT_LT(fmm.mean, 0.25 * dijkstra.mean) << "fmm " << fmm.mean << " dijkstra " << dijkstra.mean;
  EXPECT_LT(fmm.max, 0.01);
  EXPECT_GT(dijkstra.max, 0.02);
}

FieldError sphere_error(GeodesicMethod method) {
  // Distance on the unit sphere from the faces below the equator (A_v of +z with tau = 0) is the latitude
  // pi/2 - theta; the source's rim is jagged by about one edge, so compare away from it.
  const Mesh m = test::icosphere(5);
  std::vector<uint8_t> source(m.triangles.size());
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    const Tri& t = m.triangles[f];
    source[f] = triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]])[2] < 0;
  }
  std::vector<double> d;
  geodesic_distance(m, vertex_star(m, true), source, method, d);
  // The rim: the highest source vertex sets the offset of the exact answer.
  double rim = 0;
  for (size_t f = 0; f < m.triangles.size(); ++f)
    if (source[f])
      for (uint32_t v : m.triangles[f]) rim = std::max(rim, std::asin(std::clamp(m.positions[v][2], -1.0, 1.0)));
  FieldError e;
  size_t n = 0;
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const double lat = std::asin(std::clamp(m.positions[v][2], -1.0, 1.0));
    if (lat < 0.5) continue;
    const double err = std::abs(d[v] - (lat - rim));
    e.mean += err;
    e.max = std::max(e.max, err);
    ++n;
  }
  e.mean /= static_cast<double>(n);
  return e;
}

TEST(GeodesicDistance, FastMarchingIsCloserToTheTruthOnASphere) {
  const FieldError dijkstra = sphere_error(GeodesicMethod::Dijkstra);
  const FieldError fmm = sphere_error(GeodesicMethod::FastMarching);
  std::printf("sphere: fmm %.5f/%.5f dijkstra %.5f/%.5f\n", fmm.mean, fmm.max, dijkstra.mean, dijkstra.max);
  EXPECT_LT(fmm.mean, 0.5 * dijkstra.mean) << "fmm " << fmm.mean << " dijkstra " << dijkstra.mean;
  EXPECT_LT(fmm.max, 0.04);  // about one edge length: the jagged rim
}

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 e = b - a;
  const double t = std::clamp(dot(p - a, e) / norm2(e), 0.0, 1.0);
  return norm(p - (a + e * t));
}

FieldError small_source_error(GeodesicMethod method) {
  // Distance on the jittered plane from one face near the middle of the left edge: circular fronts.
  const Mesh m = jittered_plane(40, 0.3);
  const size_t src = 2 * (20 * 80 + 2);
  std::vector<uint8_t> source(m.triangles.size(), 0);
  source[src] = 1;
  std::vector<double> d;
  geodesic_distance(m, vertex_star(m, true), source, method, d);
  const Tri& t = m.triangles[src];
  FieldError e;
  size_t n = 0;
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const Vec3& p = m.positions[v];
    const double truth = std::min({segment_distance(p, m.positions[t[0]], m.positions[t[1]]),
                                   segment_distance(p, m.positions[t[1]], m.positions[t[2]]),
                                   segment_distance(p, m.positions[t[2]], m.positions[t[0]])});
    if (truth < 0.2) continue;
    const double err = std::abs(d[v] - truth);
    e.mean += err;
    e.max = std::max(e.max, err);
    ++n;
  }
  e.mean /= static_cast<double>(n);
  return e;
}

TEST(GeodesicDistance, FastMarchingFollowsCircularFronts) {
  const FieldError dijkstra = small_source_error(GeodesicMethod::Dijkstra);
  const FieldError fmm = small_source_error(GeodesicMethod::FastMarching);
  std::printf("point: fmm %.5f/%.5f dijkstra %.5f/%.5f\n", fmm.mean, fmm.max, dijkstra.mean, dijkstra.max);
  EXPECT_LT(fmm.mean, 0.5 * dijkstra.mean) << "fmm " << fmm.mean << " dijkstra " << dijkstra.mean;
}

TEST(GeodesicDistance, UnreachableVerticesAreInfinite) {
  Mesh m = test::icosphere(1);
  std::vector<uint8_t> none(m.triangles.size(), 0);
  std::vector<double> d;
  geodesic_distance(m, vertex_star(m, true), none, GeodesicMethod::FastMarching, d);
  for (double x : d) EXPECT_TRUE(std::isinf(x));
}

}  // namespace
}  // namespace prm::remesh
