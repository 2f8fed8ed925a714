// Issue 22: an open surface's boundary loops are kept by the remesher vertex for vertex (every input boundary vertex
// and every grid crossing of a boundary edge is a vertex of the output). A scan's boundary is dense and irregular, so
// before remeshing `pack` may thin it out: a 1-D simplification of each loop, by collapsing boundary vertices into a
// neighbour along the loop while the loop stays within a tolerance of the input's.
#pragma once

#include <cstddef>

#include "prm/mesh.h"

namespace prm::pipeline {

struct BoundarySimplification {
  size_t boundary_vertices_before = 0, removed = 0;
  double max_distance = 0;  // the largest distance of a removed boundary vertex to the simplified loop (model units)
};

// mesh: an oriented 2-manifold with boundary (no pinches). Each boundary vertex v whose removal keeps every input
// boundary vertex that the new edge (prev(v), next(v)) stands for within `tolerance` of it goes: v collapses into the
// nearer of its two loop neighbours (a half-edge collapse along a boundary edge), if that keeps the mesh a 2-manifold
// (the link condition), every loop at three vertices or more and every moved face's normal within 60 degrees of
// where it was. Cheapest first (the distance of v to the edge (prev, next)). Vertex properties follow their
// vertices; unused vertices are dropped. Interior vertices never move.
BoundarySimplification simplify_boundary(Mesh& mesh, double tolerance);

}  // namespace prm::pipeline
