// PackOptions::effort (`prm pack --effort`): every level meets the target error with a stream that decodes to a mesh
// without zero-area triangles; the levels outside kMinEffort..kMaxEffort are refused. (Time is measured in bench/,
// bench/README.md "pack effort", never here.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "prm/metro_distance.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack.h"
#include "test_meshes.h"

namespace {

using prm::pipeline::PackOptions;

TEST(PackEffort, LevelsOutsideTheRangeAreRefused) {
  EXPECT_THROW(prm::pipeline::effort_plan(prm::pipeline::kMinEffort - 1), std::invalid_argument);
  EXPECT_THROW(prm::pipeline::effort_plan(prm::pipeline::kMaxEffort + 1), std::invalid_argument);
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  PackOptions o;
  o.target_error = 5e-4;
  o.effort = prm::pipeline::kMaxEffort + 1;
  EXPECT_THROW(prm::pipeline::pack(input, o), std::invalid_argument);
  // The highest level is today's exhaustive search, measured at full density throughout.
  const prm::pipeline::EffortPlan top = prm::pipeline::effort_plan(prm::pipeline::kMaxEffort);
  EXPECT_TRUE(top.exhaustive);
  EXPECT_EQ(top.search_samples_per_face, 10);
  // Effort 4 compares two steps by their rounded heights and chooses the lambda of the better one only.
  const prm::pipeline::EffortPlan four = prm::pipeline::effort_plan(4);
  EXPECT_TRUE(four.defer_heights);
  EXPECT_EQ(four.steps, 2);
  EXPECT_EQ(four.coarser_step_from_grid, 0);
  // Effort 3 defers the heights too and tries the next coarser step instead when its first grid meets the target
  // and the search would go on to one of 15 quantization steps or more.
  const prm::pipeline::EffortPlan three = prm::pipeline::effort_plan(3);
  EXPECT_TRUE(three.defer_heights);
  EXPECT_EQ(three.steps, 1);
  EXPECT_EQ(three.coarser_step_from_grid, 15);
}

// spot.obj packed at effort 0 in PRM mode.
prm::pipeline::PackResult pack_spot_at_effort_zero(const prm::Mesh& spot, double target) {
  PackOptions o;
  o.target_error = target;
  o.effort = 0;
  o.mode = prm::pipeline::PackMode::prm;
  return prm::pipeline::pack(spot, o);
}

// The reported error is, bit for bit, the full-density Metro of the stream decoded, and meets the target.
void expect_report_is_full_density_metro(const prm::Mesh& input, const prm::pipeline::PackResult& r, double target) {
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  ASSERT_TRUE(decoded.ok()) << decoded.status.message;
  const prm::DistanceReport d = prm::metro_distance(input, prm::pipeline::to_mesh(decoded.value));
  EXPECT_EQ(r.remesh.error.rms, d.rel(d.rms));
  EXPECT_EQ(r.remesh.error.max, d.rel(d.max));
  EXPECT_LE(d.rel(d.rms), prm::pipeline::kQuantizationMargin * target);
}

// EffortPlan::decode_in_band (effort 0 only): spot's kept grid at 2e-4 has a sparse estimate near the target, so the
// search measured its stream at full density and the check reused that measurement. The reported error must be,
// bit for bit, the full-density Metro of the decoded stream (the candidate quantized instead of decoded gave a
// max 0.4% away: its triangles are sampled in another order).
TEST(PackEffort, EffortZeroReusesTheSearchsMeasurementOfTheStreamExactly) {
  for (int effort = prm::pipeline::kMinEffort; effort <= prm::pipeline::kMaxEffort; ++effort)
    EXPECT_EQ(prm::pipeline::effort_plan(effort).decode_in_band, effort == 0) << "effort " << effort;
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  const prm::pipeline::PackResult r = pack_spot_at_effort_zero(input, 2e-4);
  ASSERT_FALSE(r.remesh.search.empty());
  // The reuse happened: the kept grid's search error is the reported one (a sparse estimate would differ).
  const prm::remesh::SearchStep& kept = r.remesh.search.back();
  EXPECT_EQ(kept.error.rms, r.remesh.error.rms);
  EXPECT_EQ(kept.error.max, r.remesh.error.max);
  EXPECT_EQ(r.codec_options.height_lambda, 0.0);
  expect_report_is_full_density_metro(input, r, 2e-4);
}

// Effort 0's lambda round (EffortPlan::lambda_full_density): measured at full density, so that the check reuses
// it. On spot at 5e-4 the lambda stream is kept; the reported error must be, bit for bit, the full-density Metro of
// the decoded stream (a sparse estimate reused by mistake would differ). The effort-0 cuts are effort 0's only.
TEST(PackEffort, EffortZeroMeasuresItsLambdaAtFullDensityAndTheCheckReusesItExactly) {
  for (int effort = prm::pipeline::kMinEffort; effort <= prm::pipeline::kMaxEffort; ++effort) {
    const prm::pipeline::EffortPlan p = prm::pipeline::effort_plan(effort);
    EXPECT_EQ(p.lambda_full_density, effort == 0) << "effort " << effort;
    EXPECT_EQ(p.lambda_below, effort == 0 ? 0.97 : 0.0) << "effort " << effort;
    EXPECT_EQ(p.error_samples, effort == 0 ? 1 : prm::remesh::kTriangleErrorSamples) << "effort " << effort;
    EXPECT_EQ(p.error_unit_stride, effort == 0 ? 16 : 1) << "effort " << effort;
  }
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  const prm::pipeline::PackResult r = pack_spot_at_effort_zero(input, 5e-4);
  EXPECT_GT(r.codec_options.height_lambda, 0.0);  // the lambda stream was kept
  expect_report_is_full_density_metro(input, r, 5e-4);
}

// EffortPlan::coarser_step_from_grid: on a smooth sphere the default's first grid meets 5e-4 with room to spare and
// its search would go on to a grid of more than 15 steps (26 at 9 bits), so effort 3 searches the next coarser step
// instead. Both attempts are listed; the kept one is an eighth of an octave coarser and smaller, and meets the target.
TEST(PackEffort, CoarserStepWhenTheGridIsOfManySteps) {
  const prm::Mesh input = prm::test::icosphere(5);
  const double target = 5e-4;
  PackOptions o;
  o.target_error = target;
  o.effort = 3;
  o.mode = prm::pipeline::PackMode::prm;
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  ASSERT_EQ(r.tried.size(), 2u);
  auto step = [](const prm::pipeline::PackResult::Trial& t) { return t.step_scale * std::exp2(-t.bits); };
  EXPECT_NEAR(step(r.tried[1]) / step(r.tried[0]), std::exp2(0.125), 1e-9);
  EXPECT_EQ(r.tried[1].bits, r.bits);
  EXPECT_EQ(r.tried[1].step_scale, r.step_scale);
  EXPECT_EQ(r.tried[1].bytes, r.stream.size());
  EXPECT_LT(r.tried[1].bytes, r.tried[0].bytes);
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  ASSERT_TRUE(decoded.ok()) << decoded.status.message;
  const prm::DistanceReport d = prm::metro_distance(input, prm::pipeline::to_mesh(decoded.value));
  EXPECT_LE(d.rel(d.rms), target);
  // Effort 2 (no deferred heights) keeps the first step.
  o.effort = 2;
  EXPECT_EQ(prm::pipeline::pack(input, o).tried.size(), 1u);
}

// Each level below the exhaustive one (GridFromTargetError covers that) on a small real mesh: the decoded stream
// meets the target, measured independently at Metro's full density, and has no zero-area triangle. One test per
// level, so that ctest runs them side by side.
class PackEffortLevel : public ::testing::TestWithParam<int> {};

TEST_P(PackEffortLevel, MeetsTheTarget) {
  const int effort = GetParam();
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  const double target = 5e-4;
  PackOptions o;
  o.target_error = target;
  o.effort = effort;
  o.mode = prm::pipeline::PackMode::prm;  // the effort levels of the remesher's search
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  ASSERT_FALSE(r.tried.empty());
  // The attempt kept is listed with the stream's size (EffortPlan::defer_heights lists the others' rounded sizes).
  size_t kept = 0;
  for (const auto& t : r.tried)
    if (t.bits == r.bits && t.step_scale == r.step_scale && t.bytes == r.stream.size()) ++kept;
  EXPECT_EQ(kept, 1u);
  EXPECT_LE(r.remesh.error.rms, prm::pipeline::kQuantizationMargin * target);
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  ASSERT_TRUE(decoded.ok()) << decoded.status.message;
  EXPECT_EQ(prm::pipeline::count_zero_area_triangles(decoded.value), 0u);
  EXPECT_EQ(decoded.value.frame.bits, r.bits);
  const prm::DistanceReport d = prm::metro_distance(input, prm::pipeline::to_mesh(decoded.value));
  EXPECT_LE(d.rel(d.rms), target);
  // The reported error is the full-density measurement of this stream.
  EXPECT_NEAR(r.remesh.error.rms, d.rel(d.rms), 1e-3 * target);
  std::printf("spot at %g, effort %d: %zu bytes, %d bits, step x%.3f, RMS %.4e, %zu grids\n", target, effort,
              r.stream.size(), r.bits, r.step_scale, d.rel(d.rms), r.remesh_rounds);
}

INSTANTIATE_TEST_SUITE_P(BelowExhaustive, PackEffortLevel,
                         ::testing::Range(prm::pipeline::kMinEffort, prm::pipeline::kMaxEffort));

}  // namespace
