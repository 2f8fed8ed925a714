// Geodesic distance from a set of faces, piecewise linear and stored at vertices (paper §2.1, after [11, 16]).
#pragma once

#include <cstdint>
#include <vector>

#include "prm/mesh.h"
#include "prm/remesh/reliefs.h"

namespace prm::remesh {

// The mesh's vertex adjacency and the faces around each vertex, built once for several distance fields.
struct VertexStar {
  std::vector<uint32_t> offset;      // per vertex, into faces / neighbours
  std::vector<uint32_t> faces;       // faces around each vertex
  std::vector<uint32_t> nbr_offset;
  std::vector<uint32_t> neighbours;  // vertex neighbours (each once)
};
VertexStar vertex_star(const Mesh& mesh);

// d(v) = geodesic distance from the union of the faces with source[f] != 0 (their vertices get 0). Vertices that
// no source reaches (another component) get +infinity.
std::vector<double> geodesic_distance(const Mesh& mesh, const VertexStar& star, const std::vector<uint8_t>& source,
                                      GeodesicMethod method);

}  // namespace prm::remesh
