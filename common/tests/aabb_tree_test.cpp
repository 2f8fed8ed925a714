// The closest-point primitives and the AABB tree against brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "metro_test_meshes.h"
#include "prm/aabb_tree.h"
#include "prm/error.h"
#include "prm/point_triangle_distance.h"

namespace prm {
namespace {

TEST(PointTriangleDistance, EveryVoronoiRegion) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  // interior: straight above the plane
  EXPECT_DOUBLE_EQ(point_triangle_distance2({0.25, 0.25, 2}, a, b, c), 4.0);
  // vertex regions
  EXPECT_DOUBLE_EQ(point_triangle_distance2({-1, -1, 0}, a, b, c), 2.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance2({2, -1, 0}, a, b, c), 2.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance2({-1, 3, 0}, a, b, c), 1.0 + 4.0);
  // edge regions ab, ca, bc
  EXPECT_DOUBLE_EQ(point_triangle_distance2({0.5, -2, 1}, a, b, c), 4.0 + 1.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance2({-3, 0.5, 0}, a, b, c), 9.0);
  EXPECT_NEAR(point_triangle_distance2({1, 1, 0}, a, b, c), 0.5, 1e-15);
  const Vec3 q = closest_point_on_triangle({1, 1, 0}, a, b, c);
  EXPECT_NEAR(q[0], 0.5, 1e-15);
  EXPECT_NEAR(q[1], 0.5, 1e-15);
}

TEST(PointTriangleDistance, DegenerateTriangles) {
  // Collinear corners: the triangle is the segment [0, 2] on the x axis.
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{2, 0, 0};
  EXPECT_DOUBLE_EQ(point_triangle_distance2({1.5, 1, 0}, a, b, c), 1.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance2({3, 0, 0}, a, b, c), 1.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance2({-1, 0, 1}, a, b, c), 2.0);
  // Repeated corners, and a single point.
  EXPECT_DOUBLE_EQ(point_triangle_distance2({0.5, 2, 0}, a, a, b), 4.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance2({0, 0, 3}, b, b, b), 1.0 + 9.0);
  const Vec3 q = closest_point_on_triangle({7, 8, 9}, a, a, a);
  EXPECT_TRUE(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]));
}

double brute_force2(const Mesh& m, const Vec3& p) {
  double best = HUGE_VAL;
  for (const Tri& t : m.triangles)
    best = std::min(best, point_triangle_distance2(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  return best;
}

TEST(AabbTree, MatchesBruteForceOnATriangleSoup) {
  const Mesh soup = test::random_soup(3000, 7);
  const AabbTree tree(soup);
  EXPECT_EQ(tree.num_triangles(), 3000u);
  EXPECT_LT(tree.depth(), 40);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.5, 1.5);
  AabbTree::Hit hint;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    const AabbTree::Hit hit = tree.closest(p);
    ASSERT_TRUE(hit.found());
    const double expected = brute_force2(soup, p);
    ASSERT_EQ(hit.distance2, expected) << "query " << i;
    // The reported point is on the reported triangle, at the reported distance.
    const Tri& t = soup.triangles[hit.face];
    EXPECT_NEAR(point_triangle_distance2(hit.point, soup.positions[t[0]], soup.positions[t[1]], soup.positions[t[2]]),
                0.0, 1e-24);
    EXPECT_NEAR(norm2(hit.point - p), hit.distance2, 1e-15);
    // The hinted search from the previous answer finds the same distance.
    tree.closest(p, hint);
    ASSERT_EQ(hint.distance2, expected);
  }
}

// refit: a tree built on a soup, its corners then moved (each by up to a tenth of the soup), answers with the
// distances of a tree built on the moved soup, bit for bit, hinted or not; a mesh with other triangles is refused.
TEST(AabbTree, RefitGivesTheDistancesOfANewTree) {
  Mesh soup = test::random_soup(3000, 9);
  AabbTree tree(soup);
  const AabbTree before(soup);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> move(-0.1, 0.1), u(-0.5, 1.5);
  for (Vec3& p : soup.positions)
    for (double& x : p) x += move(rng);
  tree.refit(soup);
  const AabbTree fresh(soup);
  AabbTree::Hit hint;
  size_t moved = 0;  // queries whose answer the move changed
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    const AabbTree::Hit expected = fresh.closest(p);
    ASSERT_EQ(tree.closest(p).distance2, expected.distance2) << "query " << i;
    tree.closest(p, hint);
    ASSERT_EQ(hint.distance2, expected.distance2) << "query " << i;
    moved += before.closest(p).distance2 != expected.distance2;
  }
  EXPECT_GT(moved, 1000u);
  Mesh other = soup;
  other.triangles.pop_back();
  EXPECT_THROW(tree.refit(other), InputError);
}

