// The six defining vectors of paper §2.1 seen from face normals (docs/ARCHITECTURE.md: axis a in 0..5 =
// +x, -x, +y, -y, +z, -z), and the per-vertex values of the six distance fields.
#pragma once

#include <array>
#include <vector>

#include "prm/mesh.h"

namespace prm::remesh {

constexpr int kReliefAxes = 6;

// One value per axis: the six distance fields d_v at a vertex.
using AxisValues = std::array<double, kReliefAxes>;

// n . v for the defining vector v of axis a, without building v.
inline double axis_component(const Vec3& n, int axis) {
  const double c = n[static_cast<size_t>(axis >> 1)];
  return (axis & 1) ? -c : c;
}

// The axis whose defining vector is closest to the direction n (largest n . v); ties go to the lowest index.
int closest_axis(const Vec3& n);

// The unit outward normal of every face; the zero vector for a face without area.
std::vector<Vec3> face_unit_normals(const Mesh& mesh);

}  // namespace prm::remesh
