// What the decoder outputs is the PRM quantized to its frame. Vertices that the remesher placed less than a
// quantization step apart (sliced vertices next to lattice points, seam vertices) can round to one point, and a
// triangle whose corners round onto one line loses its area, or a sliver turns over: the stream would not hold the
// mesh that was remeshed. This pass moves such vertices to a nearby free quantization point (two steps, three where
// two do not help), or collapses an edge whose ends cannot be told apart, so that no triangle has zero area or turns
// over and no two vertices share a position after quantization.
#pragma once

#include <cstddef>

#include "prm/aabb_tree.h"
#include "prm/mesh.h"
#include "prm/remesh/resample.h"

namespace prm::remesh {

struct QuantizedSeparationStats {
  size_t degenerate_faces = 0;     // faces of zero area after quantization, before the pass
  size_t rounding_turned = 0;      // faces whose quantized normal points against their real one, or (with the input)
                                   // faces that faced the input as remeshed and do not as quantized, before the pass
  size_t coincident_vertices = 0;  // vertices that shared their quantized position with another, before the pass
  size_t moved = 0;                // vertices moved (to a quantization point; lattice vertices along their height)
  size_t unresolved = 0;           // faces still of zero area or turned, or vertices still sharing a position, after it
  size_t collapsed = 0;            // edges collapsed: their ends shared a point and neither could move, or an edge of
                                   // a face no move mends (zero area or turned)
  size_t boundary_rounded = 0;    // mesh-boundary vertices coded at a point nearer the input's boundary than their
                                   // rounding (issue 22)
  size_t turned = 0;               // faces that faced the input as remeshed and face away from it as quantized (at
                                   // the input's face nearest their quantized centroid), after the last pass
};

// prm: a merged PRM with its labels and frame. A vertex that is not on a lattice moves to one of the quantization
// points within two steps of where it was (nearest first); a lattice vertex moves along its relief's height axis
// by one or two steps (its lattice position, what makes a triangle regular, is kept). A move is taken only if every
// triangle around the vertex keeps a non-zero area and its orientation; moved vertices sit exactly on their
// quantization point, so that the search and the encoder see the same mesh. With the input and its tree, a move is
// also refused if a moved triangle would face away from the input's normal at the point nearest its centroid (the
// orientation test of the remesher's invariants), as remeshed and as quantized; and a face that faced the input as
// remeshed but does not as quantized (its corners rounded over a crease or a thin part's rim) is mended like one
// the rounding turned over. A face that no move mends has an edge collapsed if that keeps every face's side.
// An open input (issue 22): each vertex on the mesh boundary (the remesher never moves them) is first coded at the
// free quantization point within two steps per coordinate nearest the input's boundary polyline (not the nearest
// one) where every face around it keeps an area and its side; the passes then move other corners first, and
// collapse edges first whose end off the boundary goes; a boundary vertex they must move goes to the point nearest
// the polyline; a boundary vertex is never collapsed away.
// move_bound > 0 (the local refinement's bound, --local-refinement): while the input's side is kept, no move takes a
// vertex farther than that from the input (unless it already is); the edge collapses and the last pass still may.
// centroid_faces: per face, the input face nearest its centroid as given (AabbTree::closest's), or AabbTree::kNoFace
// (HeightFitOptions::centroid_faces); the first pass takes it instead of searching.
QuantizedSeparationStats separate_quantized_vertices(PrmMesh& prm, const Mesh* input = nullptr,
                                                     const AabbTree* tree = nullptr, double move_bound = 0,
                                                     const std::vector<uint32_t>* centroid_faces = nullptr);

}  // namespace prm::remesh
