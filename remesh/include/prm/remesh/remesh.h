// The whole remesher: reliefs (paper §2.1), resampling and merging (§2.2-2.4), and the search for the grid size
// that meets a target error (the paper chose g by hand for each model).
#pragma once

#include <functional>
#include <memory>
#include <stdexcept>
#include <vector>

#include "prm/mesh.h"
#include "prm/remesh/reliefs.h"
#include "prm/remesh/resample.h"

namespace prm::remesh {

struct RemeshOptions {
  int bits = 12;                 // quantization of the codec that will store the result (sets the lattice units)
  double step_scale = 1.0;       // the quantization step in units of 2^-bits of the extent, in [1, 2)
  ReliefOptions reliefs;         // tau, geodesics
  // The grid size: exactly one of these, or target_error and/or max_error.
  double grid_size = 0;          // model units
  double grid_fraction = 0;      // fraction of the bounding-box diagonal
  double target_error = 0;       // largest symmetric RMS distance, as a fraction of the diagonal: search g
  // Largest symmetric maximum distance (the sampled Hausdorff distance), as a fraction of the diagonal: a grid meets
  // the search's target only if the error function's max is within it too (alone, without target_error, it is the
  // target). 0: none.
  double max_error = 0;
  // Local refinement: input vertices farther than this (fraction of the diagonal) from a candidate are inserted into
  // it as irregular vertices (ResampleOptions::max_deviation). 0: max_error (0 too: none).
  double refine_error = 0;
  bool refine_thin_sheets = true;  // ResampleOptions::refine_thin_sheets
  bool refine_notches = true;      // ResampleOptions::refine_notches
  bool refine_facing_guard = true;  // ResampleOptions::refine_facing_guard
  size_t refine_rounds = 20;        // ResampleOptions::refine_rounds
  // With target_error, refine_error and no max_error: the search's grids are resampled without the local refinement,
  // and only the grid it chooses is refined (the next coarser one first when it missed the target by at most
  // kRefineLastMargin; then the next finer grids, at most kRefineLastTries in all, until one refined meets the
  // target; none: the unrefined choice). Issue 21's CPU budget: the refinement at every search step
  // cost 5-22 s CPU on the paper's models (h22max5, bench/README.md "Worst-case error"). false: every step refined.
  bool refine_last = false;
  // With refine_last and a layout: the refinement of the chosen grid is left to refine_deferred()
  // (RemeshResult::deferred), so that a caller comparing several searches refines only the one it keeps (pack's
  // effort 3: the predicted step and the next coarser one, issue 21). remesh() returns the unrefined choice.
  bool defer_refinement = false;
  double initial_grid_size = 0;  // with target_error: where the search starts (model units; 0: 1.5 mean edges)
  // A grid size per relief (spec §8.4.2, format 1.5): relief r (an id of the layout) is resampled with the grid
  // round(g x relief_grid_scale[r]) quantization steps (at least 2, at most 2^bits), g being the grid of the options
  // above or of the search, which then scales every relief's grid together. At most kMaxReliefGrids distinct
  // values. Empty: one grid g for every relief.
  std::vector<double> relief_grid_scale;
  int max_search_steps = 8;
  // With target_error: the search stops once the finest failing grid is at most this fraction (or one step) above
  // the coarsest that meets the target.
  double grid_tolerance = 0.02;
  // With target_error: the search also stops at the first grid whose error is at least this fraction of the target
  // (1: never; a lower value trades a finer grid, more bytes, for fewer remesh rounds).
  double accept_error = 1.0;
  // With target_error: the exponent p of error ~ g^p assumed for the step from the first grid (later steps fit it to
  // the last two grids). 2 is the smooth-surface law; the decoded, quantized candidates of pack grow more slowly at a
  // grid of 10-20 quantization steps (1.1-1.6 on the paper's models), since their rounding error does not shrink
  // with g.
  double first_exponent = 2.0;
  // With target_error and > 0: the search also stops at a grid g that meets the target when the next coarser grid
  // g + 1, its error extrapolated as e x ((g + 1) / g)^next_exponent, would miss it (instead of measuring g + 1).
  // 0: never (the search brackets the target between measured grids).
  double next_exponent = 0;
  // With target_error: each step aims at this fraction of the target, and rounds the predicted grid down (false: a
  // grid just below the target's, rarely over it, at the cost of more steps) or to the nearest (true).
  double aim = 0.97;
  bool round_to_nearest = false;
  // With target_error: asked before the search moves from a grid to the next one (grid: the one just measured, met:
  // whether it met the target, next: the grid the search would measure next); true ends the search there, with the
  // coarsest grid that met the target so far (TargetNotReached when none did). Empty: never.
  std::function<bool(int64_t grid, bool met, int64_t next)> stop_search;
  // The relief layout of the input (build_reliefs(input, reliefs)), when the caller built it already: a search over
  // several bit depths or step scales builds it once. Null: built here.
  const ReliefLayout* layout = nullptr;
  // The AABB tree of the input, when the caller has one (ResampleOptions::input_tree). Null: built every round.
  const AabbTree* input_tree = nullptr;
  // The most vertices a grid may give (estimated from the input's area and the lattice's cell): 0 for
  // max(kMinVertexBudget, kVertexBudgetPerInputVertex x the input's vertices). A fixed grid finer than that is
  // refused, and the search does not go finer (VertexBudgetExceeded when the target needs it).
  size_t max_vertices = 0;
  double max_normal_angle_deg = 90;
  bool parallel = true;
  bool fit_heights = true;       // least-squares heights of the lattice vertices (ResampleOptions::fit_heights)
  bool height_fit_reuse_faces = false;  // ResampleOptions::height_fit_reuse_faces
  double error_flip_weight = kDefaultErrorFlipWeight;  // error flips (ResampleOptions::error_flip_weight; < 0: none)
  int error_unit_stride = 1;  // ResampleOptions::error_unit_stride (the seam error flips' mean triangle error)
  int error_samples = kTriangleErrorSamples;  // ResampleOptions::error_samples (points per triangle, seam error flips)
};

// Symmetric RMS and maximum distance between the input and a candidate, as fractions of the input's diagonal.
struct ErrorEstimate {
  double rms = 0;
  double max = 0;
};
// The candidate is the PRM of one grid size (its mesh, frame and lattice labels).
using ErrorFunction = std::function<ErrorEstimate(const PrmMesh& candidate)>;

struct SearchStep {
  int64_t grid = 0;   // quantization steps
  double grid_size = 0;
  size_t vertices = 0;
  double regular_share = 0;
  ErrorEstimate error;
  double seconds = 0;
};

// RemeshOptions::defer_refinement: what the refinement after the search needs (remesh_pipeline.cpp).
struct DeferredRefinement;

struct RemeshResult {
  PrmMesh prm;
  ErrorEstimate error;              // of the returned mesh (measured when an error function was given)
  bool error_measured = false;
  std::vector<SearchStep> search;   // every grid size tried, in order
  size_t reliefs = 0;
  double relief_boundary_length = 0;
  double seconds_reliefs = 0, seconds_total = 0;
  // RemeshOptions::defer_refinement: the refinement still to do (refine_deferred); null when done or none.
  std::shared_ptr<const DeferredRefinement> deferred;
};

constexpr size_t kMinVertexBudget = size_t{1} << 18;
// RemeshOptions::refine_last: the grids tried with the refinement after the search, the chosen one first.
constexpr int kRefineLastTries = 3;
// RemeshOptions::refine_last: the next coarser grid is refined first when its unrefined error was at most this
// multiple of the target.
constexpr double kRefineLastMargin = 1.05;
constexpr size_t kVertexBudgetPerInputVertex = 4;
// One search step makes at most this many times the vertices of the step before (or kSearchVertexFloor): an
// extrapolation from coarse steps, where the error follows no power of the grid size, does not jump to a grid that
// costs seconds and gigabytes (CGAL's 19-vertex 3torus went from 396 vertices to 469k in one step).
constexpr size_t kSearchVertexGrowth = 16;
constexpr size_t kSearchVertexFloor = 4096;

// No grid size within the search's steps met the target error.
class TargetNotReached : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The grid asked for, or the one the target error needs, gives more vertices than RemeshOptions::max_vertices. A
// TargetNotReached too, but a finer quantization does not help.
class VertexBudgetExceeded : public TargetNotReached {
 public:
  using TargetNotReached::TargetNotReached;
};

// input: an oriented 2-manifold, closed or with boundary loops (which the output keeps: the mesh boundary is a seam
// with no neighbour, its vertices never move; issue 22), whose coordinates pass check_remesh_range()
// (prm::InputError otherwise). `error` may be empty unless target_error is set.
RemeshResult remesh(const Mesh& input, const RemeshOptions& options, const ErrorFunction& error = {});

// RemeshOptions::defer_refinement: the refinement remesh() left in result.deferred, with the same error function's
// measurements as remesh() would have made (appended to result.search); result.deferred is reset. The input and
// the layout given to remesh() must still be alive.
void refine_deferred(RemeshResult& result, const ErrorFunction& error);

}  // namespace prm::remesh
