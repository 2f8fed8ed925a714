// The remesher end to end, and the grid-size search.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

#include "prm/error.h"
#include "prm/mesh_validate.h"
#include "prm/progress.h"
#include "prm/remesh/remesh.h"
#include "prm/vec3.h"

namespace prm::remesh {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double bbox_diagonal(const Mesh& m) {
  if (m.positions.empty()) return 0;
  Vec3 lo = m.positions[0], hi = m.positions[0];
  for (const Vec3& p : m.positions)
    for (size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  return norm(hi - lo);
}

double surface_area(const Mesh& m) {
  double sum = 0;
  for (const Tri& t : m.triangles) sum += triangle_area(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  return sum;
}

double mean_edge_length(const Mesh& m) {
  double sum = 0;
  size_t n = 0;
  for (const Tri& t : m.triangles)
    for (size_t k = 0; k < 3; ++k) {
      sum += norm(m.positions[t[(k + 1) % 3]] - m.positions[t[k]]);
      ++n;
    }
  return n ? sum / static_cast<double>(n) : 0;
}

// A remeshed grid measured (when `error` is given) as a search step.
SearchStep search_step(const PrmMesh& prm, double step, const ErrorFunction& error,
                       std::chrono::steady_clock::time_point ts) {
  SearchStep s;
  s.grid = static_cast<int64_t>(prm.lattice.A);
  s.grid_size = static_cast<double>(s.grid) * step;
  s.vertices = prm.stats.vertices;
  s.regular_share = prm.stats.faces ? static_cast<double>(prm.stats.regular_faces) / prm.stats.faces : 0;
  if (error) s.error = error(prm);
  s.seconds = seconds_since(ts);
  return s;
}

// ResampleOptions::grid and relief_grid for grid g (RemeshOptions::relief_grid_scale).
void set_grid(ResampleOptions& ro, int64_t grid, const std::vector<double>& relief_grid_scale, int64_t coarsest) {
  ro.grid = grid;
  ro.relief_grid.clear();
  for (double s : relief_grid_scale)
    ro.relief_grid.push_back(std::clamp<int64_t>(std::llround(static_cast<double>(grid) * s), 2, coarsest));
}

}  // namespace

// RemeshOptions::refine_last: the grids to refine, in order, with the search's unrefined PRMs of those it made.
struct DeferredRefinement {
  std::vector<int> axes;  // in.relief_axis
  LayoutInput in;
  ResampleOptions ro;     // max_deviation: the refinement's bound
  std::vector<double> relief_grid_scale;
  int64_t coarsest = 0;
  double target_error = 0;
  std::vector<int64_t> grids;
  std::map<int64_t, PrmMesh> fitted;
};

void refine_deferred(RemeshResult& result, const ErrorFunction& error) {
  if (!result.deferred) return;
  const DeferredRefinement& d = *result.deferred;
  ResampleOptions ro = d.ro;
  for (int64_t g : d.grids) {
    const auto ts = std::chrono::steady_clock::now();
    set_grid(ro, g, d.relief_grid_scale, d.coarsest);
    const auto it = d.fitted.find(g);
    PrmMesh prm = it != d.fitted.end() ? finish_resampled(it->second, d.in, ro) : resample_and_merge(d.in, ro);
    result.search.push_back(search_step(prm, ro.frame.step, error, ts));
    if (result.search.back().error.rms / d.target_error <= 1) {
      result.prm = std::move(prm);
      result.error = result.search.back().error;
      break;
    }
  }
  result.deferred.reset();
}

RemeshResult remesh(const Mesh& input, const RemeshOptions& options, const ErrorFunction& error) {
  const auto t0 = std::chrono::steady_clock::now();
  const bool searched = options.target_error > 0 || options.max_error > 0;
  const int given = (options.grid_size > 0) + (options.grid_fraction > 0) + searched;
  if (given != 1)
    throw std::invalid_argument("remesh: give exactly one of grid_size, grid_fraction, target_error / max_error");
  if (searched && !error) throw std::invalid_argument("remesh: target_error needs an error function");
  if (input.triangles.empty()) throw InputError("the mesh has no faces");
  check_remesh_range(input);

  RemeshResult result;
  ReliefLayout built;
  if (!options.layout) {
    ReliefOptions relief_options = options.reliefs;
    relief_options.view_properties = false;  // only the layout's geometry and labels are used here
    built = build_reliefs(input, relief_options);
  }
  const ReliefLayout& layout = options.layout ? *options.layout : built;
  result.reliefs = layout.reliefs.size();
  result.relief_boundary_length = layout.boundary_length;
  result.seconds_reliefs = seconds_since(t0);
  std::vector<int> axes(layout.reliefs.size());
  for (size_t r = 0; r < axes.size(); ++r) axes[r] = layout.reliefs[r].axis;

  LayoutInput in;
  in.refined = &layout.mesh;
  in.face_relief = &layout.face_relief;
  in.relief_axis = &axes;
  in.source_face = &layout.source_face;
  in.input = &input;
  ResampleOptions ro;
  ro.frame = frame_of_mesh(input, options.bits, options.step_scale);
  ro.max_normal_angle_deg = options.max_normal_angle_deg;
  ro.parallel = options.parallel;
  ro.fit_heights = options.fit_heights;
  ro.height_fit_reuse_faces = options.height_fit_reuse_faces;
  ro.error_flip_weight = options.error_flip_weight;
  ro.error_unit_stride = options.error_unit_stride;
  ro.error_samples = options.error_samples;
  ro.input_tree = options.input_tree;
  const double diagonal = bbox_diagonal(input);
  ro.max_deviation = (options.refine_error > 0 ? options.refine_error : options.max_error) * diagonal;
  // refine_last: the search's steps unrefined; the refinement's bound is kept for the chosen grid.
  const bool refine_last = options.refine_last && searched && !(options.max_error > 0) && ro.max_deviation > 0;
  const double refine_deviation = ro.max_deviation;
  if (refine_last) ro.max_deviation = 0;
  ro.refine_thin_sheets = options.refine_thin_sheets;
  ro.refine_notches = options.refine_notches;
  ro.refine_facing_guard = options.refine_facing_guard;
  ro.refine_rounds = options.refine_rounds;
  const int64_t coarsest = int64_t{1} << options.bits;  // a grid wider than the bounding box
  auto grid_of = [&](double size) {
    const double steps = size / ro.frame.step;
    if (!(steps < static_cast<double>(coarsest))) return coarsest;
    return std::max<int64_t>(2, static_cast<int64_t>(std::llround(steps)));
  };
  // The vertices of a grid, estimated as the input's area over the lattice's cell (the reliefs' projections are
  // smaller, the seams add a few), and the coarsest grid that gives at most n.
  const double area = surface_area(input);
  auto estimated_vertices = [&](int64_t grid) {
    const HexLattice l = HexLattice::with_grid(grid);
    return area / (static_cast<double>(l.A) * static_cast<double>(l.C) * ro.frame.step * ro.frame.step);
  };
  auto grid_for_vertices = [&](double n) {
    const double guess = std::sqrt(area / (0.8660254037844386 * n)) / ro.frame.step;
    int64_t g = guess < static_cast<double>(coarsest) ? std::max<int64_t>(2, std::llround(guess)) : coarsest;
    while (g < coarsest && estimated_vertices(g) > n) ++g;
    while (g > 2 && estimated_vertices(g - 1) <= n) --g;
    return g;
  };
  const size_t budget = options.max_vertices ? options.max_vertices
                                             : std::max(kMinVertexBudget, kVertexBudgetPerInputVertex * input.positions.size());
  const int64_t finest = grid_for_vertices(static_cast<double>(budget));
  auto over_budget = [&](int64_t grid) {
    return "a grid of " + std::to_string(static_cast<double>(grid) * ro.frame.step) + " (" + std::to_string(grid) +
           " quantization steps at " + std::to_string(options.bits) + " bits) gives about " +
           std::to_string(std::llround(estimated_vertices(grid))) + " vertices, more than the remesher's limit of " +
           std::to_string(budget) + " (the larger of " + std::to_string(kMinVertexBudget) + " and " +
           std::to_string(kVertexBudgetPerInputVertex) + " per input vertex)";
  };

  if (!options.relief_grid_scale.empty()) {
    if (options.relief_grid_scale.size() != layout.reliefs.size())
      throw std::invalid_argument("remesh: relief_grid_scale needs one scale per relief");
    for (double s : options.relief_grid_scale)
      if (!(s > 0 && s < 1e3)) throw std::invalid_argument("remesh: a relief grid scale must be in (0, 1000)");
  }
  // A remeshed grid measured and recorded as a search step.
  // refine_last: each search step's PRM before the refinement, by grid (the refinement then starts from there).
  std::map<int64_t, PrmMesh> fitted;
  auto attempt = [&](int64_t grid) {
    const auto ts = std::chrono::steady_clock::now();
    set_grid(ro, grid, options.relief_grid_scale, coarsest);
    ro.fitted = refine_last ? &fitted[grid] : nullptr;
    PrmMesh prm = resample_and_merge(in, ro);
    ro.fitted = nullptr;
    result.search.push_back(search_step(prm, ro.frame.step, error, ts));
    return prm;
  };

  if (!searched) {
    const double size = options.grid_size > 0 ? options.grid_size : options.grid_fraction * diagonal;
    if (grid_of(size) < finest) throw VertexBudgetExceeded(over_budget(grid_of(size)) + ": choose a coarser grid");
    result.prm = attempt(grid_of(size));
    if (error) {
      result.error = result.search.back().error;
      result.error_measured = true;
    }
    result.seconds_total = seconds_since(t0);
    return result;
  }

  // Search: the resampling error grows roughly like g^2 (linear interpolation of a smooth surface), so each step
  // rescales g by (E / e)^(1/p), with the exponent p fitted from the last two steps (clamped to [1, 3]).
  // The search's error: the RMS error over its target, or the max over max_error, whichever is larger; 1 meets both.
  auto severity = [&](const ErrorEstimate& e) {
    return std::max(options.target_error > 0 ? e.rms / options.target_error : 0.0,
                    options.max_error > 0 ? e.max / options.max_error : 0.0);
  };
  const double target = 1;
  int64_t grid = std::max(finest,
                           grid_of(options.initial_grid_size > 0 ? options.initial_grid_size : 1.5 * mean_edge_length(input)));
  int64_t best_grid = -1;
  PrmMesh best;
  double best_error = 0;
  int64_t smallest_failing = INT64_MAX;
  Progress progress("remesh: searching the grid size at " + std::to_string(options.bits) + " bits",
                    static_cast<size_t>(options.max_search_steps));
  for (int s = 0; s < options.max_search_steps; ++s) {
    PrmMesh prm = attempt(grid);
    progress.advance();
    const SearchStep& step = result.search.back();
    const double e = severity(step.error);
    if (e <= target && grid > best_grid) {
      best_grid = grid;
      best = std::move(prm);
      best_error = e;
      result.error = step.error;
    }
    if (e > target) smallest_failing = std::min(smallest_failing, grid);
    if (best_grid > 0 &&
        smallest_failing - best_grid <=
            std::max<int64_t>(1, static_cast<int64_t>(options.grid_tolerance * static_cast<double>(best_grid))))
      break;
    if (e <= target && e >= options.accept_error * target) break;
    if (e <= target && options.next_exponent > 0 &&
        e * std::pow(static_cast<double>(grid + 1) / static_cast<double>(grid), options.next_exponent) > target)
      break;
    double p = options.first_exponent;
    if (result.search.size() >= 2) {
      const SearchStep& a = result.search[result.search.size() - 2];
      if (a.grid != step.grid && severity(a.error) > 0 && e > 0)
        p = std::clamp(std::log(e / severity(a.error)) / std::log(static_cast<double>(step.grid) / a.grid), 1.0, 3.0);
    }
    // Aim slightly below the target so that the next step is likely to be feasible.
    double next = static_cast<double>(grid) * std::pow(options.aim * target / std::max(e, 1e-12), 1.0 / p);
    int64_t g = std::max<int64_t>(2, static_cast<int64_t>(options.round_to_nearest ? std::round(next) : std::floor(next)));
    const double growth = std::max(static_cast<double>(kSearchVertexFloor),
                                   static_cast<double>(kSearchVertexGrowth) * static_cast<double>(step.vertices));
    g = std::min(std::max({g, finest, grid_for_vertices(growth)}), coarsest);
    if (best_grid > 0) g = std::max(g, best_grid + 1);
    g = std::min(g, int64_t{1} << options.bits);  // §8.4: no larger grid fits the stream
    if (smallest_failing != INT64_MAX) g = std::min(g, smallest_failing - 1);
    if (best_grid > 0 && smallest_failing != INT64_MAX && (g <= best_grid || g >= smallest_failing))
      g = (best_grid + smallest_failing) / 2;
    if (g == grid || g < finest || g > coarsest) break;
    if (options.stop_search && options.stop_search(grid, e <= target, g)) break;
    grid = g;
  }
  progress.finish();
  if (best_grid < 0 && finest > 2 && smallest_failing <= finest) {
    double finest_error = 0;
    for (const SearchStep& st : result.search)
      if (st.grid == finest) finest_error = st.error.rms;
    throw VertexBudgetExceeded("remesh: the target error " + std::to_string(options.target_error) +
                               (options.max_error > 0 ? " (max " + std::to_string(options.max_error) + ")" : "") +
                               " needs a finer grid: " + over_budget(finest - 1) +
                               "; the finest within it gives an RMS error of " + std::to_string(finest_error));
  }
  if (best_grid < 0)
    throw TargetNotReached("remesh: no grid size reached the target error " + std::to_string(options.target_error) +
                           (options.max_error > 0 ? " (max " + std::to_string(options.max_error) + ")" : "") +
                             " in " + std::to_string(options.max_search_steps) + " steps");
  result.prm = std::move(best);
  result.error_measured = true;
  (void)best_error;
  if (refine_last) {
    // The refinement lowers the RMS a little: the next coarser grid first when it missed the target unrefined by at
    // most kRefineLastMargin, then the chosen grid, then the next finer ones, until one refined meets the target
    // (none: the unrefined choice stays).
    auto d = std::make_shared<DeferredRefinement>();
    d->axes = axes;
    d->in = in;
    d->in.relief_axis = &d->axes;
    d->ro = ro;
    d->ro.max_deviation = refine_deviation;
    d->relief_grid_scale = options.relief_grid_scale;
    d->coarsest = coarsest;
    d->target_error = options.target_error;
    for (const SearchStep& st : result.search)
      if (st.grid == best_grid + 1 && severity(st.error) <= kRefineLastMargin * target) d->grids = {best_grid + 1};
    for (int64_t g = best_grid; g >= finest && d->grids.size() < static_cast<size_t>(kRefineLastTries); --g)
      d->grids.push_back(g);
    for (int64_t g : d->grids)
      if (const auto it = fitted.find(g); it != fitted.end()) d->fitted.emplace(g, std::move(it->second));
    result.deferred = std::move(d);
    if (!options.defer_refinement || !options.layout) refine_deferred(result, error);
  }
  result.seconds_total = seconds_since(t0);
  return result;
}

}  // namespace prm::remesh
