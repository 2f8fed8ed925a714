// Paper §2.1: reliefs with smooth boundaries. For each of the six axis directions v (docs/ARCHITECTURE.md: axis
// a in 0..5 = +x, -x, +y, -y, +z, -z) and a smoothing parameter tau, A_v holds the triangles whose outward normal n
// has n.v < tau; d_v is the geodesic distance from A_v; the relief of v is where d_v is the largest of the six.
// Triangles crossed by a relief boundary are split along the zero sets of the piecewise-linear differences
// d_v - d_w, so the reliefs tile the input exactly. Each connected component is one relief.
//
// Guarantees of build_reliefs() (tested on every real mesh, remesh/tests/relief_construction_test.cpp):
// - every face of a relief of axis v faces v: n.v >= tau > 0 for its input face, except the faces of small reliefs
//   that joined a neighbour: n.v >= min(merge_facing, tau) > 0 (at most merged_reliefs * the size limit of area);
// - the refined mesh is the input surface: its faces lie in their source faces and their areas add up to the
//   input's; vertices 0..n-1 are the input's, in order; it is conforming and edge-manifold, with the input's
//   boundary (no T-junctions: a split point is computed once per edge and used by both faces);
// - no refined face has zero area; split points are at least `snap` (a fraction of the edge) from the edge's ends
//   and from each other;
// - the result depends only on the input and the options (not on threads).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "prm/mesh.h"

namespace prm::remesh {

enum class GeodesicMethod {
  Dijkstra,      // shortest paths along edges (the paper's choice)
  FastMarching,  // the same front order with triangle updates: less metrication error (measured: ReliefConstruction.FastMarchingGivesShorterBoundariesThanDijkstra)
};

struct ReliefOptions {
  double tau = 0.2;  // in (0, 1/sqrt(3)); the paper finds 0.1-0.3 best
  GeodesicMethod geodesic = GeodesicMethod::FastMarching;
  bool naive = false;  // each triangle to the axis closest to its normal (the layout the paper improves on)
  bool parallel = true;
  // Envelope pieces shorter than this fraction of their edge are dropped (their split points snap onto the edge's
  // ends or merge), which keeps needles and slivers out of the refined mesh.
  double snap = 0.05;
  // Reliefs smaller than this many mean input triangles join a neighbour all their faces face by at least
  // merge_facing (0: keep every component). The seams of a small relief cost a PRM stream far more than its lattice
  // saves: at the paper's errors 256 and 0.02 make the streams 1.4-3.5% smaller than 16 and tau (measured:
  // docs/design/prm-stream.md, fifth pass).
  double min_relief_triangles = 256;
  double merge_facing = 0.02;  // in (0, 1/sqrt(3)); min(merge_facing, tau) applies
  // The layout mesh's face properties and comments (ReliefLayout::mesh), for its PLY file and pictures: four
  // doubles a refined face, which the remesher never reads (remesh and pack turn them off).
  bool view_properties = true;
};

struct Relief {
  int axis = 0;  // 0..5 = +x, -x, +y, -y, +z, -z
  double area = 0;
  size_t faces = 0;
};

struct ReliefLayout {
  Mesh mesh;                         // the refined mesh; face properties "relief" (int32), red, green, blue (uint8)
                                     // and a comment "prm-relief <id> axis <a>" per relief (if view_properties)
  std::vector<int32_t> face_relief;  // relief id per face of mesh
  std::vector<Relief> reliefs;       // per relief id
  std::vector<int32_t> source_face;  // per refined face: the input face it lies in
  double boundary_length = 0;        // total length of the relief boundaries (each seam edge once)
  size_t split_faces = 0;            // input faces cut by a relief boundary
  size_t inner_points = 0;           // points added inside input faces, where three or more reliefs meet
  size_t merged_reliefs = 0;         // small reliefs that joined a neighbour
};

// mesh: a 2-manifold triangle mesh, closed or with boundary. Throws prm::InputError on a non-manifold edge, on a
// pinched vertex (prm::repair_mesh() splits those), on an empty mesh, or on options out of range.
ReliefLayout build_reliefs(const Mesh& mesh, const ReliefOptions& options = {});

// The colour of relief `id` of `axis` in pictures: one hue per axis, lightness varied per relief.
std::array<uint8_t, 3> relief_colour(int axis, int id);

}  // namespace prm::remesh
