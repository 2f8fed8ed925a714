// The main job on one mesh (`prm pack`, bench/table1): fix what repair can fix (holes stay open unless fill_holes),
// remesh into a piecewise regular mesh that meets a target RMS error (paper §2), and encode it (spec/prm-format.md).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "prm/codec.h"
#include "prm/mesh.h"
#include "prm/mesh_repair.h"
#include "prm/remesh/remesh.h"

namespace prm::pipeline {

// The grid search measures the quantized candidate (what the decoder outputs) and aims this much below
// PackOptions::target_error, for the difference between the search's samples and an independent measurement.
constexpr double kQuantizationMargin = 0.99;
// PackOptions::bits = 0 with a target error: the bit depths the search may choose.
constexpr int kMinPackBits = 8;
constexpr int kMaxPackBits = 16;

// PackOptions::effort with a target error, bits = 0 and step_scale = 0: how hard the search looks for the smallest
// stream (in the manner of Draco's -cl). Lower efforts try fewer steps, measure the error with fewer Metro samples
// while searching (never in the final report), and stop the grid and lambda searches sooner; kMaxEffort is the
// exhaustive search (every bit depth from 12 while the stream shrinks, then kStepScales, full-density Metro
// throughout). Measured time against bytes: bench/README.md "pack effort".
constexpr int kMinEffort = 0;
constexpr int kMaxEffort = 9;
constexpr int kDefaultEffort = 3;

// The quantization step a search below kMaxEffort - 1 tries first: this many times target_error x the bounding-box
// diagonal, rounded to an eighth of an octave (bits and step scale 2^(j/8)), then its neighbours. The exhaustive
// search's steps at the paper's errors were 1.93 (horse, 2e-4), 3.09 (venus, 1.3e-4), 2.58 (feline, 2.6e-4) and
// 3.04 (bunny, 2e-4) times; 2.6 is about their geometric mean.
constexpr double kStepPerTargetError = 2.6;
// ... and its first grid size this many times target_error x the diagonal (the same searches' grids: 37, 40, 23
// and 33 times).
constexpr double kGridPerTargetError = 32;

// Which stream pack() makes (issue 22, "never worse than not remeshing"). prm: the remeshed piecewise regular mesh
// (paper §2; format 1.4). general: the input itself through the general path (format 1.0, pack_general.h) at the
// smallest bit depth that meets the target. automatic: both, and the smaller stream is kept; the piecewise regular
// one when the general path refuses the input (non-manifold), the general one when no PRM can be made (the target is
// not reached, repair cannot close the input, ...). Without a target error (a grid given) automatic is prm: there is
// no error the two could be compared at.
enum class PackMode { prm, general, automatic };
const char* pack_mode_name(PackMode mode);  // "prm", "general", "auto" (the --mode values)

// The worst case (issue 22): with PackOptions::max_error, the remesher's local refinement inserts vertices where the
// mesh strays more than kRefineShare x max_error from the input, and the search needs the decoded mesh's max within
// max_error. Without it, the local refinement (PackOptions::local_refinement: the default at every effort but 0)
// refines at kLocalRefineShare x kDefaultMaxErrorPerTarget x target_error, and the search runs unrefined and refines
// only the grid it chooses (RemeshOptions::refine_last: issue 21's CPU budget). When the heights' lambda gives a
// stream over 8x the target, a smaller one that meets both is taken (finish_at; at most kHeightGuardTries of them,
// then the rounded heights: pipeline/src/height_guard.h). When the attempt the search keeps (bit depth, step scale)
// still passes 8x the target once refined (its full-density max), the smallest of its other attempts that meets the
// target and 8x is kept instead (EffortPlan::bound_candidates; when none does, kNoBoundBytes;
// PackResult::search_note says which and why), and the exhaustive search also tries the predicted step
// (kStepPerTargetError), so that it keeps no larger stream than effort 3's first step (hsearch, bench/README.md
// "Worst-case error": the horse at 2e-4, effort 9 5,826 B 12.41x -> 5,490 B 7.48x, effort 4 5,623 B 10.92x -> 5,490
// B 7.48x; at 1.3e-4 none of the attempts is within 8x). With max_error the refinement runs without its notch steps
// (RemeshOptions::refine_notches). With refine_facing_guard (the default) no refinement step, rounding or heights'
// lambda turns a triangle away from the input. Measured at 2e-4 (bench/README.md "Worst-case error", hdefault): the
// max from 10.2-29x the target to 6.6-7.5x on the paper's models and three CGAL meshes, for -1.0% to +3.6% bytes and
// 0.9-3.6 s more CPU.
constexpr double kDefaultMaxErrorPerTarget = 8;
// When none of the search's refined attempts meets kDefaultMaxErrorPerTarget: the one with the smallest max among
// those at most this times the smallest stream (issue 22's +5% bar): the horse at 1.3e-4, effort 9, 8,340 B at 8.60x
// instead of 8,204 B at 13.69x.
constexpr double kNoBoundBytes = 1.05;
constexpr double kRefineShare = 0.6;
// The local refinement without max_error (PackOptions::local_refinement) refines at kLocalRefineShare x kDefaultMaxErrorPerTarget x
// target_error: the thin-sheet steps (remesh::DeviationRefinementOptions::thin_sheets) converge, so the bound can sit
// nearer the max aimed at than --max-error's kRefineShare (bench/README.md "Worst-case error").
constexpr double kLocalRefineShare = 0.85;
// The local refinement's rounds in pack (remesh::ResampleOptions::refine_rounds; `prm remesh` takes 20): the 2e-4
// streams are the same with 20 (the feline +1 B), but the horse at 1.3e-4 grew from 8,606 to 8,726 B and took
// ~0.5-1 s CPU more for the same max (bench/README.md "Worst-case error", h22r and h22t).
constexpr size_t kPackRefineRounds = 12;

struct PackOptions {
  PackMode mode = PackMode::automatic;
  // The grid size: exactly one of these three.
  double target_error = 0;   // largest symmetric RMS distance of the decoded mesh to the input, fraction of the
                             // bounding-box diagonal
  double grid_fraction = 0;  // fraction of the diagonal
  // With target_error (or alone, then it is the target): the largest symmetric maximum distance (the sampled
  // Hausdorff distance, Metro's ten samples per face) of the decoded mesh to the input, fraction of the diagonal.
  // 0: none (the local refinement still aims at kDefaultMaxErrorPerTarget x target_error).
  double max_error = 0;
  // Without max_error: the remesher's local refinement (see above). automatic (the default): with a target error at
  // every effort whose plan has it (EffortPlan::local_refinement: all but 0); on: at every effort; off: never.
  enum class LocalRefinement { automatic, on, off };
  LocalRefinement local_refinement = LocalRefinement::automatic;
  // With the local refinement: no refinement step, rounding or heights' lambda turns a triangle away from the input
  // (remesh::RemeshOptions::refine_facing_guard; finish_at). false: the refinement of h22max8 (bench/README.md
  // "Worst-case error": within 8x on all seven meshes, but up to 42 decoded triangles facing away).
  bool refine_facing_guard = true;
  double grid_size = 0;      // model units
  double tau = 0.2;          // relief smoothing (paper §2.1)
  int bits = 0;              // quantization of the stream, 8..20; 0: with target_error, the bit depth (8..16) that
                             // gives the smallest stream meeting it; otherwise 12
  double step_scale = 0;     // the quantization step in units of 2^-bits of the extent, in [1, 2); 0: with
                             // target_error and bits = 0, searched after the bit depth (kStepScales), otherwise 1
  size_t metro_samples = 0;  // per surface for the error (0: Metro's default, ten per face)
  bool parallel = true;
  bool fit_heights = true;   // least-squares heights (remesh::RemeshOptions::fit_heights)
  double error_flip_weight = remesh::kDefaultErrorFlipWeight;  // error flips (remesh::RemeshOptions)
  // Rate-distortion choice of the heights (codec::PrmOptions::height_lambda, within kHeightTolerance steps of the
  // remeshed heights). With a target error, the grid search rounds the heights; then the largest of kHeightLambdas
  // whose decoded mesh still meets the target is used, found by bisection (the grid size moves in whole
  // quantization steps, and the error it leaves below the target buys smaller residuals). height_lambda > 0: that
  // one, also in the grid search.
  bool optimize_heights = true;
  double height_lambda = 0;
  int height_sweeps = 4;  // codec::PrmOptions::height_sweeps: the choice refined over all heights (0: one by one)
  // The newest format 1.N the stream may need (encode_any_mesh): 4, or 3 (no patch contexts), or 2 (no seam context).
  int max_minor = codec::kFormatMinorPatchGrids;
  int effort = kDefaultEffort;  // kMinEffort..kMaxEffort (see above)
  // Close every boundary loop before remeshing (RepairOptions::fill_holes; the paper's bunny protocol).
  // The output is then closed: on an open input, mode automatic is prm and mode general std::invalid_argument.
  // False: the output keeps the input's boundary loops (the remesher treats the mesh boundary as a seam with no
  // neighbour and never moves its vertices).
  bool fill_holes = false;
  // Without fill_holes, with a target error: before remeshing, each boundary loop is thinned out (a 1-D
  // simplification, simplify_boundary) within this fraction of the target error (times the diagonal); 0: the
  // boundary vertices are all kept. The error is still measured against the input as it came.
  double boundary_simplification = 0;
  // A grid size per relief (issue 23, spec §8.4.2, format 1.5; remesh/relief_grids.h): each relief's grid scaled by
  // its measured detail (equal slope), the search scaling them together to the target. Needs max_minor >= 5
  // (otherwise ignored: one grid). false: one grid for the whole surface.
  bool adaptive = false;
  // How the adaptive allocation models each relief: measured (the default): its squared error on two uniform
  // remeshes at the search's first grid and kAdaptiveModelGridRatio times it (remesh::measure_relief_error, equal
  // slope in remesh::allocate_relief_grid_scales_measured); curvature: predicted from the input's curvature
  // (remesh::measure_relief_detail, adaptive_exponent).
  enum class AdaptiveModel { measured, curvature };
  AdaptiveModel adaptive_model = AdaptiveModel::measured;
  double adaptive_exponent = 1.0 / 6.0;  // remesh::ReliefGridOptions::exponent (the curvature model)
};

// The measured adaptive model's two grids: the search's first grid and this many times it.
constexpr double kAdaptiveModelGridRatio = 1.4142135623730951;

// What one effort level does (effort_plan()).
struct EffortPlan {
  bool exhaustive = false;        // the bit-depth scan and kStepScales (otherwise: steps around the predicted one)
  int steps = 1;                  // without `exhaustive`: how many steps (eighths of an octave) to try
  double search_samples_per_face = 10;  // Metro density while searching (MetroOptions::samples_per_face)
  int lambda_rounds = 5;          // bisection rounds over kHeightLambdas (5 finds the last one that meets)
  double grid_tolerance = 0.02;   // remesh::RemeshOptions::grid_tolerance
  double accept_error = 1.0;      // remesh::RemeshOptions::accept_error
  double first_exponent = 2.0;    // remesh::RemeshOptions::first_exponent
  double next_exponent = 0;       // remesh::RemeshOptions::next_exponent
  double aim = 0.97;              // remesh::RemeshOptions::aim
  bool round_to_nearest = false;  // remesh::RemeshOptions::round_to_nearest
  // Without `exhaustive`: the steps are compared by their streams with rounded heights, and only the best one's
  // heights are chosen by rate and distortion (the lambda bisection) and checked at full density. false: every step's.
  bool defer_heights = false;
  // Without `exhaustive`, with steps = 1 and defer_heights: when the first step's first grid meets the target and
  // its search would go on to a grid of at least this many quantization steps, that search stops there and the next
  // coarser step (an eighth of an octave) is searched instead, from that grid; the first step's search is resumed
  // only when the coarser one gives no smaller stream (rounded heights). 0: never. A grid of many steps leaves the
  // heights' rounding a small share of the error, so a coarser step costs little error and saves bits per height.
  // On the paper's four models only the venus gets there (its first grid, 12 steps at 11 bits and scale 1.09, at
  // 0.74 of the target; the next one 15): scale 1.19, 7% fewer bytes (bench/README.md "pack effort", eighth round).
  int coarser_step_from_grid = 0;
  // PackMode::automatic: the piecewise regular candidate is made first, and the general one only when its stream at
  // its fewest bits (general_floor_bytes, one encode) is smaller than the PRM stream; otherwise it is not tried (the
  // report says so). false: the general candidate is always made, first.
  bool general_floor_check = false;
  // A grid whose sparse estimate falls near the target is measured again at full density; true: on its stream
  // (rounded heights) encoded and decoded rather than on the candidate quantized, one encode more, so that the kept
  // grid's full-density check reuses that measurement when the stream stays the rounded one.
  bool decode_in_band = false;
  // The seam error flips (remesh::RemeshOptions::error_samples, error_unit_stride): closest-point samples per
  // triangle of their squared distance (7: all), and every how many faces their mean triangle error is taken over.
  int error_samples = remesh::kTriangleErrorSamples;
  int error_unit_stride = 1;
  // The lambda rounds are skipped when the rounded heights' error is already at least this fraction of the target
  // (0: never): each costs an encode, a decode and a Metro run, and near the target the lambda misses. At 0.97 (the
  // lower end of pack.cpp's kSparseBand) that error is always a full-density measurement, not an estimate. On the
  // feline at effort 0 the rounded stream is at 0.972 of the target and lambda 0.15's at 1.005 (both at full
  // density); on horse, venus and bunny_zipper lambda 0.15 moved the error by -1.2..+0.5% of the target against the
  // search's estimate of the rounded one (bench/README.md "pack effort", eleventh round).
  double lambda_below = 0;
  // The lambda rounds measure at full density instead of the search's samples, so that the check reuses the kept
  // lambda stream's measurement (its own Metro run otherwise).
  bool lambda_full_density = false;
  // The first grid is predict_first_grid's (first_grid.h, from the input's edges) when that is finer than this
  // fraction of kGridPerTargetError's (0: never): on the feline at 2.6e-4 (predicted 0.77 of the constant's) the
  // first remesh then meets the target and the second is saved; on horse, venus and bunny_zipper (0.94-0.99) the
  // constant's grid stays. The gate, not the prediction alone: the prediction lands at 0.87-0.90 of the grid needed
  // on horse, venus and bunny_zipper, where the constant's is 0.88-0.94 and a finer grid costs bytes and time
  // (bench/README.md "pack effort", twelfth round).
  double first_grid_gate = 0;
  // The heights coded by linear prediction (§9.7, its self-overlapping patches at difference depth 3) without
  // trying the seven difference depths first: one patch-section pass of the search's rounded-heights encode instead
  // of eight.
  bool predicted_heights_only = false;
  // The least-squares heights take a sample's closest point on an input triangle already known for it when the
  // sample projects well inside it (remesh::RemeshOptions::height_fit_reuse_faces, AabbTree::well_inside) instead
  // of a closest-point query: the venus at effort 0 -7% CPU; horse -1 byte, venus the same size, feline and
  // bunny_zipper the same streams (bench/README.md "pack effort", fifteenth round). Its flip tests too (nineteenth).
  bool height_fit_reuse_faces = false;
  // PackOptions::LocalRefinement::automatic refines: everywhere but at effort 0, whose budget (issue 21: 3 s CPU
  // for a 50k-vertex model) the refinement alone would use up (3-5 s on the paper's models, bench/README.md
  // "Worst-case error").
  bool local_refinement = true;
  // With the local refinement and defer_heights: when the kept attempt's refined stream passes
  // kDefaultMaxErrorPerTarget x the target (its full-density max), at most this many of the search's other attempts
  // (smallest unrefined stream first) are refined and their heights chosen, until one meets the target and the
  // bound (hsearch). Without defer_heights every attempt was refined already: the smallest within the bound is kept.
  int bound_candidates = 2;
  // ... but none whose unrefined stream is more than this times the kept attempt's unrefined stream (hcpu3: the
  // refinement shrinks or grows a stream by a few percent, so such a one would be kept at a cost in bytes past issue
  // 22's +5% bar, or not at all: the horse at 1.3e-4, 10,579 B unrefined against 8,511 B, refined to 9,626 B at
  // 22.2x for 4.4 s CPU; at 2e-4 effort 4 the one kept is 5,842 B unrefined against 5,709 B).
  double bound_candidate_bytes = 1.1;
};
EffortPlan effort_plan(int effort);  // throws std::invalid_argument outside kMinEffort..kMaxEffort
// Whether pack refines locally without max_error (PackOptions::local_refinement resolved by options.effort's plan).
bool refines_locally(const PackOptions& options);
// The remesher's refinement (RemeshOptions::refine_error, refine_notches, refine_last, refine_facing_guard) for a
// target error, as pack() asks for it: with max_error > 0 at kRefineShare x max_error, every grid of the search
// refined, no notch steps; otherwise, when `local`, at kLocalRefineShare x kDefaultMaxErrorPerTarget x target_error,
// only the chosen grid refined; otherwise none. `prm remesh --target-error` refines through it too (issue 22).
void set_refinement(remesh::RemeshOptions& ro, double target_error, double max_error, bool local, bool facing_guard);

// The search's refined attempts when the kept one's max passed the bound: each one's stream bytes and max error.
struct BoundedAttempt {
  size_t bytes = 0;
  double max = 0;
};
// The attempt kept: the smallest stream whose max is within `bound` (met_bound true); when none is, the smallest
// max among the streams at most kNoBoundBytes x the smallest (met_bound false). 0 for no attempts.
size_t pick_bounded_attempt(const std::vector<BoundedAttempt>& attempts, double bound, bool& met_bound);
constexpr double kHeightTolerance = 1.5;
// The step scales the search tries at the best bit depth: eighths of an octave towards the next coarser depth. The
// grid size is a whole number of steps, so these also move it in finer increments than the bit depths alone.
// Measured at the paper's errors (`prm pack MODEL --target-error E --bits B --step-scale S`): the feline at 10 bits
// gives 10,678 / 10,968 / 10,319 / 10,765 / 11,873 bytes at scales 1, 2^(1/8), 2^(1/4), 2^(3/8), 2^(1/2); the
// venus at 11 bits 13,251 / 12,895 / 12,831 / 12,867 / 13,294.
constexpr double kStepScales[] = {1.0905077326652577, 1.189207115002721, 1.2968395546510096};
// Increasing, a quarter of a factor 2.5 apart: the refined choice (height_sweeps) moves the error more per step of
// lambda than the greedy one did, and a coarser ladder left the bisection up to 3% of the stream away from the target.
constexpr double kHeightLambdas[] = {0.03, 0.038, 0.048, 0.06, 0.076, 0.096, 0.12, 0.15,
                                     0.19, 0.24, 0.31, 0.39, 0.49, 0.62, 0.79, 1.0};

struct PackResult {
  std::vector<uint8_t> stream;
  codec::EncodeReport report;   // of the stream kept (a general-path report when mode is general)
  remesh::RemeshResult remesh;  // the PRM (with the heights the stream holds), the error of the decoded mesh, the
                                // grid search; with mode general only remesh.error is set (the general stream's)
  RepairReport repair;
  bool repaired = false;        // the input had pinches or degenerate faces (or holes, with fill_holes)
  size_t boundary_loops_in = 0;   // of the input after the repair's pinch splits, before any hole is filled
  size_t boundary_loops_out = 0;  // of the piecewise regular mesh (the stream's; RepairReport::holes_filled: filled)
  size_t boundary_vertices_removed = 0;  // by PackOptions::boundary_simplification, before remeshing
  // Without fill_holes: the remesher could not keep the boundary (an invariant broke, std::logic_error) and pack
  // filled the holes instead, with a note in repair.notes saying so.
  bool boundary_fallback = false;
  int bits = 12;                // the stream's quantization
  codec::PrmOptions codec_options;  // what the stream was encoded with (height_lambda; without `unrounded`, `rounded_heights`)
  double step_scale = 1;        // the stream's step in units of 2^-bits of the extent
  struct Trial {
    int bits = 12;
    double step_scale = 1;
    size_t bytes = 0;
  };
  std::vector<Trial> tried;     // every (bit depth, step scale) the search tried and its stream's size
  size_t remesh_rounds = 0;     // grids remeshed by the whole search
  // The search's choice passed kDefaultMaxErrorPerTarget x the target (the local refinement's bound): which attempt
  // was kept instead and why (EffortPlan::bound_candidates); empty otherwise.
  std::string search_note;
  Mesh repaired_input;          // what was remeshed when `repaired` (the input itself otherwise, not copied)
  double seconds_repair = 0, seconds_remesh = 0, seconds_encode = 0;

