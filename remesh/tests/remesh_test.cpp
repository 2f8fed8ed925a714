// The remesher end to end on real meshes (issue 4's invariants): a closed 2-manifold with the input's components and
// genus, no zero-area and no flipped triangles, regular triangles exactly on the lattice, a PLY round trip that
// changes nothing; and the paper's regime (n_r <= n_o, mostly regular) at a target error of 2e-4.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "prm/aabb_tree.h"
#include "prm/mesh_io.h"
#include "prm/mesh_repair.h"
#include "prm/mesh_validate.h"
#include "prm/metro_distance.h"
#include "prm/remesh/remesh.h"
#include "prm/vec3.h"

namespace prm::remesh {
namespace {

Mesh load_closed(const std::string& path) {
  Mesh m = read_mesh(path);
  if (!validate_mesh(m).closed()) m = repair_mesh(m);
  return m;
}

// A closed, oriented 2-manifold with the input's components and genus, no face with a repeated corner and no
// duplicate face.
void expect_input_topology(const Mesh& input, const PrmMesh& prm, const std::string& name) {
  const MeshReport in = validate_mesh(input), out = validate_mesh(prm.mesh);
  EXPECT_TRUE(out.closed() && out.manifold() && out.oriented()) << name;
  EXPECT_EQ(out.components, in.components) << name;
  EXPECT_EQ(out.genus_sum(), in.genus_sum()) << name;
  EXPECT_EQ(out.repeated_index_faces + out.duplicate_faces, 0u) << name;
}

// max_turned: faces the quantized separation may leave turned away from the input (0 but for the known cases below).
void expect_valid_prm(const Mesh& input, const PrmMesh& prm, const std::string& name, size_t max_turned = 0) {
  expect_input_topology(input, prm, name);
  EXPECT_EQ(validate_mesh(prm.mesh).zero_area_faces, 0u) << name;
  // Flipped: the normal more than 90 degrees from the input's normal at the point nearest the centroid.
  const AabbTree tree(input);
  size_t flipped = 0;
  for (const Tri& t : prm.mesh.triangles) {
    const Vec3& a = prm.mesh.positions[t[0]];
    const Vec3& b = prm.mesh.positions[t[1]];
    const Vec3& c = prm.mesh.positions[t[2]];
    const auto hit = tree.closest((a + b + c) * (1.0 / 3.0));
    const Tri& s = input.triangles[hit.face];
    const Vec3 sn = triangle_normal_area2(input.positions[s[0]], input.positions[s[1]], input.positions[s[2]]);
    if (dot(triangle_normal_area2(a, b, c), sn) <= 0) ++flipped;
  }
  // None, also where the quantized separation moved vertices or collapsed an edge to give every face an area
  // (issue 17: its last pass, which lets the input's side go, once turned 1 face on feline_5k and 1 on cow).
  EXPECT_LE(flipped, max_turned) << name << ": flipped triangles";
  EXPECT_LE(prm.stats.quantized_turned, max_turned) << name;
  EXPECT_EQ(prm.stats.unrepaired, 0u) << name;
  // Lattice exactness.
  for (size_t v = 0; v < prm.mesh.positions.size(); ++v) {
    const int32_t r = prm.vertex_relief[v];
    if (r < 0) continue;
    const int pair = axis_pair(prm.relief_axis[static_cast<size_t>(r)]);
    // Its relief's own lattice (spec §8.4.2: a grid size per relief).
    const auto base = HexLattice::with_grid(prm.grid_of(static_cast<size_t>(r))).to_base(prm.lattice_i[v], prm.lattice_j[v]);
    ASSERT_EQ(prm.frame.quantize(prm.mesh.positions[v][static_cast<size_t>(pair_u(pair))], pair_u(pair)), base[0]) << name;
    ASSERT_EQ(prm.frame.quantize(prm.mesh.positions[v][static_cast<size_t>(pair_w(pair))], pair_w(pair)), base[1]) << name;
  }
  for (size_t f = 0; f < prm.mesh.triangles.size(); ++f) {
    if (!prm.face_regular[f]) continue;
    const Tri& t = prm.mesh.triangles[f];
    auto ij = [&](uint32_t v) { return std::array<int64_t, 2>{prm.lattice_i[v], prm.lattice_j[v]}; };
    ASSERT_TRUE(is_grid_triangle(prm.relief_axis[static_cast<size_t>(prm.face_relief[f])], ij(t[0]), ij(t[1]), ij(t[2])));
  }
}

void expect_ply_round_trip(const PrmMesh& prm, const std::string& name) {
  const std::string path = std::string(PRM_BINARY_DIR) + "/remesh_test_" + name + ".ply";
  write_mesh(prm.mesh, path, WriteOptions{MeshFormat::Ply, true, true, true});
  const PrmMesh back = load_prm_labels(read_mesh(path));
  std::remove(path.c_str());
  EXPECT_EQ(back.mesh.positions, prm.mesh.positions) << name;
  EXPECT_EQ(back.mesh.triangles, prm.mesh.triangles) << name;
  EXPECT_EQ(back.vertex_relief, prm.vertex_relief) << name;
  EXPECT_EQ(back.lattice_i, prm.lattice_i) << name;
  EXPECT_EQ(back.lattice_j, prm.lattice_j) << name;
  EXPECT_EQ(back.face_regular, prm.face_regular) << name;
  EXPECT_EQ(back.relief_axis, prm.relief_axis) << name;
  EXPECT_EQ(back.lattice.A, prm.lattice.A) << name;
  EXPECT_EQ(back.relief_grid, prm.relief_grid) << name;
  EXPECT_EQ(back.frame.origin, prm.frame.origin) << name;
  EXPECT_EQ(back.frame.step, prm.frame.step) << name;
}

void check_mesh(const std::string& path, const std::string& name, double grid_fraction, size_t max_turned = 0) {
  const Mesh input = load_closed(path);
  RemeshOptions o;
  o.grid_fraction = grid_fraction;
  const RemeshResult r = remesh(input, o);
  std::printf("%s: n_o %zu n_r %zu regular %.1f%% (quantization: %zu vertices moved, %zu edges collapsed)\n",
              name.c_str(), input.positions.size(), r.prm.stats.vertices,
              100.0 * r.prm.stats.regular_faces / r.prm.stats.faces, r.prm.stats.quantized_moves,
              r.prm.stats.quantized_collapses);
  expect_valid_prm(input, r.prm, name, max_turned);
  expect_ply_round_trip(r.prm, name);
}

// (CGAL's bones.off is left out: at these grid sizes its thin bones are narrower than a grid triangle, which can then
// lie nearer to the far side of a bone than to its own, and count as flipped by the nearest-face test.)
// Built twice: prm_remesh_mesh_tests has the small meshes and the target error on the paper's models (the
// invariants on small and dense real meshes, fast enough for the sanitizer run); prm_remesh_dense_tests
// (PRM_REMESH_DENSE, labelled heavy) two fixed grids on eight dense meshes.
#ifndef PRM_REMESH_DENSE
TEST(Remesh, SmallRealMeshes) {
  for (const char* name : {"spot.obj", "fandisk.obj", "feline_5k.obj", "rocker-arm.off"})
    check_mesh(std::string(PRM_SHARED_MESHES) + "/" + name, name, 0.01);
  for (const char* name : {"cow.off", "elephant.off", "knot1.off", "double-torus-example.off", "dino.off", "eight.off"})
    check_mesh(std::string(PRM_CGAL_MESHES) + "/" + name, name, 0.01);
}

// Regression: coarse grids on meshes with thin parts (the man's fingers and the cow's legs and horns are a few grid
// steps wide) once crashed the last-resort repair of the seams (it deleted and re-added faces while iterating over
// them). Where a part is thinner than a grid triangle the nearest-face test cannot tell which side is out (as with
// bones.off above), so the man may keep a few triangles that it counts as flipped: the mesh must still be a closed
// manifold of the input's topology and round-trip through PLY, and the count stays small.
TEST(Remesh, CoarseGridOnThinParts) {
  check_mesh(std::string(PRM_CGAL_MESHES) + "/cow.off", "cow.off", 0.008);
  const Mesh input = load_closed(std::string(PRM_CGAL_MESHES) + "/man.off");
  for (double g : {0.008, 0.015}) {
    RemeshOptions o;
    o.grid_fraction = g;
    const RemeshResult r = remesh(input, o);
    const std::string name = "man.off at " + std::to_string(g);
    expect_input_topology(input, r.prm, name);
    EXPECT_LE(r.prm.stats.unrepaired, 10u) << name;
    expect_ply_round_trip(r.prm, "man");
  }
}

// The paper's regime on its models: at an RMS error of 2e-4 of the diagonal, fewer vertices than the input and at
// least 84% regular triangles (issue 4 asked 85% of the interpolating remesher; least-squares heights meet the
// error on a coarser grid, where the seams take a larger share: feline 25,555 vertices and 85.0% regular against
// 46,475 and 88.6%).
TEST(Remesh, TargetErrorOnPaperModels) {
  for (const char* name : {"horse.ply", "venus.off", "feline.off", "bunny_zipper.ply"}) {
    const Mesh input = load_closed(std::string(PRM_SHARED_MESHES) + "/" + name);
    const MetroReference reference(input);
    RemeshOptions o;
    o.target_error = 2e-4;
    const RemeshResult r = remesh(input, o, [&](const PrmMesh& c) {
      const DistanceReport d = reference.compare(c.mesh);
      return ErrorEstimate{d.rel(d.rms), d.rel(d.max)};
    });
    const double regular = static_cast<double>(r.prm.stats.regular_faces) / static_cast<double>(r.prm.stats.faces);
    std::printf("%s: target 2e-4: g %lld steps, n_o %zu, n_r %zu, regular %.1f%%, RMS %.3e\n", name,
                static_cast<long long>(r.prm.lattice.A), input.positions.size(), r.prm.stats.vertices, 100 * regular,
                r.error.rms);
    EXPECT_LE(r.error.rms, 2e-4) << name;
    EXPECT_LE(r.prm.stats.vertices, input.positions.size()) << name;
    EXPECT_GE(regular, 0.84) << name;
    // bunny_zipper: 3 faces near its closed holes that the quantization turns away from the input and the
    // separation cannot mend (counted since it looks at every face; the stream of `prm pack --target-error 2e-4
    // --bits 12 --step-scale 1` had 10 such faces before, 3 now: issue 17).
    expect_valid_prm(input, r.prm, name, std::string(name) == "bunny_zipper.ply" ? 3 : 0);
  }
}

// The same mesh remeshed twice at one grid size (a fraction of the diagonal), once per variant of the options, with
// the RMS distance of each to the input.
struct TwoRemeshes {
  double rms[2];
  PrmMesh prm[2];
};
template <typename Configure>
TwoRemeshes remesh_two_ways(const Mesh& input, double grid_fraction, const Configure& configure) {
  const MetroReference reference(input);
  TwoRemeshes out;
  for (int variant = 0; variant < 2; ++variant) {
    RemeshOptions o;
    o.grid_fraction = grid_fraction;
    configure(variant, o);
    RemeshResult r = remesh(input, o);
    const DistanceReport d = reference.compare(r.prm.mesh);
    out.rms[variant] = d.rel(d.rms);
    out.prm[variant] = std::move(r.prm);
  }
  return out;
}

// Least-squares heights (height_fitting.h): at one grid size, the fitted PRM is closer to the input than the
// interpolating one (same vertices, same lattice, same triangles; only heights differ), and stays a valid PRM.
TEST(Remesh, LeastSquaresHeightsLowerTheError) {
  for (const char* name : {"horse.ply", "spot.obj"}) {
    const Mesh input = load_closed(std::string(PRM_SHARED_MESHES) + "/" + name);
    const double grid = std::string(name) == "spot.obj" ? 0.015 : 0.008;
    auto [rms, prm] = remesh_two_ways(input, grid, [](int fit, RemeshOptions& o) { o.fit_heights = fit == 1; });
    std::printf("%s at %g: RMS interpolated %.3e, least squares %.3e; %zu heights moved\n", name, grid, rms[0],
                rms[1], prm[1].stats.heights_moved);
    EXPECT_LT(rms[1], 0.85 * rms[0]) << name;
    EXPECT_GT(prm[1].stats.heights_moved, prm[1].stats.lattice_vertices / 2) << name;
    EXPECT_EQ(prm[1].mesh.triangles, prm[0].mesh.triangles) << name;
    EXPECT_EQ(prm[1].face_regular, prm[0].face_regular) << name;
    // Only heights moved: the two base-plane coordinates of every lattice vertex are unchanged.
    for (size_t v = 0; v < prm[0].mesh.positions.size(); ++v) {
      if (prm[0].vertex_relief[v] < 0) {
        EXPECT_EQ(prm[1].mesh.positions[v], prm[0].mesh.positions[v]);
        continue;
      }
      const int pair = axis_pair(prm[0].relief_axis[static_cast<size_t>(prm[0].vertex_relief[v])]);
      EXPECT_EQ(prm[1].mesh.positions[v][static_cast<size_t>(pair_u(pair))],
                prm[0].mesh.positions[v][static_cast<size_t>(pair_u(pair))]);
      EXPECT_EQ(prm[1].mesh.positions[v][static_cast<size_t>(pair_w(pair))],
                prm[0].mesh.positions[v][static_cast<size_t>(pair_w(pair))]);
    }
    expect_valid_prm(input, prm[1], name);
  }
}

// HeightFitOptions::reuse_faces (pack's effort 0): a sample's closest point taken on an input triangle already known
// for it when it projects well inside (AabbTree::well_inside), instead of a closest-point query. The same
// triangulation, nearly the same heights: horse 7 of 8,502 vertices differ, by up to 0.01 grid lengths, spot none;
// the RMS distance stays. Taking the known triangle whether or not the sample projects inside it fails this (every
// vertex differs, RMS x7); the interior test without the height bound let 461 and 108 vertices differ, a few of them
// by up to a quarter grid (a fold's revert in one run and not the other).
TEST(Remesh, ReusedFacesGiveNearlyTheSameHeights) {
  for (const char* name : {"horse.ply", "spot.obj"}) {
    const Mesh input = load_closed(std::string(PRM_SHARED_MESHES) + "/" + name);
    const double grid = std::string(name) == "spot.obj" ? 0.015 : 0.008;
    auto [rms, prm] =
        remesh_two_ways(input, grid, [](int reuse, RemeshOptions& o) { o.height_fit_reuse_faces = reuse == 1; });
    ASSERT_EQ(prm[1].mesh.triangles, prm[0].mesh.triangles) << name;
    const double grid_length = grid * bbox_diagonal(input);
    size_t differ = 0;
    double largest = 0;
    for (size_t v = 0; v < prm[0].mesh.positions.size(); ++v) {
      const double d = std::sqrt(norm2(prm[1].mesh.positions[v] - prm[0].mesh.positions[v]));
      differ += d > 0;
      largest = std::max(largest, d / grid_length);
    }
    std::printf("%s at %g: RMS queried %.4e, reused %.4e; %zu of %zu vertices differ, by up to %.2e grid lengths\n",
                name, grid, rms[0], rms[1], differ, prm[0].mesh.positions.size(), largest);
    EXPECT_NEAR(rms[1], rms[0], 0.002 * rms[0]) << name;
    EXPECT_LT(differ, prm[0].mesh.positions.size() / 100) << name;
    EXPECT_LE(largest, 0.25) << name;  // HeightFitOptions::max_shift
    expect_valid_prm(input, prm[1], name);
  }
}

// The error flips (SeamOptions::error_flip_weight) bring the PRM closer to the input at the same grid, touch nothing
// but the triangulation of the seams and the irregular triangles (same vertices, same positions before the height
// fit), and leave a valid PRM. Measured (this test, or `prm remesh M --grid-fraction G --error-flip-weight W
// --json`): horse at 0.008, RMS 2.58e-4 without, 2.21e-4 with the default weight 2 (451 flips); spot at 0.015,
// 6.60e-4 and 5.53e-4 (147 flips).
TEST(Remesh, ErrorFlipsLowerTheError) {
  for (const char* name : {"horse.ply", "spot.obj"}) {
    const Mesh input = load_closed(std::string(PRM_SHARED_MESHES) + "/" + name);
    const double grid = std::string(name) == "spot.obj" ? 0.015 : 0.008;
    // Variant 0 without error flips, variant 1 with the default weight (kDefaultErrorFlipWeight).
    auto [rms, prm] = remesh_two_ways(input, grid, [](int flips, RemeshOptions& o) {
      if (!flips) o.error_flip_weight = -1.0;
    });
    std::printf("%s at %g: RMS without error flips %.3e, with %.3e (%zu flips)\n", name, grid, rms[0], rms[1],
                prm[1].stats.error_flips);
    EXPECT_EQ(prm[0].stats.error_flips, 0u) << name;
    EXPECT_GT(prm[1].stats.error_flips, 0u) << name;
    EXPECT_LT(rms[1], 0.95 * rms[0]) << name;
    EXPECT_EQ(prm[1].mesh.positions.size(), prm[0].mesh.positions.size()) << name;
    EXPECT_EQ(prm[1].mesh.triangles.size(), prm[0].mesh.triangles.size()) << name;
    EXPECT_EQ(prm[1].vertex_relief, prm[0].vertex_relief) << name;
    EXPECT_EQ(prm[1].lattice_i, prm[0].lattice_i) << name;
    EXPECT_EQ(prm[1].lattice_j, prm[0].lattice_j) << name;
    EXPECT_NE(prm[1].mesh.triangles, prm[0].mesh.triangles) << name;
    expect_valid_prm(input, prm[1], name);
  }
}

#else
TEST(Remesh, DenseRealMeshes) {
  // Known defect (issue 17, open): at grid 0.004 the bunny's quantized separation still turns 2 faces in its last
  // pass (29 vertices moved); every other mesh and grid here turns none.
  for (const std::string name : {"horse.ply", "venus.off", "feline.off", "bunny_zipper.ply"})
    for (double g : {0.004, 0.008})
      check_mesh(std::string(PRM_SHARED_MESHES) + "/" + name, name, g,
                 name == "bunny_zipper.ply" && g == 0.004 ? 2 : 0);
  for (const char* name : {"bunny00.off", "refined_elephant.off", "armadillo.off", "camel.off"})
    check_mesh(std::string(PRM_CGAL_MESHES) + "/" + name, name, 0.006);
}
#endif

}  // namespace
}  // namespace prm::remesh
