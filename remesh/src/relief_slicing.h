// Paper §2.2, first half: the refinement of one relief by the three families of grid planes.
// Every triangle of the relief is cut by the planes through the grid lines (projected along the defining vector);
// the pieces are convex polygons, each inside one grid triangle, fanned into triangles. The refined relief is
// geometrically identical to the relief. Vertices are of three kinds: corners (vertices of the input refined mesh),
// crossings (an input edge meets a grid line) and lattice points (grid vertices inside an input triangle).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "prm/mesh.h"
#include "prm/remesh/lattice.h"
#include "relief_mesh.h"

namespace prm::remesh {

enum class SliceKind : uint8_t { Corner, Crossing, Lattice };

struct SliceVertex {  // fields ordered for packing: 112 bytes (a large input's remesh holds millions)
  SliceKind kind = SliceKind::Corner;
  bool boundary = false;       // on the relief's boundary: never moves during resampling
  uint8_t family = 0;          // Crossing: 0 (alpha = c), 1 (beta = c), 2 (alpha + beta = c)
  bool upper = false;          // Corner: upper (odd) grid triangle of the cell
  int32_t refined_vertex = -1;           // Corner: vertex of the refined mesh
  int64_t value = 0;           // Crossing: c
  int64_t segment = 0;         // Crossing: which grid edge of the line (see segment_of())
  int64_t i = 0, j = 0;        // Lattice: lattice coordinates; Corner: cell (floor alpha, floor beta)
  std::array<double, 3> F{};   // family values alpha, beta, alpha + beta (exact integers where on a line)
  Vec3 position{0, 0, 0};
  int32_t edge_a = -1, edge_b = -1;      // Crossing: refined edge, edge_a < edge_b
  double t = 0;                          // Crossing: parameter from edge_a to edge_b
  int32_t source_face = -1;              // input face the vertex lies on (for reference normals)
};
static_assert(sizeof(SliceVertex) <= 112, "SliceVertex grew: see the field order");

struct SlicedRelief {
  std::vector<SliceVertex> vertices;
  std::vector<std::array<int32_t, 3>> faces;  // oriented like the input
};

// Slices the faces `faces` (all of one relief with axis `axis`) of `refined`. The positions must be generic with
// respect to the lattice (make_generic()): no vertex and no edge crossing within kGenericMargin of a grid line.
SlicedRelief slice_relief(const ReliefMeshView& view, const std::vector<int32_t>& faces, int axis);

// The grid edge of line (family, value) that contains a point with family values F.
int64_t segment_of(int family, const std::array<double, 3>& F);

}  // namespace prm::remesh
