// Issue 17's zero-area sweep, in small (bench/zero_area_sweep.sh runs it over every shared and dense CGAL mesh):
// `pack` with a target error, at two targets (2e-4 at 10 bits, 1e-4 at 11: the bit depths the search picks for the
// box and the elephant; one step scale; the elephant at 5e-4 and 2e-4), on the three awkward cases (a bowtie, CGAL's
// elephant, a 1 x 1 x 0.002 box) and small real meshes. Every stream decodes, no decoded triangle has zero area, no
// two decoded vertices share a position, and except on the bowtie (which repair makes a two-sided sheet: there is no
// side) the faces the quantization turns away from the input, and the decoded triangles facing away from it, are 0
// but on feline_5k (issue 17): at 2e-4, 3 decoded faces that the remesher already placed facing away; at 1e-4, 2 that
// the separation does not mend (before: 8 turned by its last pass, 18 decoded). The box, two quantization steps thick
// at 10 bits (before: 8 and 11), is the other case where the last pass turned faces. Heavy: about four minutes in
// Release.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <string>
#include <vector>

#include "awkward_meshes.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/pack.h"
#include "prm/pipeline/stream_check.h"

namespace {

struct Target {
  double error;
  int bits;
};
constexpr Target kTargets[] = {{2e-4, 10}, {1e-4, 11}};

constexpr size_t kNoSide = SIZE_MAX;  // a two-sided sheet: facing away from the input means nothing

// max_turned: faces the quantization turned away from the input, and decoded triangles facing away from it, allowed
// at each target (kNoSide: not checked).
// refine: with the local refinement (PackOptions::local_refinement), its facing guard on or off.
enum class Refine { none, guarded, unguarded };
void expect_clean_streams(const prm::Mesh& input, const std::string& name, const std::vector<size_t>& max_turned,
                          const std::vector<Target>& targets = {std::begin(kTargets), std::end(kTargets)},
                          Refine refine = Refine::none) {
  ASSERT_EQ(max_turned.size(), targets.size());
  const prm::Mesh reference = prm::pipeline::pack_reference(input);
  for (size_t k = 0; k < targets.size(); ++k) {
    const Target& target = targets[k];
    SCOPED_TRACE(name + " at " + std::to_string(target.error));
    prm::pipeline::PackOptions o;
    o.target_error = target.error;
    o.bits = target.bits;
    o.step_scale = 1;
    o.mode = prm::pipeline::PackMode::prm;  // the remesher's path
    o.local_refinement = refine != Refine::none ? prm::pipeline::PackOptions::LocalRefinement::on
                                                : prm::pipeline::PackOptions::LocalRefinement::off;
    o.refine_facing_guard = refine == Refine::guarded;
    const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
    const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
    ASSERT_TRUE(decoded.ok()) << decoded.status.message;
    const prm::pipeline::StreamCheck c = prm::pipeline::check_decoded(decoded.value, &reference);
    EXPECT_EQ(c.zero_area, 0u);
    EXPECT_EQ(c.coincident, 0u);
    if (max_turned[k] != kNoSide) {
      EXPECT_LE(r.remesh.prm.stats.quantized_turned, max_turned[k]);
      EXPECT_LE(c.turned, max_turned[k]);
    }
    EXPECT_LE(r.remesh.error.rms, target.error);
    std::printf("%s at %.0e: %d bits, %zu bytes, %zu vertices (%zu moved, %zu edges collapsed, %zu left turned by the "
                "quantization), %zu decoded triangles facing away from the input\n",
                name.c_str(), target.error, r.bits, r.stream.size(), decoded.value.num_vertices(),
                r.remesh.prm.stats.quantized_moves, r.remesh.prm.stats.quantized_collapses,
                r.remesh.prm.stats.quantized_turned, c.turned);
  }
}

TEST(PackZeroArea, AwkwardCases) {
  // 1e-4: too many vertices
  expect_clean_streams(prm::test::bowtie(), "bowtie", {kNoSide, kNoSide}, {{5e-4, 12}, {2e-4, 12}});
  expect_clean_streams(prm::test::box(1, 1, 0.002, 10), "1 x 1 x 0.002 box", {0, 0});
  const std::string elephant = std::string(PRM_CGAL_MESHES) + "/elephant.off";
  // 1e-4 makes 72k vertices of its 2.8k: 5e-4 (pack_degenerate_test's) keeps the test short.
  if (std::filesystem::exists(elephant))
    expect_clean_streams(prm::read_mesh(elephant), "elephant.off", {0, 0}, {{5e-4, 11}, {2e-4, 10}});
}

// feline_5k at 1e-4 makes 126k vertices (about 30 s of the test).
TEST(PackZeroArea, SmallRealMeshes) {
  const std::string dir = std::string(PRM_SHARED_MESHES) + "/";
  expect_clean_streams(prm::read_mesh(dir + "rabbit_1k_decimated.off"), "rabbit_1k_decimated.off", {0, 0});
  expect_clean_streams(prm::read_mesh(dir + "feline_5k.obj"), "feline_5k.obj", {3, 2});
}

// The local refinement (issue 22 item 3) with its facing guard turns no decoded triangle away from the input where
// it did without it (elephant at 5e-4: 3, rabbit_1k at 2e-4 and 1e-4: 2 and 11, in h22max8's runs; each unguarded
// count below is what the guard takes away, so this test fails with the guard off). feline_5k is left out for time
// (its 1e-4 run is 30 s; guarded: 0 and 2 facing away, its limits 3 and 2; unguarded 14 and 18; bench/README.md
// "Worst-case error", hrefine).
TEST(PackZeroArea, LocalRefinementTurnsNoTriangleAway) {
  const std::string dir = std::string(PRM_SHARED_MESHES) + "/";
  expect_clean_streams(prm::read_mesh(dir + "rabbit_1k_decimated.off"), "rabbit_1k_decimated.off refined", {0, 0},
                       {std::begin(kTargets), std::end(kTargets)}, Refine::guarded);
  const std::string elephant = std::string(PRM_CGAL_MESHES) + "/elephant.off";
  if (std::filesystem::exists(elephant))
    expect_clean_streams(prm::read_mesh(elephant), "elephant.off refined", {0, 0}, {{5e-4, 11}, {2e-4, 10}},
                         Refine::guarded);
}

}  // namespace
