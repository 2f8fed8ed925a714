// Metro distance on a real mesh (../shared/meshes/horse.ply, 48,485 vertices): stability across seeds, and the
// size of a known perturbation recovered. Fails (does not skip) when the data is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "prm/aabb_tree.h"
#include "prm/mesh_io.h"
#include "prm/metro_distance.h"
#include "prm/point_triangle_distance.h"
#include "prm/vec3.h"

namespace prm {
namespace {

const Mesh& horse() {
  static const Mesh m = read_mesh(std::string(PRM_SHARED_MESHES) + "/horse.ply");
  return m;
}

// Every vertex moved along its (area-weighted) normal by a uniform random amount in [-amplitude, amplitude].
Mesh bumped(const Mesh& m, double amplitude, uint64_t seed) {
  std::vector<Vec3> normal(m.positions.size(), Vec3{0, 0, 0});
  for (const Tri& t : m.triangles) {
    const Vec3 n = triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
    for (uint32_t v : t) normal[v] += n;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Mesh out = m;
  for (size_t v = 0; v < out.positions.size(); ++v) out.positions[v] += normalized(normal[v]) * u(rng);
  return out;
}

TEST(MetroRealMesh, RmsIsStableAcrossSeeds) {
  const Mesh& a = horse();
  ASSERT_EQ(a.num_vertices(), 48485u);
  const double diag = bbox_diagonal(a);
  const Mesh b = bumped(a, 2e-4 * diag, 1);
  const MetroReference ref(a, MetroOptions{});  // Metro's default: ten samples per face, about a million
  std::vector<double> rms;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    MetroOptions o;
    o.seed = seed;
    rms.push_back(metro_distance(a, b, o).rms);
  }
  const auto [lo, hi] = std::minmax_element(rms.begin(), rms.end());
  EXPECT_LT((*hi - *lo) / *lo, 0.01) << "RMS varies by more than 1% across seeds";
  // A known perturbation is recovered in size: normal displacements uniform in [-e, e] have RMS e/sqrt(3) at the
  // vertices; between vertices they are interpolated (smaller), and the closest point is not always along the
  // normal (smaller again). So the RMS lies below e/sqrt(3) and well above, say, a quarter of it.
  const double e = 2e-4 * diag;
  EXPECT_LT(rms[0], e / std::sqrt(3.0));
  EXPECT_GT(rms[0], 0.25 * e / std::sqrt(3.0));
  const DistanceReport r = ref.compare(b);
  EXPECT_NEAR(r.rms, rms[0], 1e-3 * rms[0]);
  EXPECT_LE(r.max, e * 1.0001);
}

TEST(MetroRealMesh, SampleCountsFollowMetro) {
  const Mesh& a = horse();
  const DistanceReport r = metro_distance(a, a);
  EXPECT_EQ(r.a_to_b.vertex_samples, 48485u);
  EXPECT_NEAR(static_cast<double>(r.a_to_b.samples), 10.0 * static_cast<double>(a.num_faces()), 2.0);
  EXPECT_LT(r.max, 1e-12 * r.diagonal);
}

// The tree's hinted queries, as Metro makes them (runs of nearby points, each starting from the previous answer),
// give brute force's distance bit for bit on a real mesh, and a triangle at that distance. Points off the surface by
// up to 1e-3 of the diagonal, in runs of 8 near one vertex (where several triangles are often exactly as near).
TEST(MetroRealMesh, TreeQueriesMatchBruteForce) {
  const Mesh& m = horse();
  const AabbTree tree(m);
  const double diag = bbox_diagonal(m);
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<size_t> vertex(0, m.positions.size() - 1);
  std::uniform_real_distribution<double> u(-1e-3 * diag, 1e-3 * diag);
  size_t hint_kept = 0;
  for (int run = 0; run < 40; ++run) {
    const Vec3 centre = m.positions[vertex(rng)];
    AabbTree::Hit hint;
    for (int i = 0; i < 8; ++i) {
      const Vec3 p = centre + Vec3{u(rng), u(rng), u(rng)} * (i % 2 == 0 ? 1.0 : 0.01);
      double brute = HUGE_VAL;
      for (const Tri& t : m.triangles)
        brute = std::min(brute, point_triangle_distance2(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
      const uint32_t before = hint.face;
      tree.closest(p, hint);
      ASSERT_EQ(hint.distance2, brute) << "run " << run << " point " << i;
      const Tri& t = m.triangles[hint.face];
      ASSERT_EQ(point_triangle_distance2(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]), brute);
      ASSERT_EQ(tree.closest(p).distance2, brute);
      hint_kept += hint.face == before ? 1 : 0;
    }
  }
  EXPECT_GT(hint_kept, 40u);  // the hint's own triangle was often the answer: the hinted path was exercised
}

}  // namespace
}  // namespace prm
