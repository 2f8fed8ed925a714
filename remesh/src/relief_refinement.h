// Paper §2.1: "the reliefs are not [unions of the original triangles]: some triangles need to be subdivided."
// Splits every face a relief boundary crosses along the zero sets of the differences d_v - d_w, so that the labelled
// pieces tile the input surface exactly.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "prm/mesh.h"
#include "relief_axes.h"

namespace prm::remesh {

struct Refinement {
  Mesh mesh;                         // the input's vertices (same ids), then the split points, then inner points
  std::vector<int8_t> axis;          // label (axis 0..5) per refined face
  std::vector<int32_t> source_face;  // the input face each refined face lies in
  size_t split_faces = 0;            // input faces cut into more than one label
  size_t inner_points = 0;           // points inside a face where three or more labels meet
};

// adjacency: the face across edge (t[k], t[k+1]) of every face, -1 on a boundary (face_adjacency()).
// fields: the six distance fields per vertex. closest: per face, the axis closest to its normal, used where all
// six fields vanish on the whole face. snap: fraction of an edge below which a labelled piece is dropped
// (upper_envelope()).
//
// Guarantees: the refined mesh is geometrically the input (split points are on input edges, inner points inside
// input faces); it is conforming (the split points of an edge are computed once, from the edge's data, and used by
// both faces; every split point is a vertex of the triangles on both sides: no T-junctions); edge-manifold with the
// input's boundary; no triangle has zero area (three boundary points of a face are collinear exactly when they lie
// on one side, which is decided combinatorially, not by a rounded area); and a face takes a label only from a piece
// of its own edges, where that field is positive, so a face of A_v (n . v < tau) never gets label v.
Refinement refine_along_relief_boundaries(const Mesh& mesh, const std::vector<std::array<int32_t, 3>>& adjacency,
                                          const std::vector<AxisValues>& fields, const std::vector<int8_t>& closest,
                                          double snap, bool parallel);

}  // namespace prm::remesh
