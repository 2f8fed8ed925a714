// The PRM sections (§7 irregular triangles, §8 patches, §9 heights, §10.2 seeded positions) on synthetic piecewise
// regular meshes whose every position is known exactly: round trips at every height depth, the encoder's own
// regularity check, the general-path fallback, and hostile variants of a PRM stream.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <random>

#include "crc32.h"
#include "prm/codec.h"
#include "test_meshes.h"

namespace prm::codec::test {
namespace {

using QMesh = QuantizedMesh;

int64_t bumpy_top(int i, int j, const void*) {
  return 2000 + std::lround(90 * std::sin(0.3 * i) * std::cos(0.2 * j) + 3 * i);
}
int64_t bumpy_bottom(int i, int j, const void*) { return 1000 - std::lround(40 * std::cos(0.25 * i + 0.1 * j)); }

// The pillow of test_meshes.h with grid A = 8 and `perturb` random top vertices moved off the lattice.
QMesh pillow(int r, int perturb, uint32_t seed = 1) {
  std::mt19937 rng(seed);
  std::vector<std::array<int, 2>> moved;
  for (int k = 0; k < perturb; ++k)
    moved.push_back({static_cast<int>(rng() % static_cast<uint32_t>(r)) - r / 2,
                     static_cast<int>(rng() % static_cast<uint32_t>(r)) - r / 2});
  return lattice_pillow(r, 8, bumpy_top, bumpy_bottom, nullptr, moved);
}

// decode(encode(m)) is m: the same quantized positions under the reported vertex order, the same triangles.
void expect_round_trip(const QMesh& m, const std::vector<uint8_t>& stream, const EncodeReport& rep) {
  const auto dec = decode(stream.data(), stream.size());
  ASSERT_TRUE(dec.ok()) << dec.status.message << " (§" << dec.status.spec_section << ")";
  const DecodedMesh& d = dec.value;
  ASSERT_EQ(d.num_vertices(), m.nv());
  ASSERT_EQ(d.num_triangles(), m.nt());
  for (size_t k = 0; k < d.num_vertices(); ++k)
    for (int a = 0; a < 3; ++a) ASSERT_EQ(d.quantized[3 * k + a], m.q[3 * size_t{rep.vertex_order[k]} + a]) << k;
  for (size_t t = 0; t < d.num_triangles(); ++t) {
    const uint32_t in = rep.triangle_order[t], rot = rep.triangle_rotation[t];
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(rep.vertex_order[d.triangles[3 * t + c]], m.tris[3 * size_t{in} + (rot + c) % 3]) << t;
  }
}

TEST(PrmStream, PillowRoundTripsAtEveryHeightDepth) {
  const QMesh m = pillow(12, 0);
  size_t best = SIZE_MAX;
  for (int depth = 0; depth <= 7; ++depth) {  // 7: linear prediction (§9.7)
    PrmOptions o;
    o.grid = 8;
    o.height_depth = depth;
    EncodeReport rep;
    const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, &rep);
    ASSERT_TRUE(enc.ok()) << enc.status.message;
    EXPECT_EQ(rep.height_depth, depth);
    EXPECT_EQ(rep.regular_patches, 2u);  // top and bottom
    EXPECT_EQ(rep.regular_triangles, m.nt() - 2 * 6 * 12);  // all but the band
    EXPECT_EQ(rep.patch_vertices, m.nv());  // every vertex is on a patch
    EXPECT_GT(rep.irregular_bytes, 0u);
    EXPECT_EQ(rep.predicted_patches, depth == 7 ? 2u : 0u);
    // §3.2: the valence context makes every PRM stream 1.2, the seam context (the encoder's choice) 1.3, the patch
    // contexts (the default) 1.4.
    EXPECT_EQ(enc.value[6] & 0x08, 0x08);
    EXPECT_EQ(enc.value[5], kFormatMinorPatchContexts);
    expect_round_trip(m, enc.value, rep);
    best = std::min(best, enc.value.size());
  }
  // The default tries every depth and keeps the smallest.
  PrmOptions o;
  o.grid = 8;
  EncodeReport rep;
  const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, &rep);
  ASSERT_TRUE(enc.ok());
  EXPECT_EQ(enc.value.size(), best);
  // A PRM stream is far smaller than the general path on the same mesh.
  const auto general = encode_quantized(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame());
  ASSERT_TRUE(general.ok());
  EXPECT_LT(enc.value.size(), general.value.size());
}

