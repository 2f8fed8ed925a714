// What a mesh is made of, and what is wrong with it: `prm info`.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prm/mesh.h"

namespace prm {

struct ComponentReport {
  size_t vertices = 0, faces = 0, edges = 0, boundary_loops = 0;
  long euler = 0;  // V - E + F
  bool manifold = true;
  int genus =
      -1;  // (2 - euler - boundary_loops) / 2 for a manifold, oriented component; -1 otherwise
           // (a vertex shared with another component counts in both; manifold is judged per component)
};

struct MeshReport {
  size_t vertices = 0, faces = 0, edges = 0;
  size_t unreferenced_vertices = 0;
  size_t components = 0;
  size_t boundary_edges = 0, boundary_loops = 0;
  size_t non_manifold_edges = 0;     // edges with three or more faces
  size_t non_manifold_vertices = 0;  // vertices whose faces form more than one edge-connected fan (pinches)
  size_t repeated_index_faces = 0;   // a face that uses one vertex twice
  size_t zero_area_faces = 0;        // distinct vertices, zero area (collinear or coincident points)
  size_t duplicate_faces = 0;        // same three vertices as an earlier face (either orientation)
  size_t inconsistent_edges = 0;     // two faces traverse the edge in the same direction
  long euler = 0;                    // V - E + F of the whole mesh, over referenced vertices
  std::vector<ComponentReport> per_component;  // sorted by decreasing face count
  Vec3 bbox_min{0, 0, 0}, bbox_max{0, 0, 0};
  double diagonal = 0;
  // The first offenders of each kind (a few per kind), for messages ("edge (12, 40) has 3 faces").
  std::vector<std::string> examples;
  // The first offender of each topological kind (vertex indices); meaningful when its count is non-zero.
  std::array<uint32_t, 2> first_non_manifold_edge{}, first_inconsistent_edge{};
  uint32_t first_non_manifold_vertex = 0;

  bool oriented() const { return inconsistent_edges == 0; }
  bool manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0; }
  bool closed() const { return boundary_edges == 0; }
  bool clean() const { return repeated_index_faces == 0 && zero_area_faces == 0 && duplicate_faces == 0; }
  // What the remesher takes as it is; anything else goes through repair_mesh() first (which refuses what it
  // cannot fix without guessing, such as faces that are not consistently oriented).
  bool ready_for_remesh() const { return closed() && clean() && manifold() && oriented(); }
  int genus_sum() const;  // sum over components (-1 when a component has no genus)
};

// Linear-logarithmic (sort-based edge table, union-find). Throws std::invalid_argument if a triangle uses a
// vertex index out of range (read_mesh() never returns such a mesh).
MeshReport validate_mesh(const Mesh& mesh);

// The remesher and the error measure take up to fourth powers of lengths (squared distances weighted by areas), and
// quantize the bounding box into up to 2^20 steps: the coordinates must stay well inside a double's range and the
// box must be wide enough that a step is many units in the last place of its coordinates.
constexpr double kMaxRemeshCoordinate = 1e64;    // largest |coordinate|
constexpr double kMinRemeshExtent = 1e-64;       // smallest largest extent of the bounding box
constexpr double kMinRemeshExtentRelative = 1e-9;  // ... and relative to the largest |coordinate|
constexpr double kMinRemeshAreaRelative = 1e-12;   // smallest total area of the faces, relative to the extent squared
// Throws prm::InputError naming the problem when the vertices' coordinates are outside those ranges (all vertices
// coincide, or nearly for the precision of their coordinates, or a coordinate is too large or not finite) or when
// the faces have no area (all vertices on a line).
void check_remesh_range(const Mesh& mesh);

}  // namespace prm
