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
// In face order. The half-edges' ends grouped by their start (a counting sort): a half-edge's reverse is looked for
// among the few that leave its end (the venus's 300,000 half-edges: 38 -> 6 ms, the same edges; a sort and a binary
// search each before). The remesher's quantized separation asks it of the input at every grid tried.
inline std::vector<std::array<uint32_t, 2>> boundary_edges(const Mesh& m) {
  uint32_t nv = 0;
  for (const Tri& t : m.triangles) nv = std::max({nv, t[0] + 1, t[1] + 1, t[2] + 1});
  std::vector<uint32_t> first(size_t{nv} + 1, 0);  // the half-edges leaving v: ends[first[v] .. first[v + 1])
  for (const Tri& t : m.triangles)
    for (const uint32_t v : t) ++first[size_t{v} + 1];
  for (size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
  std::vector<uint32_t> ends(first.back()), fill(first.begin(), first.end() - 1);
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) ends[fill[t[k]]++] = t[(k + 1) % 3];
  std::vector<std::array<uint32_t, 2>> out;
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = t[k], b = t[(k + 1) % 3];
      const auto from_b = ends.begin() + first[b], end_b = ends.begin() + first[size_t{b} + 1];
      if (std::find(from_b, end_b, a) == end_b) out.push_back({a, b});
    }
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