TEST(PrmStream, OffLatticeVerticesArePredicted) {
  const QMesh m = pillow(12, 25, 3);
  PrmOptions o;
  o.grid = 8;
  EncodeReport rep;
  const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, &rep);
  ASSERT_TRUE(enc.ok()) << enc.status.message;
  EXPECT_LT(rep.patch_vertices, m.nv());        // the moved vertices are coded by prediction (§10)
  EXPECT_LT(rep.regular_triangles, m.nt() - 2 * 6 * 12);
  EXPECT_GT(rep.position_bytes, 0u);
  expect_round_trip(m, enc.value, rep);
}

TEST(PrmStream, WrongGridMeansGeneralPath) {
  // Grid 7 puts no triangle on the lattice: the stream is the general path's, byte for byte.
  const QMesh m = pillow(6, 0);
  PrmOptions o;
  o.grid = 7;
  EncodeReport rep;
  const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, &rep);
  ASSERT_TRUE(enc.ok());
  EXPECT_EQ(rep.regular_triangles, 0u);
  EXPECT_EQ(rep.height_depth, -1);
  const auto general = encode_quantized(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame());
  EXPECT_EQ(enc.value, general.value);
}

TEST(PrmStream, BadOptionsAreRefused) {
  const QMesh m = pillow(3, 0);
  for (int64_t grid : {int64_t{0}, int64_t{1}, int64_t{1} << 13}) {
    PrmOptions o;
    o.grid = grid;
    EXPECT_EQ(encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o).status.error,
              Error::invalid_argument);
  }
  for (int depth : {-2, 8}) {
    PrmOptions o;
    o.grid = 8;
    o.height_depth = depth;
    EXPECT_EQ(encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o).status.error,
              Error::invalid_argument);
  }
  PrmOptions o;
  o.grid = 8;
  o.height_depth = 7;
  o.overlap_depth = 7;
  EXPECT_EQ(encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o).status.error, Error::invalid_argument);
}

// §9.7 On a larger bumpy pillow linear prediction beats every difference depth, and the default picks it.
TEST(PrmStream, LinearPredictionWinsOnASmoothPatch) {
  const QMesh m = pillow(40, 0);
  size_t best_difference = SIZE_MAX;
  for (int depth = 0; depth <= 6; ++depth) {
    PrmOptions o;
    o.grid = 8;
    o.height_depth = depth;
    const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o);
    ASSERT_TRUE(enc.ok());
    best_difference = std::min(best_difference, enc.value.size());
  }
  PrmOptions o;
  o.grid = 8;
  EncodeReport rep;
  const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, &rep);
  ASSERT_TRUE(enc.ok());
  EXPECT_EQ(rep.height_depth, 7);
  EXPECT_LT(enc.value.size(), best_difference);
  expect_round_trip(m, enc.value, rep);
}

// Unrounded values for m's coordinates: each within 0.49 of its quantized value (a fixed pseudo-random offset).
std::vector<double> unrounded_near(const QMesh& m, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-0.49, 0.49);
  std::vector<double> unrounded(m.q.size());
  for (size_t i = 0; i < m.q.size(); ++i) unrounded[i] = static_cast<double>(m.q[i]) + offset(rng);
  return unrounded;
}

