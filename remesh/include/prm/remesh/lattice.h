// The quantization frame and the hexagonal lattices of the reliefs (docs/ARCHITECTURE.md, spec §8).
// Regular vertices sit exactly on lattice points expressed in quantized integer coordinates, so that the codec
// can code them without error: the remesher and the codec share these definitions.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "prm/mesh.h"

namespace prm::remesh {

// q = floor((p - origin) / step + 0.5); p' = origin + q * step.
struct QuantFrame {
  Vec3 origin{0, 0, 0};
  double step = 1;
  int bits = 12;

  // The frame of a mesh's bounding box: step = step_scale * largest extent / (2^bits - 1), step_scale in [1, 2)
  // (a coarser step than 2^-bits of the extent: the spec's header carries any step, and the grid size, a whole
  // number of steps, then comes in finer increments).
  static QuantFrame of_mesh(const Mesh& mesh, int bits, double step_scale = 1.0);

  double to_quant(double p, int axis) const { return (p - origin[axis]) / step; }
  double to_real(double q, int axis) const { return origin[axis] + q * step; }
  int32_t quantize(double p, int axis) const;
};

// Axis index a in 0..5 = +x, -x, +y, -y, +z, -z; axis pair k = a / 2.
// Base plane and height of pair k as a right-handed (u, w, h): k=0 (y,z,x), k=1 (z,x,y), k=2 (x,y,z).
inline int axis_pair(int axis) { return axis / 2; }
inline double axis_sign(int axis) { return (axis % 2) ? -1.0 : 1.0; }
inline int base_u(int pair) { return (pair + 1) % 3; }
inline int base_w(int pair) { return (pair + 2) % 3; }
inline int height_axis(int pair) { return pair; }
inline Vec3 axis_vector(int axis) {
  Vec3 v{0, 0, 0};
  v[static_cast<size_t>(axis_pair(axis))] = axis_sign(axis);
  return v;
}

// Lattice vectors e1 = (A, 0), e2 = (B, C) in quantized units; lattice point (i, j) -> (A i + B j, C j).
struct HexLattice {
  int64_t A = 2, B = 1, C = 2;

  static HexLattice with_grid(int64_t a);

  // Continuous lattice coordinates (alpha, beta) of a base point (u, w) in quantized units.
  std::array<double, 2> to_lattice(double u, double w) const {
    const double beta = w / static_cast<double>(C);
    return {(u - static_cast<double>(B) * beta) / static_cast<double>(A), beta};
  }
  std::array<int64_t, 2> to_base(int64_t i, int64_t j) const { return {A * i + B * j, C * j}; }
};

// Lattice points (i, j) and (i + di, j + dj) are neighbours: the step is one of the six directions (spec §8.1).
inline bool lattice_neighbours(int64_t di, int64_t dj) {
  return (std::abs(di) + std::abs(dj) == 1) || (di == 1 && dj == -1) || (di == -1 && dj == 1);
}

int64_t isqrt(int64_t n);

}  // namespace prm::remesh
