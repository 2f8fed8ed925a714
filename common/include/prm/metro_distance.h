// Surface-to-surface distance between two triangle meshes as the Metro tool measures it (Cignoni, Rocchini,
// Scopigno: "Metro: measuring error on simplified surfaces", 1998): the error measure of the paper's Table 1
// (paper §4, "the mean square error output by the Metro tool", as a fraction of the bounding-box diagonal).
//
// Each surface is sampled (prm/surface_sampler.h: every vertex, points along the edges, points inside the faces) and
// every sample's distance to the other surface is found exactly through an AABB tree (prm/aabb_tree.h). For each
// direction A→B and B→A this gives the mean, the RMS and the maximum of the sample distances, every sample weighing
// the same, as in Metro and in MeshLab's "Hausdorff Distance" filter. The symmetric figures are the larger of the two
// directions; the symmetric maximum is the (sampled) Hausdorff distance.
//
// Sampling and queries run in parallel (oneTBB). Results depend only on the meshes and the options (seed included),
// not on the number of threads; swapping A and B swaps the one-sided figures exactly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/mesh.h"
#include "prm/surface_sampler.h"

namespace prm {

struct MetroOptions {
  // Samples per surface, split between vertices, edges and faces as `budget` says. 0: samples_per_face per face of
  // the mesh with more faces. The distances' cost is linear in this number.
  size_t samples = 0;
  // With samples = 0: this many per face (Metro's default, 10). Fewer make a cheaper estimate in which the vertex
  // samples weigh more (`prm pack` searches with fewer at its lower efforts and reports with 10).
  double samples_per_face = 10;
  // With samples = 0 and max_samples > 0: at most this many per surface (a cheaper estimate for a large mesh, whose
  // samples_per_face x faces would be tens of millions; `prm pack`'s search estimates, issue 21). 0: no cap.
  size_t max_samples = 0;
  SampleBudget budget = SampleBudget::Metro;
  uint64_t seed = 1;  // random positions of the face samples (both surfaces use the same seed)
  bool sample_vertices = true;
  bool sample_edges = true;
  bool sample_faces = true;
  bool progress = false;  // show a prm::Progress line on stderr (terminals only)
};

// Distances from the samples of one surface to the other surface.
struct OneSidedDistance {
  double mean = 0;
  double rms = 0;
  double max = 0;
  size_t samples = 0;  // vertex_samples + edge_samples + face_samples
  size_t vertex_samples = 0;
  size_t edge_samples = 0;
  size_t face_samples = 0;
  double area = 0;  // area of the sampled surface
};

struct DistanceReport {
  OneSidedDistance a_to_b;  // samples of A, distances to B
  OneSidedDistance b_to_a;  // samples of B, distances to A
  double mean = 0;          // max(a_to_b.mean, b_to_a.mean)
  double rms = 0;           // max(a_to_b.rms, b_to_a.rms)
  double max = 0;           // max(a_to_b.max, b_to_a.max): the Hausdorff distance
  double diagonal = 0;      // length of the diagonal of A's bounding box: the unit of the relative figures
  // A distance as a fraction of A's bounding-box diagonal (0 if the diagonal is 0).
  double rel(double distance) const { return diagonal > 0 ? distance / diagonal : 0; }
};

// Metro distance between A and B. Throws prm::InputError if either mesh has no triangle, a triangle refers to a
// missing vertex, or a used vertex has a non-finite coordinate.
DistanceReport metro_distance(const Mesh& a, const Mesh& b, const MetroOptions& options = {});

// How metro_distance (and MetroReference::compare) samples each of a and b: the sample count for the pair and the
// options' budget, kinds and seed.
SamplingOptions metro_sampling(const MetroOptions& options, const Mesh& a, const Mesh& b);

// Distances from sample points to the surface in `surface` (the building block of metro_distance). Statistics are
// summed in a fixed order, so they do not depend on the thread count. If per_sample is given, it receives each
// point's distance. The counts and area of the result are copied from `samples`.
OneSidedDistance distance_to_surface(const SurfaceSamples& samples, const AabbTree& surface,
                                     std::vector<double>* per_sample = nullptr);
OneSidedDistance distance_to_surface(const std::vector<Vec3>& points, const AabbTree& surface,
                                     std::vector<double>* per_sample = nullptr);

// Where the largest deviations are (the sampled Hausdorff distance's witnesses): the samples of the two directions
// with the largest distances, at most k of them, sorted by distance, largest first, each at least `separation`
// (model units) from every larger one, so that k sites are k different places rather than one spot's neighbours.
struct DeviationSite {
  Vec3 sample{};      // the sample point (on A when a_to_b, on B otherwise)
  Vec3 closest{};     // its closest point on the other surface
  uint32_t face = 0;  // the other surface's triangle that holds `closest`
  double distance = 0;
  bool a_to_b = true;
};
std::vector<DeviationSite> worst_deviations(const Mesh& a, const Mesh& b, size_t k, double separation,
                                           const MetroOptions& options = {});

// Length of the diagonal of the bounding box of the mesh's vertices (0 for an empty mesh).
double bbox_diagonal(const Mesh& mesh);

// Many candidates against one fixed mesh (the remesher's grid-size search): the reference's tree is built once, and
// its samples are kept for the next call that needs as many. The reference plays A: relative figures are fractions
// of its diagonal. compare() may be called from several threads at once.
class MetroReference {
 public:
  explicit MetroReference(Mesh reference, const MetroOptions& options = {});
  // Borrows the mesh instead of copying it (48 bytes a vertex): *reference must outlive this object, unchanged.
  explicit MetroReference(const Mesh* reference, const MetroOptions& options = {});
  // Another sampling of the same reference: shares its mesh and tree (`prm pack`'s sparse search samples and its
  // report's full ones, one copy of a large input instead of two).
  MetroReference(const MetroReference& shared, const MetroOptions& options);
  DistanceReport compare(const Mesh& candidate) const;  // A = reference, B = candidate
  // Frees the last candidate's tree (candidate_tree below), which the samplings of this mesh share.
  void forget_candidate() const;
  double diagonal() const { return diagonal_; }
  const Mesh& mesh() const { return *mesh_; }
  const AabbTree& tree() const { return *tree_; }
  const MetroOptions& options() const { return options_; }

 private:
  // The samples are not stored (SamplePlan): at Metro's ten per face they took 24 bytes each, 480 a vertex.
  std::shared_ptr<const SamplePlan> samples_for(size_t count) const;
  // The candidate's tree: the last candidate's again for the same mesh, or refitted (AabbTree::refit) for the same
  // triangles moved (hcpu7: `prm pack`'s sparse and full-density measurements of one grid or stream, and its
  // lambda streams). Metro reads distances only, which do not depend on the tree's layout.
  std::shared_ptr<const AabbTree> candidate_tree(const Mesh& candidate) const;
  struct LastCandidate {
    std::mutex mutex;
    std::vector<Tri> triangles;
    std::vector<Vec3> positions;
    std::shared_ptr<AabbTree> tree;
  };

  std::shared_ptr<const Mesh> mesh_;
  MetroOptions options_;
  std::shared_ptr<const AabbTree> tree_;
  double diagonal_ = 0;
  mutable std::mutex mutex_;
  mutable std::shared_ptr<const SamplePlan> samples_;
  mutable size_t samples_count_ = 0;
  std::shared_ptr<LastCandidate> last_ = std::make_shared<LastCandidate>();  // shared by the samplings of one mesh
};

}  // namespace prm
