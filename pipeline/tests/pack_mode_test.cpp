// PackOptions::mode (`prm pack --mode`, issue 22 "never worse than not remeshing"): auto keeps the smaller of the
// piecewise regular stream and the input coded through the general path, both meeting the target; the forced modes
// make the stream they name; an input the general path refuses is packed as a PRM, the report saying why; a pinched
// vertex is split for the general path.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "prm/error.h"
#include "prm/mesh_io.h"
#include "prm/metro_distance.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack.h"
#include "prm/pipeline/pack_general.h"
#include "awkward_meshes.h"
#include "metro_test_meshes.h"

namespace {

using prm::pipeline::PackMode;
using prm::pipeline::PackOptions;
using prm::pipeline::PackResult;

// The decoded stream against the input, measured here at Metro's full density (independently of pack).
double decoded_rms(const prm::Mesh& input, const PackResult& r) {
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  EXPECT_TRUE(decoded.ok()) << decoded.status.message;
  const prm::DistanceReport d = prm::metro_distance(input, prm::pipeline::to_mesh(decoded.value));
  return d.rel(d.rms);
}

// Whether the stream is a PRM stream: it has the patches section (spec §3.4, section 4); a general-path stream has
// only connectivity and positions.
bool is_prm_stream(const PackResult& r) {
  const auto info = prm::codec::inspect(r.stream.data(), r.stream.size());
  EXPECT_TRUE(info.ok()) << info.status.message;
  for (const auto& s : info.value.sections)
    if (s.id == 4) return true;
  return false;
}

// auto chose the smaller of the two measured streams, and the stream kept is that candidate's.
void expect_consistent_choice(const PackResult& r) {
  ASSERT_TRUE(r.prm_candidate.made) << r.prm_candidate.refused;
  ASSERT_TRUE(r.general_candidate.made) << r.general_candidate.refused;
  if (r.mode == PackMode::general) {
    EXPECT_LT(r.general_candidate.bytes, r.prm_candidate.bytes);
    EXPECT_EQ(r.stream.size(), r.general_candidate.bytes);
    EXPECT_FALSE(is_prm_stream(r));
  } else {
    EXPECT_LE(r.prm_candidate.bytes, r.general_candidate.bytes);
    EXPECT_EQ(r.stream.size(), r.prm_candidate.bytes);
    EXPECT_TRUE(is_prm_stream(r));
  }
  EXPECT_FALSE(r.mode_reason.empty());
}

// The 12-triangle cube: a grid meeting 2e-4 has tens of thousands of vertices; coded as it is, 8 vertices.
TEST(PackMode, CubeIsCodedAsItIs) {
  const prm::Mesh cube = prm::test::box(1, 1, 1, 1);
  ASSERT_EQ(cube.triangles.size(), 12u);
  PackOptions o;
  o.target_error = 2e-4;
  const PackResult r = prm::pipeline::pack(cube, o);
  EXPECT_EQ(r.mode, PackMode::general) << r.mode_reason;
  expect_consistent_choice(r);
  EXPECT_EQ(r.report.vertices, cube.positions.size());  // n_r / n_o = 1
  EXPECT_EQ(r.input_vertices, cube.positions.size());
  EXPECT_LT(5 * r.stream.size(), r.prm_candidate.bytes) << r.stream.size() << " B against " << r.prm_candidate.bytes;
  EXPECT_GT(r.prm_candidate.vertices, 100 * cube.positions.size());
  EXPECT_LE(decoded_rms(cube, r), o.target_error);
}

// EffortPlan::general_floor_check (issue 21): below effort 9 the PRM candidate comes first, and a general stream
// whose fewest bits are already no smaller is not tried (the report says so); at effort 9 both are made, and the
// general stream kept is at least its floor (the premise: the stream grows with the bit depth).
TEST(PackMode, GeneralCandidateUntriedWhenItsFloorIsNotSmaller) {
  const prm::Mesh sphere = prm::test::icosphere(5);  // 10,242 vertices
  const size_t floor = prm::pipeline::general_floor_bytes(sphere);
  PackOptions o;
  o.target_error = 1e-3;
  for (int effort : {0, 3}) {
    o.effort = effort;
    const PackResult r = prm::pipeline::pack(sphere, o);
    EXPECT_EQ(r.mode, PackMode::prm) << r.mode_reason;
    ASSERT_TRUE(r.prm_candidate.made) << r.prm_candidate.refused;
    EXPECT_LE(r.prm_candidate.bytes, floor);
    EXPECT_FALSE(r.general_candidate.made);
    EXPECT_TRUE(r.general_candidate.refused.empty());
    EXPECT_NE(r.general_candidate.not_tried.find("not tried at effort " + std::to_string(effort)), std::string::npos)
        << r.general_candidate.not_tried;
    EXPECT_NE(r.mode_reason.find("not tried"), std::string::npos) << r.mode_reason;
    EXPECT_LE(decoded_rms(sphere, r), o.target_error);
  }
  // The premise: more bits, a larger general stream.
  size_t previous = floor;
  for (int bits = prm::pipeline::kMinGeneralBits + 1; bits <= 14; ++bits) {
    prm::codec::EncodeReport report;
    const auto encoded = prm::pipeline::encode_general_mesh(sphere, bits, &report);
    ASSERT_TRUE(encoded.ok()) << encoded.status.message;
    EXPECT_GT(encoded.value.size(), previous) << bits << " bits";
    previous = encoded.value.size();
  }
  // A given bit depth: both candidates made, as before.
  o.bits = 10;
  const PackResult both = prm::pipeline::pack(sphere, o);
  EXPECT_TRUE(both.general_candidate.not_tried.empty());
  ASSERT_TRUE(both.general_candidate.made) << both.general_candidate.refused;
  EXPECT_GE(both.general_candidate.bytes, floor);
}

// At effort 0 a general stream whose floor is smaller than the PRM one (the cube's 8 vertices) is made, after the
// PRM candidate, and auto keeps the smaller.
TEST(PackMode, EffortZeroMakesTheGeneralCandidateWhenItsFloorIsSmaller) {
  const prm::Mesh cube = prm::test::box(1, 1, 1, 1);
  PackOptions o;
  o.target_error = 1e-3;
  o.effort = 0;
  const PackResult r = prm::pipeline::pack(cube, o);
  EXPECT_EQ(r.mode, PackMode::general) << r.mode_reason;
  expect_consistent_choice(r);
  EXPECT_TRUE(r.general_candidate.not_tried.empty());
  EXPECT_EQ(r.report.vertices, cube.positions.size());
  EXPECT_LE(decoded_rms(cube, r), o.target_error);
}

// No piecewise regular mesh meets 1e-6 within the remesher's vertex budget: auto codes the cube as it is and says why.
TEST(PackMode, UnreachableTargetIsCodedAsItIs) {
  const prm::Mesh cube = prm::test::box(1, 1, 1, 1);
  PackOptions o;
  o.target_error = 1e-6;
  const PackResult r = prm::pipeline::pack(cube, o);
  EXPECT_EQ(r.mode, PackMode::general);
  EXPECT_FALSE(r.prm_candidate.made);
  EXPECT_FALSE(r.prm_candidate.refused.empty());
  EXPECT_NE(r.mode_reason.find("no piecewise regular mesh could be made"), std::string::npos) << r.mode_reason;
  EXPECT_LE(decoded_rms(cube, r), o.target_error);
}

// Forced modes make the stream they name, each meeting the target.
TEST(PackMode, ForcedModes) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  PackOptions o;
  o.target_error = 5e-4;
  o.mode = PackMode::general;
  const PackResult g = prm::pipeline::pack(input, o);
  EXPECT_EQ(g.mode, PackMode::general);
  EXPECT_FALSE(g.prm_candidate.made);
  EXPECT_EQ(g.report.vertices, input.positions.size());
  EXPECT_FALSE(is_prm_stream(g));
  EXPECT_GE(g.bits, prm::pipeline::kMinGeneralBits);
  EXPECT_LE(decoded_rms(input, g), o.target_error);
  // One bit fewer misses the target (the smallest bit depth that meets it).
  if (g.bits > prm::pipeline::kMinGeneralBits) {
    o.bits = g.bits - 1;
    EXPECT_THROW(prm::pipeline::pack(input, o), prm::remesh::TargetNotReached);
    o.bits = 0;
  }
  o.mode = PackMode::prm;
  const PackResult p = prm::pipeline::pack(input, o);
  EXPECT_EQ(p.mode, PackMode::prm);
  EXPECT_FALSE(p.general_candidate.made);
  EXPECT_TRUE(is_prm_stream(p));
  EXPECT_LE(decoded_rms(input, p), o.target_error);
  // Without a target error, auto is prm.
  PackOptions grid;
  grid.grid_fraction = 0.05;
  const PackResult q = prm::pipeline::pack(input, grid);
  EXPECT_EQ(q.mode, PackMode::prm);
  EXPECT_FALSE(q.general_candidate.made);
}

