#include "boundary_polyline.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace prm::remesh {
namespace {

// The edges (a, b) of m's faces whose reverse (b, a) and duplicate no other face has: the boundary of an oriented
// manifold. An edge two faces share in the same direction is not boundary either.
std::vector<std::array<uint32_t, 2>> boundary_edges(const Mesh& m) {
  std::vector<std::array<uint32_t, 2>> undirected;
  undirected.reserve(3 * m.triangles.size());
  for (const Tri& t : m.triangles)
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t a = t[k], b = t[(k + 1) % 3];
      undirected.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(undirected.begin(), undirected.end());
  std::vector<std::array<uint32_t, 2>> out;
  for (size_t i = 0; i < undirected.size();) {
    size_t j = i;
    while (j < undirected.size() && undirected[j] == undirected[i]) ++j;
    if (j - i == 1) out.push_back(undirected[i]);
    i = j;
  }
  return out;
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = dot(ab, ab);
  const double t = l2 > 0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
  return norm(p - (a + ab * t));
}

}  // namespace

std::vector<uint8_t> boundary_vertex_flags(const Mesh& m) {
  std::vector<uint8_t> flags(m.positions.size(), 0);
  for (const auto& e : boundary_edges(m)) flags[e[0]] = flags[e[1]] = 1;
  return flags;
}

BoundaryPolyline::Key BoundaryPolyline::key_of(const Vec3& p) const {
  return {static_cast<int64_t>(std::floor(p[0] / cell_)), static_cast<int64_t>(std::floor(p[1] / cell_)),
          static_cast<int64_t>(std::floor(p[2] / cell_))};
}

BoundaryPolyline::BoundaryPolyline(const Mesh& m, double reach) : cell_(2 * reach) {
  for (const auto& e : boundary_edges(m)) segments_.push_back({m.positions[e[0]], m.positions[e[1]]});
  // Each segment is listed in the cells of points along it at most cell/4 apart. A point within `reach` (cell/2) of
  // the segment is then within 5/8 cell of such a point, so in its cell or a neighbouring one: distance() looks at
  // the 27 cells around p.
  for (uint32_t s = 0; s < segments_.size(); ++s) {
    const Vec3 &a = segments_[s][0], &b = segments_[s][1];
    const size_t n = 1 + static_cast<size_t>(std::ceil(4 * norm(b - a) / cell_));
    for (size_t i = 0; i <= n; ++i) {
      std::vector<uint32_t>& list = cells_[key_of(a + (b - a) * (static_cast<double>(i) / static_cast<double>(n)))];
      if (list.empty() || list.back() != s) list.push_back(s);
    }
  }
}

double BoundaryPolyline::distance(const Vec3& p) const {
  const Key k = key_of(p);
  double best = HUGE_VAL;
  for (int64_t dx = -1; dx <= 1; ++dx)
    for (int64_t dy = -1; dy <= 1; ++dy)
      for (int64_t dz = -1; dz <= 1; ++dz) {
        const auto it = cells_.find(Key{k.x + dx, k.y + dy, k.z + dz});
        if (it == cells_.end()) continue;
        for (uint32_t s : it->second) best = std::min(best, point_segment_distance(p, segments_[s][0], segments_[s][1]));
      }
  return best;
}

}  // namespace prm::remesh
