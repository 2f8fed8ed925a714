#include "prm/remesh/boundary_polyline.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "prm/boundary_deviation.h"

namespace prm::remesh {

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