// The tree's triangle test (branch-free) gives closest_point_on_triangle's point and squared distance bit for bit:
// random triangles and slivers, zero-area ones, and points on the regions' borders (exact barycentric steps).
TEST(AabbTree, TriangleTestIsClosestPointOnTriangleBitForBit) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double steps[] = {-1.5, -0.5, 0.0, 0.25, 0.5, 1.0, 1.5};
  const auto same = [](const Vec3& x, const Vec3& y) { return std::memcmp(x.data(), y.data(), sizeof(Vec3)) == 0; };
  int tested = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 a{u(rng), u(rng), u(rng)};
    Vec3 b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    switch (i % 6) {
      case 1: c = a + (b - a) * 0.5; break;                        // collinear (zero area, or nearly)
      case 2: c = b; break;                                         // a repeated corner
      case 3: b = a; c = a; break;                                  // a point
      case 4: c = a + (b - a) * 0.5 + Vec3{1e-9, -2e-9, 1e-9}; break;  // a sliver
      case 5: b = a * 1e6; c = a * -3e5; break;                     // large coordinates
      default: break;
    }
    const AabbTree tree(std::vector<Vec3>{a, b, c}, std::vector<Tri>{{0, 1, 2}});
    const Vec3 n = cross(b - a, c - a);
    std::vector<Vec3> points;
    for (int k = 0; k < 8; ++k) points.push_back({2 * u(rng), 2 * u(rng), 2 * u(rng)});
    for (const double s : steps)
      for (const double t : steps) points.push_back(a + (b - a) * s + (c - a) * t + n * (0.25 * (s - t)));
    points.push_back(a);
    points.push_back(b);
    points.push_back(c);
    for (const Vec3& p : points) {
      const Vec3 q = closest_point_on_triangle(p, a, b, c);
      const AabbTree::Hit hit = tree.closest(p), on = tree.on_face(p, 0);
      ASSERT_TRUE(same(hit.point, q) && same(on.point, q)) << "triangle " << i;
      ASSERT_EQ(hit.distance2, norm2(p - q)) << "triangle " << i;
      ASSERT_EQ(on.distance2, norm2(p - q)) << "triangle " << i;
      ++tested;
    }
  }
  EXPECT_EQ(tested, 3000 * (8 + 49 + 3));
}

TEST(AabbTree, SphereQueries) {
  const Mesh sphere = test::icosphere(4, 2.0);
  const AabbTree tree(sphere);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  for (int i = 0; i < 300; ++i) {
    const Vec3 dir = normalized(Vec3{g(rng), g(rng), g(rng)});
    for (double r : {0.0, 0.5, 1.99, 2.0, 3.0, 100.0}) {
      const Vec3 p = dir * r;
      ASSERT_EQ(tree.closest(p).distance2, brute_force2(sphere, p));
    }
  }
}

TEST(AabbTree, BoundedQuery) {
  const Mesh patch = test::grid_patch(10, 10, 1.0, 1.0);
  const AabbTree tree(patch);
  EXPECT_FALSE(tree.closest({0.5, 0.5, 2.0}, 1.0).found());  // nearest is at distance 2 > 1
  const AabbTree::Hit hit = tree.closest({0.5, 0.5, 2.0}, 9.0);
  ASSERT_TRUE(hit.found());
  EXPECT_DOUBLE_EQ(hit.distance2, 4.0);
}

