// The connectivity the relief construction needs, built once from a vertex -> faces table: face adjacency across
// edges (which also finds non-manifold edges), pinched vertices, and the vertex neighbours of the distance fields.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "prm/mesh.h"

namespace prm::remesh {

struct VertexStar {
  std::vector<uint32_t> offset;      // per vertex + 1, into faces
  std::vector<uint32_t> faces;       // the faces around each vertex
  std::vector<uint32_t> nbr_offset;  // per vertex + 1, into neighbours / length (empty unless asked for)
  std::vector<uint32_t> neighbours;  // each neighbour once
  std::vector<double> length;        // |p(neighbour) - p(vertex)|
};

// with_neighbours: also the neighbours and edge lengths (for geodesic_distance()).
VertexStar vertex_star(const Mesh& mesh, bool with_neighbours);

// The face across edge (t[k], t[k + 1]) of every face, -1 on a boundary edge. Throws prm::InputError on an edge
// with three or more faces.
std::vector<std::array<int32_t, 3>> edge_adjacency(const Mesh& mesh, const VertexStar& star);

struct PinchReport {
  size_t pinched = 0;  // vertices whose faces form two or more edge-connected fans
  uint32_t first = 0;  // the lowest such vertex
  size_t fans = 0;     // its number of fans
};
PinchReport find_pinched_vertices(const Mesh& mesh, const VertexStar& star);

}  // namespace prm::remesh
