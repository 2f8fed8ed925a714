// Issue 22: how far an output's boundary lies from the input's: the distance of each boundary vertex of one mesh to
// the boundary polyline of another (the open-boundary tests, bench/boundary_distance.cpp). boundary_deviation is brute
// force over the input's boundary edges: for tests and benchmarks (the remesher buckets them: boundary_polyline.h).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "prm/mesh.h"
#include "prm/vec3.h"

namespace prm {

// The boundary edges of a manifold, oriented mesh: half-edges whose reverse no face has.
// In face order. The half-edges are 64-bit keys (from << 32 | to, ordered as the pairs are), one comparison each in
// the sort and the searches.
inline std::vector<std::array<uint32_t, 2>> boundary_edges(const Mesh& m) {
  std::vector<uint64_t> he;
  he.reserve(3 * m.triangles.size());
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) he.push_back(uint64_t{t[k]} << 32 | t[(k + 1) % 3]);
  std::vector<uint64_t> sorted = he;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::array<uint32_t, 2>> out;
  for (const uint64_t e : he)
    if (!std::binary_search(sorted.begin(), sorted.end(), e << 32 | e >> 32))
      out.push_back({static_cast<uint32_t>(e >> 32), static_cast<uint32_t>(e)});
  return out;
}

// The distance from p to the segment [a, b].
inline double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = dot(ab, ab);
  const double t = l2 > 0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
  return norm(p - (a + ab * t));
}

// The distances from the boundary vertices of `out` to the boundary polyline of `in` (model units): their largest
// and their root mean square.
struct BoundaryDeviation {
  double max = 0, rms = 0;
};
inline BoundaryDeviation boundary_deviation(const Mesh& in, const Mesh& out) {
  const auto ein = boundary_edges(in), eout = boundary_edges(out);
  BoundaryDeviation d;
  double sum2 = 0;
  for (const auto& e : eout) {  // each boundary vertex starts one boundary edge
    const Vec3& p = out.positions[e[0]];
    double best = HUGE_VAL;
    for (const auto& f : ein) best = std::min(best, point_segment_distance(p, in.positions[f[0]], in.positions[f[1]]));
    d.max = std::max(d.max, best);
    sum2 += best * best;
  }
  d.rms = eout.empty() ? 0 : std::sqrt(sum2 / static_cast<double>(eout.size()));
  return d;
}

}  // namespace prm