  // PackOptions::mode: what the stream is (prm or general) and why; both candidates as they were made or refused.
  PackMode mode = PackMode::prm;
  std::string mode_reason;
  struct Candidate {
    bool made = false;
    std::string refused;      // why it was not made (empty when made or not tried)
    size_t bytes = 0;
    uint32_t vertices = 0;
    int bits = 0;
    double rms = 0, max = 0;  // decoded mesh to what it codes (the repaired input for prm, the input for general)
    double seconds = 0;       // wall-clock seconds to make it
    std::string not_tried;    // why it was not tried (EffortPlan::general_floor_check); empty otherwise
  };
  Candidate prm_candidate, general_candidate;
  double seconds_general = 0;   // the general candidate (the whole job: repair + remesh + encode + general)
  size_t input_vertices = 0;    // n_o: the input's vertices (n_r = report.vertices)
};

// Throws prm::InputError on input the repair cannot make an oriented manifold, remesh::TargetNotReached when no grid
// size meets target_error, and prm::InputError with the codec's message if the PRM cannot be encoded (a bug); with
// mode general, prm::InputError when the general path refuses the input and TargetNotReached when no bit depth meets
// the target; with mode automatic, the PRM's error (naming the general path's too) when neither can be made.
PackResult pack(const Mesh& input, const PackOptions& options);

namespace detail {
// pack's fallback on an open surface with the piecewise regular attempt given: `attempt(input, options)` (pack's own
// remesh-and-encode) keeps the boundary loops unless options.fill_holes; if it throws std::logic_error (a broken
// remesher invariant; std::invalid_argument is rethrown, as is any error on a closed input), the attempt is made
// again with fill_holes, and the result says so (PackResult::boundary_fallback, a note in repair.notes). A seam for
// the tests: no known mesh makes the remesher fail on its boundary.
using PrmAttempt = std::function<PackResult(const Mesh&, const PackOptions&)>;
PackResult pack_keeping_boundary_or_filling(const Mesh& input, const PackOptions& options, const PrmAttempt& attempt);
}  // namespace detail

}  // namespace prm::pipeline
