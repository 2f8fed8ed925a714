// Paper §2.1 on real meshes: every relief faces its axis, the reliefs tile the input exactly, and smaller tau gives
// smoother boundaries and fewer reliefs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "prm/error.h"
#include "prm/mesh_io.h"
#include "prm/mesh_repair.h"
#include "prm/mesh_validate.h"
#include "prm/remesh/lattice.h"
#include "prm/remesh/reliefs.h"
#include "prm/vec3.h"
#include "test_meshes.h"

namespace prm::remesh {
namespace {

Mesh load_closed(const std::string& path) {
  Mesh m = read_mesh(path);
  if (!validate_mesh(m).closed()) m = repair_mesh(m);
  return m;
}

double area(const Mesh& m) {
  double a = 0;
  for (const Tri& t : m.triangles) a += triangle_area(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  return a;
}

// Every refined face faces its relief's axis, lies in its source face, and the areas add up.
void expect_exact_tiling(const Mesh& input, const ReliefLayout& L, const std::string& name) {
  ASSERT_EQ(L.face_relief.size(), L.mesh.triangles.size());
  ASSERT_EQ(L.source_face.size(), L.mesh.triangles.size());
  const double diag2 = [&] {
    Vec3 lo = input.positions[0], hi = lo;
    for (const Vec3& p : input.positions)
      for (size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    return norm2(hi - lo);
  }();
  size_t not_facing = 0, off_source = 0;
  for (size_t f = 0; f < L.mesh.triangles.size(); ++f) {
    const Tri& t = L.mesh.triangles[f];
    const int axis = L.reliefs[static_cast<size_t>(L.face_relief[f])].axis;
    const Tri& s = input.triangles[static_cast<size_t>(L.source_face[f])];
    const Vec3 sn = triangle_normal_area2(input.positions[s[0]], input.positions[s[1]], input.positions[s[2]]);
    const Vec3 n = triangle_normal_area2(L.mesh.positions[t[0]], L.mesh.positions[t[1]], L.mesh.positions[t[2]]);
    // The refined face keeps its source face's orientation, and the source faces the axis.
    if (!(dot(sn, axis_vector(axis)) > 0) || dot(n, sn) < 0) ++not_facing;
    // Its corners lie in the source face's plane.
    const Vec3 un = normalized(sn);
    for (uint32_t v : t)
      if (std::abs(dot(L.mesh.positions[v] - input.positions[s[0]], un)) > 1e-9 * std::sqrt(diag2)) ++off_source;
  }
  EXPECT_EQ(not_facing, 0u) << name;
  EXPECT_EQ(off_source, 0u) << name;
  EXPECT_NEAR(area(L.mesh), area(input), 1e-9 * area(input)) << name;
  const MeshReport in = validate_mesh(input), out = validate_mesh(L.mesh);
  EXPECT_EQ(out.boundary_edges, in.boundary_edges) << name << ": the refinement opened or closed edges";
  EXPECT_EQ(out.non_manifold_edges, 0u) << name;
  EXPECT_EQ(out.genus_sum(), in.genus_sum()) << name;
  // Every face of a relief is connected to it, and the reliefs of one axis never touch (they would be one).
  double per_relief_area = 0;
  for (const Relief& r : L.reliefs) per_relief_area += r.area;
  EXPECT_NEAR(per_relief_area, area(input), 1e-9 * area(input)) << name;
}

TEST(Reliefs, RealMeshesFaceTheirAxesAndTileTheInput) {
  for (const char* name : {"spot.obj", "fandisk.obj", "feline_5k.obj", "rocker-arm.off", "bunny_zipper.ply",
                           "horse.ply", "venus.off", "feline.off"}) {
    const Mesh m = load_closed(std::string(PRM_SHARED_MESHES) + "/" + name);
    for (double tau : {0.1, 0.2, 0.4}) {
      ReliefOptions o;
      o.tau = tau;
      const ReliefLayout L = build_reliefs(m, o);
      expect_exact_tiling(m, L, std::string(name) + " tau " + std::to_string(tau));
    }
  }
}

TEST(Reliefs, CgalMeshesFaceTheirAxes) {
  for (const char* name : {"bunny00.off", "camel.off", "cow.off", "elephant.off", "armadillo.off", "knot1.off",
                           "double-torus-example.off", "bones.off"}) {
    const Mesh m = load_closed(std::string(PRM_CGAL_MESHES) + "/" + name);
    const ReliefLayout L = build_reliefs(m, {});
    expect_exact_tiling(m, L, name);
  }
}

TEST(Reliefs, SmallerTauGivesSmootherBoundariesAndFewerReliefs) {
  const Mesh m = load_closed(std::string(PRM_SHARED_MESHES) + "/feline.off");
  ReliefOptions naive;
  naive.naive = true;
  const ReliefLayout N = build_reliefs(m, naive);
  double prev_length = HUGE_VAL;
  size_t prev_count = SIZE_MAX;
  for (double tau : {0.577, 0.4, 0.2, 0.1}) {
    // The construction of paper §2.1 alone: small reliefs merge only into neighbours they face by tau.
    ReliefOptions o;
    o.tau = tau;
    o.merge_facing = tau;
    o.min_relief_triangles = 16;
    const ReliefLayout L = build_reliefs(m, o);
    EXPECT_LT(L.boundary_length, prev_length) << "tau " << tau;
    EXPECT_LE(L.reliefs.size(), prev_count) << "tau " << tau;
    prev_length = L.boundary_length;
    prev_count = L.reliefs.size();
    if (tau == 0.2) {
      EXPECT_LT(L.boundary_length, 0.6 * N.boundary_length);
      EXPECT_LT(L.reliefs.size(), N.reliefs.size() / 5);
    }
  }
}

TEST(Reliefs, SmallReliefsJoinNeighboursTheyBarelyFace) {
  // The default merge (reliefs under 256 mean triangles, facing 0.02) against the one held to tau (16, tau): fewer
  // reliefs and shorter seams on the feline, whose paws and ears leave many small reliefs.
  const Mesh m = load_closed(std::string(PRM_SHARED_MESHES) + "/feline.off");
  ReliefOptions held;
  held.merge_facing = held.tau;
  held.min_relief_triangles = 16;
  const ReliefLayout a = build_reliefs(m, held), b = build_reliefs(m, {});
  EXPECT_GT(b.merged_reliefs, a.merged_reliefs);
  EXPECT_LT(b.reliefs.size(), a.reliefs.size());
  EXPECT_LT(b.boundary_length, a.boundary_length);
  std::printf("feline reliefs %zu -> %zu, boundary %.4f -> %.4f\n", a.reliefs.size(), b.reliefs.size(),
              a.boundary_length, b.boundary_length);
  expect_exact_tiling(m, b, "feline");
}

TEST(Reliefs, SphereHasSixEqualReliefs) {
  const Mesh sphere = test::icosphere(5);
  const ReliefLayout L = build_reliefs(sphere, {});
  ASSERT_EQ(L.reliefs.size(), 6u);
  double total = 0;
  for (const Relief& r : L.reliefs) total += r.area;
  std::array<int, 6> seen{};
  for (const Relief& r : L.reliefs) {
    EXPECT_NEAR(r.area / total, 1.0 / 6.0, 0.01);
    ++seen[static_cast<size_t>(r.axis)];
  }
  for (int s : seen) EXPECT_EQ(s, 1);
  expect_exact_tiling(sphere, L, "sphere");
}

TEST(Reliefs, ViewPropertiesOffChangesNothingButTheProperties) {
  // remesh and pack build the layout without its PLY view (four doubles a refined face): the same layout otherwise.
  const Mesh m = load_closed(std::string(PRM_SHARED_MESHES) + "/horse.ply");
  ReliefOptions bare;
  bare.view_properties = false;
  const ReliefLayout a = build_reliefs(m, {}), b = build_reliefs(m, bare);
  EXPECT_EQ(a.mesh.face_properties.size(), 4u);
  EXPECT_TRUE(b.mesh.face_properties.empty());
  EXPECT_TRUE(b.mesh.comments.empty());
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.face_relief, b.face_relief);
  EXPECT_EQ(a.source_face, b.source_face);
  EXPECT_EQ(a.reliefs.size(), b.reliefs.size());
  EXPECT_EQ(a.boundary_length, b.boundary_length);
}

TEST(Reliefs, RefusesBadTauAndNonManifoldInput) {
  const Mesh sphere = test::icosphere(1);
  ReliefOptions o;
  o.tau = 0.6;
  EXPECT_THROW(build_reliefs(sphere, o), InputError);
  o.tau = 0;
  EXPECT_THROW(build_reliefs(sphere, o), InputError);
  Mesh bad = sphere;
  bad.triangles.push_back(bad.triangles[0]);  // an edge with three faces
  EXPECT_THROW(build_reliefs(bad, {}), InputError);
}

}  // namespace
}  // namespace prm::remesh
