#include "relief_topology.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

#include "prm/error.h"
#include "prm/vec3.h"

namespace prm::remesh {

VertexStar vertex_star(const Mesh& m, bool with_neighbours) {
  const size_t nv = m.positions.size();
  VertexStar s;
  s.offset.assign(nv + 1, 0);
  for (const Tri& t : m.triangles)
    for (uint32_t v : t) ++s.offset[v + 1];
  for (size_t v = 0; v < nv; ++v) s.offset[v + 1] += s.offset[v];
  s.faces.resize(s.offset[nv]);
  {
    std::vector<uint32_t> fill(s.offset.begin(), s.offset.end() - 1);
    for (uint32_t f = 0; f < m.triangles.size(); ++f)
      for (uint32_t v : m.triangles[f]) s.faces[fill[v]++] = f;
  }
  if (!with_neighbours) return s;
  // The other corners of the faces around v, deduplicated: as many as faces for an inner manifold vertex.
  s.nbr_offset.assign(nv + 1, 0);
  s.neighbours.reserve(s.faces.size() + nv / 8);
  uint32_t tmp[64];
  std::vector<uint32_t> big;
  for (uint32_t v = 0; v < nv; ++v) {
    const size_t n = 2 * (s.offset[v + 1] - s.offset[v]);
    uint32_t* buf = tmp;
    if (n > 64) {
      big.resize(n);
      buf = big.data();
    }
    size_t k = 0;
    for (uint32_t i = s.offset[v]; i < s.offset[v + 1]; ++i)
      for (uint32_t w : m.triangles[s.faces[i]])
        if (w != v) buf[k++] = w;
    std::sort(buf, buf + k);
    k = static_cast<size_t>(std::unique(buf, buf + k) - buf);
    s.neighbours.insert(s.neighbours.end(), buf, buf + k);
    s.nbr_offset[v + 1] = static_cast<uint32_t>(s.neighbours.size());
  }
  s.length.resize(s.neighbours.size());
  for (uint32_t v = 0; v < nv; ++v)
    for (uint32_t i = s.nbr_offset[v]; i < s.nbr_offset[v + 1]; ++i)
      s.length[i] = norm(m.positions[s.neighbours[i]] - m.positions[v]);
  return s;
}

std::vector<std::array<int32_t, 3>> edge_adjacency(const Mesh& m, const VertexStar& star) {
  const size_t nf = m.triangles.size();
  std::vector<std::array<int32_t, 3>> opp(nf, {-1, -1, -1});
  for (size_t f = 0; f < nf; ++f) {
    const Tri& t = m.triangles[f];
    for (size_t k = 0; k < 3; ++k) {
      if (opp[f][k] >= 0) continue;  // set from the other side
      const uint32_t a = t[k], b = t[(k + 1) % 3];
      // The other faces around a that also use b; the first face to look at an edge sees all of them.
      int found = 0;
      for (uint32_t i = star.offset[a]; i < star.offset[a + 1]; ++i) {
        const uint32_t g = star.faces[i];
        if (g == f) continue;
        const Tri& s = m.triangles[g];
        const int kb = s[0] == b ? 0 : s[1] == b ? 1 : s[2] == b ? 2 : -1;
        if (kb < 0) continue;
        ++found;
        opp[f][k] = static_cast<int32_t>(g);
        // In g the edge runs from b to a (consistent orientation) or from a to b.
        const size_t ka = s[(kb + 1) % 3] == a ? static_cast<size_t>(kb) : static_cast<size_t>((kb + 2) % 3);
        opp[g][ka] = static_cast<int32_t>(f);
      }
      if (found > 1)
        throw InputError("non-manifold edge (" + std::to_string(std::min(a, b)) + ", " +
                         std::to_string(std::max(a, b)) + ") is shared by " + std::to_string(found + 1) + " faces");
    }
  }
  return opp;
}

PinchReport find_pinched_vertices(const Mesh& m, const VertexStar& star) {
  PinchReport report;
  std::vector<uint32_t> parent;
  std::vector<std::pair<uint32_t, uint32_t>> seen;  // (other vertex, first local face using the edge to it)
  for (uint32_t v = 0; v + 1 < star.offset.size(); ++v) {
    const uint32_t first = star.offset[v], n = star.offset[v + 1] - first;
    if (n < 2) continue;
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    // Faces around v are in one fan when they share an edge (v, w).
    seen.clear();
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t w : m.triangles[star.faces[first + i]]) {
        if (w == v) continue;
        auto it = std::find_if(seen.begin(), seen.end(), [&](const auto& e) { return e.first == w; });
        if (it == seen.end()) seen.push_back({w, i});
        else parent[find(i)] = find(it->second);
      }
    size_t fans = 0;
    for (uint32_t i = 0; i < n; ++i) fans += find(i) == i;
    if (fans > 1 && report.pinched++ == 0) {
      report.first = v;
      report.fans = fans;
    }
  }
  return report;
}

}  // namespace prm::remesh
