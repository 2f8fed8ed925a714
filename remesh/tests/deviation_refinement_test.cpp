// The local refinement's step for a lattice vertex off the input (deviation_refinement.h, issue 22): bunny00's worst
// place was a lattice vertex 2e-3 of the diagonal off a smooth part of the input, which the refinement did not move
// (lattice vertices stayed) and whose edges no split could bring down. It moves along its relief's axis only (its
// height), keeping its lattice place and its labels, with no vertex inserted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../src/deviation_refinement.h"
#include "prm/aabb_tree.h"
#include "prm/vec3.h"
#include "test_meshes.h"

namespace prm::remesh {
namespace {

TEST(DeviationRefinement, LatticeVertexOffTheInputMovesAlongItsAxis) {
  const Mesh input = test::icosphere(2, 40.0);
  const AabbTree tree(input);
  PrmMesh prm;
  prm.mesh = input;
  uint32_t pole = 0;  // the vertex of largest z: the relief's axis +z is its normal
  for (uint32_t v = 1; v < prm.mesh.positions.size(); ++v)
    if (prm.mesh.positions[v][2] > prm.mesh.positions[pole][2]) pole = v;
  prm.vertex_relief.assign(prm.mesh.positions.size(), 0);
  prm.lattice_i.assign(prm.mesh.positions.size(), 0);
  prm.lattice_j.assign(prm.mesh.positions.size(), 0);
  prm.lattice_i[pole] = 3;
  prm.lattice_j[pole] = -2;
  prm.relief_axis = {4};  // +z
  // Off the input sideways and outwards: along its axis it can come back to the sphere, not to where it was.
  const Vec3 off = prm.mesh.positions[pole] + Vec3{2.0, 0.0, 4.0};
  prm.mesh.positions[pole] = off;
  const size_t vertices = prm.mesh.positions.size();
  DeviationRefinementOptions o;
  o.max_deviation = 1.0;
  // The budget this case was written with (hear doubled the default): with 6%, the splits without lattice moves
  // below go on to rounds whose rim moves move the vertices they inserted.
  o.max_insert_share = 0.03;
  const DeviationRefinementStats st = refine_deviations(prm, input, tree, o);
  const Vec3 now = prm.mesh.positions[pole];
  std::printf("pole moved from (%.3f %.3f %.3f) to (%.3f %.3f %.3f), %.3f from the input; %zu moved, %zu inserted\n",
              off[0], off[1], off[2], now[0], now[1], now[2], std::sqrt(tree.closest(now).distance2), st.moved,
              st.inserted);
  EXPECT_EQ(now[0], off[0]);  // its lattice place
  EXPECT_EQ(now[1], off[1]);
  EXPECT_LT(tree.closest(now).distance2, o.max_deviation * o.max_deviation);
  EXPECT_GE(st.moved, 1u);
  EXPECT_EQ(st.inserted, 0u);
  EXPECT_EQ(prm.mesh.positions.size(), vertices);
  EXPECT_EQ(prm.vertex_relief[pole], 0);
  EXPECT_EQ(prm.lattice_i[pole], 3);
  EXPECT_EQ(prm.lattice_j[pole], -2);
  // Without the lattice moves (what --max-error runs: the notch steps off) it stays where it is, and the pole's
  // faces (the mesh points that stray) are split instead.
  prm.mesh.positions[pole] = off;
  DeviationRefinementOptions no_moves = o;
  no_moves.lattice_moves = false;
  const DeviationRefinementStats sn = refine_deviations(prm, input, tree, no_moves);
  EXPECT_EQ(prm.mesh.positions[pole][2], off[2]);
  EXPECT_EQ(sn.moved, 0u);
  // Without the thin-sheet steps (the first refinement) a lattice vertex stays where it is.
  prm.mesh = input;
  prm.mesh.positions[pole] = off;
  o.thin_sheets = false;
  refine_deviations(prm, input, tree, o);
  EXPECT_EQ(prm.mesh.positions[pole][2], off[2]);
}

// lattice_reach (h22thin3): an input spike (its tip pulled out 12 along +z) over a coarser mesh whose pole is a
// lattice vertex of a +z relief. The pole itself and its faces stay within the bound (5.5) of the spike's flanks, but
// the tip is missed by 12: with lattice_reach the pole moves up its axis towards the tip, with no vertex inserted;
// without it, the tip is inserted as a new vertex and the pole stays.
// An icosphere of radius 40 with its top vertex (its index in `tip`) pulled out `out` along +z.
Mesh spiked_sphere(int subdivisions, double out, uint32_t& tip) {
  Mesh input = test::icosphere(subdivisions, 40.0);
  tip = 0;
  for (uint32_t v = 1; v < input.positions.size(); ++v)
    if (input.positions[v][2] > input.positions[tip][2]) tip = v;
  input.positions[tip] = input.positions[tip] + Vec3{0.0, 0.0, out};
  return input;
}

// A PRM of a coarse icosphere (2 subdivisions, radius 40) whose vertices are all lattice vertices of one +z relief.
PrmMesh prm_of_sphere() {
  PrmMesh prm;
  prm.mesh = test::icosphere(2, 40.0);
  prm.vertex_relief.assign(prm.mesh.positions.size(), 0);
  prm.lattice_i.assign(prm.mesh.positions.size(), 0);
  prm.lattice_j.assign(prm.mesh.positions.size(), 0);
  prm.relief_axis = {4};  // +z
  return prm;
}

TEST(DeviationRefinement, LatticeVertexReachesAMissedTipAlongItsAxis) {
  uint32_t tip = 0;
  const Mesh input = spiked_sphere(3, 12.0, tip);
  const AabbTree tree(input);
  PrmMesh prm = prm_of_sphere();
  uint32_t pole = 0;
  for (uint32_t v = 1; v < prm.mesh.positions.size(); ++v)
    if (prm.mesh.positions[v][2] > prm.mesh.positions[pole][2]) pole = v;
  const Vec3 was = prm.mesh.positions[pole];
  const size_t vertices = prm.mesh.positions.size();
  ASSERT_LT(tree.closest(was).distance2, 5.5 * 5.5);  // the pole is within the bound: only the tip is missed
  DeviationRefinementOptions o;
  o.max_deviation = 5.5;
  const DeviationRefinementStats st = refine_deviations(prm, input, tree, o);
  const Vec3 now = prm.mesh.positions[pole];
  std::printf("lattice_reach: pole from z %.3f to %.3f (tip at %.3f); %zu moved, %zu inserted\n", was[2], now[2],
              input.positions[tip][2], st.moved, st.inserted);
  EXPECT_EQ(now[0], was[0]);
  EXPECT_EQ(now[1], was[1]);
  EXPECT_GT(now[2], was[2] + 1.0);
  EXPECT_GE(st.moved, 1u);
  EXPECT_EQ(st.inserted, 0u);
  EXPECT_EQ(prm.mesh.positions.size(), vertices);
  EXPECT_EQ(prm.vertex_relief[pole], 0);
  PrmMesh no_reach = prm_of_sphere();
  o.lattice_reach = false;
  const DeviationRefinementStats sn = refine_deviations(no_reach, input, tree, o);
  std::printf("without: pole at z %.3f; %zu moved, %zu inserted\n", no_reach.mesh.positions[pole][2], sn.moved,
              sn.inserted);
  EXPECT_EQ(no_reach.mesh.positions[pole][2], was[2]);
  EXPECT_GE(sn.inserted, 1u);
}

}  // namespace

// round_towards_input (h22max4): the stream holds coordinates rounded to the frame's step. A square 0.55 steps above
// the frame's origin and 0.1 above the input (a square as large at 0.45): rounding to the nearest step puts it at 1, 0.55 from
// the input; rounded down it is 0.45 away, so every vertex goes down, exactly onto its step, its lattice-exact x and y
// unchanged. With the input at 0.6 the nearest rounding is the better one and nothing moves.
namespace {
Mesh square(double z, double half) {
  Mesh m;
  m.positions = {{-half, -half, z}, {half, -half, z}, {half, half, z}, {-half, half, z}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}
}  // namespace

TEST(DeviationRefinement, RoundingTowardsTheInputNearTheBound) {
  for (const double plane : {0.45, 0.6}) {
    const Mesh input = square(plane, 5.0);
    const AabbTree tree(input);
    PrmMesh prm;
    prm.mesh = square(0.55, 5.0);
    prm.frame.bits = 8;
    prm.frame.origin = {-5.0, -5.0, 0.0};
    prm.frame.step = 1.0;
    const size_t changed = round_towards_input(prm, input, tree, 0.1);
    std::printf("input at z %.2f: %zu rounded towards it\n", plane, changed);
    for (size_t v = 0; v < 4; ++v) {
      const Vec3& p = prm.mesh.positions[v];
      EXPECT_EQ(std::fabs(p[0]), 5.0);
      EXPECT_EQ(std::fabs(p[1]), 5.0);
      EXPECT_EQ(p[2], plane < 0.5 ? 0.0 : 0.55) << "vertex " << v;
    }
    EXPECT_EQ(changed, plane < 0.5 ? 4u : 0u);
  }
}

// descent_placement (h22max5): the horse's hoof was a lattice vertex straying from the input where no move along its
// axis came within the bound. Here the sphere's pole is 4 out along its normal and its relief's axis is +x, a tangent:
// along it the pole cannot come back. With descent_placement it becomes irregular and a pattern search along all
// three axes brings it within the bound, with no vertex inserted; without it the pole stays where it is (its faces
// are split instead).
TEST(DeviationRefinement, StrayingLatticeVertexFreedWhenItsAxisCannotServe) {
  const Mesh input = test::icosphere(2, 40.0);
  const AabbTree tree(input);
  for (const bool descent : {true, false}) {
    PrmMesh prm;
    prm.mesh = input;
    uint32_t pole = 0;
    for (uint32_t v = 1; v < prm.mesh.positions.size(); ++v)
      if (prm.mesh.positions[v][2] > prm.mesh.positions[pole][2]) pole = v;
    prm.vertex_relief.assign(prm.mesh.positions.size(), 0);
    prm.lattice_i.assign(prm.mesh.positions.size(), 0);
    prm.lattice_j.assign(prm.mesh.positions.size(), 0);
    prm.relief_axis = {0};  // +x
    const Vec3 off = prm.mesh.positions[pole] + Vec3{0.0, 0.0, 4.0};
    prm.mesh.positions[pole] = off;
    DeviationRefinementOptions o;
    o.max_deviation = 1.0;
    o.descent_placement = descent;
    const DeviationRefinementStats st = refine_deviations(prm, input, tree, o);
    const double distance = std::sqrt(tree.closest(prm.mesh.positions[pole]).distance2);
    std::printf("descent %d: pole %.3f from the input, relief %d; %zu moved, %zu inserted\n", descent, distance,
                prm.vertex_relief[pole], st.moved, st.inserted);
    if (descent) {
      EXPECT_EQ(prm.mesh.positions.size(), input.positions.size());
      EXPECT_LT(distance, o.max_deviation);
      EXPECT_EQ(prm.vertex_relief[pole], -1);  // irregular now
      EXPECT_GE(st.moved, 1u);
    } else {
      EXPECT_EQ(prm.mesh.positions[pole][2], off[2]);
      EXPECT_EQ(prm.vertex_relief[pole], 0);
    }
  }
}

// all_input_faces (h22max5): bunny_zipper's worst place was inside a long input triangle whose vertices lie on the
// mesh. Input: a 10 x 10 square at z 0 and a 6 x 6 one at z -1 (a thin sheet's two sides); the mesh keeps the large
// square's rim at z 0 and dips to z -1 inside (on the small square), so every input vertex lies within the bound
// (0.8) of the mesh and every mesh point within it of the input, but the large square's middle is 1 away. Only probing
// every input triangle sees it (a vertex is inserted there); without it nothing is.
TEST(DeviationRefinement, LongInputTriangleWithItsVerticesOnTheMesh) {
  Mesh input = square(0.0, 5.0);
  const Mesh inner = square(-1.0, 3.0);
  for (const Vec3& p : inner.positions) input.positions.push_back(p);
  for (const Tri& t : inner.triangles) input.triangles.push_back({t[0] + 4, t[2] + 4, t[1] + 4});
  const AabbTree tree(input);
  Mesh mesh;
  const double at[4] = {-5.0, -5.0 / 3, 5.0 / 3, 5.0};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const bool rim = i == 0 || i == 3 || j == 0 || j == 3;
      mesh.positions.push_back({at[i], at[j], rim ? 0.0 : -1.0});
    }
  for (uint32_t j = 0; j < 3; ++j)
    for (uint32_t i = 0; i < 3; ++i) {
      const uint32_t a = 4 * j + i;
      mesh.triangles.push_back({a, a + 1, a + 5});
      mesh.triangles.push_back({a, a + 5, a + 4});
    }
  for (const bool all : {true, false}) {
    PrmMesh prm;
    prm.mesh = mesh;
    prm.vertex_relief.assign(mesh.positions.size(), -1);
    prm.lattice_i.assign(mesh.positions.size(), 0);
    prm.lattice_j.assign(mesh.positions.size(), 0);
    DeviationRefinementOptions o;
    o.max_deviation = 0.8;
    o.max_insert_share = 1.0;  // of 16 vertices
    o.all_input_faces = all;
    // The mesh's dip lies on the small square, whose normal is the other way: its triangles face away from the
    // input by construction, and with the facing guard no new triangle may (hrefine: then nothing is inserted).
    o.facing_guard = false;
    const DeviationRefinementStats st = refine_deviations(prm, input, tree, o);
    const AabbTree refined(prm.mesh);
    const double middle = std::sqrt(refined.closest(Vec3{0.0, 0.0, 0.0}).distance2);
    std::printf("all_input_faces %d: %zu inserted, %zu moved; the large square's middle %.3f from the mesh\n", all,
                st.inserted, st.moved, middle);
    if (all) {
      EXPECT_GE(st.inserted + st.moved, 1u);
      EXPECT_LT(middle, o.max_deviation);
    } else {
      EXPECT_EQ(st.inserted + st.moved, 0u);
      EXPECT_NEAR(middle, 1.0, 1e-9);
    }
  }
}

// round_towards_input counts a vertex's own distance (h22max6): the feline's worst place was a lattice vertex at a
// crease tip that a rounding took 0.6x the bound off the input, because only its triangles' probes were measured and
// they came nearer. Here a fan of long thin triangles from a sphere's pole (radius 10) to a ring at 0.59 rad sags
// 0.45 inside the sphere; the pole is 0.2 above the sphere, between the steps at 10 (on the sphere, the nearest) and
// 10.5. Rounding up lifts the triangles towards the sphere (their probes stray 0.25) but puts the pole 0.5 off
// it: counting the pole, the nearest rounding is the better one and the pole ends on the sphere.
namespace {
// A sphere's cap around its pole (0, 0, r): `rows` rings of `segments` vertices, ring i at i x pi / rings from it.
Mesh sphere_cap(int rings, int rows, int segments, double r) {
  Mesh m;
  m.positions.push_back({0.0, 0.0, r});
  for (int i = 1; i <= rows; ++i)
    for (int j = 0; j < segments; ++j) {
      const double th = M_PI * i / rings, ph = 2 * M_PI * j / segments;
      m.positions.push_back({r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th)});
    }
  const auto at = [&](int i, int j) { return static_cast<uint32_t>(1 + (i - 1) * segments + (j % segments)); };
  for (int j = 0; j < segments; ++j) {
    m.triangles.push_back({0, at(1, j), at(1, j + 1)});
    for (int i = 1; i < rows; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return m;
}
}  // namespace

TEST(DeviationRefinement, RoundingCountsTheVertexItself) {
  const int rings = 64, segments = 64, ring = 12, fan = 16;
  const Mesh input = sphere_cap(rings, ring, segments, 10.0);
  const AabbTree tree(input);
  PrmMesh prm;
  prm.mesh.positions.push_back({0.0, 0.0, 10.2});  // the pole, 0.2 above the sphere
  for (int j = 0; j < fan; ++j) prm.mesh.positions.push_back(input.positions[1 + (ring - 1) * segments + j * 4]);
  for (uint32_t j = 0; j < fan; ++j) prm.mesh.triangles.push_back({0, 1 + j, 1 + (j + 1) % fan});
  prm.frame.bits = 8;
  prm.frame.origin = {-10.0, -10.0, 0.0};
  prm.frame.step = 0.5;
  const double bound = 0.4;
  const double up = std::sqrt(tree.closest({0.0, 0.0, 10.5}).distance2);
  round_towards_input(prm, input, tree, bound);
  const Vec3& pole = prm.mesh.positions[0];
  Vec3 stored;
  for (int a = 0; a < 3; ++a)
    stored[static_cast<size_t>(a)] = prm.frame.to_real(prm.frame.quantize(pole[static_cast<size_t>(a)], a), a);
  const double d = std::sqrt(tree.closest(stored).distance2);
  std::printf("pole at z %.3f, stored at %.3f: %.3f from the sphere (rounded up it would be %.3f)\n", pole[2],
              stored[2], d, up);
  EXPECT_GT(up, 0.45);
  EXPECT_EQ(stored[2], 10.0);
  EXPECT_LT(d, 0.01);
}

// fine_probes (h22max6): the horse's worst place lay between the dense probes of a face that came to 0.99x the bound.
// Here one mesh triangle (legs 5.5, bound 1: 8 divisions a side, a probe every 0.6875 along a leg) lies 0.97 above
// tiny input triangles, one under each of its probes and corners: every probe is 0.97 from the input, but a point
// halfway between two probes along a leg is 1.03 from it. Only the grid twice as fine (16 divisions) sees that point;
// without it the refinement finds nothing to do.
TEST(DeviationRefinement, FinerProbesSeeAPlaceBetweenTheProbes) {
  const double leg = 5.5, depth = 0.97, bound = 1.0, tiny = 0.005;
  const int n = 8;
  Mesh input;
  for (int p = 0; p <= n; ++p)
    for (int q = 0; p + q <= n; ++q) {
      const Vec3 c{leg * p / n, leg * q / n, -depth};
      const uint32_t a = static_cast<uint32_t>(input.positions.size());
      input.positions.push_back(c);
      input.positions.push_back(c + Vec3{tiny, 0, 0});
      input.positions.push_back(c + Vec3{0, tiny, 0});
      input.triangles.push_back({a, a + 1, a + 2});
    }
  const AabbTree tree(input);
  for (const bool fine : {true, false}) {
    PrmMesh prm;
    prm.mesh.positions = {{0, 0, 0}, {leg, 0, 0}, {0, leg, 0}};
    prm.mesh.triangles = {{0, 1, 2}};
    prm.vertex_relief.assign(3, -1);
    prm.lattice_i.assign(3, 0);
    prm.lattice_j.assign(3, 0);
    DeviationRefinementOptions o;
    o.max_deviation = bound;
    o.max_insert_share = 1.0;  // of 3 vertices
    o.fine_probes = fine;
    const DeviationRefinementStats st = refine_deviations(prm, input, tree, o);
    const size_t acted = st.inserted + st.moved + st.flipped + st.refused;
    std::printf("fine_probes %d: %zu inserted, %zu moved, %zu flipped, %zu refused, %zu rounds\n", fine, st.inserted,
                st.moved, st.flipped, st.refused, st.rounds);
    if (fine) {
      EXPECT_GE(acted, 1u);
    } else {
      EXPECT_EQ(acted, 0u);
      EXPECT_EQ(prm.mesh.positions.size(), 3u);
    }
  }
}


// DeviationRefinementOptions::prune (h22max8): an inserted vertex whose fan can be triangulated again within the bound
// goes (a split in three, valence 3, and an edge split, valence 4, of a flat square on a flat input); one that holds
// the mesh on an input spike stays.
TEST(DeviationRefinement, PruneRemovesAnInsertedVertexOnlyWhereTheBoundHoldsWithoutIt) {
  const auto frame_of = [](PrmMesh& prm) {
    prm.frame.bits = 8;
    prm.frame.origin = {-5.0, -5.0, -5.0};
    prm.frame.step = 1.0;
  };
  const Vec3 centroid = {5.0 / 3, -5.0 / 3, 0.0};  // of the square's triangle (0, 1, 2)
  for (const bool edge : {false, true}) {
    const Mesh input = square(0.0, 5.0);
    const AabbTree tree(input);
    PrmMesh prm;
    frame_of(prm);
    prm.mesh = square(0.0, 5.0);
    if (edge) {  // edge 0-2 split at its midpoint
      prm.mesh.positions.push_back({0.0, 0.0, 0.0});
      prm.mesh.triangles = {{0, 1, 4}, {4, 1, 2}, {0, 4, 3}, {4, 2, 3}};
    } else {
      prm.mesh.positions.push_back(centroid);
      prm.mesh.triangles = {{0, 1, 4}, {1, 2, 4}, {2, 0, 4}, {0, 2, 3}};
    }
    const size_t removed = prune_inserted_vertices(prm, 4, input, tree, 0.1);
    std::printf("%s on a flat input: %zu removed, %zu triangles\n", edge ? "edge split" : "split in three", removed,
                prm.mesh.triangles.size());
    EXPECT_EQ(removed, 1u);
    EXPECT_EQ(prm.mesh.positions.size(), 4u);
    ASSERT_EQ(prm.mesh.triangles.size(), 2u);
    for (const Tri& t : prm.mesh.triangles) {  // facing up, as the square did
      const Vec3 n = triangle_normal_area2(prm.mesh.positions[t[0]], prm.mesh.positions[t[1]], prm.mesh.positions[t[2]]);
      EXPECT_GT(n[2], 0.0);
    }
  }
  // The input rises to a spike 3 above the centroid, and the inserted vertex is on it: without it the input's tip
  // would be 3 from the mesh, far past the bound.
  Mesh input = square(0.0, 5.0);
  input.positions.push_back(centroid + Vec3{0.0, 0.0, 3.0});
  input.triangles = {{0, 1, 4}, {1, 2, 4}, {2, 0, 4}, {0, 2, 3}};
  const AabbTree tree(input);
  PrmMesh prm;
  frame_of(prm);
  prm.mesh = input;
  const size_t removed = prune_inserted_vertices(prm, 4, input, tree, 1.0);
  EXPECT_EQ(removed, 0u);
  EXPECT_EQ(prm.mesh.positions.size(), 5u);
  EXPECT_EQ(prm.mesh.triangles.size(), 4u);
  // The same fan with the bound past the spike's height: it goes.
  EXPECT_EQ(prune_inserted_vertices(prm, 4, input, tree, 3.5), 1u);
}


// round_towards_input weighs the input between its vertices (hfeline): the feline's worst place at 2e-4 was the
// midpoint of an input crease edge 1.02x the bound from the refined mesh, its ends within 0.65x, and a rounding chosen
// for the input vertices and mesh probes nearby took it to 1.22x. Here a roof (eaves on their steps at z 1, ridge at
// 1.45 between the steps at 1, the nearest, and 2) lies between two input sheets: a 10 x 10 square at z 0 and a
// 4 x 10 strip at 2.6 over the ridge. The strip's corners (vertices, 1.6 from a flat roof) and the ridge's own distance
// favour the ridge rounded up; but then the square's middle, a point of its diagonal with every vertex 1 from the
// eaves, is 1.96 from the roof, against 1 with the ridge at its nearest rounding. Weighing that point, the ridge stays.
TEST(DeviationRefinement, RoundingWeighsTheInputBetweenItsVertices) {
  Mesh input = square(0.0, 5.0);
  const uint32_t s = static_cast<uint32_t>(input.positions.size());
  for (const Vec3& p : std::vector<Vec3>{{-2, -5, 2.6}, {2, -5, 2.6}, {2, 5, 2.6}, {-2, 5, 2.6}})
    input.positions.push_back(p);
  input.triangles.push_back({s, s + 1, s + 2});
  input.triangles.push_back({s, s + 2, s + 3});
  const AabbTree tree(input);
  PrmMesh prm;
  // Eaves 0-3 (left -5, right 5), ridge 4 (y -5) and 5 (y 5).
  prm.mesh.positions = {{-5, -5, 1}, {-5, 5, 1}, {5, -5, 1}, {5, 5, 1}, {0, -5, 1.45}, {0, 5, 1.45}};
  prm.mesh.triangles = {{0, 4, 5}, {0, 5, 1}, {4, 2, 3}, {4, 3, 5}};
  prm.frame.bits = 8;
  prm.frame.origin = {-8.0, -8.0, -1.0};
  prm.frame.step = 1.0;
  const double bound = 1.6;
  round_towards_input(prm, input, tree, bound);
  Mesh stored = prm.mesh;
  for (Vec3& p : stored.positions)
    for (int a = 0; a < 3; ++a)
      p[static_cast<size_t>(a)] = prm.frame.to_real(prm.frame.quantize(p[static_cast<size_t>(a)], a), a);
  const double middle = std::sqrt(AabbTree(stored).closest({0.0, 0.0, 0.0}).distance2);
  std::printf("ridge stored at z %.2f and %.2f: the input square's middle %.3f from the roof\n", stored.positions[4][2],
              stored.positions[5][2], middle);
  EXPECT_EQ(stored.positions[4][2], 1.0);
  EXPECT_EQ(stored.positions[5][2], 1.0);
  EXPECT_LT(middle, 0.75 * bound);
}

// kTradeAfter (hcrease): a missed input vertex on a narrow spike (its tip pulled out 4 along +z from a fine sphere)
// over a coarse mesh. Every split with the new vertex at the tip strays past the bound (1.5): the tent over the
// mesh's wide triangles leaves the spike's flanks (1.99 at best), so before the change the tip stayed 2.64 away
// (1.76x the bound; the mesh around it 1.43 from the input) while splits of the faces next to it put their vertex 4
// from it. From the fifth round a split whose triangles and new vertex stay within 0.8x the point's distance is kept:
// the tip ends within the bound (0.67), the mesh around it 2.15 from the input, so the place's worst is 19% less.
TEST(DeviationRefinement, MissedTipOfANarrowSpikeIsReached) {
  uint32_t tip = 0;
  const Mesh input = spiked_sphere(5, 4.0, tip);
  const AabbTree tree(input);
  PrmMesh prm = prm_of_sphere();
  const double c = std::cos(0.3), s = std::sin(0.3);  // turned about y: no mesh vertex under the tip
  for (Vec3& p : prm.mesh.positions) p = Vec3{c * p[0] + s * p[2], p[1], -s * p[0] + c * p[2]};
  DeviationRefinementOptions o;
  o.max_deviation = 1.5;
  const double before = std::sqrt(AabbTree(prm.mesh).closest(input.positions[tip]).distance2);
  const DeviationRefinementStats st = refine_deviations(prm, input, tree, o);
  const double after = std::sqrt(AabbTree(prm.mesh).closest(input.positions[tip]).distance2);
  // The refined mesh's worst place near the tip (pr>in), on a fine grid of every face within 10 of it.
  double worst2 = 0;
  for (const Tri& t : prm.mesh.triangles) {
    const Vec3 &a = prm.mesh.positions[t[0]], &b = prm.mesh.positions[t[1]], &cc = prm.mesh.positions[t[2]];
    if (norm2((1.0 / 3) * (a + b + cc) - input.positions[tip]) > 100) continue;
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; i + j <= 20; ++j)
        worst2 = std::max(worst2, tree.closest((1.0 / 20) * (i * a + j * b + (20 - i - j) * cc)).distance2);
  }
  std::printf("tip %.3f from the mesh, then %.3f (bound %.3f); mesh near it %.3f from the input; %zu rounds, "
              "%zu inserted, %zu moved\n", before, after, o.max_deviation, std::sqrt(worst2), st.rounds, st.inserted,
              st.moved);
  EXPECT_GT(before, 2 * o.max_deviation);
  EXPECT_LT(after, o.max_deviation);
  EXPECT_LT(std::max(after, std::sqrt(worst2)), 1.5 * o.max_deviation);  // (before the change: 2.64)
}

// htail: a thin sheet's tip beyond the mesh's rim (the horse's tail at 1.3e-4, bench/README.md "Worst-case error").
namespace {
// A closed slab of thickness 2h over a star-shaped outline (counter-clockwise in xy, star-shaped from `centre`): a
// fan on top (+z), one below, and walls.
Mesh slab(const std::vector<Vec3>& outline, const Vec3& centre, double h) {
  Mesh m;
  const uint32_t n = static_cast<uint32_t>(outline.size());
  for (const Vec3& p : outline) m.positions.push_back({p[0], p[1], h});
  for (const Vec3& p : outline) m.positions.push_back({p[0], p[1], -h});
  m.positions.push_back({centre[0], centre[1], h});
  m.positions.push_back({centre[0], centre[1], -h});
  const uint32_t top = 2 * n, bottom = 2 * n + 1;
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t j = (i + 1) % n;
    m.triangles.push_back({top, i, j});
    m.triangles.push_back({bottom, n + j, n + i});
    m.triangles.push_back({i, n + i, n + j});
    m.triangles.push_back({i, n + j, j});
  }
  return m;
}

// The mesh of such a slab's body (x from -20 to 0, y from -10 to 10): its rim an edge between a top fan (apex at
// z 0.3) and a bottom one (z -0.3), at z 0 but for the x = 0 side, at z rim_z; the rim's vertices lattice vertices of
// a relief along z (`lattice`: each moves only along z), else every vertex irregular.
PrmMesh sheet_body(double rim_z, bool lattice) {
  PrmMesh prm;
  for (int i = 0; i <= 10; ++i) prm.mesh.positions.push_back({-20.0 + 2.0 * i, -10, 0});
  for (int i = 1; i <= 10; ++i) prm.mesh.positions.push_back({0, -10.0 + 2.0 * i, rim_z});
  for (int i = 1; i <= 10; ++i) prm.mesh.positions.push_back({-2.0 * i, 10, 0});
  for (int i = 1; i < 10; ++i) prm.mesh.positions.push_back({-20, 10.0 - 2.0 * i, 0});
  const uint32_t n = static_cast<uint32_t>(prm.mesh.positions.size());
  prm.mesh.positions.push_back({-10, 0, 0.3});
  prm.mesh.positions.push_back({-10, 0, -0.3});
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t j = (i + 1) % n;
    prm.mesh.triangles.push_back({n, i, j});
    prm.mesh.triangles.push_back({n + 1, j, i});
  }
  prm.vertex_relief.assign(prm.mesh.positions.size(), -1);
  if (lattice) {
    prm.relief_axis = {2};
    for (uint32_t v = 0; v < n; ++v) prm.vertex_relief[v] = 0;
  }
  prm.lattice_i.assign(prm.mesh.positions.size(), 0);
  prm.lattice_j.assign(prm.mesh.positions.size(), 0);
  return prm;
}

