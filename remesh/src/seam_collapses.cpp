// Paper §2.3: loop breaking (coincident seam vertices merged) and the collapses of the vertices on relief
// boundaries onto grid vertices, never changing the topology.
#include <algorithm>
#include <cmath>
#include <vector>
#include <queue>

#include "prm/vec3.h"
#include "openmesh_edits.h"
#include "seam_optimizer.h"

namespace prm::remesh {

// How far y lies from x's tangent plane (the error of moving x to y), plus a little of the distance.
double SeamOptimizer::collapse_cost(VH x, VH y) const {
  const Vec3 d = pos(y) - pos(x);
  const double plane = dot(d, normals_[static_cast<size_t>(mv(x).source_face)]);
  return plane * plane + 1e-3 * norm2(d);
}

// Loop breaking (paper §2.3): a coincident pair of seam vertices becomes one vertex where the link condition
// allows. The geometry does not change, so no triangle test is needed.
size_t SeamOptimizer::merge_coincident() {
  size_t merged = 0;
  for (const auto& [a, b] : m_.coincident) {
    const VH x(b), y(a);
    if (mesh_.status(x).deleted() || mesh_.status(y).deleted()) continue;
    const HH h = mesh_.find_halfedge(x, y);
    if (h.is_valid() && is_collapse_ok(mesh_, h) && !moves_boundary(h)) {
      remesh::collapse(mesh_, h);
      ++merged;
    }
  }
  return merged;
}

// The cheapest lattice neighbour y whose collapse x -> y is valid; among equal costs, the first in OpenMesh's
// order around x. The candidates are tested in that (cost, order) order, so that only the first valid one and
// the invalid ones before it pay for collapse_ok.
bool SeamOptimizer::best_lattice_target(VH x, HH& best, double& best_cost) {
  best = HH();
  best_cost = HUGE_VAL;
  struct Candidate {
    double cost;
    int order;
    HH h;
  };
  constexpr int kLocal = 16;
  Candidate local[kLocal];
  std::vector<Candidate> more;  // past kLocal lattice neighbours
  int n = 0;
  for (auto h : mesh_.voh_range(x)) {
    const VH y = mesh_.to_vertex_handle(h);
    if (!mv(y).lattice) continue;
    const Candidate c{collapse_cost(x, y), n, h};
    if (!(c.cost < best_cost)) continue;  // never a target (also a NaN)
    if (n < kLocal)
      local[n] = c;
    else
      more.push_back(c);
    ++n;
  }
  Candidate *first = local, *last = local + n;
  if (n > kLocal) {
    more.insert(more.begin(), local, local + kLocal);
    first = more.data();
    last = first + more.size();
  }
  std::sort(first, last, [](const Candidate& a, const Candidate& b) {
    return a.cost < b.cost || (a.cost == b.cost && a.order < b.order);
  });
  for (const Candidate* c = first; c != last; ++c)
    if (collapse_ok(c->h)) {
      best_cost = c->cost;
      best = c->h;
      return true;
    }
  return false;
}

size_t SeamOptimizer::collapse_seam_vertices() {
  struct Item {
    double cost;
    int x, y;
    bool operator<(const Item& o) const { return cost > o.cost; }
  };
  std::priority_queue<Item> pq;
  auto push_best = [&](VH x) {
    HH h;
    double c;
    if (!mv(x).lattice && best_lattice_target(x, h, c))
      pq.push({c, x.idx(), mesh_.to_vertex_handle(h).idx()});
  };
  // Only the connectivity changes in this pass (the vertices keep their data): a triangle's test is remembered
  // until the pass ends.
  remember_collapses_ = true;
  for (auto v : mesh_.vertices()) push_best(v);
  size_t count = 0;
  while (!pq.empty()) {
    const Item it = pq.top();
    pq.pop();
    const VH x(it.x), y(it.y);
    if (mesh_.status(x).deleted() || mesh_.status(y).deleted()) continue;
    const HH h = mesh_.find_halfedge(x, y);
    if (!h.is_valid() || !collapse_ok(h)) {
      push_best(x);
      continue;
    }
    remesh::collapse(mesh_, h);
    ++count;
    for (auto w : mesh_.vv_range(y)) push_best(w);
  }
  remember_collapses_ = false;
  collapse_memo_.clear();
  return count;
}

}  // namespace prm::remesh
