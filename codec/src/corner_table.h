// Corner-table helpers (Rossignac): corner c of triangle c / 3; next and previous corner in the triangle; the
// opposite corner across the edge facing c. Standard library only; used by both sides.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace prm::codec {

// x is a multiple of 3 exactly when x * (2^32 + 2) / 3 mod 2^32 <= (2^32 - 1) / 3: one multiplication instead of a
// division (the corner tests below are on the decoder's hottest paths). Corners are below 3 * 2^29 (limits.h).
inline bool multiple_of_3(uint32_t x) { return x * 0xAAAAAAABu <= 0x55555555u; }
inline uint32_t corner_next(uint32_t c) { return multiple_of_3(c + 1) ? c - 2 : c + 1; }
inline uint32_t corner_prev(uint32_t c) { return multiple_of_3(c) ? c + 2 : c - 1; }

// Opposite corners of an indexed triangle mesh (3 vertex ids per triangle, all < num_vertices): opp[c] is the corner
// across the edge facing c, or -1 on a boundary. Fails (returning the offending triangle in `bad_triangle`) when an
// edge has more than two triangles or two triangles traverse an edge in the same direction.
enum class BuildResult : uint8_t { ok, non_manifold_edge, inconsistent_orientation };
BuildResult build_opposites(const std::vector<uint32_t>& corner_vertex, uint32_t num_vertices,
                            std::vector<int32_t>& opp, uint32_t* bad_triangle);

}  // namespace prm::codec
