// A grid size per relief (issue 23, spec §8.4.2): real meshes remeshed with reliefs on two or three different grid
// sizes stay closed manifolds of the input's topology, with every lattice vertex on its own relief's lattice, and
// the format 1.5 stream decodes to exactly the quantized PRM; the PLY labels keep each relief's grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "prm/aabb_tree.h"
#include "prm/mesh_io.h"
#include "prm/mesh_repair.h"
#include "prm/mesh_validate.h"
#include "prm/vec3.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack.h"
#include "prm/pipeline/relief_costs.h"
#include "prm/remesh/relief_grids.h"
#include "prm/remesh/remesh.h"

namespace prm {
namespace {

Mesh load_closed(const std::string& path) {
  Mesh m = read_mesh(path);
  if (!validate_mesh(m).closed()) m = repair_mesh(m);
  return m;
}

// Decoded stream == the quantized PRM under the report's vertex order.
void expect_exact(const remesh::PrmMesh& prm, const std::vector<uint8_t>& stream, const codec::EncodeReport& rep,
                  const std::string& name) {
  const auto dec = codec::decode(stream.data(), stream.size());
  ASSERT_TRUE(dec.ok()) << name << ": " << dec.status.message;
  ASSERT_EQ(dec.value.num_vertices(), prm.mesh.positions.size()) << name;
  ASSERT_EQ(dec.value.num_triangles(), prm.mesh.triangles.size()) << name;
  for (size_t k = 0; k < rep.vertex_order.size(); ++k)
    for (int a = 0; a < 3; ++a)
      ASSERT_EQ(dec.value.quantized[3 * k + static_cast<size_t>(a)],
                prm.frame.quantize(prm.mesh.positions[rep.vertex_order[k]][a], a)) << name << " vertex " << k;
  auto canon = [](std::array<uint32_t, 3> t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
  };
  std::map<std::array<uint32_t, 3>, int> expected;
  for (const Tri& t : prm.mesh.triangles) ++expected[canon({t[0], t[1], t[2]})];
  for (size_t t = 0; t < dec.value.num_triangles(); ++t) {
    const auto key = canon({rep.vertex_order[dec.value.triangles[3 * t]], rep.vertex_order[dec.value.triangles[3 * t + 1]],
                            rep.vertex_order[dec.value.triangles[3 * t + 2]]});
    auto it = expected.find(key);
    ASSERT_TRUE(it != expected.end() && it->second > 0) << name << ": decoded triangle " << t << " is not in the PRM";
    --it->second;
  }
}

void check(const std::string& path, const std::string& name) {
  const Mesh input = load_closed(path);
  const remesh::ReliefLayout layout = remesh::build_reliefs(input, {});
  remesh::RemeshOptions o;
  o.grid_fraction = 0.01;
  o.layout = &layout;
  // Three grid sizes, relief by relief: 1, 1.5 and 0.75 times the grid.
  const double scales[3] = {1.0, 1.5, 0.75};
  for (size_t r = 0; r < layout.reliefs.size(); ++r) o.relief_grid_scale.push_back(scales[r % 3]);
  const remesh::RemeshResult res = remesh::remesh(input, o);
  const remesh::PrmMesh& prm = res.prm;
  const std::set<int64_t> grids(prm.relief_grid.begin(), prm.relief_grid.end());
  EXPECT_GE(grids.size(), 2u) << name;
  // Topology and manifoldness as the input's.
  const MeshReport in = validate_mesh(input), out = validate_mesh(prm.mesh);
  EXPECT_TRUE(out.closed() && out.manifold() && out.oriented()) << name;
  EXPECT_EQ(out.components, in.components) << name;
  EXPECT_EQ(out.genus_sum(), in.genus_sum()) << name;
  EXPECT_EQ(out.zero_area_faces, 0u) << name;
  EXPECT_EQ(prm.stats.unrepaired, 0u) << name;
  // Every lattice vertex on its relief's own lattice; regular faces counted per grid size.
  std::map<int64_t, size_t> regular_per_grid;
  for (size_t v = 0; v < prm.mesh.positions.size(); ++v) {
    const int32_t r = prm.vertex_relief[v];
    if (r < 0) continue;
    const int pair = remesh::axis_pair(prm.relief_axis[static_cast<size_t>(r)]);
    const auto base = codec::HexLattice::with_grid(prm.grid_of(static_cast<size_t>(r))).to_base(prm.lattice_i[v], prm.lattice_j[v]);
    ASSERT_EQ(prm.frame.quantize(prm.mesh.positions[v][static_cast<size_t>(remesh::pair_u(pair))], remesh::pair_u(pair)), base[0]) << name;
    ASSERT_EQ(prm.frame.quantize(prm.mesh.positions[v][static_cast<size_t>(remesh::pair_w(pair))], remesh::pair_w(pair)), base[1]) << name;
  }
  for (size_t f = 0; f < prm.mesh.triangles.size(); ++f)
    if (prm.face_regular[f]) ++regular_per_grid[prm.grid_of(static_cast<size_t>(prm.face_relief[f]))];
  EXPECT_GE(regular_per_grid.size(), 2u) << name;
  // The stream: format 1.5 with the grid table, decoded exactly.
  codec::EncodeReport rep;
  const auto enc = pipeline::encode_prm_mesh(prm, &rep);
  ASSERT_TRUE(enc.ok()) << name << ": " << enc.status.message;
  EXPECT_EQ(enc.value[5], codec::kFormatMinorPatchGrids) << name;
  EXPECT_EQ(rep.grid_sizes, grids.size()) << name;
  expect_exact(prm, enc.value, rep, name);
  size_t labelled = 0;
  for (const auto& g : regular_per_grid) labelled += g.second;
  std::printf("%s: grids", name.c_str());
  for (const auto& g : regular_per_grid) std::printf(" %lld (%zu regular faces)", static_cast<long long>(g.first), g.second);
  std::printf("; %zu vertices, codec regular %u of %zu labelled, %zu bytes\n", prm.mesh.positions.size(),
              rep.regular_triangles, labelled, enc.value.size());
  // The codec finds the regular triangles on every lattice (its §7.1 check demotes a few at seams of one axis).
  EXPECT_GE(rep.regular_triangles, labelled * 9 / 10) << name;
  // With --max-version 1.4 the same PRM is one grid: the others' triangles irregular, still exact.
  codec::PrmOptions old;
  old.patch_grids = false;
  codec::EncodeReport rep14;
  const auto enc14 = pipeline::encode_prm_mesh(prm, &rep14, old);
  ASSERT_TRUE(enc14.ok());
  EXPECT_EQ(enc14.value[5], codec::kFormatMinorPatchContexts) << name;
  EXPECT_LT(rep14.regular_triangles, rep.regular_triangles) << name;
  expect_exact(prm, enc14.value, rep14, name);
  // The PLY labels keep each relief's grid.
  const std::string ply = std::string(PRM_BINARY_DIR) + "/relief_grids_test_" + name + ".ply";
  write_mesh(prm.mesh, ply, WriteOptions{MeshFormat::Ply, true, true, true});
  const remesh::PrmMesh back = remesh::load_prm_labels(read_mesh(ply));
  std::remove(ply.c_str());
  EXPECT_EQ(back.relief_grid, prm.relief_grid) << name;
  EXPECT_EQ(back.lattice.A, prm.lattice.A) << name;
}

TEST(ReliefGrids, RealMeshesOnSeveralGrids) {
  for (const char* name : {"feline_5k.obj", "horse.ply"}) check(std::string(PRM_SHARED_MESHES) + "/" + name, name);
}

// The allocation's model (remesh/relief_grids.h) on a real mesh: the reliefs' areas add up to the surface's, the
// more detailed relief never gets the coarser grid, and the scales are at most kMaxReliefGrids levels of 2^(k/4).
TEST(ReliefGrids, AllocationFollowsTheDetail) {
  const Mesh input = load_closed(std::string(PRM_SHARED_MESHES) + "/feline_5k.obj");
  const remesh::ReliefLayout layout = remesh::build_reliefs(input, {});
  const remesh::ReliefDetail detail = remesh::measure_relief_detail(input, layout);
  ASSERT_EQ(detail.area.size(), layout.reliefs.size());
  double total = 0, surface = 0;
  for (double a : detail.area) total += a;
  for (const Tri& t : input.triangles) surface += triangle_area(input.positions[t[0]], input.positions[t[1]], input.positions[t[2]]);
  EXPECT_NEAR(total, surface, 1e-9 * surface);
  const std::vector<double> scale = remesh::allocate_relief_grid_scales(detail);
  ASSERT_EQ(scale.size(), detail.area.size());
  std::set<double> levels(scale.begin(), scale.end());
  EXPECT_LE(levels.size(), remesh::kMaxReliefGrids);
  EXPECT_GE(levels.size(), 2u);  // feline_5k's reliefs differ in detail
  for (size_t r = 0; r < scale.size(); ++r) {
    const double k = std::log2(scale[r]) * 4;
    EXPECT_NEAR(k, std::round(k), 1e-9);
    EXPECT_GE(k, -3 - 1e-9);
    EXPECT_LE(k, 4 + 1e-9);
    for (size_t q = 0; q < scale.size(); ++q)
      if (detail.curvature2[r] > detail.curvature2[q]) {
        EXPECT_LE(scale[r], scale[q]) << r << " " << q;
      }
  }
}

// The measured model's equal slope on known samples: two reliefs of equal area and exponent 2 (the squared error
// doubles when the grid grows by sqrt 2), the second with 2^8 times the squared error: g^(p+2) ~ 1 / msq gives the
// second a grid 2^(8/4) = 4 times finer, that is scales 2 and 1/2 around their geometric mean (levels +4 and -4,
// clamped to -3: 2^(-3/4)). A third relief with no samples keeps 1; a relief whose error falls with the grid gets
// the smallest exponent (kMinErrorExponent) rather than a negative one.
TEST(ReliefGrids, MeasuredAllocationIsEqualSlope) {
  remesh::ReliefErrorSample a, b;
  a.grid = 1;
  b.grid = std::sqrt(2.0);
  a.area = b.area = {1, 1, 0};
  a.msq = {1e-6, 256e-6, 0};
  b.msq = {2e-6, 512e-6, 0};
  std::vector<double> scale = remesh::allocate_relief_grid_scales_measured(a, b);
  ASSERT_EQ(scale.size(), 3u);
  EXPECT_DOUBLE_EQ(scale[0], 2.0);
  EXPECT_DOUBLE_EQ(scale[1], std::exp2(-0.75));
  EXPECT_DOUBLE_EQ(scale[2], 1.0);
  // A coarser grid of lower error: p clamped to 1, so g^3 ~ 1 / msq.
  b.msq = {0.5e-6, 512e-6, 0};
  scale = remesh::allocate_relief_grid_scales_measured(a, b);
  EXPECT_GT(scale[0], scale[1]);
  EXPECT_THROW(remesh::allocate_relief_grid_scales_measured(b, a), std::invalid_argument);
}

// The measured model on a real mesh: one uniform remesh of feline_5k at two grid sizes; the reliefs' sampled areas
// cover most of the remeshed surface, the squared error grows with the grid on most reliefs, and the scales are
// levels of 2^(k/4) with the finer grid for the relief of the larger error where the exponents agree.
TEST(ReliefGrids, MeasuredModelOnARealMesh) {
  const Mesh input = load_closed(std::string(PRM_SHARED_MESHES) + "/feline_5k.obj");
  const remesh::ReliefLayout layout = remesh::build_reliefs(input, {});
  const AabbTree tree(input);
  auto sample = [&](double fraction) {
    remesh::RemeshOptions ro;
    ro.layout = &layout;
    ro.input_tree = &tree;
    ro.grid_fraction = fraction;
    const remesh::RemeshResult r = remesh::remesh(input, ro);
    double surface = 0;
    for (const Tri& t : r.prm.mesh.triangles)
      surface += triangle_area(r.prm.mesh.positions[t[0]], r.prm.mesh.positions[t[1]], r.prm.mesh.positions[t[2]]);
    remesh::ReliefErrorSample s = remesh::measure_relief_error(r.prm, tree, layout.reliefs.size(),
                                                               fraction * validate_mesh(input).diagonal);
    double sampled = 0;
    for (double a : s.area) sampled += a;
    EXPECT_GT(sampled, 0.8 * surface) << fraction;
    EXPECT_LE(sampled, surface * (1 + 1e-9)) << fraction;
    return s;
  };
  const remesh::ReliefErrorSample a = sample(0.01), b = sample(0.02);
  size_t grows = 0, measured = 0;
  for (size_t r = 0; r < a.msq.size(); ++r) {
    if (!(a.msq[r] > 0) || !(b.msq[r] > 0)) continue;
    ++measured;
    grows += b.msq[r] > a.msq[r];
  }
  EXPECT_GE(measured, a.msq.size() / 2);
  EXPECT_GE(grows, measured * 3 / 4) << "of " << measured;
  const std::vector<double> scale = remesh::allocate_relief_grid_scales_measured(a, b);
  std::set<double> levels(scale.begin(), scale.end());
  EXPECT_GE(levels.size(), 2u);
  EXPECT_LE(levels.size(), remesh::kMaxReliefGrids);
  for (double s : scale) {
    const double k = std::log2(s) * 4;
    EXPECT_NEAR(k, std::round(k), 1e-9);
  }
}

// pack --adaptive: a format 1.5 stream of several grid sizes meeting the target and decoding exactly; with
// --max-version 1.4 the option is ignored and the stream is the uniform one, byte for byte.
TEST(ReliefGrids, PackAdaptive) {
  const Mesh input = read_mesh(std::string(PRM_SHARED_MESHES) + "/feline_5k.obj");
  pipeline::PackOptions o;
  o.target_error = 1e-3;
  o.adaptive = true;
  const pipeline::PackResult r = pipeline::pack(input, o);
  EXPECT_GE(r.report.grid_sizes, 2u);
  EXPECT_EQ(r.stream[5], codec::kFormatMinorPatchGrids);
  EXPECT_LE(r.remesh.error.rms, 1e-3);
  expect_exact(r.remesh.prm, r.stream, r.report, "feline_5k adaptive");
  pipeline::PackOptions u = o;
  u.adaptive = false;
  u.max_minor = codec::kFormatMinorPatchContexts;
  pipeline::PackOptions old = o;
  old.max_minor = codec::kFormatMinorPatchContexts;
  const pipeline::PackResult a14 = pipeline::pack(input, old), u14 = pipeline::pack(input, u);
  EXPECT_EQ(a14.report.grid_sizes, 1u);
  EXPECT_EQ(a14.stream, u14.stream);
}

// pack --relief-costs (pipeline::relief_costs): on a real stream with several grids, the reliefs' bits with the
// prologue and the unattributed bits make the patches section less its termination (24 to 32 bits); every carried
// vertex is one of its relief's lattice vertices; reliefs with lattice vertices have area and a squared error.
TEST(ReliefGrids, ReliefCostsAddUpToThePatchesSection) {
  const Mesh input = load_closed(std::string(PRM_SHARED_MESHES) + "/feline_5k.obj");
  pipeline::PackOptions o;
  o.grid_fraction = 0.01;
  o.adaptive = true;
  o.adaptive_model = pipeline::PackOptions::AdaptiveModel::curvature;
  const pipeline::PackResult r = pipeline::pack(input, o);
  ASSERT_GE(r.report.grid_sizes, 2u);
  const AabbTree tree(r.repaired ? r.repaired_input : input);
  const pipeline::ReliefCosts c = pipeline::relief_costs(r.remesh.prm, r.report, tree);
  ASSERT_EQ(c.reliefs.size(), r.remesh.prm.relief_axis.size());
  double bits = c.prologue_bits + c.unattributed_bits;
  uint32_t carried = 0, lattice = 0;
  std::set<int64_t> grids;
  for (const pipeline::ReliefCost& rc : c.reliefs) {
    bits += rc.bits;
    carried += rc.carried_vertices;
    lattice += rc.lattice_vertices;
    EXPECT_LE(rc.carried_vertices, rc.lattice_vertices);
    if (rc.carried_vertices > 0) {
      EXPECT_GT(rc.bits, 0.0);
    }
    if (rc.lattice_vertices > 0) grids.insert(rc.grid);
    if (rc.lattice_vertices > 16) {
      EXPECT_GT(rc.area, 0.0);
      EXPECT_GT(rc.msq, 0.0);
      // The quarters by the faces' own error: increasing, and about averaging to the relief's msq.
      double mean = 0;
      for (size_t k = 0; k < rc.msq_quarters.size(); ++k) {
        if (k > 0) {
          EXPECT_LE(rc.msq_quarters[k - 1], rc.msq_quarters[k]);
        }
        mean += rc.msq_quarters[k] / rc.msq_quarters.size();
      }
      EXPECT_GE(rc.msq_quarters.back(), rc.msq);
      EXPECT_LE(rc.msq_quarters.front(), rc.msq);
      EXPECT_NEAR(mean, rc.msq, 0.5 * rc.msq);  // quarters of about equal area (faces are not split)
    }
  }
  EXPECT_GE(grids.size(), 2u);
  EXPECT_EQ(carried, r.report.patch_vertices);  // every vertex a patch carries is a lattice vertex of a relief
  EXPECT_LE(lattice, r.report.vertices);
  const double slack = 8.0 * static_cast<double>(r.report.patch_bytes) - bits;
  EXPECT_GE(slack, 24.0 - 1e-6);
  EXPECT_LE(slack, 32.0 + 1e-6);
  // A report of another stream is refused.
  codec::EncodeReport other = r.report;
  other.vertex_patch.pop_back();
  EXPECT_THROW(pipeline::relief_costs(r.remesh.prm, other, tree), std::invalid_argument);
}

}  // namespace
}  // namespace prm
