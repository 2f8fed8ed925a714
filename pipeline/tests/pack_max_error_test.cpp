// The worst-case error (issue 22 item 3): PackOptions::max_error is met by the decoded stream, measured by Metro on
// the stream itself (not by the search's own figures), alone or with target_error; and the remesher's local
// refinement lowers the Hausdorff distance of a default pack. The longer searches (feline_5k with both bounds, the paper
// model horse) run under PRM_PACK_MAX_ERROR_HEAVY (label heavy).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "prm/aabb_tree.h"
#include "prm/codec.h"
#include "prm/mesh_io.h"
#include "prm/metro_distance.h"
#include "prm/vec3.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack.h"
#include "prm/remesh/remesh.h"

namespace {

using prm::pipeline::PackOptions;

// Metro (ten samples per face) between the input and the decoded stream.
prm::DistanceReport decoded_distance(const prm::Mesh& input, const prm::pipeline::PackResult& r) {
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  EXPECT_TRUE(decoded.ok()) << decoded.status.message;
  return prm::metro_distance(input, prm::pipeline::to_mesh(decoded.value));
}

prm::Mesh shared_mesh(const char* file) { return prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/" + file); }

// `file` packed with o, its decoded stream measured against it (and printed).
// search_note: the pack's PackResult::search_note (printed too when there is one).
prm::DistanceReport packed_distance(const char* file, const PackOptions& o, std::string* search_note = nullptr) {
  const prm::Mesh input = shared_mesh(file);
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  const prm::DistanceReport d = decoded_distance(input, r);
  std::printf("%s at target %.3g, max %.3g, effort %d: %zu bytes, %d bits x%.4g, RMS %.3e, max %.3e\n%s\n", file,
              o.target_error, o.max_error, o.effort, r.stream.size(), r.bits, r.step_scale, d.rel(d.rms), d.rel(d.max),
              r.search_note.c_str());
  if (search_note != nullptr) *search_note = r.search_note;
  return d;
}

#ifndef PRM_PACK_MAX_ERROR_HEAVY

TEST(PackMaxError, MaxErrorAloneIsMetByTheDecodedStream) {
  PackOptions o;
  o.max_error = 4e-3;
  const prm::DistanceReport d = packed_distance("spot.obj", o);
  EXPECT_LE(d.rel(d.max), o.max_error);
}

TEST(PackMaxError, LocalRefinementLowersTheWorstCase) {
  const prm::Mesh input = shared_mesh("feline_5k.obj");
  PackOptions o;
  o.target_error = 5e-4;
  o.local_refinement = PackOptions::LocalRefinement::off;
  const prm::pipeline::PackResult before = prm::pipeline::pack(input, o);
  o.local_refinement = PackOptions::LocalRefinement::on;
  const prm::pipeline::PackResult after = prm::pipeline::pack(input, o);
  const prm::DistanceReport db = decoded_distance(input, before), da = decoded_distance(input, after);
  std::printf("feline_5k at 5e-4: without refinement %zu bytes, max %.3e; with %zu bytes, max %.3e (%zu vertices "
              "inserted)\n", before.stream.size(), db.rel(db.max), after.stream.size(), da.rel(da.max),
              after.remesh.prm.stats.deviation_inserts);
  EXPECT_EQ(before.remesh.prm.stats.deviation_inserts, 0u);
  EXPECT_GT(after.remesh.prm.stats.deviation_inserts, 0u);
  EXPECT_LE(da.rel(da.rms), o.target_error);
  EXPECT_LT(da.rel(da.max), 0.8 * db.rel(db.max));
}

// RemeshOptions::refine_last (h22max5, issue 21's CPU budget): the search's grids are resampled without the local
// refinement and only the chosen one is refined (from the step's PRM, finish_resampled: the same mesh as resampling
// and refining that grid at once), so the last step has an unrefined twin, and the refined result still meets the
// target. With refine_last false every step is refined.
TEST(LocalRefinement, RefineLastRefinesOnlyTheChosenGrid) {
  const prm::Mesh input = shared_mesh("feline_5k.obj");
  prm::remesh::RemeshOptions o;
  o.bits = 11;
  o.target_error = 5e-4;
  o.refine_error = 3.4e-3;
  const auto error = [&](const prm::remesh::PrmMesh& candidate) {
    const prm::DistanceReport d = prm::metro_distance(input, candidate.mesh);
    return prm::remesh::ErrorEstimate{d.rel(d.rms), d.rel(d.max)};
  };
  for (const bool last : {true, false}) {
    o.refine_last = last;
    const prm::remesh::RemeshResult r = prm::remesh::remesh(input, o, error);
    // A refined step has more vertices than the unrefined step at its grid, when the search measured one.
    const auto has_unrefined_twin = [&](const prm::remesh::SearchStep& st) {
      for (const prm::remesh::SearchStep& other : r.search)
        if (&other != &st && other.grid == st.grid && other.vertices < st.vertices) return true;
      return false;
    };
    size_t twins = 0;
    for (const prm::remesh::SearchStep& st : r.search) twins += has_unrefined_twin(st);
    std::printf("refine_last %d: %zu steps, %zu refined against an unrefined twin, %zu inserted, RMS %.3e\n", last,
                r.search.size(), twins, r.prm.stats.deviation_inserts, r.error.rms);
    EXPECT_GT(r.prm.stats.deviation_inserts, 0u);
    EXPECT_LE(r.error.rms, o.target_error);
    if (last) {
      EXPECT_TRUE(has_unrefined_twin(r.search.back()));  // the chosen grid, measured unrefined in the search first
      EXPECT_LE(twins, static_cast<size_t>(prm::remesh::kRefineLastTries));
      // The refinement taken on from the search step's PRM (finish_resampled) gives the mesh that resampling and
      // refining that grid at once gives.
      prm::remesh::RemeshOptions fixed = o;
      fixed.target_error = 0;
      fixed.refine_last = false;
      fixed.grid_size = r.search.back().grid_size;
      const prm::remesh::RemeshResult once = prm::remesh::remesh(input, fixed);
      EXPECT_EQ(once.prm.mesh.triangles, r.prm.mesh.triangles);
      EXPECT_EQ(once.prm.mesh.positions, r.prm.mesh.positions);
    } else {
      EXPECT_EQ(twins, 0u);  // every step refined: no grid measured twice
    }
  }
}

// RemeshOptions::defer_refinement (pack's effort 3 refines only the attempt it keeps, issue 21): remesh() returns the
// search's unrefined choice with the refinement left in RemeshResult::deferred, and refine_deferred() then gives the
// result, search steps and measurements that remesh() without deferral gives.
TEST(LocalRefinement, DeferredRefinementIsTheRefinementRemeshMakes) {
  const prm::Mesh input = shared_mesh("feline_5k.obj");
  prm::remesh::ReliefOptions ro;
  ro.view_properties = false;
  const prm::remesh::ReliefLayout layout = prm::remesh::build_reliefs(input, ro);
  prm::remesh::RemeshOptions o;
  o.layout = &layout;
  o.bits = 11;
  o.target_error = 5e-4;
  o.refine_error = 3.4e-3;
  o.refine_last = true;
  size_t measured = 0;
  const auto error = [&](const prm::remesh::PrmMesh& candidate) {
    ++measured;
    const prm::DistanceReport d = prm::metro_distance(input, candidate.mesh);
    return prm::remesh::ErrorEstimate{d.rel(d.rms), d.rel(d.max)};
  };
  const prm::remesh::RemeshResult once = prm::remesh::remesh(input, o, error);
  const size_t measured_once = measured;
  EXPECT_EQ(once.deferred, nullptr);
  o.defer_refinement = true;
  measured = 0;
  prm::remesh::RemeshResult later = prm::remesh::remesh(input, o, error);
  ASSERT_NE(later.deferred, nullptr);
  EXPECT_EQ(later.prm.stats.deviation_inserts, 0u);  // the search's unrefined choice
  EXPECT_LT(later.search.size(), once.search.size());
  prm::remesh::refine_deferred(later, error);
  EXPECT_EQ(later.deferred, nullptr);
  EXPECT_EQ(measured, measured_once);
  ASSERT_EQ(later.search.size(), once.search.size());
  for (size_t i = 0; i < once.search.size(); ++i) {
    EXPECT_EQ(later.search[i].grid, once.search[i].grid);
    EXPECT_EQ(later.search[i].vertices, once.search[i].vertices);
    EXPECT_EQ(later.search[i].error.rms, once.search[i].error.rms);
  }
  EXPECT_GT(later.prm.stats.deviation_inserts, 0u);
  EXPECT_EQ(later.error.rms, once.error.rms);
  EXPECT_EQ(later.prm.mesh.triangles, once.prm.mesh.triangles);
  EXPECT_EQ(later.prm.mesh.positions, once.prm.mesh.positions);
}

// The cause of the worst case (bench/README.md "Worst-case error"): the horse's tail and ears are thin sheets the
// hexagonal resampling cuts off. At the grid a 2e-4 pack chooses (11 bits, step x1.414, 0.007 of the diagonal), the
// refinement at 6.8x that target with its thin-sheet steps must leave a lower max than the same refinement without
// them (splits of the closest face only), and both lower than no refinement, with the vertex count within 3% more.
// Without the facing guard (hrefine): with it, both refinements refuse the places that fold a triangle, and the
// thin-sheet steps end at 2.806e-3 against the splits' 2.691e-3 (unrefined 4.526e-3).
TEST(LocalRefinement, ThinSheetStepsLowerTheMaxOnTheHorse) {
  const prm::Mesh input = shared_mesh("horse.ply");
  prm::remesh::RemeshOptions o;
  o.refine_facing_guard = false;
  o.bits = 11;
  o.step_scale = 1.4142;
  o.grid_fraction = 0.007;
  auto max_of = [&](double refine, bool thin_sheets, size_t* vertices) {
    o.refine_error = refine;
    o.refine_thin_sheets = thin_sheets;
    const prm::remesh::RemeshResult r = prm::remesh::remesh(input, o);
    *vertices = r.prm.mesh.positions.size();
    const prm::DistanceReport d = prm::metro_distance(input, r.prm.mesh);
    return d.rel(d.max);
  };
  size_t n0 = 0, n1 = 0, n2 = 0;
  const double none = max_of(0, true, &n0), splits = max_of(1.36e-3, false, &n1), thin = max_of(1.36e-3, true, &n2);
  std::printf("horse at grid 0.007: max %.3e (%zu vertices) unrefined, %.3e (%zu) splits only, %.3e (%zu) with the "
              "thin-sheet steps\n", none, n0, splits, n1, thin, n2);
  EXPECT_LT(splits, none);
  EXPECT_LT(thin, 0.95 * splits);
  EXPECT_LE(n2, n0 + n0 * 3 / 100);
}

// With the facing guard (hrefine2): where an insertion's triangles face away from the input, the edges across from
// the new vertex are flipped until they face it (repair_facing). Without the repair the guard refuses those places and
// the horse's thin-sheet steps end at 2.806e-3 (hrefine; this test then fails); with it at 1.477e-3, and they must come
// below 0.8 x 2.806e-3.
TEST(LocalRefinement, FacingRepairKeepsTheHorsesThinSheetSteps) {
  const prm::Mesh input = shared_mesh("horse.ply");
  prm::remesh::RemeshOptions o;
  o.bits = 11;
  o.step_scale = 1.4142;
  o.grid_fraction = 0.007;
  o.refine_error = 1.36e-3;
  const prm::remesh::RemeshResult r = prm::remesh::remesh(input, o);
  const prm::DistanceReport d = prm::metro_distance(input, r.prm.mesh);
  std::printf("horse at grid 0.007 with the facing guard: max %.3e (%zu vertices)\n", d.rel(d.max),
              r.prm.mesh.positions.size());
  EXPECT_LT(d.rel(d.max), 0.8 * 2.806e-3);
}

// hknife: venus at the grid a 2e-4 pack with --local-refinement chooses (11 bits, step x1.6818, grid 0.0106124). At
// a 178-degree knife edge three lattice vertices and a seam vertex round to one quantization point; the separation
// moved the seam vertex three steps off the fin, 2.10e-3 of the diagonal from the input (10.5x the target, the
// decoded stream's max). With the refinement's bound on the separation's moves (move_bound) every vertex stays within
// 8x the target (1.6e-3; the farthest, elsewhere, at 1.32e-3).
TEST(LocalRefinement, SeparationKeepsVenusKnifeEdgeOnTheInput) {
  const prm::Mesh input = shared_mesh("venus.off");
  prm::remesh::RemeshOptions o;
  o.bits = 11;
  o.step_scale = std::pow(2.0, 0.75);  // pack's step x1.6818
  o.grid_size = 0.01061242989388369;   // 13 steps
  o.refine_error = 1.36e-3;
  const prm::remesh::RemeshResult r = prm::remesh::remesh(input, o);
  const prm::AabbTree tree(input);
  double worst2 = 0;
  for (const prm::Vec3& p : r.prm.mesh.positions) worst2 = std::max(worst2, tree.closest(p).distance2);
  const double worst = std::sqrt(worst2) / prm::bbox_diagonal(input);
  std::printf("venus at grid 0.0106124 refined at 1.36e-3: farthest vertex %.3e of the diagonal (%zu vertices)\n",
              worst, r.prm.mesh.positions.size());
  EXPECT_LE(worst, 1.6e-3);
}

// When none of the search's refined attempts meets 8x, the one with the smallest max within kNoBoundBytes (5%) of the
// smallest stream is kept: the six attempts of the horse at 1.3e-4 and effort 9 in 1af193d's run (bench/README.md
// "Where the bound stands", second session), 8,340 B at 8.60x instead of the smallest, 8,204 B at 13.69x.
TEST(PackMaxError, NoAttemptWithinTheBoundKeepsTheNearestWithinFivePercent) {
  const double t = 1.3e-4;
  const std::vector<prm::pipeline::BoundedAttempt> a = {{8204, 13.69 * t}, {8301, 12.41 * t}, {8340, 8.60 * t},
                                                        {8388, 12.38 * t}, {8721, 9.59 * t},  {10533, 11.47 * t}};
  bool met = true;
  EXPECT_EQ(prm::pipeline::pick_bounded_attempt(a, 8 * t, met), 2u);
  EXPECT_FALSE(met);
  // 8,721 B is past 5% of 8,204: its 9.59x does not count against 8,340's 8.60x; without 8,340 the nearest within 5%
  // is 8,388 B at 12.38x.
  const std::vector<prm::pipeline::BoundedAttempt> b = {a[0], a[1], a[3], a[4], a[5]};
  EXPECT_EQ(prm::pipeline::pick_bounded_attempt(b, 8 * t, met), 2u);
  EXPECT_FALSE(met);
  // One within the bound: the smallest such stream, even past 5%.
  const std::vector<prm::pipeline::BoundedAttempt> c = {a[0], {9000, 7.9 * t}, {9500, 7.0 * t}, a[2]};
  EXPECT_EQ(prm::pipeline::pick_bounded_attempt(c, 8 * t, met), 1u);
  EXPECT_TRUE(met);
  EXPECT_EQ(prm::pipeline::pick_bounded_attempt({}, 8 * t, met), 0u);
  EXPECT_FALSE(met);
}

#else

TEST(PackMaxErrorHeavy, MaxErrorWithTargetErrorIsMetByTheDecodedStream) {
  PackOptions o;
  o.target_error = 5e-4;
  o.max_error = 3e-3;  // the default pack of this mesh at 5e-4 reaches 3.8e-3 (bench/README.md "Worst-case error")
  const prm::DistanceReport d = packed_distance("feline_5k.obj", o);
  EXPECT_LE(d.rel(d.rms), o.target_error);
  EXPECT_LE(d.rel(d.max), o.max_error);
}  // about 22 CPU s (the search goes to a finer grid)

// 8x the RMS target: the bound for the worst case.
constexpr double kHorseMaxError = 1.6e-3;

TEST(PackMaxErrorHeavy, HorseMaxErrorIsMet) {
  PackOptions o;
  o.target_error = 2e-4;
  o.max_error = kHorseMaxError;
  const prm::DistanceReport d = packed_distance("horse.ply", o);
  EXPECT_LE(d.rel(d.rms), o.target_error);
  EXPECT_LE(d.rel(d.max), o.max_error);
}

// The default pack of `file` at `target`: the RMS within the target, the max within 8x it.
void expect_default_pack_within_8x(const char* file, double target) {
  PackOptions o;
  o.target_error = target;
  const prm::DistanceReport d = packed_distance(file, o);
  EXPECT_LE(d.rel(d.rms), o.target_error);
  EXPECT_LE(d.rel(d.max), prm::pipeline::kDefaultMaxErrorPerTarget * o.target_error);
}

// `input` (CGAL's `file`) packed by default at `target`: the stream in *r, its decoded distance printed and returned,
// the RMS within the target.
prm::DistanceReport default_pack_within_target(const prm::Mesh& input, const char* file, double target,
                                               prm::pipeline::PackResult* r) {
  PackOptions o;
  o.target_error = target;
  *r = prm::pipeline::pack(input, o);
  const prm::DistanceReport d = decoded_distance(input, *r);
  std::printf("%s at %.3g: %zu bytes, RMS %.3e, max %.3e\n", file, target, r->stream.size(), d.rel(d.rms), d.rel(d.max));
  EXPECT_LE(d.rel(d.rms), target);
  return d;
}

// The default pack (the local refinement on at the default effort, hdefault): the horse at 2e-4 within 8x the
// target (7.48x; 24.99x with --no-local-refinement, bench/README.md "Worst-case error").
TEST(PackMaxErrorHeavy, DefaultPackKeepsTheHorseWithin8x) { expect_default_pack_within_8x("horse.ply", 2e-4); }

// hnine: at 1.3e-4 the horse's tail tip, beyond a thin sheet's rim, stalled from round 6 at 1.6-1.8x the
// refinement's bound: every split of its closest face turned a triangle away, and the split of a neighbouring face
// that faces the input put its vertex no nearer. After kFacingNearerAfter rounds that split is kept only where it
// brings the missed point nearer: 11.55x -> 10.96x the target (hnine). htail: the tip stalled because moving its rim
// vertex out to it made a face across the notch beside it stray 1.25x the bound; the tip move (move_rim_vertex's
// `reached`) takes that trade, and later rounds split the face: 9.88x (still over 8x: bench/README.md "Worst-case
// error", htail). hcrease's trade (a missed point's split may stray within 0.8x its distance from the fifth round) and
// rim guard: 9.42x (htail alone: 9.88x). h115: the next tail point, whose every split off the input left a face
// facing away, is reached by the split with its new vertex on the input (reach_onto_input, now the last step), and
// the 115-degree place keeps its tip move: 8.08x. The bound below fails without reach_onto_input (9.42x).
TEST(PackMaxErrorHeavy, HorseTailTipComesNearerAtOnePointThreeEMinus4) {
  PackOptions o;
  o.target_error = 1.3e-4;
  const prm::DistanceReport d = packed_distance("horse.ply", o);
  EXPECT_LE(d.rel(d.rms), o.target_error);
  EXPECT_LE(d.rel(d.max), 8.5 * o.target_error);
}

// The largest distance to `to` of the points of `from`'s triangles with a corner within `radius` of `at`, on a
// barycentric grid of 10 divisions a side.
double sampled_distance_near(const prm::Mesh& from, const prm::Mesh& to, const prm::Vec3& at, double radius) {
  using prm::operator+, prm::operator-, prm::operator*;
  const prm::AabbTree tree(to);
  double worst = 0;
  for (const prm::Tri& t : from.triangles) {
    const prm::Vec3 &a = from.positions[t[0]], &b = from.positions[t[1]], &c = from.positions[t[2]];
    if (std::min({prm::norm2(a - at), prm::norm2(b - at), prm::norm2(c - at)}) > radius * radius) continue;
    for (int p = 0; p <= 10; ++p)
      for (int q = 0; p + q <= 10; ++q)
        worst = std::max(worst, std::sqrt(tree.closest(0.1 * (double(p) * a + double(q) * b + double(10 - p - q) * c)).distance2));
  }
  return worst;
}

// h115: the horse's 115-degree place at 1.3e-4, an input vertex on a sharp crease (-0.0037, 0.0287, -0.0618) beside
// the edge between a lattice vertex and an irregular one. The irregular vertex's tip move took it there in round 2;
// in round 3 its move for a straying point of one of its faces took it back, and from round 5 every step for that
// vertex and for a point of the crease beside it (1.40x the refinement's bound) was refused. A tip move is now kept
// against such moves (move_rim_vertex's `tips`). Measured here (both directions, input and decoded triangles with a
// corner within 1.5e-3 of the place, 10 divisions a side; the horse's diagonal is 0.253): 1.226e-3 of the diagonal
// (9.43x the target) before, 1.015e-3 (7.81x) now; prm_bench_max_error_sites: 1.190e-3 -> 1.051e-3.
TEST(PackMaxErrorHeavy, HorseCreaseVertexKeepsItsTipMoveAtOnePointThreeEMinus4) {
  PackOptions o;
  o.target_error = 1.3e-4;
  const prm::Mesh input = shared_mesh("horse.ply");
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  ASSERT_TRUE(decoded.ok()) << decoded.status.message;
  const prm::Mesh out = prm::pipeline::to_mesh(decoded.value);
  const prm::DistanceReport d = decoded_distance(input, r);
  const prm::Vec3 place = {-0.0037, 0.0290, -0.0618};
  const double missed = d.rel(sampled_distance_near(input, out, place, 1.5e-3)),
               strays = d.rel(sampled_distance_near(out, input, place, 1.5e-3));
  std::printf("horse 1.3e-4, %zu bytes: the 115-degree place missed by %.3e, strays %.3e (max %.3e)\n",
              r.stream.size(), missed, strays, d.rel(d.max));
  EXPECT_LE(std::max(missed, strays), 8.2 * o.target_error);
}

// h22t: the default stream of the horse at 1.3e-4 was 8.08x the target (8,620 B): two faces the refinement left at
// 1.03x and 1.02x the aim (dense probes), at the 115-degree place and at (-0.0072, 0.0366, -0.0759), where the
// rounding to the stream's step and the heights had taken the refinement's faces past the aim (Metro 1.051e-3 and
// 1.050e-3). round_worst_sites moves three of their vertices' quantized points by a step: 7.98x, 8,606 B. Fails
// without it (8.08x).
TEST(PackMaxErrorHeavy, WorstSitesRoundedIntoEightTimesOnTheHorseAtOnePointThreeEMinus4) {
  expect_default_pack_within_8x("horse.ply", 1.3e-4);
}

// h22homer: homer (CGAL's data, 4,930 vertices, the PRM 3.4x denser) at 2e-4 was 8.53x the target (5,842 B): an
// input point at the bottom of a slit between two fingers, narrower than a quantization step there, that the mesh
// bridges. The refinement's moves and splits there turn a face away from the input (a face across the slit faces a
// wall), and round_worst_sites' one-step moves stopped 2.04e-3 from it (model units; the aim 1.91e-3). Its in>pr
// moves of up to two steps: 7.16x, 5,861 B, within issue 22's +5% over --no-local-refinement (5,723 B). Fails
// without them (8.53x).
TEST(PackMaxErrorHeavy, HomersSlitBetweenFingersRoundedIntoEightTimesAtTwoEMinus4) {
  const std::string path = std::string(PRM_CGAL_MESHES) + "/homer.off";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is missing";
  const prm::Mesh input = prm::read_mesh(path);
  prm::pipeline::PackResult r;
  const prm::DistanceReport d = default_pack_within_target(input, "homer.off", 2e-4, &r);
  EXPECT_LE(d.rel(d.max), prm::pipeline::kDefaultMaxErrorPerTarget * 2e-4);
  PackOptions o;
  o.target_error = 2e-4;
  o.local_refinement = PackOptions::LocalRefinement::off;
  const prm::pipeline::PackResult unrefined = prm::pipeline::pack(input, o);
  EXPECT_LE(static_cast<double>(r.stream.size()), 1.05 * static_cast<double>(unrefined.stream.size()));
}

// h22homer: refined_elephant (CGAL's data) at 2e-4 was 7.998x the target (5,011 B), a pr>in place at the bound that
// any change could tip over it; a stream within kRoundMargin under the bound is rounded towards that margin: 7.40x,
// 5,018 B (--no-local-refinement: 5,019 B). Fails without it (7.998x).
TEST(PackMaxErrorHeavy, RefinedElephantRoundedToAMarginUnderEightTimesAtTwoEMinus4) {
  const std::string path = std::string(PRM_CGAL_MESHES) + "/refined_elephant.off";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is missing";
  prm::pipeline::PackResult r;
  const prm::DistanceReport d = default_pack_within_target(prm::read_mesh(path), "refined_elephant.off", 2e-4, &r);
  EXPECT_LE(d.rel(d.max), 0.99 * prm::pipeline::kDefaultMaxErrorPerTarget * 2e-4);  // 1% under the bound
}

// hsearch: at effort 4 the smaller unrefined attempt (11 bits x1.542) refines to 10.92x the target on the horse at
// 2e-4; the search then refines its other attempt (11 bits x1.414) and keeps it, 5,490 B at 7.48x (smaller too), and
// says so (PackResult::search_note). Fails without the search's bound (10.92x).
TEST(PackMaxErrorHeavy, SearchKeepsAnAttemptWithin8xAtEffort4) {
  PackOptions o;
  o.target_error = 2e-4;
  o.effort = 4;
  std::string note;
  const prm::DistanceReport d = packed_distance("horse.ply", o, &note);
  EXPECT_LE(d.rel(d.rms), o.target_error);
  EXPECT_LE(d.rel(d.max), prm::pipeline::kDefaultMaxErrorPerTarget * o.target_error);
  EXPECT_NE(note.find("the smallest within the bound"), std::string::npos) << note;
}

// The horse at 1.3e-4 and effort 9 (every attempt refined): until this session none of its six attempts was within
// 8x (8,330 B at 8.46x kept, the nearest within 5%); with h22r's groove moves and h22t's worst-site rounding the
// attempt at 12 bits x1.834 refines to 7.99x, 8,255 B, smaller than that, and the search keeps it.
TEST(PackMaxErrorHeavy, EffortNineKeepsTheHorsesAttemptWithin8xAtOnePointThreeEMinus4) {
  PackOptions o;
  o.target_error = 1.3e-4;
  o.effort = prm::pipeline::kMaxEffort;
  std::string note;
  const prm::DistanceReport d = packed_distance("horse.ply", o, &note);
  EXPECT_LE(d.rel(d.rms), o.target_error);
  EXPECT_LE(d.rel(d.max), prm::pipeline::kDefaultMaxErrorPerTarget * o.target_error);
  EXPECT_NE(note.find("the smallest within the bound"), std::string::npos) << note;
}

// `prm remesh FILE --target-error 2e-4` (12 bits, refined as pack refines): the remesh's distance to the input, with
// `samples` per surface (0: Metro's default).
prm::DistanceReport remesh_distance(const char* file, double target_error, size_t samples = 0) {
  const prm::Mesh input = shared_mesh(file);
  prm::remesh::RemeshOptions o;
  o.target_error = target_error;
  prm::pipeline::set_refinement(o, o.target_error, 0, true, true);
  const auto error = [&](const prm::remesh::PrmMesh& candidate) {
    const prm::DistanceReport d = prm::metro_distance(input, candidate.mesh);
    return prm::remesh::ErrorEstimate{d.rel(d.rms), d.rel(d.max)};
  };
  const prm::remesh::RemeshResult r = prm::remesh::remesh(input, o, error);
  prm::MetroOptions mo;
  mo.samples = samples;
  const prm::DistanceReport d = prm::metro_distance(input, r.prm.mesh, mo);
  std::printf("%s remesh at %g: %zu inserted, %zu moved, RMS %.3e, max %.3e (%zu samples)\n", file, target_error,
              r.prm.stats.deviation_inserts, r.prm.stats.deviation_moves, d.rel(d.rms), d.rel(d.max), d.a_to_b.samples);
  return d;
}

// hear: `prm remesh horse.ply --target-error 2e-4` (12 bits, refined as pack refines) spent the refinement's vertex
// budget (3% of the mesh's) by round 8 with the horse's leg tip 1.77x the bound away: 11.1x the target. With 6% and
// the split across the crease (insert_across_crease) the worst is the ear (bench/README.md "Worst-case error", hear):
// 9.40x as Metro's default samples see it, 10.2x with 5M samples (hfold: the peak is the midpoint of a lattice edge
// across a 148-degree groove, between the refinement's probes). hfold's descent (kDescendGain) mends the ear's
// straying lattice vertex, after which the default samples find that peak: 10.29x. hgroove: that edge lies along the
// rim of the thin ear (a knife edge, not a groove); after the rounds an end of it is moved so that the edge follows
// the input (move_groove_end): 8.57x (9.19x with 5M samples). Still fails with 3% (11.1x). h22r: measured with 5M
// samples (a peak between Metro's default samples is real); 20 rounds (the 135-degree crease was still being split in
// round 12) and the groove moves judged on the faces' fine probes: 7.95x (9.19x before).
TEST(PackMaxErrorHeavy, RemeshOfTheHorseKeepsRefiningPastItsOldBudget) {
  const double target = 2e-4;
  const prm::DistanceReport d = remesh_distance("horse.ply", target, 5000000);
  EXPECT_LE(d.rel(d.rms), target);
  EXPECT_LE(d.rel(d.max), 8.0 * target);
}

// hfold: `prm remesh feline.off --target-error 2e-4` was 8.27x, its worst a lattice vertex that two rim moves for its
// faces' points left 1.22x the bound from the input; the descent found a place 1.13x away and kept none beyond the
// bound. With kDescendGain: 7.73x.
TEST(PackMaxErrorHeavy, RemeshOfTheFelineMovesItsStrayingVertexNearer) {
  const double target = 2e-4;
  const prm::DistanceReport d = remesh_distance("feline.off", target);
  EXPECT_LE(d.rel(d.rms), target);
  EXPECT_LE(d.rel(d.max), 8.0 * target);
}

#endif

}  // namespace
