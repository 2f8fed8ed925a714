// The triangulation of a hole's boundary loop that folds least (Liepa 2003, "Filling holes in meshes", §3: the
// triangulation whose largest dihedral angle, with its own triangles and with the faces along the loop, is
// smallest; among those, the smallest area), by dynamic programming over the loop's sub-chains, O(n^3) in the loop's
// length n. prm repair closes holes with it (a centroid fan, the paper's §4, folds back over the surface where a
// scan's rim curls: bench/README.md "Worst-case error", "Holes closed without folds").
#pragma once

#include <cstdint>
#include <unordered_set>
#include <vector>

#include "prm/mesh.h"

namespace prm {

// loop: the hole's vertices in the direction of the faces' half-edges along it (a face has loop[i] -> loop[i + 1],
// and loop[n - 1] -> loop[0]); rim_normal[i]: that face's unit normal. edges: the mesh's edges between two
// vertices of the loop (key edge_key), which no new triangle may repeat. Appends n - 2 triangles oriented as the
// mesh and returns true; returns false (out unchanged) when every triangulation repeats an edge or has a triangle
// without area (area vector at most min_area2 long).
bool triangulate_hole(const Mesh& m, const std::vector<uint32_t>& loop, const std::vector<Vec3>& rim_normal,
                      const std::unordered_set<uint64_t>& edges, double min_area2, std::vector<Tri>& out);

inline uint64_t edge_key(uint32_t a, uint32_t b) {
  return a < b ? (uint64_t{a} << 32) | b : (uint64_t{b} << 32) | a;
}

}  // namespace prm
