// Issue 23: a grid size per relief (spec §8.4.2), chosen by equal slope. The squared interpolation error of a relief
// resampled on grid g grows as a_r g^4 (a_r: its area-weighted mean squared curvature), its bytes as area_r / g^2;
// minimising the bytes for a given total squared error makes every relief's marginal bytes per unit of squared
// error equal, which gives g_r proportional to a_r^(-1/6). The scales g_r / g go to RemeshOptions::relief_grid_scale,
// and the remesher's grid search then scales all grids together until the target error is met.
#pragma once

#include <array>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/mesh.h"
#include "prm/remesh/reliefs.h"
#include "prm/remesh/resample.h"

namespace prm::remesh {

// The detail of each relief of `layout` (built from `input` by build_reliefs): its area and the area-weighted mean
// of the squared curvature of the input faces under it (per input face: sum over its edges of half of
// dihedral^2 x length / centroid distance, over the face's area; model units^-2).
struct ReliefDetail {
  std::vector<double> area;
  std::vector<double> curvature2;
};
ReliefDetail measure_relief_detail(const Mesh& input, const ReliefLayout& layout);

struct ReliefGridOptions {
  // g_r proportional to curvature2_r^(-exponent): 1/6 from error ~ g^2 (RMS) and bytes ~ g^-2.
  double exponent = 1.0 / 6.0;
  // Scales are rounded to 2^(k / levels_per_octave), k in [finest_level, coarsest_level]: at most
  // kMaxReliefGrids distinct grid sizes (resample.h), and the scale 1 (k = 0) for the reliefs of the typical detail.
  int levels_per_octave = 4;
  int finest_level = -3;
  int coarsest_level = 4;
};
// Per relief id: its grid scale, relative to the area-weighted geometric mean detail (scale 1).
std::vector<double> allocate_relief_grid_scales(const ReliefDetail& detail, const ReliefGridOptions& options = {});

// The measured model (pack --adaptive's default): the error of each relief measured on a remeshed surface at two
// grid sizes instead of predicted from the curvature. One remesh (one grid for every relief) gives, per relief, the
// area of its faces and the mean squared distance of points on them to the input (seven points a face: the centroid,
// the edge midpoints and the points halfway between the centroid and the corners; a face belongs to the relief of
// its first grid vertex, faces without one are left out).
struct ReliefErrorSample {
  double grid = 0;  // model units
  std::vector<double> area, msq;  // per relief id; msq in model units squared
  // Per relief id: its faces sorted by their own mean squared distance and cut into kErrorQuarters runs of about
  // equal area (a face is not split), each run's area-weighted msq, lowest first (issue 23's bound on splitting a
  // relief along its detail, bench/relief_bound.py). Zeros for a relief without faces.
  static constexpr int kErrorQuarters = 4;
  std::vector<std::array<double, kErrorQuarters>> msq_quarters;
};
// Per face of prm.mesh (measure_relief_error's samples): its relief (-1: no grid vertex of a relief, not sampled),
// area, mean squared distance of its seven points to the input, and the input face closest to its centroid.
struct FaceErrors {
  std::vector<int32_t> relief;
  std::vector<double> area, msq;
  std::vector<double> sum;           // the seven squared distances' sum (msq = sum / 7)
  std::vector<uint32_t> input_face;  // AabbTree::kNoFace when not sampled
};
FaceErrors measure_face_error(const PrmMesh& prm, const AabbTree& input_tree, size_t reliefs);
ReliefErrorSample measure_relief_error(const PrmMesh& prm, const AabbTree& input_tree, size_t reliefs, double grid);

// Equal slope from two samples a (grid g_a) and b (g_b > g_a): per relief, msq_r(g) = msq_r(g_a) (g / g_a)^p_r with
// p_r fitted to the two (clamped to [kMinErrorExponent, kMaxErrorExponent]), and its bytes area_r / g^2 times one
// cost per lattice vertex for every relief. Minimising the bytes for a total squared error (sum of area_r msq_r)
// makes every relief's marginal bytes per unit of squared error equal: g_r^(p_r + 2) proportional to
// 1 / (p_r msq_r(g_a) g_a^-p_r). Scales relative to their area-weighted geometric mean, rounded as options says
// (options.exponent is not used). A relief with no samples in either keeps scale 1.
constexpr double kMinErrorExponent = 1.0;
constexpr double kMaxErrorExponent = 6.0;
std::vector<double> allocate_relief_grid_scales_measured(const ReliefErrorSample& a, const ReliefErrorSample& b,
                                                         const ReliefGridOptions& options = {});

}  // namespace prm::remesh