// The largest distance to `to` of the points of `from`'s triangles on a barycentric grid (10 divisions a side).
double sampled_max_distance(const Mesh& from, const AabbTree& to) {
  double worst = 0;
  for (const Tri& t : from.triangles)
    for (int p = 0; p <= 10; ++p)
      for (int q = 0; p + q <= 10; ++q) {
        const Vec3 x = 0.1 * (static_cast<double>(p) * from.positions[t[0]] +
                              static_cast<double>(q) * from.positions[t[1]] +
                              static_cast<double>(10 - p - q) * from.positions[t[2]]);
        worst = std::max(worst, std::sqrt(to.closest(x).distance2));
      }
  return worst;
}
}  // namespace

// The input: a sheet 0.6 thick, a body (x from -20 to 0, y from -10 to 10) and a strand 0.6 wide out to a tip at
// (6, 0). The mesh: the body only, its rim (z = 0) an edge between its top and bottom fans, with an irregular rim
// vertex at (0, 0), the mesh's closest point to the tip. Every split for the tip turns a face over, faces away from
// the input or strays past the bound (0.5) across the notches beside the strand, and so does every move of the rim
// vertex within the bound: without the tip move the tip stays 6 from the mesh. The rim vertex, moved to the tip,
// makes faces stray across the notches by less than that, and later rounds bring them within the bound.
TEST(DeviationRefinement, ThinSheetTipBeyondTheRimIsReached) {
  const Mesh input = slab({{-20, -10, 0}, {0, -10, 0}, {0, -0.3, 0}, {6, 0, 0}, {0, 0.3, 0}, {0, 10, 0}, {-20, 10, 0}},
                          {-10, 0, 0}, 0.3);
  const AabbTree tree(input);
  PrmMesh prm = sheet_body(0, false);
  const Vec3 tip = {6, 0, 0};
  ASSERT_NEAR(std::sqrt(AabbTree(prm.mesh).closest(tip).distance2), 6.0, 1e-9);
  DeviationRefinementOptions o;
  o.max_deviation = 0.5;
  o.max_insert_share = 1.0;  // (3% of 43 vertices would be one)
  const DeviationRefinementStats st = refine_deviations(prm, input, tree, o);
  const AabbTree refined(prm.mesh);
  const double missed = sampled_max_distance(input, refined), stray = sampled_max_distance(prm.mesh, tree);
  std::printf("tip %.3f from the refined mesh; input to mesh %.3f, mesh to input %.3f; %zu moved, %zu inserted, "
              "%zu refused, %zu rounds\n",
              std::sqrt(refined.closest(tip).distance2), missed, stray, st.moved, st.inserted, st.refused, st.rounds);
  EXPECT_LE(missed, o.max_deviation);  // 6.007 without the tip move
  EXPECT_LE(stray, o.max_deviation);
}

