// Paper §2.3, first step: the resampled reliefs are joined into one closed manifold. Along every edge pq of the
// refined mesh that separates two reliefs, the vertices each relief put on pq form a loop p -> (relief 1) -> q ->
// (relief 2) -> p, filled with zero-area triangles. Where both reliefs put a vertex at the same point of pq (the same
// grid plane cut pq for both: reliefs of one axis pair), the pair is recorded; optimize_seams() merges it when that
// keeps the mesh manifold, which breaks the loop into two that each pass through a vertex once. (Merging them
// unconditionally is wrong at folds, where the two reliefs overlap in projection and share a grid edge.)
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "relief_mesh.h"
#include "relief_resampling.h"

namespace prm::remesh {

struct MergedVertex {
  Vec3 position{0, 0, 0};
  bool lattice = false;     // a grid vertex of relief `relief`
  int32_t relief = -1;      // the relief the vertex came from; -1 for refined vertices shared by several reliefs
  int64_t i = 0, j = 0;     // lattice coordinates (lattice vertices)
  int32_t source_face = -1; // input face the vertex lies on (or lay on, before a repair moved it)
  bool on_input = true;     // the position lies on source_face
};

struct MergedMesh {
  std::vector<MergedVertex> vertices;
  std::vector<std::array<int32_t, 3>> faces;
  std::vector<int32_t> face_relief;  // the relief a face came from; -1 for loop-fill triangles
  std::vector<std::pair<int32_t, int32_t>> coincident;  // vertex pairs at one point of a seam (see above)
  size_t fill_triangles = 0;
  // Set by optimize_seams: per face, kTriangleErrorSamples entries, the input triangle closest to each of its
  // kTriangleSamples points (triangle_samples.h), as the error flips' mean triangle error found it, on a face those
  // flips left as it was; AabbTree::kNoFace on the others and the faces it skipped. Empty: no error flips.
  std::vector<uint32_t> sample_face;
};

// reliefs[r] is the resampled relief r of the view's refined mesh.
MergedMesh merge_reliefs(const ReliefMeshView& view, const std::vector<ResampledRelief>& reliefs);

}  // namespace prm::remesh