// A pinched vertex: the general path codes the input with the pinch split (one copy per extra fan, the geometry
// unchanged), the report naming the copy; an edge with three faces is refused by both paths, by name.
TEST(PackMode, PinchedVertexIsSplitForTheGeneralPath) {
  const prm::Mesh bowtie = prm::test::bowtie();
  PackOptions o;
  o.target_error = 2e-4;
  o.bits = 12;
  o.step_scale = 1;
  const PackResult r = prm::pipeline::pack(bowtie, o);
  expect_consistent_choice(r);
  EXPECT_EQ(r.mode, PackMode::general) << r.mode_reason;
  EXPECT_EQ(r.general_candidate.vertices, 6u);  // 5 + the pinched vertex's copy
  EXPECT_TRUE(r.repaired);
  EXPECT_EQ(r.repair.pinched_vertices_split, 1u);
  EXPECT_NE(r.mode_reason.find("pinched vertices split (1 cop"), std::string::npos) << r.mode_reason;
  EXPECT_EQ(r.boundary_loops_in, 2u);
  EXPECT_EQ(r.boundary_loops_out, 2u);
  EXPECT_LE(decoded_rms(bowtie, r), o.target_error);
  o.mode = PackMode::general;
  const PackResult g = prm::pipeline::pack(bowtie, o);
  EXPECT_EQ(g.mode, PackMode::general);
  EXPECT_EQ(g.repair.pinched_vertices_split, 1u);

  prm::Mesh fin = bowtie;  // a third triangle on the edge (0, 1): an edge with three faces
  fin.positions.push_back({1, 0.5, 1});
  fin.triangles.push_back({0, 1, 5});
  o.mode = PackMode::automatic;
  try {
    prm::pipeline::pack(fin, o);
    ADD_FAILURE() << "an edge with three faces was packed";
  } catch (const prm::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the general path"), std::string::npos) << e.what();
  }
}

