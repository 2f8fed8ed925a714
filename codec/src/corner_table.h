// Corner-table helpers (Rossignac): corner c of triangle c / 3; next and previous corner in the triangle; the
// opposite corner across the edge facing c. Standard library only; used by both sides.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace prm::codec {

inline uint32_t corner_next(uint32_t c) { return c % 3 == 2 ? c - 2 : c + 1; }
inline uint32_t corner_prev(uint32_t c) { return c % 3 == 0 ? c + 2 : c - 1; }

// Opposite corners of an indexed triangle mesh (3 vertex ids per triangle, all < num_vertices): opp[c] is the corner
// across the edge facing c, or -1 on a boundary. Fails (returning the offending triangle in `bad_triangle`) when an
// edge has more than two triangles or two triangles traverse an edge in the same direction.
enum class BuildResult : uint8_t { ok, non_manifold_edge, inconsistent_orientation };
BuildResult build_opposites(const std::vector<uint32_t>& corner_vertex, uint32_t num_vertices,
                            std::vector<int32_t>& opp, uint32_t* bad_triangle);

}  // namespace prm::codec
