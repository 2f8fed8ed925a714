// §8.2 Regular patches: the connected sets of regular triangles, derived identically by the encoder and the
// decoder from the closed mesh (§6.1) and the set of irregular triangles (§7).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "closed_mesh.h"

namespace prm::codec {

// §7.1 Triangle classes.
enum TriangleClass : uint8_t {
  kRegular = 0,
  kIrregular = 1,
  kDummyTriangle = 2,  // has a dummy vertex (§6.7): neither regular nor irregular
};

// §7.1 Dummy triangles: those with a dummy vertex.
inline std::vector<uint8_t> dummy_triangles(const ClosedMesh& mesh) {
  const uint32_t nt = mesh.num_triangles();
  std::vector<uint8_t> cls(nt, kRegular);
  // A mesh without dummy vertices (no holes, §6.7) has none: one pass over the vertices instead of the corners.
  if (std::none_of(mesh.is_dummy.begin(), mesh.is_dummy.end(), [](uint8_t d) { return d != 0; })) return cls;
  for (uint32_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.is_dummy[mesh.corner_vertex[3 * t + k]]) cls[t] = kDummyTriangle;
  return cls;
}

// §8.2 Patches: scan the triangles in increasing index; an unvisited regular triangle starts a patch, grown
// breadth-first across edges to regular neighbours, visiting the neighbours across the edges opposite corners 0, 1
// and 2 in that order. `order` lists the triangles of patch p at order[start[p] .. start[p + 1]).
struct PatchSet {
  std::vector<uint32_t> order;
  std::vector<uint32_t> start;  // size patches + 1
  size_t size() const { return start.empty() ? 0 : start.size() - 1; }
};

inline PatchSet build_patches(const ClosedMesh& mesh, const std::vector<uint8_t>& cls) {
  PatchSet ps;
  const uint32_t nt = mesh.num_triangles();
  // Per triangle: 1 while it is regular and not yet in a patch (one load per neighbour looked at).
  std::vector<uint8_t> open(nt);
  for (uint32_t t = 0; t < nt; ++t) open[t] = cls[t] == kRegular;
  ps.start.push_back(0);
  for (uint32_t t0 = 0; t0 < nt; ++t0) {
    if (!open[t0]) continue;
    open[t0] = 0;
    size_t head = ps.order.size();
    ps.order.push_back(t0);
    while (head < ps.order.size()) {
      const uint32_t t = ps.order[head++];
      for (int k = 0; k < 3; ++k) {
        const uint32_t n = static_cast<uint32_t>(mesh.opp[3 * t + k]) / 3;
        if (open[n]) {
          open[n] = 0;
          ps.order.push_back(n);
        }
      }
    }
    ps.start.push_back(static_cast<uint32_t>(ps.order.size()));
  }
  return ps;
}

}  // namespace prm::codec
