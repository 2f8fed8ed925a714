// Surface-to-surface distance as the Metro tool measures it (Cignoni, Rocchini, Scopigno 1998) and MeshLab's
// "Hausdorff Distance" filter computes it: one surface is sampled — every vertex, `samples` points spread uniformly
// along the edges and `samples` area-weighted random points on the faces — and each sample's distance to the other
// surface is measured exactly through an AABB tree. The one-sided mean, RMS and maximum are over all samples; the
// symmetric values are the larger of the two directions.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/mesh.h"

namespace prm {

struct MetroOptions {
  size_t samples = 100000;  // edge samples and face samples per direction (each), as MeshLab's SampleNum
  uint64_t seed = 1;
  bool sample_vertices = true, sample_edges = true, sample_faces = true;
};

struct OneSidedDistance {
  double mean = 0, rms = 0, max = 0;
  size_t samples = 0;
};

struct DistanceReport {
  OneSidedDistance a_to_b, b_to_a;
  double mean = 0, rms = 0, max = 0;  // symmetric: the larger of the two directions
  double diagonal = 0;                // of A's bounding box: the unit of the relative figures
  double rel(double d) const { return diagonal > 0 ? d / diagonal : 0; }
};

// Points on the surface of `mesh` as Metro samples it.
std::vector<Vec3> sample_surface(const Mesh& mesh, const MetroOptions& options);

// Distances from points to a surface.
OneSidedDistance distance_to_surface(const std::vector<Vec3>& points, const AabbTree& surface);

DistanceReport metro_distance(const Mesh& a, const Mesh& b, const MetroOptions& options = {});

// A reference surface prepared once (its tree and its samples) and compared with many candidates: the remesher's
// grid-size search compares every candidate with the same input.
class MetroReference {
 public:
  MetroReference(const Mesh& reference, const MetroOptions& options = {});
  DistanceReport compare(const Mesh& candidate) const;  // a = reference, b = candidate
  double diagonal() const { return diagonal_; }

 private:
  MetroOptions options_;
  AabbTree tree_;
  std::vector<Vec3> samples_;
  double diagonal_ = 0;
};

}  // namespace prm
