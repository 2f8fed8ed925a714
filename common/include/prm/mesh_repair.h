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
  size_t pinched_vertices_split = 0;  // copies made of pinched vertices, one per extra fan of faces
  size_t zero_area_flipped = 0;       // zero-area slivers removed by flipping their longest edge
  size_t holes_filled = 0;            // boundary loops closed (by a triangulation of the loop, or a fan)
  size_t holes_fanned = 0;            // of those, closed by a fan around a new vertex at the loop's centroid (paper §4)
  size_t fill_triangles = 0;
  size_t unreferenced_removed = 0;
  std::vector<std::string> notes;
};

struct RepairOptions {
  // Close every boundary loop (paper §4, the bunny protocol; by the triangulation that folds least, not the paper's
  // fan, where the loop is short enough: hole_triangulation.h). False: the boundary loops stay, the result
  // is an oriented 2-manifold with boundary (what `prm pack` remeshes by default; issue 22).
  bool fill_holes = true;
};

// Removes repeated-index and duplicate faces, splits pinched vertices (one copy per extra fan of faces),
// flips away zero-area slivers where that is safe (the others are kept and noted), closes every boundary loop
// (up to 400 vertices, within a total cost bound: by the triangulation of the loop whose largest dihedral angle is
// smallest, Liepa 2003; otherwise, or where every triangulation would repeat an edge or have a triangle without
// area, with a triangle fan around a new vertex at its centroid, paper §4) and drops unreferenced vertices. The result is closed,
// manifold and consistently oriented. Throws prm::InputError naming the first offending edge for input that
// cannot be repaired without guessing: an edge with three or more faces, or faces that are not consistently
// oriented (after the face removals). Properties are dropped (the face set changes); comments are kept. Without
// options.fill_holes the loops stay open (and the result is closed only if the input was).
Mesh repair_mesh(const Mesh& mesh, RepairReport* report = nullptr, const RepairOptions& options = {});

// The pinch split of repair_mesh alone: each vertex whose faces form several fans (joined across edges with two
// faces) gets one copy per extra fan, at its position and with its vertex property values; the faces of that fan
// take the copy. Requires no edge with three or more faces. Returns the number of copies made
// (RepairReport::pinched_vertices_split). The geometry is unchanged.
size_t split_pinched_vertices(Mesh& m);

// What a repair changed, one phrase per kind of change it made ("2 duplicate face(s) removed", "5 hole(s) closed
// with 223 triangles"); empty when it changed nothing. (What it left as it was is in report.notes.)
std::vector<std::string> repair_summary(const RepairReport& report);

}  // namespace prm
