// Paper §2.1: reliefs with smooth boundaries. For each of the six axis directions v and a smoothing parameter tau,
// A_v holds the triangles whose outward normal n has n.v < tau; d_v is the geodesic distance from A_v; the relief of
// v is where d_v is the largest of the six. Triangles crossed by a relief boundary are split along the zero sets of
// the piecewise-linear differences d_v - d_w, so the reliefs tile the input exactly; every relief triangle faces its
// axis (n.v >= tau > 0). Each connected component is one relief.
#pragma once

#include <cstdint>
#include <vector>

#include "prm/mesh.h"

namespace prm::remesh {

enum class GeodesicMethod {
  Dijkstra,      // shortest paths along edges (the paper's choice)
  FastMarching,  // Dijkstra order with planar-front triangle updates: less metrication error
};

struct ReliefOptions {
  double tau = 0.2;  // in (0, 1/sqrt(3)); the paper finds 0.1-0.3 best
  GeodesicMethod geodesic = GeodesicMethod::FastMarching;
  bool naive = false;  // each triangle to the axis closest to its normal (the layout the paper improves on)
  bool parallel = true;
};

struct Relief {
  int axis = 0;  // 0..5 = +x, -x, +y, -y, +z, -z
  double area = 0;
  size_t faces = 0;
};

struct ReliefLayout {
  Mesh mesh;                         // the refined mesh; face properties "relief", red, green, blue
  std::vector<int32_t> face_relief;  // relief id per face of mesh
  std::vector<Relief> reliefs;       // per relief id
  std::vector<int32_t> source_face;  // per refined face: the input face it lies in
  double boundary_length = 0;        // total length of the relief boundaries (each seam edge once)
  size_t split_faces = 0;            // input faces cut by a relief boundary
};

// mesh: a 2-manifold (closed or with boundary). Throws prm::InputError on non-manifold input or a tau out of range.
ReliefLayout build_reliefs(const Mesh& mesh, const ReliefOptions& options = {});

// The colour of relief `id` with `axis` in pictures: a hue per axis, shaded per component.
std::array<uint8_t, 3> relief_colour(int axis, int id);

}  // namespace prm::remesh