// PrmOptions::height_lambda: the encoder may code, for the heights of linear-prediction patches, another integer
// than the rounded one, within the tolerance of the unrounded value; everything else decodes exactly, the stream is
// an ordinary 1.2 one, and smaller than the lossless one.
TEST(PrmStream, HeightFreedomStaysWithinTheTolerance) {
  const QMesh m = pillow(40, 0);
  const std::vector<double> unrounded = unrounded_near(m, 7);
  PrmOptions lossless;
  lossless.grid = 8;
  const auto base = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), lossless);
  ASSERT_TRUE(base.ok());
  for (double lambda : {0.25, 1.0, 4.0}) {
    PrmOptions o = lossless;
    o.height_tolerance = 1.5;
    o.height_lambda = lambda;
    o.unrounded = unrounded.data();
    EncodeReport rep;
    const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, &rep);
    ASSERT_TRUE(enc.ok()) << enc.status.message;
    EXPECT_EQ(rep.height_depth, 7);
    const auto dec = decode(enc.value.data(), enc.value.size());
    ASSERT_TRUE(dec.ok()) << dec.status.message;
    const DecodedMesh& d = dec.value;
    ASSERT_EQ(d.num_vertices(), m.nv());
    size_t moved = 0;
    for (size_t k = 0; k < d.num_vertices(); ++k) {
      const size_t in = rep.vertex_order[k];
      int differing = 0;
      for (int a = 0; a < 3; ++a) {
        const uint32_t got = d.quantized[3 * k + a];
        EXPECT_LE(std::fabs(static_cast<double>(got) - unrounded[3 * in + a]), 1.5) << k;
        differing += got != m.q[3 * in + a];
        // The pillow's patches face +-z: x and y are lattice coordinates and never move.
        if (a < 2) {
          EXPECT_EQ(got, m.q[3 * in + a]) << k;
        }
      }
      EXPECT_LE(differing, 1);
      moved += differing;
    }
    EXPECT_GT(moved, 0u) << lambda;
    EXPECT_LT(enc.value.size(), base.value.size()) << lambda;
    std::printf("lambda %.2f: %zu bytes (lossless %zu), %zu heights moved\n", lambda, enc.value.size(),
                base.value.size(), moved);
    // The decoded mesh is a PRM like any other: encoding it losslessly round trips.
    QMesh again = m;
    for (size_t k = 0; k < d.num_vertices(); ++k)
      for (int a = 0; a < 3; ++a) again.q[3 * size_t{rep.vertex_order[k]} + a] = d.quantized[3 * k + a];
    EncodeReport rep2;
    const auto enc2 = encode_prm(again.q.data(), again.nv(), again.tris.data(), again.nt(), unit_frame(), lossless, &rep2);
    ASSERT_TRUE(enc2.ok());
    expect_round_trip(again, enc2.value, rep2);
  }
  // Without unrounded values, or with lambda 0, the encoder is lossless.
  PrmOptions o = lossless;
  o.height_tolerance = 1.5;
  o.height_lambda = 1;
  const auto no_values = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o);
  ASSERT_TRUE(no_values.ok());
  EXPECT_EQ(no_values.value, base.value);
  o.unrounded = unrounded.data();
  o.height_lambda = 0;
  const auto zero = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o);
  ASSERT_TRUE(zero.ok());
  EXPECT_EQ(zero.value, base.value);
  // Refused: a tolerance or lambda out of range, an unrounded value that is NaN or not near its quantized value.
  for (auto [tolerance, lambda] : {std::pair{17.0, 1.0}, std::pair{-1.0, 1.0}, std::pair{1.5, -1.0},
                                   std::pair{1.5, std::nan("")}}) {
    PrmOptions bad = o;
    bad.height_tolerance = tolerance;
    bad.height_lambda = lambda;
    EXPECT_EQ(encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), bad).status.error,
              Error::invalid_argument);
  }
  for (double wrong : {std::nan(""), 2.0}) {
    std::vector<double> u = unrounded;
    u[3 * 17 + 2] = static_cast<double>(m.q[3 * 17 + 2]) + wrong;
    PrmOptions bad = o;
    bad.height_lambda = 1;
    bad.unrounded = u.data();
    EXPECT_EQ(encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), bad).status.error,
              Error::invalid_argument);
  }
}

