// Least-squares heights: after merging, every lattice vertex moves along its relief's axis so that the piecewise
// regular mesh approximates the input surface in the least-squares sense instead of interpolating it at the lattice
// points. The lattice projection (what makes a triangle regular) is untouched; only heights change.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/mesh.h"
#include "prm/remesh/resample.h"

namespace prm::remesh {

struct HeightFitOptions {
  int iterations = 2;
  double max_shift = 0.25;  // largest total move, in grid lengths
  // A sample's closest point is taken on a known input triangle, without a tree query, when the sample projects well
  // inside it (AabbTree::well_inside): the triangle the same sample had in the previous iteration, else the previous
  // sample's. Nearly always the same point; pack's effort 0 (on the venus, the samples' query time 0.48 -> 0.32 s).
  // The flip tests take the triangle of a face's centroid sample so too (the first ones after the first iteration's
  // samples, at the same positions): the same effort-0 streams (bench/README.md "pack effort", nineteenth round).
  bool reuse_faces = false;
  // Without reuse_faces: per face of the PRM, kTriangleErrorSamples entries, the input triangle closest to each of
  // the face's points (triangle_samples.h) at the positions given, or AabbTree::kNoFace (MergedMesh::sample_face).
  // The first iteration takes its closest point there instead of searching. Null: none.
  const std::vector<uint32_t>* closest_faces = nullptr;
  // When given, set to: per face, the input face nearest its centroid at the returned positions
  // (AabbTree::closest((a + b + c) * (1.0 / 3.0)).face, the flip test's), or AabbTree::kNoFace where not known.
  std::vector<uint32_t>* centroid_faces = nullptr;
};

struct HeightFitStats {
  size_t moved = 0;     // lattice vertices that moved
  size_t reverted = 0;  // moves undone because a triangle around the vertex would have folded
};

// prm: a merged PRM with its labels (vertex_relief, relief_axis); tree: the input's closest-point tree.
HeightFitStats fit_heights(PrmMesh& prm, const Mesh& input, const AabbTree& tree, const HeightFitOptions& options);

}  // namespace prm::remesh
