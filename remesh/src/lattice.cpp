#include "prm/remesh/lattice.h"

#include <stdexcept>
#include <string>

#include "prm/error.h"

namespace prm::remesh {

QuantFrame frame_of_mesh(const Mesh& mesh, int bits, double step_scale) {
  if (bits < codec::kMinPositionBits || bits > codec::kMaxPositionBits)
    throw std::invalid_argument("quantization bits must be in 8..20");
  if (!(step_scale >= 1.0 && step_scale < 2.0))
    throw std::invalid_argument("the quantization step scale must be in [1, 2)");
  return codec::frame_of_points(mesh.positions.empty() ? nullptr : mesh.positions[0].data(), mesh.positions.size(),
                                bits, step_scale);
}

HexLattice lattice_of_grid(int64_t grid, int bits) {
  if (!valid_grid_size(grid, bits))
    throw InputError("the grid size, " + std::to_string(grid) + " quantization steps, is outside 2..2^" +
                     std::to_string(bits) + " (spec §8.4): at " + std::to_string(bits) +
                     " bits a grid cannot be larger than the model's largest extent");
  return HexLattice::with_grid(grid);
}

}  // namespace prm::remesh