// PrmOptions::rounded_heights (hrefine3): the vertices it marks keep their rounded heights, the others may still
// move; all marked, the stream is the lossless one.
TEST(PrmStream, RoundedHeightsStayRounded) {
  const QMesh m = pillow(40, 0);
  std::vector<uint8_t> held(m.nv(), 0);
  for (size_t v = 0; v < held.size(); v += 2) held[v] = 1;
  const std::vector<double> unrounded = unrounded_near(m, 7);
  PrmOptions o;
  o.grid = 8;
  o.height_tolerance = 1.5;
  o.height_lambda = 1.0;
  o.unrounded = unrounded.data();
  o.rounded_heights = held.data();
  EncodeReport rep;
  const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, &rep);
  ASSERT_TRUE(enc.ok()) << enc.status.message;
  const auto dec = decode(enc.value.data(), enc.value.size());
  ASSERT_TRUE(dec.ok()) << dec.status.message;
  size_t moved = 0;
  for (size_t k = 0; k < dec.value.num_vertices(); ++k) {
    const size_t in = rep.vertex_order[k];
    for (int a = 0; a < 3; ++a) {
      const bool differs = dec.value.quantized[3 * k + a] != m.q[3 * in + a];
      if (held[in]) EXPECT_FALSE(differs) << in;
      moved += differs;
    }
  }
  EXPECT_GT(moved, 0u);
  std::fill(held.begin(), held.end(), uint8_t{1});
  PrmOptions lossless;
  lossless.grid = 8;
  EXPECT_EQ(encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o).value,
            encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), lossless).value);
}

// PrmOptions::height_sweeps (spec Appendix B.2): the heights chosen one by one, refined together, give a lower
// rate-distortion objective (squared distance to the unrounded values plus lambda times the stream's bits) than the
// one-by-one choice, on the same PRM and at the same lambda; both streams decode.
TEST(PrmStream, RefinedHeightsLowerTheObjective) {
  const QMesh m = pillow(40, 0);
  const std::vector<double> unrounded = unrounded_near(m, 5);
  for (double lambda : {0.25, 1.0, 4.0}) {
    double j[2] = {0, 0};
    size_t bytes[2] = {0, 0};
    for (int refined = 0; refined < 2; ++refined) {
      PrmOptions o;
      o.grid = 8;
      o.height_tolerance = 1.5;
      o.height_lambda = lambda;
      o.unrounded = unrounded.data();
      o.height_sweeps = refined ? 4 : 0;
      EncodeReport rep;
      const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, &rep);
      ASSERT_TRUE(enc.ok()) << enc.status.message;
      const auto dec = decode(enc.value.data(), enc.value.size());
      ASSERT_TRUE(dec.ok()) << dec.status.message;
      double d2 = 0;
      for (size_t k = 0; k < dec.value.num_vertices(); ++k)
        for (int a = 0; a < 3; ++a) {
          const double d = dec.value.quantized[3 * k + a] - unrounded[3 * size_t{rep.vertex_order[k]} + a];
          EXPECT_LE(std::fabs(d), 1.5);
          d2 += d * d;
        }
      bytes[refined] = enc.value.size();
      j[refined] = d2 + lambda * 8.0 * static_cast<double>(enc.value.size());
    }
    EXPECT_LT(j[1], j[0]) << lambda;
    std::printf("lambda %.2f: one by one %zu bytes (objective %.1f), refined %zu bytes (%.1f)\n", lambda, bytes[0], j[0],
                bytes[1], j[1]);
  }
  PrmOptions bad;
  bad.grid = 8;
  for (int sweeps : {-1, 17}) {
    bad.height_sweeps = sweeps;
    EXPECT_EQ(encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), bad).status.error,
              Error::invalid_argument);
  }
}

void fix_crc(std::vector<uint8_t>& s) {
  const uint32_t c = crc32(s.data(), s.size() - 4);
  for (int i = 0; i < 4; ++i) s[s.size() - 4 + i] = static_cast<uint8_t>(c >> (8 * i));
}

// Every outcome of a hostile stream is a mesh or a named error; a mesh must reference its own vertices.
void decode_any(const std::vector<uint8_t>& s) {
  std::unique_ptr<uint8_t[]> buf(new uint8_t[s.size() ? s.size() : 1]);
  if (!s.empty()) std::memcpy(buf.get(), s.data(), s.size());
  const auto res = decode(buf.get(), s.size());
  if (!res.ok()) {
    EXPECT_NE(res.status.error, Error::internal) << res.status.message;
    EXPECT_FALSE(res.status.message.empty());
  } else {
    for (uint32_t v : res.value.triangles) EXPECT_LT(v, res.value.num_vertices());
  }
}

