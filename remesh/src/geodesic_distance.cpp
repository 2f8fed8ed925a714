#include "geodesic_distance.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "prm/vec3.h"

namespace prm::remesh {

VertexStar vertex_star(const Mesh& m) {
  const size_t nv = m.positions.size();
  VertexStar s;
  s.offset.assign(nv + 1, 0);
  for (const Tri& t : m.triangles)
    for (uint32_t v : t) ++s.offset[v + 1];
  for (size_t v = 0; v < nv; ++v) s.offset[v + 1] += s.offset[v];
  s.faces.resize(s.offset[nv]);
  std::vector<uint32_t> fill(s.offset.begin(), s.offset.end() - 1);
  for (uint32_t f = 0; f < m.triangles.size(); ++f)
    for (uint32_t v : m.triangles[f]) s.faces[fill[v]++] = f;
  // Neighbours: the other corners of the faces around v, deduplicated.
  s.nbr_offset.assign(nv + 1, 0);
  std::vector<uint32_t> tmp;
  for (uint32_t v = 0; v < nv; ++v) {
    tmp.clear();
    for (uint32_t i = s.offset[v]; i < s.offset[v + 1]; ++i)
      for (uint32_t w : m.triangles[s.faces[i]])
        if (w != v) tmp.push_back(w);
    std::sort(tmp.begin(), tmp.end());
    tmp.erase(std::unique(tmp.begin(), tmp.end()), tmp.end());
    s.neighbours.insert(s.neighbours.end(), tmp.begin(), tmp.end());
    s.nbr_offset[v + 1] = static_cast<uint32_t>(s.neighbours.size());
  }
  return s;
}

namespace {

// Distance at x from a planar front through a (distance da) and b (distance db): the virtual source s lies at
// distances da, db from a, b on the far side of ab; valid when the ray s -> x crosses segment ab.
double triangle_update(const Vec3& a, const Vec3& b, const Vec3& x, double da, double db) {
  const Vec3 e = b - a;
  const double L = norm(e);
  if (L <= 0) return HUGE_VAL;
  const Vec3 ex = e * (1.0 / L);
  const Vec3 ax = x - a;
  const double x1 = dot(ax, ex);
  const double x2 = norm(ax - ex * x1);  // x at (x1, x2), x2 >= 0
  if (x2 <= 0) return HUGE_VAL;
  // Source s = (s1, -s2): s1^2 + s2^2 = da^2, (s1 - L)^2 + s2^2 = db^2.
  const double s1 = (da * da - db * db + L * L) / (2 * L);
  const double s2sq = da * da - s1 * s1;
  if (s2sq < 0) return HUGE_VAL;  // the front cannot pass through both a and b
  const double s2 = std::sqrt(s2sq);
  // Where the segment s -> x crosses the line of ab (y = 0): parameter along ab.
  const double t = s1 + (x1 - s1) * (s2 / (s2 + x2));
  if (t < 0 || t > L) return HUGE_VAL;
  const double dx = x1 - s1, dy = x2 + s2;
  return std::sqrt(dx * dx + dy * dy);
}

}  // namespace

std::vector<double> geodesic_distance(const Mesh& m, const VertexStar& star, const std::vector<uint8_t>& source,
                                      GeodesicMethod method) {
  const size_t nv = m.positions.size();
  std::vector<double> d(nv, HUGE_VAL);
  std::vector<uint8_t> done(nv, 0);
  using Item = std::pair<double, uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (uint32_t f = 0; f < m.triangles.size(); ++f)
    if (source[f])
      for (uint32_t v : m.triangles[f])
        if (d[v] != 0) {
          d[v] = 0;
          heap.push({0.0, v});
        }
  auto relax = [&](uint32_t v, double value) {
    if (value < d[v]) {
      d[v] = value;
      heap.push({value, v});
    }
  };
  while (!heap.empty()) {
    const auto [du, u] = heap.top();
    heap.pop();
    if (done[u] || du > d[u]) continue;
    done[u] = 1;
    for (uint32_t i = star.nbr_offset[u]; i < star.nbr_offset[u + 1]; ++i) {
      const uint32_t w = star.neighbours[i];
      if (!done[w]) relax(w, du + norm(m.positions[w] - m.positions[u]));
    }
    if (method != GeodesicMethod::FastMarching) continue;
    // Triangle updates: in each face (u, w, x) with w settled, x gets the planar-front distance.
    for (uint32_t i = star.offset[u]; i < star.offset[u + 1]; ++i) {
      const Tri& t = m.triangles[star.faces[i]];
      for (int k = 0; k < 3; ++k) {
        const uint32_t x = t[static_cast<size_t>(k)];
        if (x == u || done[x]) continue;
        const uint32_t w = t[0] != u && t[0] != x ? t[0] : t[1] != u && t[1] != x ? t[1] : t[2];
        if (!done[w]) continue;
        relax(x, triangle_update(m.positions[u], m.positions[w], m.positions[x], d[u], d[w]));
      }
    }
  }
  return d;
}

}  // namespace prm::remesh
