// The whole job on real meshes: repair, remesh, encode, decode. The decoded mesh must be exactly the quantized PRM
// (same triangles up to the spec's vertex order, same integer positions), and close to the input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <stdexcept>
#include <map>
#include <tuple>
#include <string>

#include "prm/metro_distance.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack.h"
#include "prm/remesh/lattice.h"
#include "prm/remesh/reliefs.h"
#include "prm/remesh/resample.h"
#include "test_meshes.h"

namespace {

using prm::pipeline::PackOptions;

// Decodes `stream` and checks it against the PRM the pack encoded: vertex k of the stream is PRM vertex
// report.vertex_order[k], with the PRM's quantized position, and the triangles are the PRM's under that map.
void expect_exact_round_trip(const prm::remesh::PrmMesh& prm, const std::vector<uint8_t>& stream,
                              const prm::codec::EncodeReport& report) {
  const auto decoded = prm::codec::decode(stream.data(), stream.size());
  ASSERT_TRUE(decoded.ok()) << decoded.status.message;
  const auto& order = report.vertex_order;
  ASSERT_EQ(decoded.value.num_vertices(), prm.mesh.positions.size());
  ASSERT_EQ(order.size(), prm.mesh.positions.size());
  for (size_t k = 0; k < order.size(); ++k)
    for (int a = 0; a < 3; ++a)
      ASSERT_EQ(decoded.value.quantized[3 * k + static_cast<size_t>(a)],
                static_cast<uint32_t>(prm.frame.quantize(prm.mesh.positions[order[k]][a], a)))
          << "vertex " << k << " axis " << a;
  // Triangles as rotation-normalised triples of PRM vertex ids.
  auto canon = [](std::array<uint32_t, 3> t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
  };
  std::map<std::array<uint32_t, 3>, int> expected;
  for (const prm::Tri& t : prm.mesh.triangles) ++expected[canon({t[0], t[1], t[2]})];
  ASSERT_EQ(decoded.value.num_triangles(), prm.mesh.triangles.size());
  for (size_t t = 0; t < decoded.value.num_triangles(); ++t) {
    const auto key = canon({order[decoded.value.triangles[3 * t]], order[decoded.value.triangles[3 * t + 1]],
                            order[decoded.value.triangles[3 * t + 2]]});
    auto it = expected.find(key);
    ASSERT_TRUE(it != expected.end() && it->second > 0) << "decoded triangle " << t << " is not in the PRM";
    --it->second;
  }
}

void expect_exact_round_trip(const prm::pipeline::PackResult& r) {
  expect_exact_round_trip(r.remesh.prm, r.stream, r.report);
}

double largest_extent(const prm::Mesh& m) {
  double extent = 0;
  for (int a = 0; a < 3; ++a) {
    double lo = m.positions[0][a], hi = lo;
    for (const prm::Vec3& p : m.positions) lo = std::min(lo, p[a]), hi = std::max(hi, p[a]);
    extent = std::max(extent, hi - lo);
  }
  return extent;
}

struct Case {
  const char* file;
  double grid_fraction;
};

TEST(Pack, RealMeshesRoundTripExactly) {
  for (const Case& c : {Case{"spot.obj", 0.02}, Case{"feline_5k.obj", 0.01}, Case{"fandisk.obj", 0.01},
                        Case{"bunny_zipper.ply", 0.01}}) {
    SCOPED_TRACE(c.file);
    const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/" + c.file);
    PackOptions o;
    o.grid_fraction = c.grid_fraction;
    const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
    // bunny_zipper's 5 holes stay open (issue 22): nothing to repair, and the stream has the same 5 loops.
    EXPECT_FALSE(r.repaired);
    EXPECT_EQ(r.boundary_loops_in, std::string(c.file) == "bunny_zipper.ply" ? 5u : 0u);
    EXPECT_EQ(r.boundary_loops_out, r.boundary_loops_in);
    EXPECT_GT(r.remesh.prm.stats.regular_faces, r.remesh.prm.stats.faces / 2);
    EXPECT_EQ(r.stream.size(), r.report.total_bytes);
    expect_exact_round_trip(r);
    // The decoded mesh is as close to the input as the remeshed one: quantization adds almost nothing.
    const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
    const prm::Mesh out = prm::pipeline::to_mesh(decoded.value);
    const prm::DistanceReport d = prm::metro_distance(input, out);
    EXPECT_LT(d.rel(d.rms), 1.25 * r.remesh.error.rms + 2e-5) << "remeshed " << r.remesh.error.rms;
  }
}

TEST(Pack, SelfOverlappingPatchRoundTrips) {
  // The helical ramp's top overlaps itself along z: patches whose lattice points repeat (spec §8.3, §9.2 work on
  // the combinatorial patch, never on the projection).
  const prm::Mesh ramp = prm::test::helical_ramp();
  prm::remesh::ReliefOptions ro;
  ro.naive = true;
  const prm::remesh::ReliefLayout layout = prm::remesh::build_reliefs(ramp, ro);
  std::vector<int> axes;
  for (const prm::remesh::Relief& r : layout.reliefs) axes.push_back(r.axis);
  prm::remesh::LayoutInput in;
  in.refined = &layout.mesh;
  in.face_relief = &layout.face_relief;
  in.relief_axis = &axes;
  in.input = &ramp;
  prm::remesh::ResampleOptions o;
  o.frame = prm::remesh::frame_of_mesh(ramp, 12);
  o.grid = 40;
  const prm::remesh::PrmMesh prm = prm::remesh::resample_and_merge(in, o);
  prm::codec::EncodeReport rep;
  const auto enc = prm::pipeline::encode_prm_mesh(prm, &rep);
  ASSERT_TRUE(enc.ok()) << enc.status.message;
  EXPECT_GT(rep.regular_triangles, prm.mesh.triangles.size() / 2);
  // Some patch has two vertices on one lattice point.
  bool overlap = false;
  {
    std::map<std::tuple<int32_t, int32_t, int32_t>, int> seen;
    for (size_t v = 0; v < prm.mesh.positions.size(); ++v)
      if (prm.vertex_relief[v] >= 0 && ++seen[{prm.vertex_relief[v], prm.lattice_i[v], prm.lattice_j[v]}] == 2) overlap = true;
  }
  EXPECT_TRUE(overlap);
  expect_exact_round_trip(prm, enc.value, rep);
  // Linear prediction (§9.7): the overlapping patches by difference patches, or by prediction too (§9.7.3 defines
  // the raster of a patch whose lattice points repeat); both decode exactly.
  for (bool every : {false, true}) {
    prm::codec::PrmOptions po;
    po.height_depth = 7;
    po.predict_every_patch = every;
    prm::codec::EncodeReport r7;
    const auto e7 = prm::pipeline::encode_prm_mesh(prm, &r7, po);
    ASSERT_TRUE(e7.ok()) << e7.status.message;
    EXPECT_EQ(r7.height_depth, 7);
    if (every) EXPECT_EQ(r7.predicted_patches, r7.regular_patches);
    else EXPECT_LT(r7.predicted_patches, r7.regular_patches);
    expect_exact_round_trip(prm, e7.value, r7);
  }
}

// Format 1.4's patch contexts (spec §8.4.1 bases from their references, §9.7.4 sign contexts) on a real PRM: the
// stream with them is smaller than without, and both decode to the PRM exactly.
TEST(Pack, PatchContextsShrinkARealPrm) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  PackOptions o;
  o.grid_fraction = 0.008;
  o.bits = 11;
  o.optimize_heights = false;
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  size_t bytes[2] = {0, 0}, patches[2] = {0, 0};
  for (int with = 0; with < 2; ++with) {
    prm::codec::PrmOptions po;
    po.patch_contexts = with != 0;
    prm::codec::EncodeReport rep;
    const auto enc = prm::pipeline::encode_prm_mesh(r.remesh.prm, &rep, po);
    ASSERT_TRUE(enc.ok()) << enc.status.message;
    EXPECT_EQ(enc.value[5], with ? prm::codec::kFormatMinorPatchContexts : (enc.value[6] & 0x04 ? 3 : 2));
    EXPECT_EQ((enc.value[6] & 0x08) != 0, with != 0);
    expect_exact_round_trip(r.remesh.prm, enc.value, rep);
    bytes[with] = enc.value.size();
    patches[with] = rep.patch_bytes;
  }
  std::printf("spot, grid 0.008 of the diagonal, 11 bits: %zu bytes without the patch contexts (patches %zu), %zu with "
              "(patches %zu)\n", bytes[0], patches[0], bytes[1], patches[1]);
  EXPECT_LT(patches[1], patches[0]);
  EXPECT_LT(bytes[1], bytes[0]);
}