std::vector<uint8_t> small_prm_stream(int depth = -1) {
  const QMesh m = pillow(4, 3, 5);
  PrmOptions o;
  o.grid = 8;
  o.height_depth = depth;
  EncodeReport rep;
  auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, &rep);
  EXPECT_TRUE(enc.ok());
  EXPECT_GT(rep.regular_triangles, 0u);
  return enc.value;
}

class PrmStreamHostile : public ::testing::TestWithParam<int> {};

TEST_P(PrmStreamHostile, EveryByteFlippedWithTheCrcFixed) {
  const std::vector<uint8_t> s = small_prm_stream(GetParam());
  size_t accepted = 0;
  for (size_t i = 6; i + 4 < s.size(); ++i)
    for (uint8_t x : {0x01, 0x10, 0x80, 0xFF}) {
      std::vector<uint8_t> t = s;
      t[i] ^= x;
      fix_crc(t);
      const auto res = decode(t.data(), t.size());
      accepted += res.ok();
      decode_any(t);
    }
  EXPECT_LT(accepted, 2 * s.size());  // most flips are caught by the sections' own checks
  // Flags bit 3 toggled (§3.3): the patches section read with or without the patch contexts (§8.4.1, §9.7.4).
  std::vector<uint8_t> t = s;
  t[6] ^= 0x08;
  fix_crc(t);
  decode_any(t);
}

TEST_P(PrmStreamHostile, EveryTruncationAndRandomSections) {
  const std::vector<uint8_t> s = small_prm_stream(GetParam());
  for (size_t len = 0; len < s.size(); ++len) {
    std::vector<uint8_t> t(s.begin(), s.begin() + static_cast<long>(len));
    EXPECT_FALSE(decode(t.data(), t.size()).ok()) << len;
    if (len >= 10) {
      t.resize(len + 4);
      fix_crc(t);
      decode_any(t);
    }
  }
  std::mt19937 rng(11);
  for (int trial = 0; trial < 3000; ++trial) {  // valid container prefix, random payload bytes
    std::vector<uint8_t> t = s;
    const size_t from = 60 + rng() % (s.size() - 64);
    for (size_t i = from; i + 4 < t.size(); ++i) t[i] = static_cast<uint8_t>(rng());
    fix_crc(t);
    decode_any(t);
  }
}

// The reference encoder's choice, difference patches of depth 3 (§9.1-§9.3) and linear prediction (§9.7).
INSTANTIATE_TEST_SUITE_P(HeightCodings, PrmStreamHostile, ::testing::Values(-1, 3, 7));

}  // namespace
}  // namespace prm::codec::test

namespace prm::codec::test {
namespace {

// A golden PRM stream (format 1.2), by fingerprint: the encoder must keep producing exactly these bytes from the
// generating mesh, and they must keep decoding. A format change bumps the version (spec/CHANGES.md) and records a
// new fingerprint; never update this silently. (The 1.1 fingerprint was 159 bytes, 14658986233315911954; a 1.1
// stream is kept as conformance/vectors/010-prm-1.1-pillow.)
uint64_t fnv_bytes(const std::vector<uint8_t>& b) {
  uint64_t h = 1469598103934665603ull;
  for (uint8_t x : b) {
    h ^= x;
    h *= 1099511628211ull;
  }
  return h;
}

TEST(PrmStream, GoldenFingerprint) {
  const QMesh m = pillow(4, 3, 5);
  PrmOptions o;
  o.grid = 8;
  o.patch_contexts = false;  // the 1.2 writer
  EncodeReport rep;
  const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), unit_frame(), o, &rep);
  ASSERT_TRUE(enc.ok());
  EXPECT_EQ(enc.value[5], kFormatMinorPredicted);
  EXPECT_EQ(enc.value.size(), size_t{160});
  EXPECT_EQ(fnv_bytes(enc.value), uint64_t{8373705955872552472ull}) << fnv_bytes(enc.value);
  expect_round_trip(m, enc.value, rep);
}

}  // namespace
}  // namespace prm::codec::test
