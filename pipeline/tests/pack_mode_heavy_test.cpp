// PackOptions::mode on a paper model (issue 22): at the paper's error the piecewise regular stream is the smaller,
// so auto keeps it (a 50k-vertex pack: Release run only).
#include <gtest/gtest.h>

#include <string>

#include "prm/mesh_io.h"
#include "prm/pipeline/pack.h"
#include "prm/pipeline/pack_general.h"

namespace {

TEST(PackModeHeavy, HorseStaysPrm) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/horse.ply");
  prm::pipeline::PackOptions o;
  o.target_error = 2e-4;
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  std::printf("horse: %s, PRM %zu B, general %zu B at %d bits\n", prm::pipeline::pack_mode_name(r.mode),
              r.prm_candidate.bytes, r.general_candidate.bytes, r.general_candidate.bits);
  ASSERT_TRUE(r.prm_candidate.made) << r.prm_candidate.refused;
  EXPECT_EQ(r.mode, prm::pipeline::PackMode::prm) << r.mode_reason;
  EXPECT_LE(r.remesh.error.rms, o.target_error);
  // Below effort 9 the general candidate is made only when its 8-bit stream is smaller (issue 21): on the horse it
  // is not, so it is not tried, and the report says so.
  EXPECT_FALSE(r.general_candidate.made);
  EXPECT_FALSE(r.general_candidate.not_tried.empty()) << r.mode_reason;
  EXPECT_LE(r.prm_candidate.bytes, prm::pipeline::general_floor_bytes(input));
}

// The exhaustive search makes both candidates, and the PRM stream is the smaller.
TEST(PackModeHeavy, HorseStaysPrmAtEffort9) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/horse.ply");
  prm::pipeline::PackOptions o;
  o.target_error = 2e-4;
  o.effort = prm::pipeline::kMaxEffort;
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  ASSERT_TRUE(r.prm_candidate.made && r.general_candidate.made);
  EXPECT_EQ(r.mode, prm::pipeline::PackMode::prm) << r.mode_reason;
  EXPECT_LT(r.prm_candidate.bytes, r.general_candidate.bytes);
  EXPECT_LE(r.remesh.error.rms, o.target_error);
}

}  // namespace
