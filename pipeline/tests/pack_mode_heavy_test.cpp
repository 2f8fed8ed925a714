// PackOptions::mode on a paper model (issue 22): at the paper's error the piecewise regular stream is the smaller,
// so auto keeps it (a 50k-vertex pack: Release run only).
#include <gtest/gtest.h>

#include <string>

#include "prm/mesh_io.h"
#include "prm/pipeline/pack.h"

namespace {

TEST(PackModeHeavy, HorseStaysPrm) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/horse.ply");
  prm::pipeline::PackOptions o;
  o.target_error = 2e-4;
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  std::printf("horse: %s, PRM %zu B, general %zu B at %d bits\n", prm::pipeline::pack_mode_name(r.mode),
              r.prm_candidate.bytes, r.general_candidate.bytes, r.general_candidate.bits);
  ASSERT_TRUE(r.prm_candidate.made && r.general_candidate.made);
  EXPECT_EQ(r.mode, prm::pipeline::PackMode::prm) << r.mode_reason;
  EXPECT_LT(r.prm_candidate.bytes, r.general_candidate.bytes);
  EXPECT_LE(r.remesh.error.rms, o.target_error);
}

}  // namespace