// rabbit_1k_decimated has one pinched vertex: the general path codes its split copy, and auto keeps that stream
// (a PRM would have n_r/n_o 14.4 there), within the target against the input (Metro here, at full density).
TEST(PackMode, PinchedRabbitIsCodedAsItIs) {
  const prm::Mesh rabbit = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/rabbit_1k_decimated.off");
  PackOptions o;
  o.target_error = 2e-4;
  const PackResult r = prm::pipeline::pack(rabbit, o);
  expect_consistent_choice(r);
  EXPECT_EQ(r.mode, PackMode::general) << r.mode_reason;
  EXPECT_EQ(r.repair.pinched_vertices_split, 1u);
  EXPECT_EQ(r.report.vertices, rabbit.num_vertices() + 1);
  const double rms = decoded_rms(rabbit, r);
  EXPECT_LE(rms, o.target_error);
  std::printf("rabbit_1k_decimated: %s, %zu B (PRM %zu B), %u vertices (n_r/n_o %.3f), decoded RMS %.3e: %s\n",
              prm::pipeline::pack_mode_name(r.mode), r.stream.size(), r.prm_candidate.bytes, r.report.vertices,
              static_cast<double>(r.report.vertices) / static_cast<double>(rabbit.num_vertices()), rms,
              r.mode_reason.c_str());
}

