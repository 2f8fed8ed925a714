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

// The same samples without storing them (issue 21: 24 bytes a sample, 20 samples an input vertex at Metro's ten per
// face, were most of a large input's memory): the counts per vertex, edge and face, from which any chunk of
// kSampleChunk consecutive samples is computed on demand, equal to the stored ones bit for bit. About 50 bytes a
// vertex of the mesh instead of 24 a sample. The mesh must outlive the plan and not change.
class SamplePlan {
 public:
  static constexpr size_t kSampleChunk = 1024;
  // Throws prm::InputError if a triangle refers to a missing vertex.
  SamplePlan(const Mesh& mesh, const SamplingOptions& options);
  size_t size() const { return vertex_samples + edge_samples + face_samples; }
  size_t chunks() const { return (size() + kSampleChunk - 1) / kSampleChunk; }
  // Samples [c * kSampleChunk, min(size(), (c + 1) * kSampleChunk)) into out (resized to their number).
  void chunk(size_t c, std::vector<Vec3>& out) const;

  size_t vertex_samples = 0;
  size_t edge_samples = 0;
  size_t face_samples = 0;
  double area = 0;
  double edge_length = 0;

 private:
  // Where a chunk starts: the element (vertex, unique edge or face, in sample order) and the samples of it before.
  struct Start {
    size_t element = 0;
    uint32_t skip = 0;
  };
  const Mesh& mesh_;
  uint64_t seed_ = 0;
  std::vector<uint32_t> vertices_;     // referenced vertices, in index order
  std::vector<uint64_t> edges_;        // unique edges (lower << 32 | higher), in sorted order
  std::vector<uint32_t> edge_counts_;  // samples inside each edge
  std::vector<uint32_t> face_counts_;  // samples inside each face
  std::vector<Start> starts_;          // one per chunk
};

// Every sample of the plan, stored. Throws prm::InputError if a triangle refers to a missing vertex.
SurfaceSamples sample_surface(const Mesh& mesh, const SamplingOptions& options);

// Total area of the mesh's triangles.
double surface_area(const Mesh& mesh);

}  // namespace prm