// With a target error and no bit depth, the exhaustive search (kMaxEffort) tries the bit depths and then the step
// scales of kStepScales at the best one, and keeps the smallest stream of all it tried, whose decoded mesh meets the
// target.
TEST(Pack, GridFromTargetError) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  PackOptions o;
  o.target_error = 5e-4;
  o.effort = prm::pipeline::kMaxEffort;
  o.mode = prm::pipeline::PackMode::prm;  // the remesher's path
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  EXPECT_LE(r.remesh.error.rms, prm::pipeline::kQuantizationMargin * 5e-4);
  expect_exact_round_trip(r);
  size_t smallest = SIZE_MAX, scaled = 0;
  for (const auto& t : r.tried) {
    smallest = std::min(smallest, t.bytes);
    scaled += t.step_scale != 1.0;
    std::printf("spot at 5e-4: %d bits, step x%.3f: %zu bytes\n", t.bits, t.step_scale, t.bytes);
  }
  EXPECT_EQ(scaled, std::size(prm::pipeline::kStepScales));
  EXPECT_EQ(r.stream.size(), smallest);
  const double extent = largest_extent(input);
  EXPECT_NEAR(r.remesh.prm.frame.step, r.step_scale * extent / static_cast<double>((1 << r.bits) - 1), 1e-12 * extent);
  // The decoded mesh itself meets the target.
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  ASSERT_TRUE(decoded.ok());
  EXPECT_DOUBLE_EQ(decoded.value.frame.step, r.remesh.prm.frame.step);
  const prm::DistanceReport d = prm::metro_distance(input, prm::pipeline::to_mesh(decoded.value));
  EXPECT_LE(d.rel(d.rms), 5e-4);
}