// Small real meshes at 2e-4 (a CAD part, a sparse cow): whichever auto keeps is the smaller stream, and both meet
// the target.
class PackModeAuto : public ::testing::TestWithParam<const char*> {};

TEST_P(PackModeAuto, KeepsTheSmallerStream) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/" + GetParam());
  PackOptions o;
  o.target_error = 2e-4;
  const PackResult r = prm::pipeline::pack(input, o);
  std::printf("%s: %s, PRM %zu B, general %zu B at %d bits: %s\n", GetParam(), prm::pipeline::pack_mode_name(r.mode),
              r.prm_candidate.bytes, r.general_candidate.bytes, r.general_candidate.bits, r.mode_reason.c_str());
  expect_consistent_choice(r);
  EXPECT_LE(r.prm_candidate.rms, o.target_error);
  EXPECT_LE(r.general_candidate.rms, o.target_error);
  EXPECT_LE(decoded_rms(input, r), o.target_error);
  EXPECT_EQ(r.input_vertices, input.positions.size());
}

INSTANTIATE_TEST_SUITE_P(SmallMeshes, PackModeAuto, ::testing::Values("fandisk.obj", "spot.obj"));

// pack_general measures only the bit depths whose outcome it cannot tell otherwise (issue 21): its displacement bound
// is at least the Metro maximum at every depth, and its choice and reported distances are those of Metro at every
// depth (measured here one by one, independently of its shortcuts), at targets on both sides of its depths' errors.
TEST(PackGeneral, BitDepthIsMetrosChoice) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  const prm::MetroReference reference(&input);
  struct Depth {
    bool zero_area;
    double rms, max;
  };
  std::vector<Depth> depths;
  for (int b = prm::pipeline::kMinGeneralBits; b <= prm::pipeline::kMaxGeneralBits; ++b) {
    prm::codec::EncodeReport report;
    const auto encoded = prm::pipeline::encode_general_mesh(input, b, &report);
    ASSERT_TRUE(encoded.ok()) << encoded.status.message;
    const auto decoded = prm::codec::decode(encoded.value.data(), encoded.value.size());
    ASSERT_TRUE(decoded.ok()) << decoded.status.message;
    const prm::DistanceReport d = reference.compare(prm::pipeline::to_mesh(decoded.value));
    depths.push_back({prm::pipeline::count_zero_area_triangles(decoded.value) > 0, d.rel(d.rms), d.rel(d.max)});
    // At a fixed depth pack_general measures and reports the bound beside the distances (a zero-area triangle is
    // refused).
    if (depths.back().zero_area) {
      EXPECT_THROW(prm::pipeline::pack_general(input, reference, 0, b), prm::remesh::TargetNotReached);
      continue;
    }
    const prm::pipeline::GeneralPack fixed = prm::pipeline::pack_general(input, reference, 0, b);
    ASSERT_TRUE(fixed.measured);
    ASSERT_GE(fixed.bound, 0) << b << " bits: spot's decoded triangles are its own";
    EXPECT_GE(fixed.bound, fixed.max) << b << " bits";
    EXPECT_EQ(fixed.max, d.rel(d.max));
  }
  int skipped = 0;
  for (double target : {1e-3, 2e-4, 5e-5, 1e-5}) {
    int expected = -1;
    for (int b = prm::pipeline::kMinGeneralBits; b <= prm::pipeline::kMaxGeneralBits && expected < 0; ++b) {
      const Depth& d = depths[static_cast<size_t>(b - prm::pipeline::kMinGeneralBits)];
      if (!d.zero_area && d.rms <= target) expected = b;
    }
    ASSERT_GT(expected, 0);
    const prm::pipeline::GeneralPack g = prm::pipeline::pack_general(input, reference, target, 0);
    EXPECT_EQ(g.bits, expected) << "target " << target;
    EXPECT_TRUE(g.measured);
    EXPECT_EQ(g.rms, depths[static_cast<size_t>(expected - prm::pipeline::kMinGeneralBits)].rms);
    for (const auto& t : g.tried) skipped += t.rms < 0;
  }
  EXPECT_GT(skipped, 0) << "every depth was measured: the bound never decided";
}

}  // namespace
