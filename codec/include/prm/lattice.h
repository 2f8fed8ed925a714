// prm/lattice.h: the quantization frame (spec §10.1) and the hexagonal lattices (spec §8.1) of a piecewise regular
// mesh, defined once. The encoder, the decoder and the remesher all use these definitions: regular vertices sit
// exactly on lattice points in quantized integer coordinates, so the three must compute the same points.
//
// C++17 and the standard library only; everything here is inline.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace prm::codec {

// §3.3 Position_Bits: B, 8 <= B <= 20.
constexpr int kMinPositionBits = 8;
constexpr int kMaxPositionBits = 20;
// §8.4.2 The grid table (format 1.5): Grid_Size and at most 7 extra grid sizes.
constexpr int kMaxExtraGrids = 7;
constexpr int kMaxGridSizes = kMaxExtraGrids + 1;

// ---------------------------------------------------------------------------------------------------------------
// §10.1 The quantization frame: q = floor((p - origin) / step + 0.5) clamped to [0, 2^bits - 1]; a quantized value
// decodes to origin + q * step (IEEE double, §10.5).

// q_k for one coordinate (NaN quantizes to 0).
inline uint32_t quantize(double p, double origin, double step, int bits) {
  const double qmax = static_cast<double>((uint64_t{1} << bits) - 1);
  double x = std::floor((p - origin) / step + 0.5);
  if (!(x >= 0)) x = 0;  // also NaN
  if (x > qmax) x = qmax;
  return static_cast<uint32_t>(x);
}
inline double dequantize(uint32_t q, double origin, double step) { return origin + static_cast<double>(q) * step; }

struct Frame {
  int bits = 12;                          // 8..20
  std::array<double, 3> origin{0, 0, 0};
  double step = 1.0;                      // > 0 and finite

  // Coordinate `axis` of p in quantization steps, before rounding.
  double to_quant(double p, int axis) const { return (p - origin[static_cast<size_t>(axis)]) / step; }
  // The position of (possibly fractional) quantized coordinate q on `axis`: origin + q * step.
  double to_real(double q, int axis) const { return origin[static_cast<size_t>(axis)] + q * step; }
  uint32_t quantize(double p, int axis) const {
    return codec::quantize(p, origin[static_cast<size_t>(axis)], step, bits);
  }
};

// §10.1 The reference frame of the points xyz[3 * n] (float or double): origin = the minimum corner of their
// bounding box, step = step_scale * E / (2^bits - 1) with E the largest extent (1 when all points coincide).
// The reference encoder uses step_scale 1; the remesher may pass any step_scale in [1, 2). bits must be 8..20.
template <typename T>
Frame frame_of_points(const T* xyz, size_t n, int bits, double step_scale = 1.0) {
  Frame f;
  f.bits = bits;
  if (n == 0) return f;
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = static_cast<double>(xyz[k]);
  for (size_t i = 1; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const double v = static_cast<double>(xyz[3 * i + static_cast<size_t>(k)]);
      if (v < lo[k]) lo[k] = v;
      if (v > hi[k]) hi[k] = v;
    }
  double extent = 0;
  for (int k = 0; k < 3; ++k) {
    f.origin[static_cast<size_t>(k)] = lo[k];
    if (hi[k] - lo[k] > extent) extent = hi[k] - lo[k];
  }
  const double qmax = static_cast<double>((uint64_t{1} << bits) - 1);
  f.step = extent > 0 ? step_scale * extent / qmax : 1.0;
  return f;
}

// ---------------------------------------------------------------------------------------------------------------
// §8.1 Axes. Axis a in 0..5 = +x, -x, +y, -y, +z, -z; its pair is k = a / 2 and it is positive when a is even. The
// base plane of pair k is spanned by coordinates U(k) = (k + 1) mod 3 and W(k) = (k + 2) mod 3, and its height is
// coordinate k, so (U, W, height) is right-handed: pair 0 (y, z, x), pair 1 (z, x, y), pair 2 (x, y, z).
constexpr int axis_pair(int axis) { return axis / 2; }
constexpr bool axis_positive(int axis) { return axis % 2 == 0; }
constexpr int pair_u(int pair) { return (pair + 1) % 3; }
constexpr int pair_w(int pair) { return (pair + 2) % 3; }
constexpr int pair_height(int pair) { return pair; }