// PackOptions::optimize_heights (the default): the heights the encoder chooses still meet the target, the stream
// is smaller than with rounded heights, the result's PRM is what the stream holds, and it differs from the rounded
// PRM in heights only, each by at most kHeightTolerance steps.
TEST(Pack, ChosenHeightsMeetTheTargetInASmallerStream) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  PackOptions o;
  o.target_error = 5e-4;
  o.bits = 11;
  o.optimize_heights = false;
  o.mode = prm::pipeline::PackMode::prm;  // the remesher's path
  const prm::pipeline::PackResult rounded = prm::pipeline::pack(input, o);
  EXPECT_EQ(rounded.codec_options.height_lambda, 0.0);
  o.optimize_heights = true;
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  EXPECT_GT(r.codec_options.height_lambda, 0.0);
  EXPECT_LT(r.stream.size(), rounded.stream.size());
  std::printf("spot at 5e-4, 11 bits: rounded heights %zu bytes (RMS %.4e), lambda %.2f: %zu bytes (RMS %.4e)\n",
              rounded.stream.size(), rounded.remesh.error.rms, r.codec_options.height_lambda, r.stream.size(),
              r.remesh.error.rms);
  expect_exact_round_trip(r);
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  ASSERT_TRUE(decoded.ok());
  const prm::DistanceReport d = prm::metro_distance(input, prm::pipeline::to_mesh(decoded.value));
  EXPECT_LE(d.rel(d.rms), 5e-4);
  // Same remesh, same lattice; only heights moved.
  const prm::remesh::PrmMesh &a = rounded.remesh.prm, &b = r.remesh.prm;
  ASSERT_EQ(a.lattice.A, b.lattice.A);
  ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
  size_t moved = 0;
  for (size_t v = 0; v < a.mesh.positions.size(); ++v) {
    int differing = 0;
    for (int k = 0; k < 3; ++k) {
      const int32_t qa = a.frame.quantize(a.mesh.positions[v][k], k), qb = b.frame.quantize(b.mesh.positions[v][k], k);
      EXPECT_LE(std::abs(qa - qb), 2) << v;  // |chosen - unrounded| <= 1.5 and |rounded - unrounded| <= 0.5
      // The unrounded value (a vertex outside the frame is clamped to its face and counts as on it).
      const double x = std::clamp(a.frame.to_quant(a.mesh.positions[v][k], k), qa - 0.5, qa + 0.5);
      EXPECT_LE(std::fabs(qb - x), prm::pipeline::kHeightTolerance + 1e-9) << v;
      differing += qa != qb;
    }
    EXPECT_LE(differing, 1) << v;
    moved += differing;
  }
  EXPECT_GT(moved, 0u);
}

