// Paper §2.3, last paragraph: edges joining vertices of different reliefs are flipped while that decreases
// the surface area.
#include <deque>

#include "prm/vec3.h"
#include "seam_optimizer.h"

namespace prm::remesh {

// Flip e if both new triangles are valid and the area shrinks.
bool SeamOptimizer::try_area_flip(EH e) {
  Quad q;
  if (!flippable(e, q) || !(q.area_after < q.area_before * (1.0 - 1e-9)) || !flip_is_valid(q)) return false;
  mesh_.flip(e);
  return true;
}

size_t SeamOptimizer::reduce_area_by_flips() {
  std::deque<int> queue;
  std::vector<uint8_t> queued(mesh_.n_edges(), 0);
  for (auto e : mesh_.edges())
    if (!mesh_.status(e).deleted() && joins_reliefs(e)) {
      queue.push_back(e.idx());
      queued[static_cast<size_t>(e.idx())] = 1;
    }
  size_t flips = 0;
  const size_t limit = 50 * mesh_.n_edges() + 1000;
  while (!queue.empty() && flips < limit) {
    const EH e(queue.front());
    queue.pop_front();
    queued[static_cast<size_t>(e.idx())] = 0;
    if (mesh_.status(e).deleted() || !joins_reliefs(e) || !try_area_flip(e)) continue;
    ++flips;
    const HH h = mesh_.halfedge_handle(e, 0), o = mesh_.halfedge_handle(e, 1);
    for (HH k : {mesh_.next_halfedge_handle(h), mesh_.prev_halfedge_handle(h), mesh_.next_halfedge_handle(o),
                 mesh_.prev_halfedge_handle(o)}) {
      const EH n = mesh_.edge_handle(k);
      if (!queued[static_cast<size_t>(n.idx())] && joins_reliefs(n)) {
        queue.push_back(n.idx());
        queued[static_cast<size_t>(n.idx())] = 1;
      }
    }
  }
  return flips;
}

}  // namespace prm::remesh
