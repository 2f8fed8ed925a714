// A bounding-volume hierarchy over the triangles of a mesh, for closest-point queries (Metro-style distances,
// reference normals). Built in O(n log n) by median splits; queries are exact point-triangle distances.
#pragma once

#include <cstdint>
#include <vector>

#include "prm/mesh.h"

namespace prm {

class AabbTree {
 public:
  AabbTree() = default;
  explicit AabbTree(const Mesh& mesh);

  struct Hit {
    double distance2 = 0;  // squared distance
    Vec3 point{0, 0, 0};   // closest point on the surface
    uint32_t face = UINT32_MAX;
  };
  // Closest point of the surface to p. The tree must not be empty.
  Hit closest(const Vec3& p) const;
  // Same, with an upper bound on the squared distance known in advance (a hint: faster when tight).
  Hit closest(const Vec3& p, double bound2) const;
  bool empty() const { return tris_.empty(); }

 private:
  struct Node {
    Vec3 lo, hi;
    uint32_t first;  // leaf: first triangle in order_; inner: right child (left child is this + 1)
    uint32_t count;  // leaf: triangle count; inner: 0
  };
  struct Triangle {
    Vec3 a, b, c;
  };
  uint32_t build(const Mesh& mesh, uint32_t begin, uint32_t end, std::vector<uint32_t>& order,
                 const std::vector<Vec3>& centroid);
  std::vector<Node> nodes_;
  std::vector<Triangle> tris_;   // in leaf order
  std::vector<uint32_t> face_;   // original face of tris_[i]
};

// Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision Detection §5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace prm