// A given step scale (PackOptions::step_scale) sets the stream's step.
TEST(Pack, StepScaleSetsTheStep) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  const double extent = largest_extent(input);
  PackOptions o;
  o.target_error = 5e-4;
  o.bits = 10;
  o.step_scale = 1.3;
  o.mode = prm::pipeline::PackMode::prm;  // the remesher's path
  const prm::pipeline::PackResult fixed = prm::pipeline::pack(input, o);
  EXPECT_EQ(fixed.step_scale, 1.3);
  ASSERT_EQ(fixed.tried.size(), 1u);
  EXPECT_NEAR(fixed.remesh.prm.frame.step, 1.3 * extent / 1023.0, 1e-12 * extent);
  expect_exact_round_trip(fixed);
  const auto fixed_decoded = prm::codec::decode(fixed.stream.data(), fixed.stream.size());
  ASSERT_TRUE(fixed_decoded.ok());
  EXPECT_EQ(fixed_decoded.value.frame.bits, 10);
  EXPECT_DOUBLE_EQ(fixed_decoded.value.frame.step, fixed.remesh.prm.frame.step);
  const prm::DistanceReport fd = prm::metro_distance(input, prm::pipeline::to_mesh(fixed_decoded.value));
  EXPECT_LE(fd.rel(fd.rms), 5e-4);

  EXPECT_THROW(prm::remesh::frame_of_mesh(input, 10, 2.0), std::invalid_argument);
  EXPECT_THROW(prm::remesh::frame_of_mesh(input, 10, 0.99), std::invalid_argument);
}

TEST(Pack, PrmFileIsRecognisedByEncodeAnyMesh) {
  const prm::Mesh input = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  PackOptions o;
  o.grid_fraction = 0.02;
  prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  prm::remesh::store_prm_labels(r.remesh.prm);
  const std::string path = std::string(PRM_BINARY_DIR) + "/pack_test_spot.prm.ply";
  prm::write_mesh(r.remesh.prm.mesh, path, prm::WriteOptions{prm::MeshFormat::Ply, true, true, true});
  bool was_prm = false;
  prm::codec::EncodeReport rep;
  const auto enc = prm::pipeline::encode_any_mesh(prm::read_mesh(path), 12, &rep, &was_prm);
  ASSERT_TRUE(enc.ok()) << enc.status.message;
  EXPECT_TRUE(was_prm);
  EXPECT_EQ(enc.value, r.stream);  // the file round trip keeps every label and position the encoder reads
}

}  // namespace
