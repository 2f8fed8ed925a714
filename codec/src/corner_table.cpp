#include "corner_table.h"

#include <algorithm>

namespace prm::codec {

// Outgoing edges grouped by their start vertex (CSR), then matched with their reverse.
BuildResult build_opposites(const std::vector<uint32_t>& cv, uint32_t num_vertices, std::vector<int32_t>& opp,
                            uint32_t* bad_triangle) {
  const size_t nc = cv.size();
  std::vector<uint32_t> start(size_t{num_vertices} + 1, 0);
  // The edge facing corner c runs from next(c) to prev(c).
  for (size_t c = 0; c < nc; ++c) ++start[cv[corner_next(static_cast<uint32_t>(c))] + 1];
  for (uint32_t v = 0; v < num_vertices; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  std::vector<uint32_t> edges(nc);  // corner ids, grouped by edge start vertex
  for (size_t c = 0; c < nc; ++c) edges[fill[cv[corner_next(static_cast<uint32_t>(c))]]++] = static_cast<uint32_t>(c);
  opp.assign(nc, -1);
  for (size_t c = 0; c < nc; ++c) {
    const uint32_t from = cv[corner_next(static_cast<uint32_t>(c))], to = cv[corner_prev(static_cast<uint32_t>(c))];
    // Same direction twice?
    for (uint32_t k = start[from]; k < start[from + 1]; ++k) {
      const uint32_t d = edges[k];
      if (d != c && cv[corner_prev(d)] == to) {
        if (bad_triangle) *bad_triangle = static_cast<uint32_t>(c / 3);
        // Two triangles using one directed edge: either a third triangle on the edge or flipped orientation.
        uint32_t reverse = 0;
        for (uint32_t m = start[to]; m < start[to + 1]; ++m) reverse += cv[corner_prev(edges[m])] == from;
        return reverse > 0 ? BuildResult::non_manifold_edge : BuildResult::inconsistent_orientation;
      }
    }
    if (opp[c] >= 0) continue;
    int32_t match = -1;
    for (uint32_t k = start[to]; k < start[to + 1]; ++k) {
      const uint32_t d = edges[k];
      if (cv[corner_prev(d)] == from) {
        if (match >= 0) {
          if (bad_triangle) *bad_triangle = static_cast<uint32_t>(c / 3);
          return BuildResult::non_manifold_edge;
        }
        match = static_cast<int32_t>(d);
      }
    }
    if (match >= 0) {
      opp[c] = match;
      opp[static_cast<size_t>(match)] = static_cast<int32_t>(c);
    }
  }
  return BuildResult::ok;
}

}  // namespace prm::codec
