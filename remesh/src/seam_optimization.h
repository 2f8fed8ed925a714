// Paper §2.3-2.4 after the loop fill: vertices on relief boundaries are collapsed onto grid vertices (never changing
// the topology), edges joining vertices of different reliefs are flipped while that reduces the area, and the
// triangles that end up flipped (normal more than 90 degrees from the input surface's nearby normal) or with zero
// area are removed by local collapses and flips. Then (ours) seam edges are flipped towards valence 6, and
// irregular edges where that brings the surface closer to the input.
#pragma once

#include <cstddef>
#include <vector>

#include "loop_fill.h"
#include "prm/aabb_tree.h"
#include "prm/remesh/resample.h"

namespace prm::remesh {

struct SeamOptions {
  double max_normal_angle_deg = 90.0;  // a triangle is flipped beyond this angle from the reference normal
  double grid_length = 1.0;            // the grid size in model units (sets the zero-area tolerance)
  // Error flips after the valence flips (error_flips.cpp, try_error_flip): an edge with no face that may be
  // regular (the seams, the irregular triangles inside a relief) is flipped when that brings its two triangles 10%
  // closer to the input and, where it moves valences away from 6, by at least this many mean triangle errors per
  // unit of (valence - 6)^2 added. Negative: no error flips; 0: valences are not weighed.
  double error_flip_weight = kDefaultErrorFlipWeight;
  // The error flips' squared distance of a triangle: closest-point samples at the first error_samples of
  // kTriangleErrorSamples fixed points (the centroid first; fewer: cheaper and coarser). Their mean triangle error
  // (the unit of the valence weight) is taken over every error_unit_stride-th face in the mesh's order (1: all).
  int error_samples = kTriangleErrorSamples;
  int error_unit_stride = 1;
};

struct SeamStats {
  size_t loops_broken = 0;        // coincident seam vertex pairs merged
  size_t boundary_collapses = 0;
  size_t area_flips = 0;
  size_t valence_flips = 0;       // seam flips towards valence 6
  size_t error_flips = 0;         // flips of irregular edges that bring the surface closer to the input
  size_t repairs = 0;             // collapses and flips that removed flipped or zero-area triangles
  size_t unrepaired = 0;          // flipped or zero-area triangles left (0 on success)
  size_t non_lattice_vertices = 0;
};

// input: the input surface (a 2-manifold; its boundary, if any, is the merged mesh's, which no pass moves); input_normals: unit normal of every input face
// (MergedVertex::source_face indexes it); input_tree: the input's faces, for the normal of the input nearest to a
// triangle (all the nearest, when the nearest point is on an edge or a corner). On return, mesh has no deleted
// elements.
SeamStats optimize_seams(MergedMesh& mesh, const Mesh& input, const std::vector<Vec3>& input_normals,
                         const AabbTree& input_tree, const SeamOptions& options);

}  // namespace prm::remesh
