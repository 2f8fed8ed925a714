// A bounding-volume hierarchy (axis-aligned boxes) over the triangles of a mesh, for closest-point queries.
//
// Build: binned surface-area heuristic on the triangle centroids, O(n log n), the upper levels in parallel (oneTBB).
// Query: depth-first, nearer child first, pruned by the best squared distance so far; leaves hold at most a few
// triangles whose closest points are computed exactly in double precision (prm/point_triangle_distance.h).
// The tree copies the geometry it needs (the used vertices once, and the triangles as indices into them): the mesh
// may change or die after the build. Queries are const and may run
// concurrently from any number of threads.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "prm/mesh.h"
#include "prm/point_triangle_distance.h"

namespace prm {

class AabbTree {
 public:
  static constexpr uint32_t kNoFace = std::numeric_limits<uint32_t>::max();

  // The answer to a closest-point query: its squared distance to the query point, a point of the surface, and the
  // index (into the mesh's triangles) of a triangle it lies on.
  struct Hit {
    double distance2 = std::numeric_limits<double>::infinity();
    Vec3 point{};
    uint32_t face = kNoFace;
    bool found() const { return face != kNoFace; }
  };

  AabbTree() = default;
  // Throws prm::InputError if a triangle refers to a missing vertex or a used vertex is not finite.
  explicit AabbTree(const Mesh& mesh);
  AabbTree(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles);

  // The closest point of the surface to p. On an empty tree, returns a Hit with found() false.
  Hit closest(const Vec3& p) const;
  // Only looks for points closer than sqrt(bound2) (a known upper bound makes the search faster); returns a Hit with
  // found() false if there is none.
  Hit closest(const Vec3& p, double bound2) const;
  // Starts from `hint`, the answer for a nearby query point: the exact distance from p to the hint's triangle bounds
  // the search from the start, which makes coherent query sequences much faster. `hint` is updated in place to the
  // answer for p. A hint with found() false starts an unbounded search.
  void closest(const Vec3& p, Hit& hint) const;
  // Is some triangle within squared distance bound2 of p (at most)? Tries `hint`'s triangle first (a nearby query's
  // answer) and its neighbours in leaf order, then stops at the first triangle found that near: cheaper than closest() when the only question is
  // whether p is that near. Yes: `hint` is set to that triangle and its closest point and squared distance (not
  // necessarily the closest). No: `hint` is left as it was.
  bool within(const Vec3& p, double bound2, Hit& hint) const;
  // A known triangle instead of a search (an estimate: nearly always the closest, not always). well_inside: p
  // projects onto the interior of triangle `face`, each barycentric coordinate above kWellInside (Ericson's
  // Voronoi-region test), and no farther from the plane than that projection is from each edge: a nearer triangle
  // then folds back over this one by more than 90 degrees or is another sheet of the surface. (A margin of 0.05
  // gave the same four effort-0 streams and reused fewer samples: bench/README.md "pack effort", fifteenth round.)
  // on_face: the closest point of that triangle to p. closest_reusing: on_face(p, hint.face) where p is well inside
  // the hint's triangle, closest(p, hint) otherwise.
  static constexpr double kWellInside = 0.0;
  bool well_inside(const Vec3& p, uint32_t face) const;
  Hit on_face(const Vec3& p, uint32_t face) const;
  void closest_reusing(const Vec3& p, Hit& hint) const;

  // The same triangles (mesh.triangles as built) with their corners moved to mesh.positions: the boxes fitted again
  // in place, the layout kept. Queries give the distances a new tree gives, bit for bit (on a tie, maybe another
  // face). Throws prm::InputError if the triangles are not the tree's.
  void refit(const Mesh& mesh);

  size_t num_triangles() const { return triangles_.size(); }
  bool empty() const { return triangles_.empty(); }
  // Box of all triangles: {min corner, max corner}; both zero for an empty tree.
  std::array<Vec3, 2> bounds() const;
  // Number of nodes and depth, for tests and tuning.
  size_t num_nodes() const { return 2 * pairs_.size(); }
  int depth() const;

 private:
  // The nodes two by two, 64 bytes (one cache line): node i is side i % 2 of pairs_[i / 2]. Node 0 is the root (its
  // side 1 an empty box nothing enters); the children of an inner node are nodes 2j and 2j + 1, one pair, whose
  // boxes are stored [axis][side] so that one 8-byte load gives an axis of both. Boxes are floats rounded outwards,
  // so they always contain the double-precision triangles.
  struct alignas(64) NodePair {
    float lo[3][2];
    float hi[3][2];
    uint32_t first[2];  // leaf: first triangle in triangles_; inner: left child (even)
    uint32_t count[2];  // leaf: number of triangles (> 0); inner: 0
  };
  // A triangle's corners: indices into points_ (24 bytes a triangle with the points, instead of 72 for the corners'
  // coordinates; the tree is the largest structure a large input's pack keeps).
  struct Triangle {
    uint32_t a, b, c;
  };

  void build(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles);
  // Renumbers the pairs in depth-first order (side 0's subtree right after its parent): the parallel build numbers
  // its upper levels in the order its threads claimed them. The tree, and every query's order and answer, stay the same.
  void order_depth_first();
  // Depth-first search for a point closer than sqrt(best2); updates hit when it finds one. Triangle `skip` (a slot
  // in triangles_, or kNoFace) is not tested: the hinted query has tested it already, and its distance, best2, could
  // not be beaten by itself.
  void search(const Vec3& p, Hit& hit, double best2, uint32_t skip = kNoFace) const;

  std::vector<NodePair> pairs_;
  std::vector<Triangle> triangles_;  // in leaf order
  std::vector<Vec3> points_;         // the mesh's used vertices, numbered in the order the leaves first use them
  std::vector<uint32_t> ids_;        // triangles_[k] is the mesh's triangle ids_[k]
  std::vector<uint32_t> slot_;       // the inverse: triangle f is triangles_[slot_[f]]
};

}  // namespace prm
