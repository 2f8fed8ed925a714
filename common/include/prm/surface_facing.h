// Which way a triangle faces a surface (issue 17's test): forwards when its normal and the normal of the surface's
// face closest to its centroid make an angle under 90 degrees. One test for the remesher's invariants (height
// fitting, the quantized separation, the local refinement) and the decoded stream's check (pipeline stream_check).
#pragma once

#include <cstdint>

#include "prm/aabb_tree.h"
#include "prm/mesh.h"
#include "prm/vec3.h"

namespace prm {

// The test against a known face of the surface (the closest to the centroid): the normals under 90 degrees apart.
inline bool faces_surface_face(const Vec3& normal, const Mesh& surface, uint32_t face) {
  const Tri& s = surface.triangles[face];
  return dot(normal, triangle_normal_area2(surface.positions[s[0]], surface.positions[s[1]], surface.positions[s[2]])) > 0;
}

// normal: the triangle's (any length, e.g. triangle_normal_area2); centroid: its centroid. tree: surface's tree.
// True when the surface has no face to compare with. `nearest`: when given, set to tree.closest(centroid).face.
inline bool faces_surface(const Vec3& normal, const Vec3& centroid, const Mesh& surface, const AabbTree& tree,
                          uint32_t* nearest = nullptr) {
  const AabbTree::Hit hit = tree.closest(centroid);
  if (nearest) *nearest = hit.face;
  return !hit.found() || faces_surface_face(normal, surface, hit.face);
}

inline bool faces_surface(const Vec3& a, const Vec3& b, const Vec3& c, const Mesh& surface, const AabbTree& tree) {
  return faces_surface(triangle_normal_area2(a, b, c), (a + b + c) * (1.0 / 3.0), surface, tree);
}

}  // namespace prm
