// prm/lattice.h, the one definition of the frame and the lattices that the encoder, the decoder and the remesher
// share, pinned against the spec's own figures (§3.6, §8.1, §8.5, §10.1).
#include <gtest/gtest.h>

#include <cstring>

#include "prm/lattice.h"

namespace prm::codec::test {
namespace {

// §8.1 "For A = 4: B = 2, C = floor((6 + 1) / 2) = 3", checked at compile time too.
static_assert(HexLattice::with_grid(4).A == 4 && HexLattice::with_grid(4).B == 2 && HexLattice::with_grid(4).C == 3);
static_assert(isqrt(48) == 6 && isqrt(49) == 7 && isqrt(0) == 0 && isqrt(-5) == 0);

TEST(Lattice, AxesAndPairsAsSection8_1) {
  // §8.1 the axis table and (U, W, H): pair 0 (y, z, x), pair 1 (z, x, y), pair 2 (x, y, z).
  const int pair[6] = {0, 0, 1, 1, 2, 2};
  for (int a = 0; a < 6; ++a) {
    EXPECT_EQ(axis_pair(a), pair[a]);
    EXPECT_EQ(axis_positive(a), a % 2 == 0);
  }
  const int uwh[3][3] = {{1, 2, 0}, {2, 0, 1}, {0, 1, 2}};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(pair_u(k), uwh[k][0]);
    EXPECT_EQ(pair_w(k), uwh[k][1]);
    EXPECT_EQ(pair_height(k), uwh[k][2]);
  }
}

TEST(Lattice, IsqrtIsExactOverEveryGridSize) {
  // isqrt(n) = floor(sqrt(n)) exactly, at and around every square the constants of 2 <= A <= 2^20 can meet.
  for (int64_t r : {int64_t{1}, int64_t{2}, int64_t{3}, int64_t{1000}, int64_t{1} << 20, int64_t{1816186},
                    int64_t{1816187}, int64_t{3037000498}}) {
    EXPECT_EQ(isqrt(r * r), r);
    EXPECT_EQ(isqrt(r * r - 1), r - 1);
    EXPECT_EQ(isqrt(r * r + 2 * r), r);  // (r + 1)^2 - 1
  }
  for (int64_t a = 2; a <= 5000; ++a) {
    const int64_t n = 3 * a * a, r = isqrt(n);
    ASSERT_TRUE(r * r <= n && (r + 1) * (r + 1) > n) << a;
  }
  // The largest grid: C = floor((isqrt(3 * 2^40) + 1) / 2), C ~ A sqrt(3) / 2.
  const HexLattice big = HexLattice::with_grid(int64_t{1} << 20);
  EXPECT_EQ(big.B, int64_t{1} << 19);
  EXPECT_EQ(isqrt(3 * (int64_t{1} << 40)), 1816186);
  EXPECT_EQ(big.C, 908093);
}

TEST(Lattice, GridSizeRangeIsSection8_4) {
  // §8.4 Grid_Size: 2 <= A <= 2^Bits (one check for the encoder, the decoder and the remesher).
  EXPECT_FALSE(valid_grid_size(1, 12));
  EXPECT_TRUE(valid_grid_size(2, 12));
  EXPECT_TRUE(valid_grid_size(4096, 12));
  EXPECT_FALSE(valid_grid_size(4097, 12));
  EXPECT_TRUE(valid_grid_size(int64_t{1} << 20, 20));
  EXPECT_FALSE(valid_grid_size((int64_t{1} << 20) + 1, 20));
  EXPECT_FALSE(valid_grid_size(4, 7));   // Position_Bits outside 8..20
  EXPECT_FALSE(valid_grid_size(4, 21));
}

TEST(Lattice, WorkedExampleOfSection8_5) {
  // Axis 1 (-x: pair 0, U = y, W = z, not positive), Base (2, 0), Alignment 1, A = 4 (B = 2, C = 3).
  const int axis = 1;
  EXPECT_EQ(axis_pair(axis), 0);
  EXPECT_FALSE(axis_positive(axis));
  EXPECT_EQ(pair_u(0), 1);
  EXPECT_EQ(pair_w(0), 2);
  const HexLattice l = HexLattice::with_grid(4);
  const std::array<int64_t, 2> c0 = {2, 0};
  const std::array<int64_t, 2> c1 = {c0[0] + kDirection[1][0], c0[1] + kDirection[1][1]};
  const std::array<int64_t, 2> c2 = third_corner(c0, c1, axis_positive(axis));
  const std::array<int64_t, 2> c3 = third_corner(c2, c1, axis_positive(axis));  // second triangle (2, 1, 3)
  EXPECT_EQ(c1, (std::array<int64_t, 2>{2, 1}));
  EXPECT_EQ(c2, (std::array<int64_t, 2>{3, 0}));
  EXPECT_EQ(c3, (std::array<int64_t, 2>{3, 1}));
  // (U, W) = (4i + 2j, 3j): y, z = (8, 0), (10, 3), (12, 0), (14, 3).
  const std::array<int64_t, 2> uw[4] = {l.to_base(c0[0], c0[1]), l.to_base(c1[0], c1[1]), l.to_base(c2[0], c2[1]),
                                        l.to_base(c3[0], c3[1])};
  const int64_t want[4][2] = {{8, 0}, {10, 3}, {12, 0}, {14, 3}};
  for (int v = 0; v < 4; ++v) {
    EXPECT_EQ(uw[v][0], want[v][0]) << v;
    EXPECT_EQ(uw[v][1], want[v][1]) << v;
    int64_t i = 0, j = 0;
    ASSERT_TRUE(l.to_lattice(uw[v][0], uw[v][1], i, j));  // and back, exactly
    const std::array<double, 2> ab = l.to_lattice(static_cast<double>(uw[v][0]), static_cast<double>(uw[v][1]));
    EXPECT_EQ(ab[0], static_cast<double>(i));
    EXPECT_EQ(ab[1], static_cast<double>(j));
  }
  int64_t i = 0, j = 0;
  EXPECT_FALSE(l.to_lattice(9, 0, i, j));  // between lattice points
  EXPECT_FALSE(l.to_lattice(8, 1, i, j));
}

TEST(Lattice, DirectionsTurnBy60Degrees) {
  // §8.1 e_{n+1} = Rot+60(e_n); a neighbour step is one of the six directions.
  for (int n = 0; n < kLatticeDirections; ++n) {
    const auto& e = kDirection[static_cast<size_t>(n)];
    const auto& f = kDirection[static_cast<size_t>((n + 1) % 6)];
    EXPECT_EQ((std::array<int64_t, 2>{-e[1], e[0] + e[1]}), f) << n;
    EXPECT_EQ(direction_index(e[0], e[1]), n);
    EXPECT_TRUE(lattice_neighbours(e[0], e[1]));
  }
  EXPECT_FALSE(lattice_neighbours(1, 1));
  EXPECT_FALSE(lattice_neighbours(0, 0));
  EXPECT_EQ(direction_index(2, 0), -1);
}

TEST(Frame, WorkedExampleOfSection3_6) {
  // The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) at B = 12: origin 0, Step = 1/4095 = 0x3F30010010010010.
  const float xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const Frame f = frame_of_points(xyz, 4, 12);
  EXPECT_EQ(f.origin, (std::array<double, 3>{0, 0, 0}));
  uint64_t bits = 0;
  std::memcpy(&bits, &f.step, sizeof bits);
  EXPECT_EQ(bits, 0x3F30010010010010ull);
  // §10.1 q = floor((p - o) / s + 0.5) clamped to [0, 2^B - 1]: the unit coordinates quantize to 4095 (the Bbox
  // extent of §3.6).
  EXPECT_EQ(f.quantize(1.0, 0), 4095u);
  EXPECT_EQ(f.quantize(0.0, 1), 0u);
  EXPECT_EQ(f.quantize(2.0, 2), 4095u);  // clamped
  EXPECT_EQ(f.quantize(-1.0, 2), 0u);
  EXPECT_EQ(quantize(std::nan(""), 0, 1, 12), 0u);
  EXPECT_EQ(f.quantize(0.5 / 4095 * 0.999, 0), 0u);  // rounds half up: just below half a step
  EXPECT_EQ(f.quantize(0.5 / 4095 * 1.001, 0), 1u);
  // §10.5 output o + q s; the remesher's step scale sigma in [1, 2) multiplies the step.
  EXPECT_EQ(f.to_real(4095, 0), dequantize(4095, 0, f.step));
  EXPECT_EQ(frame_of_points(xyz, 4, 12, 1.5).step, 1.5 * 1.0 / 4095);
  // All points equal: step 1.
  const double one[] = {3, 4, 5};
  EXPECT_EQ(frame_of_points(one, 1, 12).step, 1.0);
}

}  // namespace
}  // namespace prm::codec::test
