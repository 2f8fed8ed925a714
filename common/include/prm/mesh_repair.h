// `prm repair`: what the remesher needs before it starts — a closed 2-manifold.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "prm/mesh.h"

namespace prm {

struct RepairReport {
  size_t repeated_index_removed = 0;  // faces that used a vertex twice
  size_t duplicate_removed = 0;       // faces repeating an earlier face's vertices
  size_t holes_filled = 0;            // boundary loops closed by a fan around the loop's centroid (paper §4)
  size_t fill_triangles = 0;
  size_t unreferenced_removed = 0;
  std::vector<std::string> notes;
};

// Removes repeated-index and duplicate faces, then closes every boundary loop with a triangle fan around its
// centroid. Throws prm::InputError (naming the edge or vertex) for non-manifold or inconsistently oriented input,
// which cannot be repaired safely. Properties are dropped (the face set changes).
Mesh repair_mesh(const Mesh& mesh, RepairReport* report = nullptr);

}  // namespace prm
