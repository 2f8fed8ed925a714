#include "prm/pipeline/pack.h"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <cmath>
#include <stdexcept>
#include <algorithm>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "prm/boundary_deviation.h"
#include "prm/error.h"
#include "prm/mesh_validate.h"
#include "prm/metro_distance.h"
#include "prm/progress.h"
#include "prm/pipeline/boundary_simplification.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/first_grid.h"
#include "prm/pipeline/pack_general.h"
#include "prm/remesh/lattice.h"
#include "prm/remesh/relief_grids.h"
#include "height_guard.h"
#include "worst_site_rounding.h"
#include "prm/pipeline/stream_check.h"

namespace prm::pipeline {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Sparse estimates of a grid's error in [kSparseBand[0], kSparseBand[1]] x the target are measured again at full
// density (the lambda bisection keeps the sparse ones: the result's full-density check corrects it).
constexpr double kSparseBand[2] = {0.97, 1.08};

// The search's sparse estimates take at most this many samples per surface (MetroOptions::max_samples): on a
// 2M-vertex input, 4 per face of the input were 17M per surface and estimate, most of the pack's time (issue 21),
// where 2M give the RMS to well under 1%. The 50k-vertex paper models (at most 4 x ~100k faces) are below it, their
// searches unchanged; the full-density measurements (the band above, the report) are not capped.
constexpr size_t kSearchMaxSamples = 2000000;

// For the progress line's estimate of the time left: the attempts of the exhaustive search (12, 11, 10 bits and the
// three kStepScales, as on the paper's models) and the grid rounds of one attempt's remesh (its lambda bisection adds
// EffortPlan::lambda_rounds).
constexpr int kExpectedExhaustiveAttempts = 6;
constexpr int kExpectedGridRounds = 3;
// finish_at's facing guard: how many times a lambda's stream is encoded again with more of its heights rounded
// (hrefine3: 3 gave the same bytes on camel, armadillo, venus and feline, and venus 1.2 s more CPU).
constexpr int kFacingRounds = 1;

// What one search shares across its attempts: the repaired input, its relief layout, and the Metro references of the
// search (plan.search_samples_per_face) and of the report (Metro's ten per face, or PackOptions::metro_samples).
struct SearchContext {
  const Mesh& source;
  const remesh::ReliefLayout& layout;
  const MetroReference& search;
  const MetroReference& full;
  EffortPlan plan;
  const AabbTree* source_tree = nullptr;  // source's tree when source is not the references' mesh (a thinned boundary)
  std::vector<double> relief_grid_scale;  // PackOptions::adaptive: per relief of `layout` (empty: one grid)
};

remesh::ErrorEstimate measure_with(const MetroReference& r, const Mesh& m) {
  const DistanceReport d = r.compare(m);
  return remesh::ErrorEstimate{d.rel(d.rms), d.rel(d.max)};
}

// The stream of a candidate with options o, and the error of its decoded mesh (`measure`).
// zero_area: the decoded mesh's triangles of zero area (the chosen heights can put a corner on a line);
// coincident: its vertices that share their point with another. Both are set before `measure` is called, which may
// read them (finish_at's bisection does not measure a stream it refuses for them).
template <class Measure>
remesh::ErrorEstimate encode_and_measure(const remesh::PrmMesh& prm, const codec::PrmOptions& o,
                                         codec::EncodeReport* report, std::vector<uint8_t>* stream,
                                         const Measure& measure, size_t* zero_area = nullptr,
                                         size_t* coincident = nullptr) {
  auto encoded = encode_prm_mesh(prm, report, o);
  if (!encoded.ok())
    throw InputError("the piecewise regular mesh could not be encoded (a remesher or codec bug): " +
                     encoded.status.message + " (spec §" + encoded.status.spec_section + ")");
  auto decoded = codec::decode(encoded.value.data(), encoded.value.size());
  if (!decoded.ok()) throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
  if (zero_area) *zero_area = count_zero_area_triangles(decoded.value);
  if (coincident) *coincident = count_coincident_vertices(decoded.value);
  const Mesh mesh = to_mesh(decoded.value);
  if (stream) *stream = std::move(encoded.value);
  return measure(mesh);
}

struct Measuring;

// One bit depth and step scale remeshed and encoded (heights rounded, or PackOptions::height_lambda): what
// finish_at() needs to choose the heights' lambda and check the stream at full density.
struct Remeshed {
  PackResult out;
  double target = 0, max_target = 0;  // the search's RMS and max targets (remesh::RemeshOptions)
  // The full / sparse ratio of the last grid measured both ways (1: none was), which scales the lambda
  // bisection's sparse estimates.
  double sparse_bias = 1;
  // out.remesh.error was measured at full density on out.stream decoded (the kept grid's sparse estimate fell in
  // kSparseBand): finish_at's check needs no second measurement while the stream stays the search's.
  bool error_at_full_density = false;
  // remesh_at's error function's state, kept for a deferred refinement (RemeshOptions::defer_refinement).
  std::shared_ptr<Measuring> measuring;
  // round_worst_sites' reach at in>pr places (kAloneMissedReach where the search has no other attempt to keep).
  int missed_reach = 1;
};

// remesh_at's measurements: the search's grids, then those of its refinement (deferred or not).
struct Measuring {
  remesh::QuantFrame frame;  // the stream's
  codec::PrmOptions po;      // the rounded heights' encoding
  double target_error = 0, max_error = 0;  // remesh::RemeshOptions'
  // The error of a decoded candidate: the search's samples decide unless they fall within kSparseBand of the target,
  // where the full density decides (the sparser samples weigh the vertices more: +0.5% at 4 per face, +4% at 2 on
  // the horse), so that every decision is the one the full density would make.
  double sparse_bias = 1;
  // Per grid measured (remesh::RemeshResult::search): measured at full density on the decoded stream itself, the
  // mesh finish_at's check would measure (the same stream decoded: the same Metro result, bit for bit).
  std::vector<bool> decoded_at_full_density;
  // The stream (and its report) of the last measurement encoded for it (EffortPlan::decode_in_band), by its index
  // above: encode_remeshed takes it when that grid is kept instead of encoding the same mesh again.
  size_t encoded_index = SIZE_MAX;
  std::vector<uint8_t> encoded_stream;
  codec::EncodeReport encoded_report;
  // EffortPlan::decode_in_band for these measurements (refine_remeshed: the refined grid's, so that finish_at knows the
  // rounded heights' stream at full density, which its check and the heights' guard measure otherwise).
  bool decode_in_band = false;
};

remesh::ErrorFunction error_function(const SearchContext& ctx, Measuring& s) {
  auto grid_error = [&ctx, &s](const remesh::PrmMesh& prm) {
    const MetroReference& reference = ctx.search;
    // m: the candidate quantized (or decoded, `decoded`) as the stream will hold it.
    auto measure = [&](const Mesh& m, bool decoded) {
      remesh::ErrorEstimate e = measure_with(reference, m);
      if (&reference == &ctx.full) return e;
      const bool max_in_band = s.max_error > 0 && e.max >= kSparseBand[0] * s.max_error;
      if ((e.rms < kSparseBand[0] * s.target_error || e.rms > kSparseBand[1] * s.target_error) && !max_in_band)
        return e;
      // EffortPlan::decode_in_band: the stream encoded and decoded, so that its check can reuse this measurement.
      const bool encode = !decoded && (ctx.plan.decode_in_band || s.decode_in_band);
      const auto full_measure = [&](const Mesh& d) { return measure_with(ctx.full, d); };
      if (encode) s.encoded_index = s.decoded_at_full_density.size() - 1;
      const remesh::ErrorEstimate full =
          encode ? encode_and_measure(prm, s.po, &s.encoded_report, &s.encoded_stream, full_measure) : full_measure(m);
      if (e.rms > 0) s.sparse_bias = full.rms / e.rms;
      s.decoded_at_full_density.back() = decoded || encode;
      return full;
    };
    ProgressJob::advance_round();
    s.decoded_at_full_density.push_back(false);
    if (s.po.height_lambda > 0)
      return encode_and_measure(prm, s.po, nullptr, nullptr, [&](const Mesh& m) { return measure(m, true); });
    const Mesh& candidate = prm.mesh;
    Mesh q;
    q.triangles = candidate.triangles;
    q.positions.resize(candidate.positions.size());
    for (size_t v = 0; v < q.positions.size(); ++v)
      for (int a = 0; a < 3; ++a)
        q.positions[v][static_cast<size_t>(a)] =
            s.frame.to_real(s.frame.quantize(candidate.positions[v][static_cast<size_t>(a)], a), a);
    return measure(q, false);
  };
  // Metro keeps its last candidate's tree for the next measurement of the same triangles (MetroReference): a grid's
  // is freed before the next grid's remesh, whose peak it would add to (hcpu7: armadillo 2e-4 108 -> 125 MB).
  return [&ctx, grid_error](const remesh::PrmMesh& prm) {
    const remesh::ErrorEstimate e = grid_error(prm);
    ctx.search.forget_candidate();
    ctx.full.forget_candidate();
    return e;
  };
}

// The remeshed attempt's kept grid, encoded with rounded heights (rm.measuring: its measurements).
void encode_remeshed(Remeshed& rm) {
  const Measuring& s = *rm.measuring;
  PackResult& out = rm.out;
  // The kept grid's measurement (remesh() copies it into out.remesh.error).
  rm.error_at_full_density = false;
  size_t kept = SIZE_MAX;
  for (size_t i = 0; i < out.remesh.search.size() && i < s.decoded_at_full_density.size(); ++i)
    if (s.decoded_at_full_density[i] && out.remesh.search[i].grid == out.remesh.prm.lattice.A &&
        out.remesh.search[i].error.rms == out.remesh.error.rms && out.remesh.search[i].error.max == out.remesh.error.max) {
      rm.error_at_full_density = true;
      kept = i;
    }
  rm.sparse_bias = s.sparse_bias;
  out.codec_options = s.po;
  if (kept == s.encoded_index && !s.encoded_stream.empty()) {
    out.stream = s.encoded_stream;
    out.report = s.encoded_report;
    out.seconds_encode = 0;
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  auto encoded = encode_prm_mesh(out.remesh.prm, &out.report, s.po);
  out.seconds_encode = seconds_since(t0);
  if (!encoded.ok())
    throw InputError("the piecewise regular mesh could not be encoded (a remesher or codec bug): " +
                     encoded.status.message + " (spec §" + encoded.status.spec_section + ")");
  out.stream = std::move(encoded.value);
}

// RemeshOptions::defer_refinement: the refinement of rm's chosen grid, measured as its search was, and the refined
// grid encoded (nothing when none was deferred).
void refine_remeshed(const SearchContext& ctx, Remeshed& rm) {
  if (!rm.out.remesh.deferred) return;
  const auto t0 = std::chrono::steady_clock::now();
  rm.measuring->decode_in_band = true;
  remesh::refine_deferred(rm.out.remesh, error_function(ctx, *rm.measuring));
  rm.out.seconds_remesh += seconds_since(t0);
  encode_remeshed(rm);
}

using StopSearch = std::function<bool(int64_t grid, bool met, int64_t next)>;

// One bit depth and step scale: repair (done by the caller), remesh, encode with rounded heights.
// stop_search: remesh::RemeshOptions::stop_search; defer_refinement: RemeshOptions::defer_refinement (refine_remeshed).
Remeshed remesh_at(const SearchContext& ctx, const PackOptions& options, int bits, double step_scale,
                   double initial_grid, const StopSearch& stop_search = {}, bool defer_refinement = false) {
  const Mesh& source = ctx.source;
  PackResult out;
  ProgressJob::stage("remesh");
  auto t0 = std::chrono::steady_clock::now();
  remesh::RemeshOptions ro;
  ro.layout = &ctx.layout;
  ro.input_tree = ctx.source_tree ? ctx.source_tree : &ctx.full.tree();  // the tree of source
  ro.grid_tolerance = ctx.plan.grid_tolerance;
  ro.accept_error = ctx.plan.accept_error;
  ro.first_exponent = ctx.plan.first_exponent;
  ro.next_exponent = ctx.plan.next_exponent;
  ro.aim = ctx.plan.aim;
  ro.round_to_nearest = ctx.plan.round_to_nearest;
  ro.stop_search = stop_search;
  ro.bits = bits;
  ro.step_scale = step_scale;
  ro.reliefs.tau = options.tau;
  ro.reliefs.parallel = options.parallel;
  ro.parallel = options.parallel;
  ro.fit_heights = options.fit_heights;
  ro.height_fit_reuse_faces = ctx.plan.height_fit_reuse_faces;
  ro.error_flip_weight = options.error_flip_weight;
  ro.error_unit_stride = ctx.plan.error_unit_stride;
  ro.error_samples = ctx.plan.error_samples;
  ro.grid_size = options.grid_size;
  ro.grid_fraction = options.grid_fraction;
  ro.initial_grid_size = initial_grid;
  ro.relief_grid_scale = ctx.relief_grid_scale;
  ro.target_error = kQuantizationMargin * options.target_error;
  // The worst case: --max-error is a constraint of the search and sets the local refinement's bound
  // (deviation_refinement.h); without it, the refinement (when asked for) aims at kDefaultMaxErrorPerTarget x the
  // target.
  ro.max_error = kQuantizationMargin * options.max_error;
  set_refinement(ro, options.target_error, options.max_error, ctx.plan.local_refinement, options.refine_facing_guard);
  ro.refine_rounds = kPackRefineRounds;  // `prm remesh` (set_refinement alone) takes ResampleOptions' 20
  ro.defer_refinement = defer_refinement;
  // The search measures what the decoder will output: the candidate quantized to the stream's frame (its lattice
  // vertices are exact already; the heights and the other vertices round to the nearest step), or, when the
  // encoder may choose the heights, the candidate encoded and decoded.
  auto measuring = std::make_shared<Measuring>();
  Measuring& ms = *measuring;
  ms.frame = remesh::frame_of_mesh(source, bits, step_scale);
  codec::PrmOptions& po = ms.po;
  if (options.height_lambda > 0) {
    po.height_tolerance = kHeightTolerance;
    po.height_lambda = options.height_lambda;
  }
  po.height_sweeps = options.height_sweeps;
  if (ctx.plan.predicted_heights_only) po.height_depth = codec::kLinearPredictionDepth;
  po.seam_context = options.max_minor >= codec::kFormatMinorSeam ? -1 : 0;
  po.patch_contexts = options.max_minor >= codec::kFormatMinorPatchContexts;
  po.patch_grids = options.max_minor >= codec::kFormatMinorPatchGrids;
  ms.target_error = ro.target_error;
  ms.max_error = ro.max_error;
  out.remesh = remesh::remesh(source, ro, error_function(ctx, ms));
  out.seconds_remesh = seconds_since(t0);
  out.bits = bits;
  out.step_scale = step_scale;
  Remeshed rm{std::move(out), ro.target_error, ro.max_error, 1, false, std::move(measuring)};
  encode_remeshed(rm);
  return rm;
}

// Is some vertex of m farther than `limit` (a fraction of the diagonal) from the reference's mesh? Then its Metro max
// passes `limit` too, when the reference samples the vertices (vertex_distance_max is at most that max): a stream can
// be refused for its max without its Metro run (hcpu5).
bool vertices_pass(const MetroReference& reference, const Mesh& m, double limit) {
  return reference.options().sample_vertices && reference.diagonal() > 0 &&
         vertex_distance_max(m, reference.tree()) / reference.diagonal() > limit;
}

// The heights of a remeshed attempt: the lambda bisection (its sparse estimates scaled by rm.sparse_bias), then the
// check at full density. `measured`: false when the chosen stream, measured at full density, misses what the
// search's sparser samples promised (the caller repeats at full density).
PackResult finish_at(const SearchContext& ctx, const PackOptions& options, Remeshed rm, bool* measured = nullptr) {
  PackResult out = std::move(rm.out);
  const codec::PrmOptions po = out.codec_options;
  const int bits = out.bits;
  const double step_scale = out.step_scale;
  // The rounded heights' max (the search's samples, fewer than the check's): over the heights' guard's aim, the guard
  // below cannot help (its last try is these heights, measured with more samples) and is skipped.
  const double rounded_max = out.remesh.error.max;
  // EffortPlan::lambda_full_density: the lambda rounds measure at full density, so that the check reuses it.
  const bool lambda_full = ctx.plan.lambda_full_density;
  // The rounded heights' stream, when its error is known at full density (rm.error_at_full_density): the check and
  // the heights' guard take that error for a stream of the same bytes instead of measuring it again.
  const std::vector<uint8_t> rounded_stream = rm.error_at_full_density ? out.stream : std::vector<uint8_t>{};
  const remesh::ErrorEstimate rounded_error = out.remesh.error;
  auto measure = [&](const Mesh& m) {
    if (lambda_full) return measure_with(ctx.full, m);
    remesh::ErrorEstimate e = measure_with(ctx.search, m);
    if (&ctx.search != &ctx.full) e.rms *= rm.sparse_bias;
    return e;
  };
  // With the local refinement (no max_error), heights chosen by rate and distortion must not turn a triangle away from
  // the input either (issue 22 item 3; the refinement's small triangles beside lattice vertices: CGAL's elephant at
  // 5e-4, one): a lambda whose stream has more than the rounded heights' is refused like one that misses the target.
  const bool facing_guard = ctx.plan.local_refinement && options.refine_facing_guard && !(options.max_error > 0);
  // The rounded heights' decoded mesh and its turned triangles: a lambda's stream moves some heights only, and its
  // other triangles are not tested again.
  TurnedTriangles base;
  const size_t base_turned = [&] {
    if (!facing_guard) return size_t{0};
    const auto decoded = codec::decode(out.stream.data(), out.stream.size());
    if (!decoded.ok()) return size_t{0};
    base.mesh = to_mesh(decoded.value);
    base.turned = turned_triangles(base.mesh, ctx.full.mesh(), ctx.full.tree());
    return base.turned.size();
  }();
  // Such a lambda's stream is encoded again with the rounded heights at the corners of its turned triangles
  // (PrmOptions::rounded_heights), kFacingRounds times at most, so that its heights still apply elsewhere (hrefine3:
  // refusing the whole lambda cost the camel +12.6% bytes). `held`: the mask of the last encoding; `out_held`: that
  // of out.codec_options.
  std::vector<uint8_t> held, out_held;
  const auto encode_facing = [&](codec::PrmOptions& o, codec::EncodeReport* report, std::vector<uint8_t>* stream,
                                 const auto& measure_kept, size_t* zero_area, size_t* coincident) {
    o.rounded_heights = nullptr;
    held.clear();
    for (int round = 0;; ++round) {
      bool again = false;
      const auto check = [&](const Mesh& m) {
        if (!facing_guard) return measure_kept(m);
        const std::vector<size_t> turned = turned_triangles(m, ctx.full.mesh(), ctx.full.tree(), &base);
        if (turned.size() <= base_turned) return measure_kept(m);
        if (round < kFacingRounds && o.height_lambda > 0) {
          held.resize(out.remesh.prm.mesh.positions.size(), 0);
          const std::vector<uint32_t>& order = report->vertex_order;
          for (const size_t t : turned)
            for (const uint32_t v : m.triangles[t])
              if (v < order.size() && order[v] < held.size()) again |= !std::exchange(held[order[v]], uint8_t{1});
        }
        return remesh::ErrorEstimate{HUGE_VAL, HUGE_VAL};
      };
      const remesh::ErrorEstimate e = encode_and_measure(out.remesh.prm, o, report, stream, check, zero_area, coincident);
      if (!again) return e;
      o.rounded_heights = held.data();
    }
  };
  const auto keep_options = [&](const codec::PrmOptions& o) {
    out_held = o.rounded_heights ? held : std::vector<uint8_t>{};
    out.codec_options = o;
    out.codec_options.rounded_heights = o.rounded_heights ? out_held.data() : nullptr;
  };
  // The error left below the target buys smaller residuals: the largest lambda that still meets it.
  if (options.optimize_heights && options.height_lambda <= 0 && options.target_error > 0 &&
      !(ctx.plan.lambda_below > 0 && out.remesh.error.rms >= ctx.plan.lambda_below * rm.target)) {
    const auto t1 = std::chrono::steady_clock::now();
    ProgressJob::stage("heights");
    ProgressJob::rounds_left(ctx.plan.lambda_rounds + 1);  // and the check at full density
    // The error grows with lambda: bisection for the last one that meets the target (in at most plan.lambda_rounds).
    int lo = -1, hi = static_cast<int>(std::size(kHeightLambdas));  // lo meets (-1: rounding), hi does not
    // Heights chosen by rate and distortion must not put a vertex on another's point (issue 17): a lambda whose stream
    // has more coincident vertices than the rounded heights' is refused like one that misses the target.
    const size_t base_coincident = [&] {
      const auto decoded = codec::decode(out.stream.data(), out.stream.size());
      return decoded.ok() ? count_coincident_vertices(decoded.value) : size_t{0};
    }();
    // --local-refinement (no max_error): a lambda whose max passes the heights' guard's aim (below) is refused too,
    // when the rounded heights' max is within it, so that the guard has less to undo (h22max8: the venus's chosen
    // lambda, 1.65e-3 here already, was measured again at full density and then replaced by the next smaller one).
    const double guard_aim = ctx.plan.local_refinement && !(options.max_error > 0) &&
                                     out.remesh.error.max <= kDefaultMaxErrorPerTarget * options.target_error
                                 ? kDefaultMaxErrorPerTarget * options.target_error
                                 : 0;
    // A stream whose vertices already pass guard_aim is refused for the max without its Metro run: vertex_distance_max
    // is at most Metro's max (the candidate's vertices are among its samples). Whether that stream also missed the
    // RMS target (2, not 1) matters only to the lambda above it, tried once more below: its decoded mesh is kept here
    // and measured only then (hcpu5: on the venus at 1.3e-4 the first lambda and that retry, two Metro runs).
    const MetroReference& measured_by = lambda_full ? ctx.full : ctx.search;
    std::optional<Mesh> unmeasured;
    // Lambda j's stream tried: kept when it meets everything and is smaller. 0: it met; 1: refused only for passing
    // guard_aim; 2: refused otherwise; 3: 1 or 2, its vertices past guard_aim (`unmeasured`: its mesh).
    // kept_after_unmeasured: the lambda below j returned 3, and j's stream is kept only if that one was 1.
    const auto try_lambda = [&](int j, bool kept_after_unmeasured) {
      codec::PrmOptions o = po;
      o.height_tolerance = kHeightTolerance;
      o.height_lambda = kHeightLambdas[j];
      o.height_sweeps = options.height_sweeps;
      // Only linear prediction takes the freedom; the difference depths would code the same heights as above.
      if (out.report.height_depth == codec::kLinearPredictionDepth) {
        o.height_depth = out.report.height_depth;
        o.overlap_depth = out.report.overlap_depth;
      }
      codec::EncodeReport report;
      std::vector<uint8_t> stream;
      size_t zero_area = 0, coincident = 0;
      // A stream refused for its triangles or its points is not measured (h22max8: the feline's bisection refused
      // three of its four lambdas so, 0.34 s CPU each).
      bool over_aim = false;
      const auto measure_unless_refused = [&](const Mesh& m) {
        if (zero_area > 0 || coincident > base_coincident) return remesh::ErrorEstimate{HUGE_VAL, HUGE_VAL};
        if (guard_aim > 0 && vertices_pass(measured_by, m, guard_aim)) {
          over_aim = true;
          unmeasured = m;
          return remesh::ErrorEstimate{0, HUGE_VAL};
        }
        return measure(m);
      };
      const remesh::ErrorEstimate e =
          encode_facing(o, &report, &stream, measure_unless_refused, &zero_area, &coincident);
      if (over_aim) return 3;
      if (e.rms > rm.target || (rm.max_target > 0 && e.max > rm.max_target) || zero_area > 0 ||
          coincident > base_coincident)
        return 2;
      if (guard_aim > 0 && e.max > guard_aim) return 1;
      if (kept_after_unmeasured && measure(*unmeasured).rms > rm.target) return 2;
      if (stream.size() < out.stream.size()) {
        rm.error_at_full_density = lambda_full;  // another stream, measured here
        out.stream = std::move(stream);
        out.report = report;
        out.remesh.error = e;
        keep_options(o);
      }
      return 0;
    };
    bool over_aim_at_hi = false, unmeasured_at_hi = false;
    for (int round = 0; hi - lo > 1 && round < ctx.plan.lambda_rounds; ++round) {
      const int mid = (lo + hi) / 2;
      ProgressJob::advance_round();
      const int r = try_lambda(mid, false);
      if (r == 0) {
        lo = mid;
      } else {
        hi = mid;
        over_aim_at_hi = r == 1;
        unmeasured_at_hi = r == 3;
      }
    }
    // The max does not grow with lambda everywhere (hfeline: venus with the rounding's face probes passed the aim at
    // 0.15 and not at 0.19, 7,563 B against 7,339 B): a lambda refused only for the max, next to the last one that
    // met, gives way to the one above it once.
    // With hi's RMS not measured (3), the one above it is tried first: kept only if hi then meets the RMS target.
    if ((over_aim_at_hi || unmeasured_at_hi) && hi == lo + 1 && hi + 1 < static_cast<int>(std::size(kHeightLambdas))) {
      ProgressJob::advance_round();
      if (try_lambda(hi + 1, unmeasured_at_hi) == 0) lo = hi + 1;
    }
    out.seconds_remesh += seconds_since(t1);  // part of the search
  }
  // The stream must hold the mesh that was remeshed: no triangle may lose its area (the remesher separates what
  // rounding would collapse; heights chosen by rate and distortion, given here, may still put a corner on a line).
  auto zero_area_of = [](const std::vector<uint8_t>& stream) {
    const auto decoded = codec::decode(stream.data(), stream.size());
    if (!decoded.ok()) throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
    return count_zero_area_triangles(decoded.value);
  };
  size_t zero_area = zero_area_of(out.stream);
  if (zero_area > 0 && out.codec_options.height_lambda > 0) {
    codec::PrmOptions rounded = out.codec_options;
    rounded.height_lambda = 0;
    auto encoded = encode_prm_mesh(out.remesh.prm, &out.report, rounded);
    if (!encoded.ok())
      throw InputError("the piecewise regular mesh could not be encoded (a remesher or codec bug): " +
                       encoded.status.message + " (spec §" + encoded.status.spec_section + ")");
    out.stream = std::move(encoded.value);
    out.codec_options = rounded;
    rm.error_at_full_density = false;
    zero_area = zero_area_of(out.stream);
  }
  // --local-refinement (no max_error): the stream's worst places past kDefaultMaxErrorPerTarget x the target, their
  // vertices' quantized points moved by a step where that brings them nearer (round_worst_sites), kept when the
  // stream then meets the target with a smaller max and turns no more triangles (h22t: the horse at 1.3e-4). Before
  // the heights' guard, which it spares a measurement of the rounded heights where it brings the max within the aim.
  // A stream within kRoundMargin under the bound is rounded towards that margin (h22homer: refined_elephant at 2e-4,
  // 7.998x, a pr>in place at 8.00x).
  const auto round_sites = [&] {
    const double bound = kDefaultMaxErrorPerTarget * options.target_error;
    const double aim_share = out.remesh.error.max > bound ? 1.0 : kRoundMargin;
    if (zero_area > 0 || !ctx.plan.local_refinement || options.max_error > 0 || !(options.target_error > 0) ||
        out.remesh.error.max <= aim_share * bound)
      return;
    const auto decoded = codec::decode(out.stream.data(), out.stream.size());
    if (!decoded.ok()) throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
    const std::vector<Vec3> positions = out.remesh.prm.mesh.positions;
    std::vector<uint8_t> mask = out.codec_options.rounded_heights ? out_held : std::vector<uint8_t>{};
    const size_t base_coincident = count_coincident_vertices(decoded.value);
    const double aim = aim_share * bound * ctx.full.diagonal();
    if (round_worst_sites(out.remesh.prm, decoded.value, to_mesh(decoded.value), out.report.vertex_order, ctx.full,
                          aim, out.remesh.error.max * ctx.full.diagonal(), mask, rm.missed_reach) > 0) {
      codec::PrmOptions o = out.codec_options;
      o.rounded_heights = o.height_lambda > 0 ? mask.data() : nullptr;
      codec::EncodeReport report;
      std::vector<uint8_t> stream;
      size_t za = 0, coincident = 0;
      const remesh::ErrorEstimate e = encode_and_measure(
          out.remesh.prm, o, &report, &stream,
          [&](const Mesh& m) {
            if (facing_guard && turned_triangles(m, ctx.full.mesh(), ctx.full.tree(), &base).size() > base_turned)
              return remesh::ErrorEstimate{HUGE_VAL, HUGE_VAL};
            return measure_with(ctx.full, m);
          },
          &za, &coincident);
      if (za == 0 && coincident <= base_coincident && e.rms <= kQuantizationMargin * options.target_error &&
          e.max < out.remesh.error.max) {
        out.stream = std::move(stream);
        out.report = report;
        out.remesh.error = e;
        out_held = std::move(mask);
        out.codec_options = o;
        out.codec_options.rounded_heights = o.height_lambda > 0 ? out_held.data() : nullptr;
      } else {
        out.remesh.prm.mesh.positions = positions;
      }
    }
  };
  // The search measured with fewer samples than the report: the chosen stream at full density. Where that misses
  // the target, smaller lambdas (then rounding) are tried at full density; `measured` false if none meets it.
  if (&ctx.search != &ctx.full && (options.target_error > 0 || options.max_error > 0) && zero_area == 0) {
    const double target = kQuantizationMargin * options.target_error;
    const double max_target = kQuantizationMargin * options.max_error;
    auto meets = [&](const remesh::ErrorEstimate& e) {
      return (options.target_error <= 0 || e.rms <= target) && (max_target <= 0 || e.max <= max_target);
    };
    ProgressJob::stage("check");
    ProgressJob::rounds_left(1);
    // refuse_over > 0: a stream whose vertices pass that max is refused without its Metro run (vertex_distance_max).
    auto full_error = [&](codec::PrmOptions& o, std::vector<uint8_t>* stream, codec::EncodeReport* report,
                          double refuse_over) {
      size_t za = 0;
      auto full = [&](const Mesh& m) {
        if (!rounded_stream.empty() && *stream == rounded_stream) return rounded_error;
        if (refuse_over > 0 && vertices_pass(ctx.full, m, refuse_over)) return remesh::ErrorEstimate{HUGE_VAL, HUGE_VAL};
        return measure_with(ctx.full, m);
      };
      const remesh::ErrorEstimate e = encode_facing(o, report, stream, full, &za, nullptr);
      return za > 0 ? remesh::ErrorEstimate{HUGE_VAL, HUGE_VAL} : e;
    };
    // The stream the search measured at full density (the rounded heights, or PackOptions::height_lambda's): its
    // error is known. Otherwise the chosen stream decoded and measured.
    if (!rm.error_at_full_density) {
      const auto decoded = codec::decode(out.stream.data(), out.stream.size());
      if (!decoded.ok()) throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
      const DistanceReport d = ctx.full.compare(to_mesh(decoded.value));
      out.remesh.error = remesh::ErrorEstimate{d.rel(d.rms), d.rel(d.max)};
    }
    bool met = meets(out.remesh.error);
    int k = 0;  // the kept lambda's index (the search's choice, or the smaller one the check falls back to)
    while (k < static_cast<int>(std::size(kHeightLambdas)) && kHeightLambdas[k] < out.codec_options.height_lambda) ++k;
    for (int j = k - 1; !met && out.codec_options.height_lambda > 0 && j >= -1; --j) {
      codec::PrmOptions o = out.codec_options;
      o.height_lambda = j >= 0 ? kHeightLambdas[j] : 0;  // -1: rounded heights
      std::vector<uint8_t> stream;
      codec::EncodeReport report;
      const remesh::ErrorEstimate e = full_error(o, &stream, &report, 0);
      if (!meets(e)) continue;
      met = true;
      out.stream = std::move(stream);
      out.report = report;
      out.remesh.error = e;
      keep_options(o);
      k = j;  // the heights' guard below starts under it (h115b: it measured the check's lambda again)
    }
    // --local-refinement (no max_error): the heights' freedom must not undo the refinement (h22max6: a variant's venus
    // was 1.37e-3 with rounded heights and 1.65e-3 decoded). When the stream's max passes kDefaultMaxErrorPerTarget x
    // the target, the largest smaller lambda (then rounding) whose stream meets both is taken; with none, the stream
    // stays (that max is the refinement's aim, not a constraint of the search: `measured` is the RMS's).
    const double aim = kDefaultMaxErrorPerTarget * options.target_error;
    // At most kHeightGuardTries lambdas, then rounding (height_guard.h). try_lambda keeps lambda j's stream (-1: the
    // rounded heights) when it meets both: one whose vertices pass the aim is refused unmeasured.
    struct Encoded {
      std::vector<uint8_t> stream;
      codec::EncodeReport report;
      remesh::ErrorEstimate error;
      codec::PrmOptions options;
    };
    const auto encode_lambda = [&](int j) {
      Encoded c;
      c.options = out.codec_options;
      c.options.height_lambda = j >= 0 ? kHeightLambdas[j] : 0;
      c.error = full_error(c.options, &c.stream, &c.report, aim);
      return c;
    };
    const auto keep_if_meets = [&](Encoded& c) {
      if (!meets(c.error) || c.error.max > aim) return false;
      out.stream = std::move(c.stream);
      out.report = c.report;
      out.remesh.error = c.error;
      keep_options(c.options);
      return true;
    };
    if (met) round_sites();
    if (met && ctx.plan.local_refinement && !(options.max_error > 0) && options.target_error > 0 &&
        out.remesh.error.max > aim && rounded_max <= kHeightGuardSparseMargin * aim &&
        out.codec_options.height_lambda > 0) {
      // The rounded heights are the guard's last try and, as a rule, its smallest max: they are measured first (their
      // max in the search's sparser samples can pass the aim where the full density's does not, and the other way
      // round: kHeightGuardSparseMargin), and the guard runs only if they meet (h115b: the horse at 1.3e-4, rounded
      // 1.033e-3 sparse and 1.051e-3 at full density against 1.04e-3: four lambdas measured in vain, 3.5 s CPU).
      Encoded rounded = encode_lambda(-1);
      if (meets(rounded.error) && rounded.error.max <= aim)
        height_guard_choice(k, [&](int j) {
          if (j < 0) return keep_if_meets(rounded);
          Encoded c = encode_lambda(j);
          return keep_if_meets(c);
        });
    }
    if (measured) *measured = met;
  }
  if (&ctx.search == &ctx.full) round_sites();  // (the search measured at full density: no check above)
  if (zero_area > 0)
    throw remesh::TargetNotReached(std::to_string(zero_area) + " triangle(s) of the piecewise regular mesh have zero "
                                   "area once quantized to " + std::to_string(bits) + " bits (step scale " +
                                   std::to_string(step_scale) + "): vertices too close to separate");
  out.codec_options.rounded_heights = nullptr;  // out_held is finish_at's
  if (out.codec_options.height_lambda > 0) {
    // The PRM of the result is the one the stream holds: its heights are the encoder's choice.
    const auto decoded = codec::decode(out.stream.data(), out.stream.size());
    if (!decoded.ok()) throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
    const std::vector<uint32_t>& order = out.report.vertex_order;
    Mesh& m = out.remesh.prm.mesh;
    for (size_t k = 0; k < order.size(); ++k)
      for (int a = 0; a < 3; ++a)
        m.positions[order[k]][static_cast<size_t>(a)] =
            out.remesh.prm.frame.to_real(decoded.value.quantized[3 * k + static_cast<size_t>(a)], a);
  }
  return out;
}

// One bit depth and step scale, remeshed (remesh_at) and its heights chosen (finish_at).
PackResult pack_at(const SearchContext& ctx, const PackOptions& options, int bits, double step_scale,
                   double initial_grid, bool* measured = nullptr) {
  return finish_at(ctx, options, remesh_at(ctx, options, bits, step_scale, initial_grid), measured);
}

// The step of ladder position p (eighths of an octave below the extent): bits ceil(p / 8), scale 2^(j/8).
struct Step {
  int bits;
  double scale;
};
Step step_at(int p) {
  const int bits = (p + 7) / 8;
  return {bits, std::exp2(static_cast<double>(8 * bits - p) / 8.0)};
}

}  // namespace

EffortPlan effort_plan(int effort) {
  if (effort < kMinEffort || effort > kMaxEffort)
    throw std::invalid_argument("effort " + std::to_string(effort) + " is outside " + std::to_string(kMinEffort) +
                                ".." + std::to_string(kMaxEffort));
  EffortPlan p;
  // Effort 0 tries one lambda (the bisection's middle, kHeightLambdas[7]): on the paper's horse, venus and bunny a
  // second round changed nothing (the same streams); on the feline it found a larger lambda whose stream is 3.5%
  // smaller. One round saves 0.1-0.7 s CPU there (bench/README.md "pack effort", fifth round).
  // Effort 4 tries two steps as effort 5 does, but chooses the heights' lambda and checks at full density only the
  // better one (defer_heights): effort 5's streams on the paper's four models (the venus +0.06% against effort 9,
  // where effort 3 is +7.8%) for 3-29% less CPU than effort 5 and 1-4.6 s more than effort 3 (bench/README.md
  // "pack effort", sixth round).
  // Effort 3 defers the heights too (with one step, the same streams as before) and searches the next coarser step
  // instead of the predicted one when its first grid meets the target and its search would go on to a grid of 15
  // quantization steps or more (coarser_step_from_grid): on the paper's models only the venus, whose stream went
  // from +7.8% to +0.06% against effort 9 for about the same CPU; on a smooth sphere it cost 1.5-5% at three of four
  // targets (bench/README.md "pack effort", eighth round).
  // Effort 3 codes the heights by linear prediction only (predicted_heights_only), as effort 0 does: its search's
  // three rounded-heights encodes on the venus at 1.3e-4 wrote the patch section eight times each; the streams of the
  // paper's four models and armadillo, camel, bunny00 are the same sizes (bench/README.md "pack effort", sixteenth
  // round).
  // Effort 0 also cheapens the seam error flips (one closest-point sample per triangle instead of seven, their mean
  // error over every 16th face), measures its lambda round at full density (the check reuses it) and skips that
  // round when the rounded heights are at 0.97 of the target or more: 15-20% fewer CPU samples on the venus and the
  // feline, streams within -0.1..+0.8% on the paper's models (bench/README.md "pack effort", eleventh round).
  switch (effort) {
    case 0:
      p.steps = 1; p.search_samples_per_face = 2; p.lambda_rounds = 1; p.grid_tolerance = 0.15; p.accept_error = 0;
      p.decode_in_band = true; p.error_samples = 1; p.error_unit_stride = 16; p.lambda_below = 0.97;
      p.first_grid_gate = 0.9;
      p.lambda_full_density = true;
      p.predicted_heights_only = true;
      p.height_fit_reuse_faces = true;
      p.local_refinement = false;
      break;
    case 1: p.steps = 1; p.search_samples_per_face = 2; p.lambda_rounds = 3; p.grid_tolerance = 0.1; p.accept_error = 0.85; break;
    case 2: p.steps = 1; p.search_samples_per_face = 4; p.lambda_rounds = 4; p.grid_tolerance = 0.06; p.accept_error = 0.9; break;
    case 3:
      p.steps = 1; p.defer_heights = true; p.coarser_step_from_grid = 15; p.search_samples_per_face = 4;
      p.lambda_rounds = 4; p.predicted_heights_only = true;
      break;
    case 4: p.steps = 2; p.defer_heights = true; p.search_samples_per_face = 4; break;
    case 5: p.steps = 2; p.search_samples_per_face = 4; break;
    case 6: p.steps = 3; p.search_samples_per_face = 4; break;
    case 7: p.steps = 5; p.search_samples_per_face = 4; break;
    case 8: p.exhaustive = true; p.search_samples_per_face = 4; break;
    default: p.exhaustive = true; break;
  }
  // Below the exhaustive search the general candidate's bisection (up to five encodes and Metro runs, 1-2 s CPU on a
  // 50k-vertex model) is made only when its fewest bits could beat the PRM stream.
  p.general_floor_check = effort < kMaxEffort;
  if (effort < kMaxEffort) {
    // The grid predicted from the first grid's error (error ~ g^1.4 between grids of 10-20 quantization steps on
    // the paper's models), rounded to the nearest, and no measurement of the next coarser grid when it is predicted
    // to miss: two grids per step on the paper's models instead of 2-5 (bench/README.md "pack effort").
    p.first_exponent = 1.4;
    p.next_exponent = 1.0;
    p.aim = 0.99;
    p.round_to_nearest = true;
  }
  return p;
}

bool refines_locally(const PackOptions& options) {
  using R = PackOptions::LocalRefinement;
  return options.local_refinement == R::on ||
         (options.local_refinement == R::automatic && effort_plan(options.effort).local_refinement);
}

size_t pick_bounded_attempt(const std::vector<BoundedAttempt>& attempts, double bound, bool& met_bound) {
  size_t pick = SIZE_MAX;
  for (size_t i = 0; i < attempts.size(); ++i)
    if (attempts[i].max <= bound && (pick == SIZE_MAX || attempts[i].bytes < attempts[pick].bytes)) pick = i;
  met_bound = pick != SIZE_MAX;
  if (met_bound || attempts.empty()) return met_bound ? pick : 0;
  // None within the bound: the nearest to it among those at most kNoBoundBytes x the smallest stream.
  size_t smallest = 0;
  for (size_t i = 1; i < attempts.size(); ++i)
    if (attempts[i].bytes < attempts[smallest].bytes) smallest = i;
  const double budget = kNoBoundBytes * static_cast<double>(attempts[smallest].bytes);
  pick = smallest;
  for (size_t i = 0; i < attempts.size(); ++i)
    if (static_cast<double>(attempts[i].bytes) <= budget && attempts[i].max < attempts[pick].max) pick = i;
  return pick;
}

void set_refinement(remesh::RemeshOptions& ro, double target_error, double max_error, bool local, bool facing_guard) {
  ro.refine_error = max_error > 0 ? kRefineShare * max_error
                    : local       ? kLocalRefineShare * kDefaultMaxErrorPerTarget * target_error
                                  : 0;
  // The notch steps (DeviationRefinementOptions::lattice_moves .. stray_check) only for the local refinement: with
  // --max-error the search keeps the first thin-sheet refinement (bench/README.md "Worst-case error", h22thin3).
  ro.refine_notches = !(max_error > 0);
  ro.refine_facing_guard = facing_guard;
  ro.refine_last = local && !(max_error > 0);  // issue 21's CPU budget (h22max5)
}

namespace {

// PackMode::prm. input_reference: the input's Metro reference (options.metro_samples), used when no repair is needed;
// input_check: validate_mesh(input) when the caller has it (null: computed here).
PackResult pack_prm(const Mesh& input, const PackOptions& options, const MetroReference* input_reference,
                    const MeshReport* input_check) {
  auto t0 = std::chrono::steady_clock::now();
  // The effort applies to the search of the step; a given bit depth or step scale is searched as it always was.
  EffortPlan plan =
      effort_plan(options.bits > 0 || options.step_scale > 0 ? kMaxEffort : (effort_plan(options.effort), options.effort));
  plan.local_refinement = refines_locally(options);  // by the effort asked for, also with a bit depth given
  const bool searched = options.target_error > 0 || options.max_error > 0;
  const bool one_attempt = options.bits > 0 || !searched;
  // The step and grid predictions scale with the target: with --max-error alone, the RMS error it allows by default.
  const double predicted_error =
      options.target_error > 0 ? options.target_error : options.max_error / kDefaultMaxErrorPerTarget;
  const bool rate_distortion = options.optimize_heights && options.height_lambda <= 0 && options.target_error > 0;
  ProgressJob progress(one_attempt ? 1 : plan.exhaustive ? kExpectedExhaustiveAttempts : plan.steps,
                       kExpectedGridRounds + (rate_distortion ? plan.lambda_rounds : 0));
  ProgressJob::stage("repair");
  // The remesher needs a consistently oriented 2-manifold. Its boundary loops stay open (issue 22: a range scan is
  // an open surface), unless fill_holes closes them (paper §4, the bunny protocol; repair_mesh).
  const MeshReport check = input_check ? *input_check : validate_mesh(input);
  Mesh closed;
  RepairReport repair;
  const bool ready = check.clean() && check.manifold() && check.oriented() && (check.closed() || !options.fill_holes);
  const bool repaired = !ready;
  RepairOptions repair_options;
  repair_options.fill_holes = options.fill_holes;
  if (repaired) closed = repair_mesh(input, &repair, repair_options);  // throws InputError when it cannot
  const Mesh& measured_against = repaired ? closed : input;  // what the error is measured against
  const size_t loops_in =
      repaired ? validate_mesh(measured_against).boundary_loops + repair.holes_filled : check.boundary_loops;
  // A thinned-out boundary (PackOptions::boundary_simplification): what is remeshed, with its own tree.
  Mesh thinned;
  std::unique_ptr<AabbTree> thinned_tree;
  size_t boundary_removed = 0;
  if (options.boundary_simplification > 0 && options.target_error > 0 && !options.fill_holes && loops_in > 0) {
    thinned = measured_against;
    boundary_removed =
        simplify_boundary(thinned, options.boundary_simplification * options.target_error * check.diagonal).removed;
    if (boundary_removed > 0) thinned_tree = std::make_unique<AabbTree>(thinned);
  }
  const Mesh& source = boundary_removed > 0 ? thinned : measured_against;
  const double seconds_repair = seconds_since(t0);
  ProgressJob::stage("reliefs");
  MetroOptions mo;
  mo.samples = options.metro_samples;  // 0: Metro's ten per face, as `prm compare` measures
  std::unique_ptr<MetroReference> own_reference;
  if (repaired || !input_reference)
    own_reference = std::make_unique<MetroReference>(&measured_against, mo);  // borrowed: it outlives the search
  const MetroReference& reference = own_reference ? *own_reference : *input_reference;
  // The search's own, sparser samples (only where they are fewer than the report's).
  MetroOptions so = mo;
  so.samples_per_face = plan.search_samples_per_face;
  so.max_samples = kSearchMaxSamples;
  const bool sparse = options.metro_samples == 0 && searched && plan.search_samples_per_face < 10;
  std::unique_ptr<MetroReference> sparse_reference;
  if (sparse) sparse_reference = std::make_unique<MetroReference>(reference, so);  // one mesh and tree for both
  remesh::ReliefOptions relief_options;
  relief_options.tau = options.tau;
  relief_options.parallel = options.parallel;
  relief_options.view_properties = false;
  const remesh::ReliefLayout layout = remesh::build_reliefs(source, relief_options);
  // Issue 23: a grid scale per relief from its measured detail (format 1.5 only).
  std::vector<double> relief_grid_scale;
  if (options.adaptive && options.max_minor >= codec::kFormatMinorPatchGrids) {
    remesh::ReliefGridOptions go;
    go.exponent = options.adaptive_exponent;
    if (options.adaptive_model == PackOptions::AdaptiveModel::curvature) {
      relief_grid_scale = remesh::allocate_relief_grid_scales(remesh::measure_relief_detail(source, layout), go);
    } else {
      ProgressJob::stage("allocation");
      // Two uniform remeshes (no error search): the search's first grid (or the grid given) and a coarser one.
      const AabbTree& tree = thinned_tree ? *thinned_tree : reference.tree();
      const double first = options.grid_size > 0       ? options.grid_size
                           : options.grid_fraction > 0 ? options.grid_fraction * reference.diagonal()
                                                       : kGridPerTargetError * predicted_error * reference.diagonal();
      auto sample = [&](double grid) {
        remesh::RemeshOptions ro;
        ro.layout = &layout;
        ro.input_tree = &tree;
        ro.reliefs.tau = options.tau;
        ro.reliefs.parallel = options.parallel;
        ro.parallel = options.parallel;
        ro.fit_heights = options.fit_heights;
        ro.error_flip_weight = options.error_flip_weight;
        ro.grid_size = grid;
        const remesh::RemeshResult r = remesh::remesh(source, ro);
        return remesh::measure_relief_error(r.prm, tree, layout.reliefs.size(), grid);
      };
      relief_grid_scale = remesh::allocate_relief_grid_scales_measured(
          sample(first), sample(first * kAdaptiveModelGridRatio), go);
    }
  }
  const SearchContext ctx{source, layout, sparse ? *sparse_reference : reference, reference, plan,
                          thinned_tree.get(), relief_grid_scale};
  const SearchContext full_ctx{source, layout, reference, reference, plan, thinned_tree.get(), relief_grid_scale};
  size_t rounds = 0;
  int attempts = 0;
  // One bit depth and step scale; repeated with full-density Metro when the sparse samples promised too much.
  auto pack_one = [&](int bits, double scale, double initial_grid) {
    bool measured = true;
    ProgressJob::attempt(++attempts);
    PackResult r = pack_at(ctx, options, bits, scale, initial_grid, &measured);
    rounds += r.remesh.search.size();
    if (!measured) {
      r = pack_at(full_ctx, options, bits, scale, initial_grid);
      rounds += r.remesh.search.size();
    }
    return r;
  };

  PackResult out;
  const double fixed_scale = options.step_scale > 0 ? options.step_scale : 1.0;
  if (one_attempt) {
    out = pack_one(options.bits > 0 ? options.bits : 12, fixed_scale, 0);
    out.tried.push_back({out.bits, out.step_scale, out.stream.size()});
    ProgressJob::best_bytes(out.stream.size());
  } else {
    // The bit depth is part of the search: fewer bits make every height cheaper and add quantization error, which a
    // finer grid must buy back. Each grid search starts from the previous grid size.
    double grid = 0, seconds = 0;
    bool have = false;
    enum class Outcome { unreachable, smaller, larger };
    // EffortPlan::defer_heights: the attempts are compared by their streams with rounded heights; the best one's
    // heights are chosen (finish_at) once the search is over.
    std::unique_ptr<Remeshed> best_remeshed;
    size_t best_unrefined_bytes = 0;  // its stream before the deferred refinement (EffortPlan::bound_candidate_bytes)
    double best_initial_grid = 0;  // the grid the best attempt's search started from
    // The bound of the local refinement without max_error (kDefaultMaxErrorPerTarget x the target): the attempts not
    // kept, for when the kept one's refined stream passes it (the bound check after the search).
    const bool bound_check = plan.local_refinement && !(options.max_error > 0) && options.target_error > 0;
    std::vector<PackResult> finished_others;                 // without defer_heights: refined, heights chosen
    std::vector<std::unique_ptr<Remeshed>> remeshed_others;  // with defer_heights: unrefined
    auto keep_other = [&](PackResult&& r, std::unique_ptr<Remeshed>&& remeshed) {
      if (remeshed) remeshed_others.push_back(std::move(remeshed));
      else finished_others.push_back(std::move(r));
    };
    auto attempt = [&](int bits, double scale, const StopSearch& stop_search = {}) {
      const double initial_grid = grid;
      PackResult r;
      std::unique_ptr<Remeshed> remeshed;
      try {
        if (plan.defer_heights) {
          ProgressJob::attempt(++attempts);
          // The local refinement (RemeshOptions::refine_last) only for the attempt kept (refine_remeshed below): the
          // attempts are compared unrefined.
          remeshed = std::make_unique<Remeshed>(remesh_at(ctx, options, bits, scale, grid, stop_search, true));
          rounds += remeshed->out.remesh.search.size();
          // The rounded stream must keep every triangle's area (finish_at would refuse the attempt).
          const auto decoded = codec::decode(remeshed->out.stream.data(), remeshed->out.stream.size());
          if (!decoded.ok())
            throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
          if (count_zero_area_triangles(decoded.value) > 0) return Outcome::unreachable;
          r = remeshed->out;  // a copy: the search's bookkeeping below
        } else {
          r = pack_one(bits, scale, grid);
        }
      } catch (const remesh::VertexBudgetExceeded&) {
        if (!have) throw;  // more bits would not make the grid it needs coarser
        return Outcome::unreachable;
      } catch (const remesh::TargetNotReached&) {
        return Outcome::unreachable;
      }
      seconds += r.seconds_remesh + r.seconds_encode;
      out.tried.push_back({bits, scale, r.stream.size()});
      grid = static_cast<double>(r.remesh.prm.lattice.A) * r.remesh.prm.frame.step;
      if (have && r.stream.size() >= out.stream.size()) {
        if (bound_check) keep_other(std::move(r), std::move(remeshed));
        return Outcome::larger;
      }
      auto tried = std::move(out.tried);
      if (bound_check && have) keep_other(std::move(out), std::move(best_remeshed));
      out = std::move(r);
      out.tried = std::move(tried);
      best_remeshed = std::move(remeshed);
      best_initial_grid = initial_grid;
      have = true;
      ProgressJob::best_bytes(out.stream.size());
      return Outcome::smaller;
    };
    // The step predicted from the target (kStepPerTargetError): its ladder position (step_at).
    const int lowest = 8 * kMinPackBits - 7, highest = 8 * kMaxPackBits;
    const auto predicted_p = [&] {
      const remesh::QuantFrame unit = remesh::frame_of_mesh(source, kMinPackBits, 1.0);
      const double extent = unit.step * static_cast<double>((1 << kMinPackBits) - 1);
      const double wanted = kStepPerTargetError * predicted_error * reference.diagonal();
      return std::clamp(static_cast<int>(std::lround(-8.0 * std::log2(wanted / extent))), lowest, highest);
    };
    if (plan.exhaustive) {
      // From 12 bits down while the stream shrinks (up from 12 while the target is out of reach).
      if (attempt(12, fixed_scale) == Outcome::unreachable) {
        for (int bits = 13; bits <= kMaxPackBits && !have; ++bits) attempt(bits, fixed_scale);
      } else {
        for (int bits = 11; bits >= kMinPackBits && attempt(bits, fixed_scale) == Outcome::smaller; --bits) {
        }
      }
      // Between the bit depths: steps coarser than 2^-b, b the best depth, each grid search starting from b's grid.
      if (have && options.step_scale <= 0) {
        const int b = out.bits;
        const double best_grid = static_cast<double>(out.remesh.prm.lattice.A) * out.remesh.prm.frame.step;
        for (double s : kStepScales) {
          grid = best_grid;
          attempt(b, s);
        }
        // The predicted step (the first of the searches below kMaxEffort - 1) when the ladder above passed it by (a
        // step between two bit depths): so that the exhaustive search keeps no larger stream than effort 3's first
        // step (hsearch: the horse at 2e-4, effort 3's 11 bits x1.414 between effort 9's 11 and 10 bits).
        const Step predicted = step_at(predicted_p());
        const bool tried = std::any_of(out.tried.begin(), out.tried.end(), [&](const PackResult::Trial& t) {
          return t.bits == predicted.bits && std::abs(t.step_scale / predicted.scale - 1) < 1e-9;
        });
        if (!tried) {
          grid = best_grid;
          attempt(predicted.bits, predicted.scale);
        }
      }
    } else {
      // The step predicted from the target (kStepPerTargetError), then its neighbours an eighth of an octave apart,
      // nearest the best so far first, each grid search starting from the best grid.
      int best_p = predicted_p();
      std::vector<int> tried_p;
      auto untried = [&](int p) {
        return p >= lowest && p <= highest && std::find(tried_p.begin(), tried_p.end(), p) == tried_p.end();
      };
      int p = best_p;
      grid = kGridPerTargetError * predicted_error * reference.diagonal();
      if (plan.first_grid_gate > 0) {
        const double unit = predicted_error * reference.diagonal();
        const double predicted = predict_first_grid(surface_grid_statistics(source, unit, reference.diagonal()), unit);
        if (predicted > 0 && predicted < plan.first_grid_gate * grid) grid = predicted;
      }
      // EffortPlan::coarser_step_from_grid: the first step's search stops after its first grid when that grid meets
      // the target and the next one would be of that many quantization steps or more; the next coarser step is
      // tried instead, from that next grid, and the first step's search is resumed only when the coarser step
      // gives no smaller stream.
      int64_t coarser_from = 0;  // the grid (quantization steps of the first step) the search would have tried next
      StopSearch stop_first;
      if (plan.coarser_step_from_grid > 0 && plan.steps == 1 && plan.defer_heights)
        stop_first = [&, first = true](int64_t, bool met, int64_t next) mutable {
          const bool stop = first && met && next >= plan.coarser_step_from_grid;
          first = false;
          if (stop) coarser_from = next;
          return stop;
        };
      for (int n = 0; n < plan.steps && p != INT32_MIN; ++n) {
        tried_p.push_back(p);
        const Step st = step_at(p);
        const double start_grid = grid;
        const Outcome o = attempt(st.bits, st.scale, n == 0 ? stop_first : StopSearch{});
        if (coarser_from > 0 && o == Outcome::smaller && untried(p - 1)) {
          const int first_p = p;
          grid = static_cast<double>(coarser_from) * out.remesh.prm.frame.step;
          coarser_from = 0;
          tried_p.push_back(p - 1);
          const Step coarser = step_at(p - 1);
          if (attempt(coarser.bits, coarser.scale) == Outcome::smaller) {
            best_p = p - 1;
            break;
          }
          grid = start_grid;  // the first step's search again, as it would have gone on
          attempt(st.bits, st.scale);
          best_p = first_p;
          break;
        }
        if (o == Outcome::smaller) best_p = p;
        if (o == Outcome::unreachable && !have) {
          // The target needs a finer step: down by an octave at a time.
          p = untried(p + 8) ? p + 8 : INT32_MIN;
          best_p = p;
          --n;
          continue;
        }
        if (have) grid = static_cast<double>(out.remesh.prm.lattice.A) * out.remesh.prm.frame.step;
        // Next: the untried neighbour nearest the best, coarser first (fewer bits per height).
        p = INT32_MIN;
        for (int d = 1; d <= 8 && p == INT32_MIN; ++d) {
          if (untried(best_p - d)) p = best_p - d;
          else if (untried(best_p + d)) p = best_p + d;
        }
      }
    }
    if (!have)
      throw remesh::TargetNotReached("no grid size reached the target error " + std::to_string(options.target_error) +
                                     " at 12 to " + std::to_string(kMaxPackBits) + " bits");
    // An attempt's deferred refinement; a refined stream that loses a triangle's area (which the attempt's check
    // would have refused) gives way to the unrefined one.
    const auto refine_attempt = [&](Remeshed& rm) {
      if (!rm.out.remesh.deferred) return;
      Remeshed refined = rm;
      refine_remeshed(ctx, refined);
      rounds += refined.out.remesh.search.size() - rm.out.remesh.search.size();
      const auto decoded = codec::decode(refined.out.stream.data(), refined.out.stream.size());
      if (!decoded.ok())
        throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
      if (count_zero_area_triangles(decoded.value) == 0) rm = std::move(refined);
    };
    // An attempt's entry in `tried`: its stream's final size (the others' are their rounded heights' sizes).
    const auto final_bytes = [](std::vector<PackResult::Trial>& tried, const PackResult& r) {
      for (PackResult::Trial& t : tried)
        if (t.bits == r.bits && t.step_scale == r.step_scale) t.bytes = r.stream.size();
    };
    if (best_remeshed) {
      // The best attempt's heights; where its full-density check misses, the attempt again at full density.
      const int bits = out.bits;
      const double scale = out.step_scale;
      const double best_grid = static_cast<double>(out.remesh.prm.lattice.A) * out.remesh.prm.frame.step;
      auto tried = std::move(out.tried);
      bool measured = true;
      const auto t1 = std::chrono::steady_clock::now();
      best_unrefined_bytes = best_remeshed->out.stream.size();
      refine_attempt(*best_remeshed);
      if (finished_others.empty() && remeshed_others.empty()) best_remeshed->missed_reach = kAloneMissedReach;
      out = finish_at(ctx, options, std::move(*best_remeshed), &measured);
      if (!measured) {
        // One step (as pack_one would): again from the grid its search started from; several: from the best grid.
        out = pack_at(full_ctx, options, bits, scale, plan.steps == 1 ? best_initial_grid : best_grid);
        rounds += out.remesh.search.size();
      }
      seconds += seconds_since(t1);
      final_bytes(tried, out);
      out.tried = std::move(tried);
      ProgressJob::best_bytes(out.stream.size());
    }
    // The kept stream's max (full density) over the bound: the smallest of the other attempts, refined and their
    // heights chosen, that meets the RMS target and the bound; when none does, the nearest to it within kNoBoundBytes.
    const double bound = kDefaultMaxErrorPerTarget * options.target_error;
    if (bound_check && out.remesh.error.max > bound && (!finished_others.empty() || !remeshed_others.empty())) {
      const auto t1 = std::chrono::steady_clock::now();
      auto tried = std::move(out.tried);
      const PackResult::Trial first{out.bits, out.step_scale, out.stream.size()};
      const double first_max = out.remesh.error.max;
      const int64_t first_grid = out.remesh.prm.lattice.A;
      std::vector<PackResult> refined = std::move(finished_others);  // each met the RMS target at full density
      refined.push_back(std::move(out));
      const auto within = [&](const PackResult& r) { return r.remesh.error.max <= bound; };
      // With defer_heights: the unrefined attempts, smallest stream first, at most plan.bound_candidates of them,
      // until one meets the bound, none past plan.bound_candidate_bytes x the kept one's unrefined stream.
      std::stable_sort(remeshed_others.begin(), remeshed_others.end(),
                       [](const auto& a, const auto& b) { return a->out.stream.size() < b->out.stream.size(); });
      int refined_others = 0;
      for (auto& c : remeshed_others) {
        if (refined_others >= plan.bound_candidates || std::any_of(refined.begin(), refined.end(), within)) break;
        if (static_cast<double>(c->out.stream.size()) > plan.bound_candidate_bytes * best_unrefined_bytes) break;
        ++refined_others;
        refine_attempt(*c);
        bool met = true;
        PackResult r = finish_at(ctx, options, std::move(*c), &met);
        final_bytes(tried, r);
        if (met) refined.push_back(std::move(r));  // one that misses the RMS target at full density is no candidate
      }
      std::vector<BoundedAttempt> attempts;
      for (const PackResult& r : refined) attempts.push_back({r.stream.size(), r.remesh.error.max});
      bool met_bound = false;
      const size_t pick = pick_bounded_attempt(attempts, bound, met_bound);
      out = std::move(refined[pick]);
      out.tried = std::move(tried);
      const auto frame = [&](int bits, double scale, int64_t grid, size_t bytes, double max) {
        char b[160];
        std::snprintf(b, sizeof b, "%d bits, step scale %.4g, grid %lld steps (%zu B, max %.2fx the target)", bits,
                      scale, static_cast<long long>(grid), bytes, max / options.target_error);
        return std::string(b);
      };
      const auto frame_of = [&](const PackResult& r) {
        return frame(r.bits, r.step_scale, r.remesh.prm.lattice.A, r.stream.size(), r.remesh.error.max);
      };
      std::string others;
      for (size_t i = 0; i < refined.size(); ++i)
        if (i != pick)
          others += "; " + frame_of(refined[i]);
      out.search_note = "the search's choice, " + frame(first.bits, first.step_scale, first_grid, first.bytes, first_max) +
                        ", passes the " + std::to_string(static_cast<int>(kDefaultMaxErrorPerTarget)) + "x bound; kept " +
                        frame_of(out) +
                        (met_bound ? ", the smallest within the bound"
                                   : ", the nearest to it within 5% of the smallest stream: none is within the bound") +
                        " (" + std::to_string(refined.size()) + " attempts refined" + others + ")";
      seconds += seconds_since(t1);
      ProgressJob::best_bytes(out.stream.size());
    }
    out.seconds_remesh = seconds - out.seconds_encode;  // the whole search
  }
  out.remesh_rounds = rounds;
  out.boundary_loops_in = loops_in;
  // A closed mesh (every half-edge's reverse is some face's: no edge of one face) has no boundary loop; only an open
  // one is validated in full for its loops (the venus at effort 0: 0.04 s less).
  const Mesh& remeshed = out.remesh.prm.mesh;
  out.boundary_loops_out = boundary_edges(remeshed).empty() ? 0 : validate_mesh(remeshed).boundary_loops;
  out.boundary_vertices_removed = boundary_removed;
  out.seconds_repair = seconds_repair;
  out.repaired = repaired;
  out.repair = repair;
  if (repaired) out.repaired_input = std::move(closed);
  return out;
}

// pack_prm on an open surface: its boundary loops are kept (issue 22) unless fill_holes; when the remesher cannot keep
// them (a broken invariant, std::logic_error), the paper's protocol instead, named in the report
// (RepairReport::notes) and by boundary_fallback. Never a crash.
PackResult pack_prm_open(const Mesh& input, const PackOptions& options, const MetroReference* input_reference,
                         const MeshReport* input_check) {
  return detail::pack_keeping_boundary_or_filling(input, options, [&](const Mesh& m, const PackOptions& o) {
    return pack_prm(m, o, input_reference, &m == &input ? input_check : nullptr);
  });
}

}  // namespace

PackResult detail::pack_keeping_boundary_or_filling(const Mesh& input, const PackOptions& options,
                                                    const PrmAttempt& attempt) {
  if (options.fill_holes) return attempt(input, options);
  try {
    return attempt(input, options);
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::logic_error& e) {
    if (validate_mesh(input).closed()) throw;
    PackOptions filled = options;
    filled.fill_holes = true;
    PackResult r = attempt(input, filled);
    r.boundary_fallback = true;
    r.repair.notes.push_back("the remesher could not keep the open boundary (" + std::string(e.what()) + "): its " +
                             std::to_string(r.repair.holes_filled) + " boundary loop(s) were closed instead");
    return r;
  }
}

PackResult pack(const Mesh& input, const PackOptions& options) {
  check_remesh_range(input);  // before anything squares a length
  if (options.bits <= 0 && options.step_scale <= 0) effort_plan(options.effort);  // refused before any work
  const bool has_target = options.target_error > 0 || options.max_error > 0;
  // --fill-holes asks for a closed output: the general path codes the input as it is, open, so auto is prm then.
  const MeshReport input_check = validate_mesh(input);
  const bool fill_open = options.fill_holes && input_check.boundary_loops > 0;
  if (fill_open && options.mode == PackMode::general)
    throw std::invalid_argument("--fill-holes closes the input's boundary loops, which --mode general keeps as they are");
  const PackMode mode =
      options.mode == PackMode::automatic && (!has_target || fill_open) ? PackMode::prm : options.mode;
  // Both candidates are measured against the target with the PRM search's margin.
  const double target = kQuantizationMargin * options.target_error;
  MetroOptions mo;
  mo.samples = options.metro_samples;
  std::unique_ptr<MetroReference> input_reference;
  if (mode != PackMode::prm) input_reference = std::make_unique<MetroReference>(&input, mo);  // borrowed

  // The general path codes a manifold: a pinched vertex (its faces in several fans, no edge with three faces) is
  // split first, one copy per extra fan as the repair does, which leaves the geometry as it is (the report names the
  // copies).
  PackResult::Candidate general;
  GeneralPack general_pack;
  Mesh general_input;  // the pinch-split copy, when the input has pinches
  size_t general_pinches_split = 0;
  auto general_coded = [&]() -> const Mesh& {
    if (input_check.non_manifold_vertices > 0 && input_check.non_manifold_edges == 0) {
      if (general_pinches_split == 0) {
        general_input = input;
        general_pinches_split = split_pinched_vertices(general_input);
      }
      return general_input;
    }
    return input;
  };
  auto make_general = [&] {
    const auto t0 = std::chrono::steady_clock::now();
    const Mesh* coded = &general_coded();
    try {
      general_pack = pack_general(*coded, *input_reference, target, options.bits, options.max_minor,
                                  kQuantizationMargin * options.max_error);
      general.made = true;
      general.bytes = general_pack.stream.size();
      general.vertices = general_pack.report.vertices;
      general.bits = general_pack.bits;
      general.rms = general_pack.rms;
      general.max = general_pack.max;
    } catch (const InputError& e) {
      if (mode == PackMode::general) throw;
      general.refused = e.what();
    } catch (const remesh::TargetNotReached& e) {
      if (mode == PackMode::general) throw;
      general.refused = e.what();
    }
    general.seconds = seconds_since(t0);
  };
  // The general candidate: the input as it comes (with its boundaries), made first, unless the effort plan puts the
  // PRM first (EffortPlan::general_floor_check): then the general one follows only where its fewest bits could beat
  // the PRM stream.
  const bool floor_check = mode == PackMode::automatic && options.bits <= 0 && options.step_scale <= 0 &&
                           effort_plan(options.effort).general_floor_check;
  if (mode != PackMode::prm && !floor_check) make_general();
  auto general_result = [&](std::string reason) {
    PackResult out;
    out.stream = std::move(general_pack.stream);
    out.report = std::move(general_pack.report);
    out.bits = general_pack.bits;
    out.step_scale = 1;
    out.remesh.error = remesh::ErrorEstimate{general.rms, general.max};
    out.seconds_general = general.seconds;
    for (const GeneralPack::Trial& t : general_pack.tried) out.tried.push_back({t.bits, 1.0, t.bytes});
    out.mode = PackMode::general;
    out.mode_reason = std::move(reason);
    out.general_candidate = general;
    out.input_vertices = input.num_vertices();
    if (general_pinches_split > 0) {  // what was coded: the input with its pinched vertices split
      out.repaired = true;
      out.repair.pinched_vertices_split = general_pinches_split;
      out.repaired_input = general_input;
    }
    // The general stream codes the input as it is (pinches split): its boundary loops are the input's.
    out.boundary_loops_in = out.boundary_loops_out = validate_mesh(out.repaired ? general_input : input).boundary_loops;
    return out;
  };
  if (mode == PackMode::general) return general_result("--mode general");

  // The piecewise regular candidate.
  PackResult::Candidate prm;
  PackResult out;
  const auto t0 = std::chrono::steady_clock::now();
  bool prm_unreachable = false;  // the PRM's failure: TargetNotReached (otherwise InputError)
  try {
    out = pack_prm_open(input, options, input_reference.get(), &input_check);
    prm.made = true;
  } catch (const remesh::TargetNotReached& e) {
    if (mode == PackMode::prm) throw;
    prm.refused = e.what();
    prm_unreachable = true;
  } catch (const InputError& e) {
    if (mode == PackMode::prm) throw;
    prm.refused = e.what();
  }
  prm.seconds = seconds_since(t0);
  if (prm.made) {
    prm.bytes = out.stream.size();
    prm.vertices = out.report.vertices;
    prm.bits = out.bits;
    prm.rms = out.remesh.error.rms;
    prm.max = out.remesh.error.max;
  }
  if (floor_check) {
    const auto t1 = std::chrono::steady_clock::now();
    size_t floor = 0;
    bool refused = false;
    if (prm.made) {
      try {
        floor = general_floor_bytes(general_coded(), options.max_minor);
      } catch (const InputError& e) {
        general.refused = e.what();
        refused = true;
      }
    }
    if (refused) {
      general.seconds = seconds_since(t1);
    } else if (prm.made && floor >= prm.bytes) {
      general.not_tried = "not tried at effort " + std::to_string(options.effort) + ": at its fewest bits (" +
                          std::to_string(kMinGeneralBits) + ") the general stream is " + std::to_string(floor) +
                          " B, not smaller than the piecewise regular one";
      general.seconds = seconds_since(t1);
    } else {
      make_general();
      general.seconds = seconds_since(t1);  // the floor's encode included
    }
  }
  if (!prm.made && !general.made) {
    const std::string both = prm.refused + "; the general path: " + general.refused;
    if (prm_unreachable) throw remesh::TargetNotReached(both);
    throw InputError(both);
  }
  auto bytes_rms = [](const PackResult::Candidate& c) {
    return std::to_string(c.bytes) + " B at " + std::to_string(c.bits) + " bits, RMS " + std::to_string(c.rms);
  };
  if (mode == PackMode::automatic && !prm.made) {
    PackResult g = general_result("auto: no piecewise regular mesh could be made (" + prm.refused + ")");
    g.prm_candidate = prm;
    return g;
  }
  if (mode == PackMode::automatic && general.made && general.bytes < prm.bytes) {
    std::string reason = "auto: the general stream (" + bytes_rms(general) + ") is smaller than the piecewise "
                         "regular one (" + bytes_rms(prm) + ")";
    if (out.repaired && out.repair.holes_filled > 0)
      reason += "; the piecewise regular mesh needed repair (" + std::to_string(out.repair.holes_filled) +
                " hole(s) filled), the general stream codes the input as it is";
    if (general_pinches_split > 0)
      reason += "; the general stream codes the input with its pinched vertices split (" +
                std::to_string(general_pinches_split) + (general_pinches_split == 1 ? " copy)" : " copies)");
    PackResult g = general_result(std::move(reason));
    g.prm_candidate = prm;
    g.seconds_repair = out.seconds_repair;
    g.seconds_remesh = out.seconds_remesh;
    g.remesh_rounds = out.remesh_rounds;
    return g;
  }
  out.mode = PackMode::prm;
  if (mode == PackMode::prm)
    out.mode_reason = options.mode == PackMode::prm ? "--mode prm"
                      : fill_open ? "auto with --fill-holes on an open input: prm (the general path keeps the holes)"
                                  : "auto without a target error (a grid was given): prm";
  else if (general.made)
    out.mode_reason = "auto: the piecewise regular stream (" + bytes_rms(prm) + ") is not larger than the general "
                      "one (" + bytes_rms(general) + ")";
  else if (!general.not_tried.empty())
    out.mode_reason = "auto: the piecewise regular stream (" + bytes_rms(prm) + "); the general one was " +
                      general.not_tried;
  else
    out.mode_reason = "auto: the general path cannot code the input (" + general.refused + ")";
  out.prm_candidate = prm;
  out.general_candidate = general;
  out.seconds_general = general.seconds;
  out.input_vertices = input.num_vertices();
  return out;
}

const char* pack_mode_name(PackMode mode) {
  switch (mode) {
    case PackMode::prm: return "prm";
    case PackMode::general: return "general";
    case PackMode::automatic: return "auto";
  }
  return "?";
}

}  // namespace prm::pipeline
