// Paper §2.1: "each relief is split into connected components; each component is one relief". Components of equal
// labels across edges, the merging of reliefs too small to hold a grid triangle, and the boundary length.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "prm/mesh.h"
#include "prm/remesh/reliefs.h"

namespace prm::remesh {

// face_relief[f]: component id of face f; faces are connected through edges whose two faces have the same label.
// Ids are numbered in order of their lowest face; Relief::area and ::faces are filled in.
void label_components(const Mesh& mesh, const std::vector<std::array<int32_t, 3>>& adjacency,
                      const std::vector<int8_t>& axis, std::vector<int32_t>& face_relief,
                      std::vector<Relief>& reliefs);

// A relief smaller than min_area (slivers where the envelope turns for a moment, islands left by snapping) holds
// no grid triangle at any useful grid size, and its seams cost a PRM stream far more than its area. Each one takes
// the axis of the neighbour it shares the longest boundary with among those whose axis every one of its faces faces
// by at least min_facing (0 < min_facing <= tau: the merged relief is still a height field over its axis). Repeats
// while something changes (at most `passes` times); returns the number of reliefs merged.
size_t merge_small_reliefs(const Mesh& mesh, const std::vector<std::array<int32_t, 3>>& adjacency,
                           const std::vector<Vec3>& face_normals, double min_facing, double min_area, int passes,
                           std::vector<int8_t>& axis, std::vector<int32_t>& face_relief, std::vector<Relief>& reliefs);

// Total length of the edges whose two faces lie in different reliefs, each edge once.
double relief_boundary_length(const Mesh& mesh, const std::vector<std::array<int32_t, 3>>& adjacency,
                              const std::vector<int32_t>& face_relief);

}  // namespace prm::remesh
