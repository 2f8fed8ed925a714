#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "../src/height_fitting.h"
#include "../src/triangle_samples.h"
#include "prm/aabb_tree.h"
#include "prm/error.h"
#include "prm/remesh/lattice.h"
#include "prm/remesh/reliefs.h"
#include "prm/remesh/resample.h"
#include "prm/vec3.h"
#include "test_meshes.h"

namespace prm::remesh {
namespace {

// Resampling on the naive layout (each face to its closest axis): many small reliefs, a hard case for merging.
PrmMesh run(const Mesh& m, int64_t grid, bool fit_heights = true) {
  ReliefOptions ro;
  ro.naive = true;
  const ReliefLayout layout = build_reliefs(m, ro);
  std::vector<int> axes;
  for (const Relief& r : layout.reliefs) axes.push_back(r.axis);
  LayoutInput in;
  in.refined = &layout.mesh;
  in.face_relief = &layout.face_relief;
  in.relief_axis = &axes;
  in.input = &m;
  ResampleOptions o;
  o.frame = frame_of_mesh(m, 12);
  o.grid = grid;
  o.fit_heights = fit_heights;
  return resample_and_merge(in, o);
}

TEST(Lattice, GridTriangles) {
  EXPECT_TRUE(is_grid_triangle(4, {0, 0}, {1, 0}, {0, 1}));
  EXPECT_TRUE(is_grid_triangle(4, {1, 0}, {1, 1}, {0, 1}));
  EXPECT_FALSE(is_grid_triangle(4, {0, 0}, {0, 1}, {1, 0}));
  EXPECT_TRUE(is_grid_triangle(5, {0, 0}, {0, 1}, {1, 0}));
  EXPECT_FALSE(is_grid_triangle(4, {0, 0}, {1, 1}, {0, 1}));
  const HexLattice l = HexLattice::with_grid(10);
  EXPECT_EQ(l.B, 5);
  EXPECT_EQ(l.C, 9);
}

// The remesher's lattice is the codec's (prm/lattice.h), with the stream's range of grid sizes: 2..2^bits (§8.4).
TEST(Lattice, GridSizesTheStreamCanCarry) {
  EXPECT_EQ(lattice_of_grid(4096, 12).C, HexLattice::with_grid(4096).C);
  EXPECT_THROW(lattice_of_grid(4097, 12), InputError);
  EXPECT_THROW(lattice_of_grid(1, 12), InputError);
  EXPECT_THROW(frame_of_mesh(test::icosphere(1, 1.0, 0.0), 21), std::invalid_argument);
}

TEST(Resample, SphereIsClosedManifoldAndMostlyRegular) {
  const Mesh sphere = test::icosphere(5, 1.0, 0.05);
  const PrmMesh prm = run(sphere, 40);
  const auto t = test::topology(prm.mesh);
  EXPECT_TRUE(t.closed_manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus_sum, 0);
  EXPECT_EQ(t.degenerate, 0u);
  const auto& s = prm.stats;
  std::printf("sphere: V %zu F %zu regular %.1f%% lattice %zu stuck %zu collapses %zu flips %zu seam %zu area_flips %zu repairs %zu unrepaired %zu fill %zu broken %zu generic %zu\n",
              s.vertices, s.faces, 100.0 * s.regular_faces / s.faces, s.lattice_vertices, s.stuck, s.collapses,
              s.cell_flips, s.seam_collapses, s.area_flips, s.repairs, s.unrepaired, s.fill_triangles, s.loops_broken,
              s.generic_moves);
  EXPECT_EQ(s.unrepaired, 0u);
  EXPECT_GT(static_cast<double>(s.regular_faces) / static_cast<double>(s.faces), 0.6);
}

TEST(Resample, TorusKeepsGenus) {
  const Mesh torus = test::torus(120, 60);
  const PrmMesh prm = run(torus, 30);
  const auto t = test::topology(prm.mesh);
  EXPECT_TRUE(t.closed_manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus_sum, 1);
  const auto& s = prm.stats;
  std::printf("torus: V %zu F %zu regular %.1f%% stuck %zu unrepaired %zu\n", s.vertices, s.faces,
              100.0 * s.regular_faces / s.faces, s.stuck, s.unrepaired);
}

// Every grid vertex sits exactly on its lattice point in quantized coordinates, and every regular triangle
// is a grid triangle of its relief facing the relief's axis.
void expect_exact_lattice(const PrmMesh& prm) {
  size_t checked = 0;
  for (size_t v = 0; v < prm.mesh.positions.size(); ++v) {
    const int32_t r = prm.vertex_relief[v];
    if (r < 0) continue;
    const int pair = axis_pair(prm.relief_axis[static_cast<size_t>(r)]);
    const auto base = prm.lattice.to_base(prm.lattice_i[v], prm.lattice_j[v]);
    ASSERT_EQ(prm.frame.quantize(prm.mesh.positions[v][static_cast<size_t>(pair_u(pair))], pair_u(pair)), base[0]);
    ASSERT_EQ(prm.frame.quantize(prm.mesh.positions[v][static_cast<size_t>(pair_w(pair))], pair_w(pair)), base[1]);
    ++checked;
  }
  EXPECT_GT(checked, 0u);
  for (size_t f = 0; f < prm.mesh.triangles.size(); ++f) {
    if (!prm.face_regular[f]) continue;
    const Tri& t = prm.mesh.triangles[f];
    const int axis = prm.relief_axis[static_cast<size_t>(prm.face_relief[f])];
    auto ij = [&](uint32_t v) { return std::array<int64_t, 2>{prm.lattice_i[v], prm.lattice_j[v]}; };
    ASSERT_TRUE(is_grid_triangle(axis, ij(t[0]), ij(t[1]), ij(t[2])));
    const Vec3 n = triangle_normal_area2(prm.mesh.positions[t[0]], prm.mesh.positions[t[1]], prm.mesh.positions[t[2]]);
    ASSERT_GT(dot(n, axis_vector(axis)), 0.0);
  }
}

TEST(Resample, RegularVerticesAreExactLatticePoints) {
  const PrmMesh prm = run(test::icosphere(4, 1.0, 0.05), 60);
  expect_exact_lattice(prm);
}

TEST(Resample, SelfOverlappingReliefWorks) {
  // The ramp's top overlaps itself in projection along z: one relief with two sheets over the same lattice points.
  const Mesh ramp = test::helical_ramp();
  ASSERT_TRUE(test::topology(ramp).closed_manifold);
  const PrmMesh prm = run(ramp, 40);
  const auto t = test::topology(prm.mesh);
  EXPECT_TRUE(t.closed_manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus_sum, 0);
  EXPECT_EQ(prm.stats.unrepaired, 0u);
  expect_exact_lattice(prm);
  // Two distinct grid vertices of one relief with the same lattice coordinates: the relief overlaps itself.
  std::map<std::tuple<int32_t, int32_t, int32_t>, int> seen;
  int overlaps = 0;
  for (size_t v = 0; v < prm.mesh.positions.size(); ++v)
    if (prm.vertex_relief[v] >= 0 && ++seen[{prm.vertex_relief[v], prm.lattice_i[v], prm.lattice_j[v]}] == 2) ++overlaps;
  EXPECT_GT(overlaps, 100);
  std::printf("ramp: V %zu F %zu regular %.1f%% overlapping lattice points %d\n", prm.stats.vertices, prm.stats.faces,
              100.0 * prm.stats.regular_faces / prm.stats.faces, overlaps);
  EXPECT_GT(static_cast<double>(prm.stats.regular_faces) / static_cast<double>(prm.stats.faces), 0.7);
}


// HeightFitOptions::closest_faces (the seam error flips' closest input faces of each face's samples): the first
// iteration takes its points on those faces instead of searching, and the heights are the searched ones, bit for bit.
// And the faces nearest the centroids it hands on (HeightFitOptions::centroid_faces) are the search's.
TEST(HeightFit, ClosestFacesGiveTheSearchedHeights) {
  const Mesh sphere = test::icosphere(5, 1.0, 0.05);
  const PrmMesh merged = run(sphere, 40, false);
  const AabbTree tree(sphere);
  std::vector<uint32_t> faces;
  for (const Tri& t : merged.mesh.triangles)
    for (const auto& w : kTriangleSamples) {
      const Vec3& a = merged.mesh.positions[t[0]];
      const Vec3& b = merged.mesh.positions[t[1]];
      const Vec3& c = merged.mesh.positions[t[2]];
      faces.push_back(faces.size() % 5 == 3 ? AabbTree::kNoFace : tree.closest(a * w[0] + b * w[1] + c * w[2]).face);
    }
  PrmMesh searched = merged, given = merged;
  const HeightFitStats s1 = fit_heights(searched, sphere, tree, HeightFitOptions());
  HeightFitOptions with_faces;
  with_faces.closest_faces = &faces;
  std::vector<uint32_t> centroid_faces;
  with_faces.centroid_faces = &centroid_faces;
  const HeightFitStats s2 = fit_heights(given, sphere, tree, with_faces);
  // HeightFitOptions::centroid_faces: where known, the search's answer at the returned positions.
  ASSERT_EQ(centroid_faces.size(), given.mesh.triangles.size());
  size_t known = 0, wrong = 0;
  for (size_t f = 0; f < centroid_faces.size(); ++f) {
    if (centroid_faces[f] == AabbTree::kNoFace) continue;
    ++known;
    const Tri& t = given.mesh.triangles[f];
    const std::vector<Vec3>& x = given.mesh.positions;
    const Vec3 centroid = (x[t[0]] + x[t[1]] + x[t[2]]) * (1.0 / 3.0);
    wrong += tree.closest(centroid).face != centroid_faces[f];
  }
  EXPECT_GT(known, given.mesh.triangles.size() / 2);
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(s1.moved, 100u);
  EXPECT_EQ(s1.moved, s2.moved);
  EXPECT_EQ(s1.reverted, s2.reverted);
  ASSERT_EQ(searched.mesh.positions.size(), given.mesh.positions.size());
  size_t differ = 0;
  for (size_t v = 0; v < given.mesh.positions.size(); ++v)
    differ += searched.mesh.positions[v] != given.mesh.positions[v];
  EXPECT_EQ(differ, 0u);
}

}  // namespace
}  // namespace prm::remesh
