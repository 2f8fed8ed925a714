// Metro-style sampling of a triangle surface: points at the vertices, along the edges and inside the faces.
//
// Following Metro (Cignoni, Rocchini, Scopigno 1998): every referenced vertex is a sample; each edge (shared edges
// once) gets a number of evenly spaced interior samples proportional to its length; each face gets a number of
// uniformly random interior samples proportional to its area. Per-edge and per-face counts are rounded with error
// diffusion along the edge/face order, so the totals match the requested densities and every element gets its
// share (stratified sampling; Metro's "-S0" Monte Carlo face sampling).
//
// The result depends only on the mesh and the options (seed included), never on the number of threads: each face
// draws its random points from its own counter-based generator.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prm/mesh.h"

namespace prm {

// How a sample budget is split between vertices, edges and faces.
enum class SampleBudget {
  // Metro's rule: `samples` in all. Every referenced vertex first (even if there are more than `samples`); with the
  // remaining n samples and the area a, the edges get sqrt(n / a) samples per unit length (so that they are about
  // as dense along the edges as inside the faces), but never more than n in all; what is then left goes to the
  // faces, by area. Below a few samples per face, the faces get none.
  Metro,
  // MeshLab's "Hausdorff Distance" filter: every referenced vertex, plus `samples` spread over the edges by length,
  // plus `samples` spread over the faces by area.
  PerKind,
};

struct SamplingOptions {
  size_t samples = 100000;
  SampleBudget budget = SampleBudget::Metro;
  bool vertices = true;  // sample the referenced vertices
  bool edges = true;     // sample along the (unique) edges
  bool faces = true;     // sample inside the faces
  uint64_t seed = 0;     // face samples' random positions
};

struct SurfaceSamples {
  std::vector<Vec3> points;  // vertex samples first, then edge samples (edge by edge), then face samples (face by face)
  size_t vertex_samples = 0;
  size_t edge_samples = 0;
  size_t face_samples = 0;
  double area = 0;         // area of the sampled surface
  double edge_length = 0;  // total length of its unique edges
};

// Throws prm::InputError if a triangle refers to a missing vertex.
SurfaceSamples sample_surface(const Mesh& mesh, const SamplingOptions& options);

// Total area of the mesh's triangles.
double surface_area(const Mesh& mesh);

}  // namespace prm
