// Geodesic distance from a set of faces, piecewise linear and stored at vertices (paper §2.1, after [11, 16]):
// the six fields d_v of the relief construction.
#pragma once

#include <cstdint>
#include <vector>

#include "prm/mesh.h"
#include "prm/remesh/reliefs.h"
#include "relief_axes.h"
#include "relief_topology.h"

namespace prm::remesh {

// star: vertex_star(mesh, true).
// d[v] = geodesic distance from the union of the faces with source[f] != 0 (their vertices get 0); +infinity where
// no source is reachable (a component without sources). Dijkstra: shortest paths along edges. FastMarching:
// the same front order with planar-front triangle updates (Kimmel and Sethian), which removes most of the edge
// paths' metrication error.
void geodesic_distance(const Mesh& mesh, const VertexStar& star, const std::vector<uint8_t>& source,
                       GeodesicMethod method, std::vector<double>& d);

// Paper §2.1: the six fields d_v, the geodesic distance from A_v = {faces f : n_f . v < tau} (faces without area
// belong to no A_v). Where A_v is unreachable (every face of the component faces v), d_v is a common value larger
// than any finite distance. `normals` from face_unit_normals(); the six fields run in parallel if asked.
std::vector<AxisValues> axis_distance_fields(const Mesh& mesh, const VertexStar& star,
                                             const std::vector<Vec3>& normals, double tau, GeodesicMethod method,
                                             bool parallel);

}  // namespace prm::remesh