// well_inside / on_face / closest_reusing: a known triangle instead of a search, only where the point projects onto
// its interior away from its edges; elsewhere closest_reusing searches (the same answer as closest()).
TEST(AabbTree, ReusesAKnownTriangleOnlyWellInside) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.5}};
  m.triangles = {{0, 1, 2}, {1, 3, 2}};
  const AabbTree tree(m);
  EXPECT_TRUE(tree.well_inside({0.25, 0.25, 0.1}, 0));
  EXPECT_FALSE(tree.well_inside({0.25, 0.25, 0.1}, 1));
  EXPECT_FALSE(tree.well_inside({0.02, 0.5, 0.1}, 0));  // 0.1 over the plane, 0.02 from an edge
  EXPECT_TRUE(tree.well_inside({0.02, 0.5, 0.01}, 0));
  EXPECT_FALSE(tree.well_inside({-0.1, 0.5, 0.1}, 0));  // outside
  EXPECT_FALSE(tree.well_inside({0.25, 0.25, 0.1}, 7));  // no such triangle
  EXPECT_FALSE(tree.well_inside({0.25, 0.25, 0.3}, 0));  // farther from the plane (0.3) than from an edge (0.25)
  const AabbTree::Hit on = tree.on_face({0.25, 0.25, 0.1}, 0);
  EXPECT_EQ(on.face, 0u);
  EXPECT_DOUBLE_EQ(on.distance2, 0.01);
  EXPECT_EQ(on.point, (Vec3{0.25, 0.25, 0}));
  // Near the shared edge, on triangle 1's side: the hint (triangle 0) is not taken.
  for (const Vec3 p : {Vec3{0.52, 0.52, 0.3}, Vec3{0.7, 0.7, 0.4}, Vec3{0.25, 0.25, 0.1}}) {
    AabbTree::Hit hint = tree.on_face(p, 0);
    tree.closest_reusing(p, hint);
    const AabbTree::Hit exact = tree.closest(p);
    EXPECT_EQ(hint.face, exact.face);
    EXPECT_DOUBLE_EQ(hint.distance2, exact.distance2);
  }
  // A point well inside the hint's triangle takes it, even where another is nearer (the estimate's one error).
  Mesh two = m;
  two.positions.push_back({0, 0, 0.2});
  two.positions.push_back({1, 0, 0.2});
  two.positions.push_back({0, 1, 0.2});
  two.triangles.push_back({4, 5, 6});
  const AabbTree tree2(two);
  AabbTree::Hit hint = tree2.on_face({0.25, 0.25, 0.15}, 0);
  tree2.closest_reusing({0.25, 0.25, 0.15}, hint);
  EXPECT_EQ(hint.face, 0u);
  EXPECT_EQ(tree2.closest({0.25, 0.25, 0.15}).face, 2u);
}

// within(p, bound2) says whether the closest point is within sqrt(bound2), whatever the hint; a yes gives a
// triangle that near.
TEST(AabbTree, WithinMatchesTheClosestDistance) {
  const Mesh soup = test::random_soup(3000, 5);
  const AabbTree tree(soup);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-0.5, 1.5);
  AabbTree::Hit chained;
  int yes = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    const double closest2 = brute_force2(soup, p);
    for (double bound2 : {0.0, 1e-4, 1e-3, 1e-2, closest2}) {
      AabbTree::Hit fresh;
      const bool near = tree.within(p, bound2, fresh);
      ASSERT_EQ(near, closest2 <= bound2) << "query " << i << " bound2 " << bound2;
      const AabbTree::Hit before = chained;
      ASSERT_EQ(tree.within(p, bound2, chained), near) << "query " << i << " from a hint";
      if (!near) {
        EXPECT_EQ(chained.face, before.face);  // left as it was
        continue;
      }
      ++yes;
      for (const AabbTree::Hit& h : {fresh, chained}) {
        ASSERT_TRUE(h.found());
        EXPECT_LE(h.distance2, bound2);
        EXPECT_GE(h.distance2, closest2);
        const Tri& t = soup.triangles[h.face];
        EXPECT_EQ(h.distance2, point_triangle_distance2(p, soup.positions[t[0]], soup.positions[t[1]],
                                                        soup.positions[t[2]]));
      }
    }
  }
  EXPECT_GT(yes, 2000);  // every query at its own distance, and some at the fixed bounds
}

TEST(AabbTree, IdenticalTrianglesKeepTheTreeShallow) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles.assign(5000, Tri{0, 1, 2});
  const AabbTree tree(m);
  EXPECT_LE(tree.depth(), 20);
  EXPECT_DOUBLE_EQ(tree.closest({0.2, 0.2, 1.0}).distance2, 1.0);
}

TEST(AabbTree, EmptyAndInvalid) {
  const AabbTree empty{Mesh{}};
  EXPECT_TRUE(empty.empty());
  EXPECT_FALSE(empty.closest({1, 2, 3}).found());

  Mesh bad;
  bad.positions = {{0, 0, 0}, {1, 0, 0}};
  bad.triangles = {{0, 1, 2}};
  EXPECT_THROW(AabbTree{bad}, InputError);
  bad.positions.push_back({0, NAN, 0});
  EXPECT_THROW(AabbTree{bad}, InputError);
}

TEST(AabbTree, Bounds) {
  const AabbTree tree(test::grid_patch(3, 4, 2.0, 5.0, 1.5));
  const auto b = tree.bounds();
  EXPECT_EQ(b[0], (Vec3{0, 0, 1.5}));
  EXPECT_EQ(b[1], (Vec3{2, 5, 1.5}));
}

}  // namespace
}  // namespace prm
