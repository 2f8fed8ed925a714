// §8.1 The hexagonal lattices of a piecewise regular mesh, in quantized integer coordinates, shared by the encoder
// and the decoder: axis pairs, lattice constants, the six lattice directions and the 60-degree rotations.
#pragma once

#include <array>
#include <cstdint>

namespace prm::codec {

// §8.1 Axis a in 0..5 = +x, -x, +y, -y, +z, -z; pair k = a / 2. The base plane of pair k is spanned by coordinate
// U(k) = (k + 1) mod 3 and W(k) = (k + 2) mod 3, and its height is coordinate k, so (U, W, H) is right-handed.
inline int pair_u(int pair) { return (pair + 1) % 3; }
inline int pair_w(int pair) { return (pair + 2) % 3; }

// §8.1 isqrt(n) = floor(sqrt(n)) for n >= 0, exactly (integer Newton iteration).
inline int64_t isqrt64(int64_t n) {
  if (n <= 0) return 0;
  int64_t x = n, y = (x + 1) / 2;
  while (y < x) {
    x = y;
    y = (x + n / x) / 2;
  }
  return x;
}

// §8.1 Lattice constants from the grid size A >= 2: B = floor(A / 2), C = floor((isqrt(3 A^2) + 1) / 2). Lattice
// point (i, j) of pair k sits at (U, W) = (A i + B j, C j).
struct LatticeConstants {
  int64_t a = 2, b = 1, c = 2;
  static LatticeConstants of(int64_t grid) {
    LatticeConstants l;
    l.a = grid;
    l.b = grid / 2;
    l.c = (isqrt64(3 * grid * grid) + 1) / 2;
    return l;
  }
  // The lattice point at base-plane position (u, w), if there is one.
  bool to_lattice(int64_t u, int64_t w, int64_t& i, int64_t& j) const {
    if (w % c != 0) return false;
    j = w / c;
    const int64_t r = u - b * j;
    if (r % a != 0) return false;
    i = r / a;
    return true;
  }
};

// §8.1 The six lattice directions, in counter-clockwise order: e0 = (1, 0), e1 = (0, 1), e2 = (-1, 1), then their
// negatives. Direction n + 1 is direction n turned by 60 degrees counter-clockwise.
constexpr int kLatticeDirections = 6;
constexpr std::array<std::array<int64_t, 2>, 6> kDirection = {
    {{{1, 0}}, {{0, 1}}, {{-1, 1}}, {{-1, 0}}, {{0, -1}}, {{1, -1}}}};

// The index 0..5 of a unit lattice step, or -1.
inline int direction_index(int64_t di, int64_t dj) {
  for (int n = 0; n < kLatticeDirections; ++n)
    if (kDirection[n][0] == di && kDirection[n][1] == dj) return n;
  return -1;
}

// §8.3 The third corner of a grid triangle from its first two corners p, q (in corner order): counter-clockwise
// (axis facing +) r = p + rot60(q - p), clockwise (axis facing -) r = p + rot-60(q - p).
inline std::array<int64_t, 2> third_corner(const std::array<int64_t, 2>& p, const std::array<int64_t, 2>& q,
                                           bool positive) {
  const int64_t di = q[0] - p[0], dj = q[1] - p[1];
  if (positive) return {p[0] - dj, p[1] + di + dj};
  return {p[0] + di + dj, p[1] - di};
}

}  // namespace prm::codec