// reach_onto_input (htail2's step, made the last one in h115): htail's slab with a shorter strand (its tip 3 or 4.5
// out), the mesh's rim side at x = 0 at z rim_z. Every split of the tip's closest edge off the input leaves a face
// whose centroid is nearer the strand's far side (facing away); the split with its new vertex on the input faces it.
// The larger of the two one-sided distances (bound 0.5), without the step / with it: 1.008 / 0.518 (strand 0.6 wide,
// tip 3 out, rim 0.2 below the middle, irregular rim) and 0.826 / 0.513 (1.2 wide, 4.5 out, rim at the middle,
// lattice rim). A narrow margin in the geometry: over 120 variants of strand width, length, rim height and rim kind
// the step changed 4, 3 for the better; one went from 0.826 to 0.960 (0.6 wide, 3 out, rim 0.1 below, lattice).
TEST(DeviationRefinement, StrandTipIsReachedOnTheInput) {
  struct Case {
    double width, length, rim_z;
    bool lattice;
  };
  for (const Case& c : {Case{0.6, 3.0, -0.2, false}, Case{1.2, 4.5, 0.0, true}}) {
    const Mesh input = slab({{-20, -10, 0}, {0, -10, 0}, {0, -c.width / 2, 0}, {c.length, 0, 0}, {0, c.width / 2, 0},
                             {0, 10, 0}, {-20, 10, 0}},
                            {-10, 0, 0}, 0.3);
    const AabbTree tree(input);
    double worst[2] = {0, 0};
    for (const bool onto_input : {false, true}) {
      PrmMesh prm = sheet_body(c.rim_z, c.lattice);
      DeviationRefinementOptions o;
      o.max_deviation = 0.5;
      o.max_insert_share = 1.0;
      o.reach_onto_input = onto_input;
      const DeviationRefinementStats st = refine_deviations(prm, input, tree, o);
      worst[onto_input] =
          std::max(sampled_max_distance(input, AabbTree(prm.mesh)), sampled_max_distance(prm.mesh, tree));
      std::printf("strand %.1f wide, tip %.1f out: reach_onto_input %d, %.3f apart; %zu moved, %zu inserted\n",
                  c.width, c.length, onto_input, worst[onto_input], st.moved, st.inserted);
    }
    EXPECT_GE(worst[0], 0.8);
    EXPECT_LE(worst[1], 0.55);
  }
}

}  // namespace prm::remesh
