// Issue 23: a grid size per relief (spec §8.4.2), chosen by equal slope. The squared interpolation error of a relief
// resampled on grid g grows as a_r g^4 (a_r: its area-weighted mean squared curvature), its bytes as area_r / g^2;
// minimising the bytes for a given total squared error makes every relief's marginal bytes per unit of squared
// error equal, which gives g_r proportional to a_r^(-1/6). The scales g_r / g go to RemeshOptions::relief_grid_scale,
// and the remesher's grid search then scales all grids together until the target error is met.
#pragma once

#include <vector>

#include "prm/mesh.h"
#include "prm/remesh/reliefs.h"

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

}  // namespace prm::remesh
