// `prm pack --target-bytes` (issue 23, pipeline/pack_to_bytes.h) on a real mesh: the stream kept fits the budget, is
// the lowest-RMS fitting stream of the search, decodes to what its report says, and a larger budget gives an RMS no
// worse; a budget below every stream is refused with BudgetTooSmall, a target error beside it with invalid_argument.
#include <gtest/gtest.h>

#include <string>

#include "prm/codec.h"
#include "prm/mesh_io.h"
#include "prm/metro_distance.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack_to_bytes.h"

namespace prm {
namespace {

Mesh feline() { return read_mesh(std::string(PRM_SHARED_MESHES) + "/feline_5k.obj"); }

// The fastest search (effort 0) on the piecewise regular path, so that the test is a few packs of a 5k-vertex mesh.
pipeline::PackOptions fast_prm() {
  pipeline::PackOptions o;
  o.mode = pipeline::PackMode::prm;
  o.effort = 0;
  return o;
}

void expect_kept_within(const Mesh& input, const pipeline::PackToBytesResult& r, size_t budget) {
  ASSERT_FALSE(r.result.stream.empty());
  EXPECT_LE(r.result.stream.size(), budget);
  ASSERT_FALSE(r.steps.empty());
  bool kept_seen = false;
  for (const pipeline::BytesSearchStep& s : r.steps) {
    if (!s.made || s.bytes > budget) continue;
    EXPECT_GE(s.rms, r.result.remesh.error.rms) << "a fitting stream of lower RMS was not kept (" << s.target_error << ")";
    kept_seen |= s.target_error == r.target_error && s.bytes == r.result.stream.size();
  }
  EXPECT_TRUE(kept_seen) << "the stream kept is not one of the search's steps";
  // The report's RMS is the decoded stream's, measured again here.
  const auto decoded = codec::decode(r.result.stream.data(), r.result.stream.size());
  ASSERT_TRUE(decoded.ok()) << decoded.status.message;
  const DistanceReport d = MetroReference(&input).compare(pipeline::to_mesh(decoded.value));
  EXPECT_NEAR(d.rel(d.rms), r.result.remesh.error.rms, 1e-3 * r.result.remesh.error.rms);
}

TEST(PackToBytes, FitsTheBudgetAndALargerBudgetIsNoWorse) {
  const Mesh input = feline();
  const pipeline::PackOptions o = fast_prm();
  const pipeline::PackToBytesResult a = pipeline::pack_to_bytes(input, 6000, o);
  expect_kept_within(input, a, 6000);
  // 10% more bytes: at least as good.
  const pipeline::PackToBytesResult b = pipeline::pack_to_bytes(input, 6600, o);
  expect_kept_within(input, b, 6600);
  EXPECT_LE(b.result.remesh.error.rms, a.result.remesh.error.rms);
  EXPECT_FALSE(a.finest);
}

TEST(PackToBytes, RefusesABudgetBelowTheCoarsestStream) {
  const Mesh input = feline();
  try {
    pipeline::pack_to_bytes(input, 400, fast_prm());
    FAIL() << "a 400-byte budget for feline_5k was met";
  } catch (const pipeline::BudgetTooSmall& e) {
    EXPECT_GT(e.smallest_bytes, 400u);
    EXPECT_NE(std::string(e.what()).find("no stream fits 400 bytes"), std::string::npos) << e.what();
  }
}

TEST(PackToBytes, RefusesATargetErrorOrGridBesideIt) {
  const Mesh input = feline();
  pipeline::PackOptions o = fast_prm();
  o.target_error = 2e-4;
  EXPECT_THROW(pipeline::pack_to_bytes(input, 6000, o), std::invalid_argument);
  o.target_error = 0;
  o.grid_fraction = 0.01;
  EXPECT_THROW(pipeline::pack_to_bytes(input, 6000, o), std::invalid_argument);
  EXPECT_THROW(pipeline::pack_to_bytes(input, 0, fast_prm()), std::invalid_argument);
}

}  // namespace
}  // namespace prm