// §8.1 isqrt(n) = floor(sqrt(n)) for n >= 0, exactly, on integers (Newton's iteration; 0 for n <= 0).
constexpr int64_t isqrt(int64_t n) {
  if (n <= 0) return 0;
  int64_t x = n, y = x / 2 + (x & 1);  // ceil(n / 2) without overflow
  while (y < x) {
    x = y;
    y = (x + n / x) / 2;
  }
  return x;
}

// §8.1, §8.4 A grid size A is valid for Position_Bits `bits` when 2 <= A <= 2^bits (and bits is 8..20).
constexpr bool valid_grid_size(int64_t grid, int bits) {
  return bits >= kMinPositionBits && bits <= kMaxPositionBits && grid >= 2 && grid <= (int64_t{1} << bits);
}

// §8.1 The lattice of grid size A (named as in the spec): B = floor(A / 2), C = floor((isqrt(3 A^2) + 1) / 2), and
// lattice point (i, j) of a pair sits at base-plane position (U, W) = (A i + B j, C j), in quantized units.
struct HexLattice {
  int64_t A = 2, B = 1, C = 2;

  // The constants of grid size A; the caller checks valid_grid_size() first.
  static constexpr HexLattice with_grid(int64_t grid) {
    HexLattice l;
    l.A = grid;
    l.B = grid / 2;
    l.C = (isqrt(3 * grid * grid) + 1) / 2;
    return l;
  }
  constexpr std::array<int64_t, 2> to_base(int64_t i, int64_t j) const { return {A * i + B * j, C * j}; }
  // The lattice point at base-plane position (u, w), if there is one.
  constexpr bool to_lattice(int64_t u, int64_t w, int64_t& i, int64_t& j) const {
    if (w % C != 0) return false;
    j = w / C;
    const int64_t r = u - B * j;
    if (r % A != 0) return false;
    i = r / A;
    return true;
  }
  // Continuous lattice coordinates (alpha, beta) of a base-plane point (u, w) in quantized units.
  std::array<double, 2> to_lattice(double u, double w) const {
    const double beta = w / static_cast<double>(C);
    return {(u - static_cast<double>(B) * beta) / static_cast<double>(A), beta};
  }
};

// §8.1 The six lattice directions, counter-clockwise in the (U, W) plane: e0 = (1, 0), e1 = (0, 1), e2 = (-1, 1),
// then their negatives. Direction n + 1 is direction n turned by 60 degrees counter-clockwise.
constexpr int kLatticeDirections = 6;
constexpr std::array<std::array<int64_t, 2>, 6> kDirection = {
    {{{1, 0}}, {{0, 1}}, {{-1, 1}}, {{-1, 0}}, {{0, -1}}, {{1, -1}}}};

// The index 0..5 of a unit lattice step (di, dj), or -1.
constexpr int direction_index(int64_t di, int64_t dj) {
  for (int n = 0; n < kLatticeDirections; ++n)
    if (kDirection[static_cast<size_t>(n)][0] == di && kDirection[static_cast<size_t>(n)][1] == dj) return n;
  return -1;
}
// Lattice points (i, j) and (i + di, j + dj) are neighbours: the step is one of the six directions.
constexpr bool lattice_neighbours(int64_t di, int64_t dj) { return direction_index(di, dj) >= 0; }

// §8.1 ThirdCorner(p, q, positive): p + Rot+60(q - p) if positive (the triangle on the left of p -> q,
// counter-clockwise), else p + Rot-60(q - p), with Rot+60(di, dj) = (-dj, di + dj), Rot-60(di, dj) = (di + dj, -di).
constexpr std::array<int64_t, 2> third_corner(const std::array<int64_t, 2>& p, const std::array<int64_t, 2>& q,
                                              bool positive) {
  const int64_t di = q[0] - p[0], dj = q[1] - p[1];
  if (positive) return {p[0] - dj, p[1] + di + dj};
  return {p[0] + di + dj, p[1] - di};
}

}  // namespace prm::codec
