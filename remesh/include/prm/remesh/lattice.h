// The quantization frame and the hexagonal lattices of the reliefs (docs/ARCHITECTURE.md, spec §8.1, §10.1).
// Regular vertices sit exactly on lattice points in quantized integer coordinates, so that the codec can code them
// without error: the remesher uses the codec's own definitions (prm/lattice.h), never a copy.
#pragma once

#include "prm/lattice.h"
#include "prm/mesh.h"

namespace prm::remesh {

// §10.1 The frame: q = floor((p - origin) / step + 0.5) clamped to [0, 2^bits - 1]; p' = origin + q * step.
using QuantFrame = codec::Frame;

// The frame of a mesh's bounding box: step = step_scale * largest extent / (2^bits - 1), step_scale in [1, 2)
// (a coarser step than 2^-bits of the extent: the spec's header carries any step, and the grid size, a whole
// number of steps, then comes in finer increments). Throws std::invalid_argument on bits outside 8..20 or a
// step_scale outside [1, 2).
QuantFrame frame_of_mesh(const Mesh& mesh, int bits, double step_scale = 1.0);

// §8.1 Axes, lattices and directions, as the codec defines them.
using codec::axis_pair;
using codec::HexLattice;
using codec::isqrt;
using codec::lattice_neighbours;
using codec::pair_height;
using codec::pair_u;
using codec::pair_w;
using codec::valid_grid_size;

// The unit vector of axis a (+x, -x, +y, -y, +z, -z), and its sign.
inline double axis_sign(int axis) { return codec::axis_positive(axis) ? 1.0 : -1.0; }
inline Vec3 axis_vector(int axis) {
  Vec3 v{0, 0, 0};
  v[static_cast<size_t>(axis_pair(axis))] = axis_sign(axis);
  return v;
}

// The lattice of grid size A for a frame of `bits` bits; throws InputError unless 2 <= A <= 2^bits (spec §8.4).
HexLattice lattice_of_grid(int64_t grid, int bits);

}  // namespace prm::remesh
