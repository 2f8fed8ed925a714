// §8.4.2 Format 1.5's grid table: patches on lattices of different grid sizes in one stream, the encoder's choice
// of the table, and the decoder on damaged two-grid streams.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "crc32.h"
#include "prm/codec.h"
#include "test_meshes.h"

namespace prm::codec::test {
namespace {

int64_t top(int i, int j, const void*) { return 2000 + std::lround(90 * std::sin(0.3 * i) * std::cos(0.2 * j) + 3 * i); }
int64_t bottom(int i, int j, const void*) { return 1000 - std::lround(40 * std::cos(0.25 * i + 0.1 * j)); }

// Two pillows in one mesh: one on grid size 8, one on grid size 6 moved 30 of its lattice steps along x.
QuantizedMesh two_pillows() {
  const QuantizedMesh a = lattice_pillow(6, 8, top, bottom, nullptr, {{1, -2}});
  const QuantizedMesh b = lattice_pillow(5, 6, top, bottom, nullptr, {{-3, 2}});
  QuantizedMesh m = a;
  for (size_t v = 0; v < b.nv(); ++v) m.q.insert(m.q.end(), {b.q[3 * v] + 6 * 30, b.q[3 * v + 1], b.q[3 * v + 2]});
  for (uint32_t t : b.tris) m.tris.push_back(t + static_cast<uint32_t>(a.nv()));
  return m;
}

Result<std::vector<uint8_t>> encode(const QuantizedMesh& m, int64_t grid, std::vector<int64_t> extra,
                                    EncodeReport* rep = nullptr, int depth = -1) {
  PrmOptions o;
  o.grid = grid;
  o.extra_grids = std::move(extra);
  o.height_depth = depth;
  return encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, rep);
}

void expect_round_trip(const QuantizedMesh& m, const std::vector<uint8_t>& stream, const EncodeReport& rep) {
  const auto dec = decode(stream.data(), stream.size());
  ASSERT_TRUE(dec.ok()) << dec.status.message << " (§" << dec.status.spec_section << ")";
  ASSERT_EQ(dec.value.num_vertices(), m.nv());
  ASSERT_EQ(dec.value.num_triangles(), m.nt());
  for (size_t k = 0; k < m.nv(); ++k)
    for (int a = 0; a < 3; ++a) ASSERT_EQ(dec.value.quantized[3 * k + a], m.q[3 * size_t{rep.vertex_order[k]} + a]);
  for (size_t t = 0; t < m.nt(); ++t)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(rep.vertex_order[dec.value.triangles[3 * t + c]],
                m.tris[3 * size_t{rep.triangle_order[t]} + (rep.triangle_rotation[t] + c) % 3]);
}

void fix_crc(std::vector<uint8_t>& s) {
  const uint32_t c = crc32(s.data(), s.size() - 4);
  for (int i = 0; i < 4; ++i) s[s.size() - 4 + i] = static_cast<uint8_t>(c >> (8 * i));
}

TEST(PatchGrids, TwoGridsRoundTripAtEveryHeightCoding) {
  const QuantizedMesh m = two_pillows();
  EncodeReport one;
  const auto single = encode(m, 8, {}, &one);
  ASSERT_TRUE(single.ok());
  for (int depth : {-1, 0, 3, 7}) {
    EncodeReport rep;
    const auto enc = encode(m, 8, {6}, &rep, depth);
    ASSERT_TRUE(enc.ok()) << enc.status.message;
    EXPECT_EQ(enc.value[5], kFormatMinorPatchGrids);
    EXPECT_EQ(enc.value[6] & 0x10, 0x10);
    EXPECT_EQ(rep.grid_sizes, 2u);
    // Both pillows' tops and bottoms are regular, 2 x 6 x 6^2 and 2 x 6 x 5^2 triangles, but the 6 around each of
    // the two vertices moved off the lattice.
    EXPECT_EQ(rep.regular_triangles, 2u * 6 * 36 + 2u * 6 * 25 - 2 * 6) << depth;
    EXPECT_GT(rep.regular_triangles, one.regular_triangles);
    expect_round_trip(m, enc.value, rep);
  }
  // The second pillow's lattice in the table makes the stream smaller than the general path's for it.
  EncodeReport rep;
  const auto two = encode(m, 8, {6}, &rep);
  EXPECT_LT(two.value.size(), single.value.size());
  // The grid sizes' order in the table is the encoder's: either way the same mesh.
  EncodeReport swapped_rep;
  const auto swapped = encode(m, 6, {8}, &swapped_rep);
  ASSERT_TRUE(swapped.ok());
  expect_round_trip(m, swapped.value, swapped_rep);
}

TEST(PatchGrids, AnUnusedGridChangesNothing) {
  // Only the first pillow: the extra grid 6 holds no regular triangle, so the stream is the single grid's (1.4).
  const QuantizedMesh m = lattice_pillow(6, 8, top, bottom, nullptr, {{1, -2}});
  EncodeReport rep;
  const auto with = encode(m, 8, {6, 10}, &rep);
  const auto without = encode(m, 8, {});
  ASSERT_TRUE(with.ok());
  ASSERT_TRUE(without.ok());
  EXPECT_EQ(with.value, without.value);
  EXPECT_EQ(with.value[5], kFormatMinorPatchContexts);
  EXPECT_EQ(rep.grid_sizes, 1u);
}

TEST(PatchGrids, BadGridTablesAreRefused) {
  const QuantizedMesh m = two_pillows();
  for (const std::vector<int64_t>& extra :
       {std::vector<int64_t>{8}, {6, 6}, {1}, {int64_t{1} << 13}, {3, 4, 5, 6, 7, 9, 10, 11}}) {
    const auto enc = encode(m, 8, extra);
    EXPECT_EQ(enc.status.error, Error::invalid_argument) << extra.size();
  }
}

TEST(PatchGrids, ClearingTheFlagLosesTheSecondLattice) {
  const QuantizedMesh m = two_pillows();
  const auto enc = encode(m, 8, {6});
  ASSERT_TRUE(enc.ok());
  const auto good = decode(enc.value.data(), enc.value.size());
  ASSERT_TRUE(good.ok());
  std::vector<uint8_t> s = enc.value;
  s[6] = static_cast<uint8_t>(s[6] & ~0x10);
  fix_crc(s);
  const auto bad = decode(s.data(), s.size());
  EXPECT_TRUE(!bad.ok() || bad.value.quantized != good.value.quantized);
}

TEST(PatchGrids, EveryByteFlippedIsAMeshOrANamedError) {
  const QuantizedMesh m = two_pillows();
  const auto enc = encode(m, 8, {6}, nullptr, 7);
  ASSERT_TRUE(enc.ok());
  size_t rejected = 0;
  for (size_t i = 6; i + 4 < enc.value.size(); ++i)
    for (uint8_t x : {0x01, 0x10, 0x80, 0xFF}) {
      std::vector<uint8_t> t = enc.value;
      t[i] ^= x;
      fix_crc(t);
      std::unique_ptr<uint8_t[]> buf(new uint8_t[t.size()]);
      std::memcpy(buf.get(), t.data(), t.size());
      const auto res = decode(buf.get(), t.size());
      if (res.ok()) {
        for (uint32_t v : res.value.triangles) ASSERT_LT(v, res.value.num_vertices());
      } else {
        ++rejected;
        EXPECT_NE(res.status.error, Error::internal) << res.status.message;
      }
    }
  EXPECT_GT(rejected, 0u);
}

// The encoder's per-patch costs (EncodeReport::patch_costs): the prologue and every patch's header and height bits
// add up to the patches section less the range coder's termination (24 to 32 bits, §5.6); every patch vertex is
// charged to exactly one patch, the one counting it. At every height coding, on one grid and on two.
TEST(PatchGrids, PatchCostsAddUpToTheSection) {
  const QuantizedMesh m = two_pillows();
  for (const std::vector<int64_t>& extra : {std::vector<int64_t>{}, std::vector<int64_t>{6}})
    for (int depth : {-1, 0, 3, 7}) {
      EncodeReport rep;
      const auto enc = encode(m, 8, extra, &rep, depth);
      ASSERT_TRUE(enc.ok()) << enc.status.message;
      ASSERT_EQ(rep.patch_costs.size(), rep.regular_patches) << depth;
      ASSERT_GT(rep.patch_costs.size(), 0u);
      double total = rep.patch_prologue_bits;
      uint32_t vertices = 0;
      for (const EncodeReport::PatchCost& c : rep.patch_costs) {
        EXPECT_GT(c.header_bits, 0.0);  // at least its axis and alignment
        EXPECT_GE(c.height_bits, 0.0);
        total += c.header_bits + c.height_bits;
        vertices += c.vertices;
      }
      EXPECT_EQ(vertices, rep.patch_vertices);
      const double slack = 8.0 * static_cast<double>(rep.patch_bytes) - total;
      EXPECT_GE(slack, 24.0 - 1e-6) << "depth " << depth << " grids " << extra.size() + 1;
      EXPECT_LE(slack, 32.0 + 1e-6) << "depth " << depth << " grids " << extra.size() + 1;
      ASSERT_EQ(rep.vertex_patch.size(), m.nv());
      std::vector<uint32_t> counted(rep.patch_costs.size(), 0);
      for (uint32_t p : rep.vertex_patch)
        if (p != UINT32_MAX) {
          ASSERT_LT(p, counted.size());
          ++counted[p];
        }
      for (size_t p = 0; p < counted.size(); ++p) EXPECT_EQ(counted[p], rep.patch_costs[p].vertices) << p;
    }
  // A general stream has no patches section and no costs.
  EncodeReport rep;
  const std::vector<float> xyz(m.q.begin(), m.q.end());
  ASSERT_TRUE(codec::encode(xyz.data(), m.nv(), m.tris.data(), m.nt(), {}, &rep).ok());
  EXPECT_TRUE(rep.patch_costs.empty());
  EXPECT_TRUE(rep.vertex_patch.empty());
}

}  // namespace
}  // namespace prm::codec::test
