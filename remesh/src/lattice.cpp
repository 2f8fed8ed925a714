#include "prm/remesh/lattice.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace prm::remesh {

QuantFrame QuantFrame::of_mesh(const Mesh& mesh, int bits, double step_scale) {
  if (bits < 8 || bits > 20) throw std::invalid_argument("quantization bits must be in 8..20");
  if (!(step_scale >= 1.0 && step_scale < 2.0)) throw std::invalid_argument("the quantization step scale must be in [1, 2)");
  QuantFrame f;
  f.bits = bits;
  if (mesh.positions.empty()) return f;
  Vec3 lo = mesh.positions[0], hi = mesh.positions[0];
  for (const Vec3& p : mesh.positions)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  f.origin = lo;
  f.step = extent > 0 ? step_scale * extent / static_cast<double>((int64_t{1} << bits) - 1) : 1.0;
  return f;
}

int32_t QuantFrame::quantize(double p, int axis) const {
  const double q = std::floor(to_quant(p, axis) + 0.5);
  const double hi = static_cast<double>((int64_t{1} << bits) - 1);
  return static_cast<int32_t>(std::clamp(q, 0.0, hi));
}

int64_t isqrt(int64_t n) {
  if (n <= 0) return 0;
  int64_t r = static_cast<int64_t>(std::sqrt(static_cast<double>(n)));
  while (r * r > n) --r;
  while ((r + 1) * (r + 1) <= n) ++r;
  return r;
}

HexLattice HexLattice::with_grid(int64_t a) {
  if (a < 2 || a > (int64_t{1} << 20)) throw std::invalid_argument("grid size must be in 2..2^20 quantization steps");
  HexLattice l;
  l.A = a;
  l.B = a / 2;
  l.C = (isqrt(3 * a * a) + 1) / 2;
  return l;
}

}  // namespace prm::remesh
