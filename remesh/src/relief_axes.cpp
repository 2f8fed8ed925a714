#include "relief_axes.h"

#include "prm/vec3.h"

namespace prm::remesh {

int closest_axis(const Vec3& n) {
  int best = 0;
  for (int a = 1; a < kReliefAxes; ++a)
    if (axis_component(n, a) > axis_component(n, best)) best = a;
  return best;
}

std::vector<Vec3> face_unit_normals(const Mesh& mesh) {
  std::vector<Vec3> n(mesh.triangles.size());
  for (size_t f = 0; f < n.size(); ++f) {
    const Tri& t = mesh.triangles[f];
    n[f] = normalized(triangle_normal_area2(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]));
  }
  return n;
}

}  // namespace prm::remesh
