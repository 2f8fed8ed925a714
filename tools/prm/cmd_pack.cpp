// prm pack IN -o OUT.prm (--target-error E | --target-bytes N | --grid G | --grid-fraction F) [--mode prm|general|auto] [--tau T]
// [--bits B] [--fill-holes] [--json]: the main job. Fix what repair can fix (boundary loops stay open unless
// --fill-holes), remesh into a piecewise regular mesh (paper §2), encode it (spec/prm-format.md); with --mode auto
// also code the input itself through the general path and keep the smaller stream; report which, sizes, error and
// times.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "codec_cli_util.h"
#include "commands.h"
#include "json_report.h"
#include "gltf_commands.h"
#include "prm_stream_info.h"
#include "remesher_options.h"
#include "prm/aabb_tree.h"
#include "prm/error.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/pack.h"
#include "prm/pipeline/pack_to_bytes.h"
#include "prm/pipeline/relief_costs.h"

namespace prm::cli {
namespace {

// --relief-costs (issue 23, pipeline/relief_costs.h): per relief, the patch bits charged to it beside its lattice
// vertices, area and squared error; measured against what was remeshed (the repaired input when repaired).
nlohmann::json relief_costs_json(const pipeline::PackResult& r, const Mesh& input) {
  const AabbTree tree(r.repaired ? r.repaired_input : input);
  const pipeline::ReliefCosts c = pipeline::relief_costs(r.remesh.prm, r.report, tree);
  nlohmann::json reliefs = nlohmann::json::array();
  for (const pipeline::ReliefCost& rc : c.reliefs)
    reliefs.push_back({{"grid_steps", rc.grid}, {"bits", rc.bits}, {"lattice_vertices", rc.lattice_vertices},
                       {"carried_vertices", rc.carried_vertices}, {"area", rc.area}, {"msq", rc.msq},
                       {"msq_quarters", rc.msq_quarters}});
  return {{"prologue_bits", c.prologue_bits}, {"unattributed_bits", c.unattributed_bits}, {"reliefs", reliefs}};
}

}  // namespace

void add_pack_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "pack", "Remesh a mesh into a piecewise regular mesh and compress it into a .prm stream (repair + remesh + encode)");
  struct Options {
    std::string input, output, keep_prm;
    double target = 0, max_error = 0, grid = 0, grid_fraction = 0, tau = 0.2, lambda = 0, step_scale = 0;
    double boundary_simplification = pipeline::PackOptions{}.boundary_simplification;
    int bits = 0, sweeps = 4, effort = pipeline::kDefaultEffort;
    std::string max_version = "1.5", mode = "auto", adaptive_model = "measured";
    size_t samples = 0, target_bytes = 0;
    bool json = false, no_fit = false, round_heights = false, fallback = false, fill_holes = false, refine_on = false,
         refine_off = false,
         adaptive = false, relief_costs = false;
    double adaptive_exponent = 1.0 / 6.0;
    double error_flip_weight = remesh::kDefaultErrorFlipWeight;
  };
  auto opt = std::make_shared<Options>();
  cmd->add_option("input", opt->input, "Mesh file (OBJ/PLY/OFF/STL/glTF); its boundary loops stay open unless --fill-holes")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", opt->output, "Output .prm stream, or .glb/.gltf: a glTF asset with PRM_mesh_compression (a glTF input keeps its whole scene, each triangle primitive remeshed in its own frame)")->required();
  auto* te = cmd->add_option("--target-error", opt->target,
                             "Largest RMS distance to the input, as a fraction of the bounding-box diagonal "
                             "(e.g. 2e-4): the grid size is searched")
                 ->check(CLI::Range(1e-7, 0.1));
  auto* g = cmd->add_option("--grid", opt->grid, "Grid size in model units")->check(CLI::PositiveNumber);
  auto* gf = cmd->add_option("--grid-fraction", opt->grid_fraction, "Grid size as a fraction of the diagonal")
                 ->check(CLI::Range(1e-6, 0.5));
  auto* me = cmd->add_option("--max-error", opt->max_error,
                             "Largest maximum distance (sampled Hausdorff, Metro's ten samples per face) between the "
                             "decoded mesh and the input, as a fraction of the bounding-box diagonal (e.g. 1.6e-3); "
                             "alone or with --target-error, the search meets both; the remesher also inserts vertices "
                             "where the mesh strays more than " + std::to_string(pipeline::kRefineShare).substr(0, 3) +
                                 " x this from the input (bench/README.md 'Worst-case error'). Default: none")
                 ->check(CLI::Range(1e-7, 0.1));
  auto* tb = cmd->add_option("--target-bytes", opt->target_bytes,
                             "A byte budget instead of --target-error: the stream of the lowest RMS error whose size is at "
                             "most this many bytes (the target error is searched over a ladder of " +
                                 std::to_string(pipeline::kBytesLadderSteps) +
                                 " steps an octave, one whole pack per step tried, about 4-8 packs). Exit 3 when even "
                                 "the coarsest stream is larger. Alone or with --adaptive, --max-error, --mode, --effort")
                 ->check(CLI::PositiveNumber);
  tb->excludes(te)->excludes(g)->excludes(gf);
  te->excludes(g)->excludes(gf);
  me->excludes(g)->excludes(gf);
  g->excludes(gf);
  cmd->add_option("--tau", opt->tau, "Relief smoothing parameter in (0, 0.577) (default 0.2; paper: 0.1-0.3)");
  cmd->add_option("--bits", opt->bits,
                  "Quantization bits per coordinate (8..20). Default: with --target-error, the bit depth (8..16) that "
                  "gives the smallest stream meeting it; otherwise 12")
      ->check(CLI::Range(8, 20));
  cmd->add_option("--step-scale", opt->step_scale,
                  "Quantization step in units of 2^-bits of the bounding box's largest extent, in [1, 2). Default: with "
                  "--target-error and no --bits, 1 and then 2^(1/8), 2^(1/4), 2^(3/8) at the best bit depth (three "
                  "more grid searches; --step-scale 1 skips them); otherwise 1")
      ->check(CLI::Range(1.0, 1.999999));
  cmd->add_option("--effort", opt->effort,
                  "With --target-error: how hard to look for the smallest stream, 0 (fastest) to 9 (the exhaustive "
                  "search over bit depths and step scales; bench/README.md 'pack effort' measures time against bytes). "
                  "Default " + std::to_string(pipeline::kDefaultEffort))
      ->check(CLI::Range(pipeline::kMinEffort, pipeline::kMaxEffort));
  cmd->add_option("--mode", opt->mode,
                  "prm: remesh and code the piecewise regular mesh; general: code the input itself through the general "
                  "path (format 1.0, or 1.3 with the seam context, as `prm encode`) at the smallest bit depth (8..20) "
                  "that meets --target-error and --max-error (exit 2 if it refuses the input: non-manifold; 3 if no bit depth meets the "
                  "target without collapsing a triangle); auto "
                  "(default): make both and keep the smaller stream (below --effort 9 the general one only when its stream "
                  "at 8 bits is smaller than the piecewise regular one, otherwise it cannot win and is not tried; prm "
                  "when the general path refuses the input, "
                  "general when no piecewise regular mesh meets the target; prm without --target-error or --max-error, and "
                  "with --fill-holes on an open input, whose holes the general path would keep). The report "
                  "says which and why")
      ->check(CLI::IsMember({"prm", "general", "auto"}));
  cmd->add_option("--samples", opt->samples, "Metro samples per surface for the target-error search (default 0: Metro's ten per face)");
  cmd->add_option("--keep-prm", opt->keep_prm, "Also write the piecewise regular mesh (PLY with lattice labels)");
  add_remesher_options(cmd, opt->error_flip_weight, opt->no_fit);
  cmd->add_option("--height-lambda", opt->lambda,
                  "Rate-distortion weight of the coded heights (squared quantization steps per bit; each height may "
                  "move up to 1.5 steps; spec Appendix B). Default: with --target-error, the largest of sixteen values "
                  "from 0.03 to 1 that still meets the target (bisection); otherwise 0 (heights rounded)")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--height-sweeps", opt->sweeps,
                  "Sweeps of the refinement of that choice over all heights together, each height also weighing the "
                  "residuals it predicts (spec Appendix B.2; default 4; 0: each height alone, in coding order)")
      ->check(CLI::Range(0, 16));
  auto* refine_on = cmd->add_flag(
      "--local-refinement", opt->refine_on,
      "Without --max-error, the default at every --effort but 0 (whose budget it would use up; this flag asks for it "
      "there too): insert or move vertices where the remeshed surface strays more than " +
          std::to_string(pipeline::kLocalRefineShare * pipeline::kDefaultMaxErrorPerTarget).substr(0, 3) +
          " x --target-error from the input (thin sheets the grid cuts off, lattice vertices off the input; "
          "near that bound, the rounding to the step that strays least; no step, rounding or heights' lambda "
          "turns a triangle away from the input, an insertion's edges flipped until they face it, a lambda's heights "
          "rounded at the corners it would turn, and the separation of vertices sharing a quantization point "
          "moves none beyond that bound; bench/README.md "
          "'Worst-case error': the horse's max from 25x to 7.5x the target for +3.6% bytes, venus from 16x to "
          "7.4x for +2.9%, the feline from 19x to 7.5x for +1.3%, the camel from 29x to 7.5x for -1.0%)");
  cmd->add_flag("--no-local-refinement", opt->refine_off,
                "Without --max-error: no local refinement (the streams of before it was the default: smaller by up to "
                "4% on the paper's models, their max error up to 34x the target)")
      ->excludes(refine_on);
  cmd->add_flag("--adaptive", opt->adaptive,
                "A grid size per relief (format 1.5, spec §8.4.2): each relief's grid chosen by equal slope (the same "
                "marginal bytes per unit of squared error in every relief) from its error measured on two uniform "
                "remeshes (--adaptive-model), the search scaling them together to the target; ignored with "
                "--max-version below 1.5");
  cmd->add_option("--adaptive-model", opt->adaptive_model,
                  "With --adaptive: measured (default: each relief's squared error on two uniform remeshes, at the "
                  "search's first grid and 1.41 times it, fitted to error ~ g^p) or curvature (predicted from the "
                  "input's mean squared curvature, --adaptive-exponent; no extra remesh)")
      ->check(CLI::IsMember({"measured", "curvature"}));
  cmd->add_option("--adaptive-exponent", opt->adaptive_exponent,
                  "With --adaptive-model curvature: a relief's grid goes as its mean squared curvature to the minus this power (default "
                  "1/6: RMS error ~ g^2, bytes ~ g^-2)")
      ->check(CLI::Range(0.01, 1.0));
  cmd->add_flag("--relief-costs", opt->relief_costs,
                "With --json, a PRM stream: relief_costs, per relief its grid, the patch bits charged to it (each "
                "patch's header and height bits shared among the reliefs of the vertices it carries), its lattice "
                "vertices, area and mean squared distance to the input (bench/README.md 'The bound')");
  cmd->add_flag("--round-heights", opt->round_heights,
                "Round every height to the nearest step (no rate-distortion choice; for comparison)");
  cmd->add_option("--max-version", opt->max_version,
                  "Newest format the stream may need, for older decoders: 1.5 (default), 1.4 (one grid size for every "
                  "patch, spec §8.4.2), 1.3 (no patch contexts either, "
                  "§8.4.1), 1.2 (no CLERS seam context either, §6.5.2)")
      ->check(CLI::IsMember({"1.2", "1.3", "1.4", "1.5"}));
  cmd->add_flag("--fallback", opt->fallback,
                "With a .glb/.gltf output: also store the decoded geometry uncompressed, so that loaders without "
                "PRM_mesh_compression show it (the extension is then not required)");
  cmd->add_flag("--fill-holes", opt->fill_holes,
                "Close every boundary loop before remeshing (the paper's bunny protocol, bench/table1; by the triangulation "
                "of the loop that folds least, a fan around its centroid as the paper's for loops over 400 vertices). "
                "Default: the output keeps the input's boundary loops");
  cmd->add_option("--boundary-simplification", opt->boundary_simplification,
                  "Open surfaces, with --target-error: before remeshing, thin out each boundary loop (collapse boundary "
                  "vertices along it) while it stays within this fraction of the target error of the input's loop; 0: "
                  "keep every boundary vertex")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--json", opt->json, kJsonFlagHelp);
  cmd->callback([opt] {
    if (is_prm_stream_path(opt->input) && is_gltf_file_path(opt->output))
      return wrap_prm_stream(opt->input, opt->output, opt->fallback, opt->json);
    if (opt->grid <= 0 && opt->grid_fraction <= 0 && opt->target <= 0 && opt->max_error <= 0 && opt->target_bytes == 0)
      throw CLI::ValidationError("pack", "give one of --target-error (and/or --max-error), --target-bytes, --grid or "
                                         "--grid-fraction");
    if (opt->target_bytes > 0 && is_gltf_file_path(opt->output))
      throw CLI::ValidationError("pack", "--target-bytes writes a .prm stream (not a glTF asset)");
    check_pack_output(opt->output, opt->fallback);
    pipeline::PackOptions po;
    po.target_error = opt->target;
    po.max_error = opt->max_error;
    using Refinement = pipeline::PackOptions::LocalRefinement;
    po.local_refinement = opt->refine_on ? Refinement::on : opt->refine_off ? Refinement::off : Refinement::automatic;
    po.grid_size = opt->grid;
    po.grid_fraction = opt->grid_fraction;
    po.tau = opt->tau;
    po.bits = opt->bits;
    po.step_scale = opt->step_scale;
    po.metro_samples = opt->samples;
    po.fit_heights = !opt->no_fit;
    po.error_flip_weight = opt->error_flip_weight;
    po.height_lambda = opt->lambda;
    po.optimize_heights = !opt->round_heights;
    po.adaptive = opt->adaptive;
    po.adaptive_exponent = opt->adaptive_exponent;
    po.adaptive_model = opt->adaptive_model == "curvature" ? pipeline::PackOptions::AdaptiveModel::curvature
                                                           : pipeline::PackOptions::AdaptiveModel::measured;
    po.height_sweeps = opt->sweeps;
    po.max_minor = opt->max_version[2] - '0';
    po.effort = opt->effort;
    po.mode = opt->mode == "prm" ? pipeline::PackMode::prm
              : opt->mode == "general" ? pipeline::PackMode::general : pipeline::PackMode::automatic;
    if (po.mode == pipeline::PackMode::general && opt->target <= 0 && opt->max_error <= 0 && opt->bits <= 0 &&
        opt->target_bytes == 0)
      throw CLI::ValidationError("pack", "--mode general needs --target-error, --target-bytes, --max-error or --bits");
    if (po.mode == pipeline::PackMode::general && opt->fill_holes)
      throw CLI::ValidationError("pack", "--fill-holes closes the input's holes, which --mode general keeps");
    po.fill_holes = opt->fill_holes;
    po.boundary_simplification = opt->boundary_simplification;
    if (is_gltf_file_path(opt->output)) return run_gltf_pack(opt->input, opt->output, po, opt->fallback, opt->json);
    note_gltf_to_prm(opt->input);
    ReadReport read;
    const Mesh input = read_mesh(opt->input, {}, &read);
    pipeline::PackResult r;
    pipeline::PackToBytesResult budgeted;  // --target-bytes: the search (r is its stream)
    try {
      if (opt->target_bytes > 0) {
        budgeted = pipeline::pack_to_bytes(input, opt->target_bytes, po);
        r = std::move(budgeted.result);
      } else {
        r = pipeline::pack(input, po);
      }
    } catch (const pipeline::BudgetTooSmall& e) {
      throw Failure(opt->input + ": --target-bytes " + std::to_string(opt->target_bytes) + ": " + e.what());
    } catch (const remesh::TargetNotReached& e) {
      throw Failure(opt->input + ": " + e.what());
    } catch (const InputError& e) {
      throw InputError(opt->input + ": " + e.what());
    }
    // Nothing is dropped or moved silently: what reading, repair and quantization changed.
    std::vector<std::string> changes;
    if (read.unreferenced_dropped) changes.push_back(std::to_string(read.unreferenced_dropped) + " unreferenced vertices dropped on reading");
    if (read.degenerate_dropped) changes.push_back(std::to_string(read.degenerate_dropped) + " face(s) with a repeated index dropped on reading");
    if (read.vertices_welded) changes.push_back(std::to_string(read.vertices_welded) + " coincident vertices welded on reading");
    for (const std::string& c : repair_summary(r.repair)) changes.push_back(c);
    if (r.boundary_vertices_removed)
      changes.push_back(std::to_string(r.boundary_vertices_removed) + " boundary vertices thinned out of the input's "
                        "loops before remeshing (--boundary-simplification: within " +
                        std::to_string(opt->boundary_simplification) + " x the target of the input's loops)");
    if (const size_t moved = r.remesh.prm.stats.quantized_moves)
      changes.push_back(std::to_string(moved) + " remeshed vertices moved by up to two quantization steps so that no "
                        "triangle loses its area");
    if (const size_t collapsed = r.remesh.prm.stats.quantized_collapses)
      changes.push_back(std::to_string(collapsed) + " remeshed edge(s) collapsed whose two ends the quantization put on "
                        "one point, or of a sliver no move kept whole and facing the input (one vertex and two "
                        "triangles each)");
    if (const size_t turned = r.remesh.prm.stats.quantized_turned)
      changes.push_back(std::to_string(turned) + " remeshed triangle(s) facing the input turned away from it by the "
                        "quantization (what the separation could not mend)");
    const bool general = r.mode == pipeline::PackMode::general;
    std::vector<std::string> notes = r.repair.notes;
    if (!r.search_note.empty()) notes.push_back(r.search_note);
    write_file_bytes(opt->output, r.stream);
    if (!opt->keep_prm.empty()) {
      if (general)
        notes.push_back("--keep-prm: nothing written, the stream codes the input itself (no piecewise regular mesh)");
      else
        write_mesh(r.remesh.prm.mesh, opt->keep_prm, WriteOptions{MeshFormat::Ply, true, true, true});
    }

    const codec::EncodeReport& rep = r.report;
    const auto& s = r.remesh.prm.stats;
    const double n_r = rep.vertices ? rep.vertices : 1;
    const double n_o = static_cast<double>(input.num_vertices());
    const double g = static_cast<double>(r.remesh.prm.lattice.A) * r.remesh.prm.frame.step;
    const size_t geometry = rep.total_bytes - rep.header_bytes - rep.framing_bytes - rep.connectivity_bytes -
                            rep.irregular_bytes;
    double seconds = r.seconds_repair + r.seconds_remesh + r.seconds_encode + r.seconds_general;
    if (opt->target_bytes > 0) {  // every pack of the search
      seconds = 0;
      for (const pipeline::BytesSearchStep& st : budgeted.steps) seconds += st.seconds;
    }
    if (opt->json) {
      nlohmann::json search = nlohmann::json::array();  // the chosen step's grid search
      for (const auto& st : r.remesh.search) search.push_back({{"grid_steps", st.grid}, {"rms", st.error.rms}});
      nlohmann::json tried = nlohmann::json::array();
      for (const auto& t : r.tried) tried.push_back({{"bits", t.bits}, {"step_scale", t.step_scale}, {"bytes", t.bytes}});
      auto candidate = [](const pipeline::PackResult::Candidate& c) {
        nlohmann::json j = {{"made", c.made}, {"seconds", c.seconds}};
        if (c.made) {
          j["bytes"] = c.bytes;
          j["vertices"] = c.vertices;
          j["bits"] = c.bits;
          j["rms_rel"] = c.rms;
          j["max_rel"] = c.max;
        } else if (!c.refused.empty()) {
          j["refused"] = c.refused;
        } else if (!c.not_tried.empty()) {
          j["not_tried"] = c.not_tried;
        }
        return j;
      };
      // The shared schema (json_report.h, docs/cli-json.md), then pack's own keys.
      JsonReport j("pack");
      j.input(opt->input).output(opt->output).mesh_size(rep.vertices, rep.triangles);
      j.bytes(rep.total_bytes, rep.vertices,
              {{"connectivity", rep.connectivity_bytes},
               {"irregular", rep.irregular_bytes},
               {"geometry", geometry},
               {"header_and_framing", rep.header_bytes + rep.framing_bytes}});
      j.seconds(seconds);
      j.distance(r.remesh.error.rms, r.remesh.error.max);
      j["seconds_by_stage"] = {{"repair", r.seconds_repair},
                               {"remesh", r.seconds_remesh},
                               {"encode", r.seconds_encode},
                               {"general", r.seconds_general}};
      j["mode"] = pipeline::pack_mode_name(r.mode);
      j["mode_requested"] = opt->mode;
      j["mode_reason"] = r.mode_reason;
      j["candidates"] = {{"prm", candidate(r.prm_candidate)}, {"general", candidate(r.general_candidate)}};
      j["n_o"] = input.num_vertices();
      j["n_r"] = rep.vertices;
      j["n_r_over_n_o"] = n_o > 0 ? rep.vertices / n_o : 0.0;
      j["holes_closed"] = r.repair.holes_filled;
      j["boundary_loops_in"] = r.boundary_loops_in;
      j["boundary_loops_out"] = r.boundary_loops_out;
      j["boundary_fallback"] = r.boundary_fallback;
      j["boundary_vertices_removed"] = r.boundary_vertices_removed;
      j["changes"] = changes;
      j["notes"] = notes;
      j["bits"] = r.bits;
      j["step_scale"] = r.step_scale;
      j["tried"] = tried;
      j["effort"] = opt->effort;
      j["max_error"] = opt->max_error;
      if (opt->target_bytes > 0) {
        nlohmann::json steps = nlohmann::json::array();
        for (const pipeline::BytesSearchStep& st : budgeted.steps) {
          nlohmann::json js = {{"target_error", st.target_error}, {"made", st.made}, {"seconds", st.seconds}};
          if (st.made) {
            js["bytes"] = st.bytes;
            js["rms_rel"] = st.rms;
            js["max_rel"] = st.max;
          }
          steps.push_back(js);
        }
        j["target_bytes"] = opt->target_bytes;
        j["target_error"] = budgeted.target_error;
        j["bytes_search"] = steps;
        j["bytes_search_finest"] = budgeted.finest;
      }
      if (!general) {
        j["grid_size"] = g;
        j["grid_steps"] = r.remesh.prm.lattice.A;
        j["grid_sizes"] = rep.grid_sizes;  // §8.4.2: 1, or 2..8 with --adaptive
        j["adaptive"] = opt->adaptive;
        if (opt->adaptive) j["adaptive_model"] = opt->adaptive_model;
        if (opt->relief_costs) j["relief_costs"] = relief_costs_json(r, input);
        j["tau"] = opt->tau;
        j["step"] = r.remesh.prm.frame.step;
        j["remesh_rounds"] = r.remesh_rounds;
        j["search"] = search;
        j["regular_share"] = s.faces ? static_cast<double>(s.regular_faces) / s.faces : 0.0;
        j["regular_patches"] = rep.regular_patches;
        // The refinement ran: --max-error's, or the local one (with a target error, by --effort unless asked).
        j["local_refinement"] = po.max_error > 0 || (po.target_error > 0 && pipeline::refines_locally(po));
        j["refined_vertices"] = s.deviation_inserts;
        j["refined_moves"] = s.deviation_moves;
        j["refined_rounded"] = s.deviation_rounded;
        j["refined_facing_skips"] = s.deviation_facing_skipped;
        j["height_lambda"] = r.codec_options.height_lambda;
        j["height_sweeps"] = r.codec_options.height_lambda > 0 ? r.codec_options.height_sweeps : 0;
      }
      j.print();
    } else {
      std::printf("%s -> %s: %zu bytes, %.3f bits per vertex\n", opt->input.c_str(), opt->output.c_str(),
                  rep.total_bytes, 8.0 * rep.total_bytes / n_r);
      std::printf("  mode: %s (%s)\n", pipeline::pack_mode_name(r.mode), r.mode_reason.c_str());
      if (opt->target_bytes > 0) {
        std::printf("  target bytes %zu: kept the stream packed at target error %.4g (%zu packs, %.1f s:", opt->target_bytes,
                    budgeted.target_error, budgeted.steps.size(), seconds);
        for (const pipeline::BytesSearchStep& st : budgeted.steps) {
          if (st.made)
            std::printf(" %.3g: %zu B", st.target_error, st.bytes);
          else
            std::printf(" %.3g: not made", st.target_error);
        }
        std::printf(")%s\n", budgeted.finest ? "; the budget holds even the finest target error tried" : "");
      }
      for (const std::string& c : changes) std::printf("  changed: %s\n", c.c_str());
      for (const std::string& n : notes) std::printf("  note: %s\n", n.c_str());
      if (general)
        std::printf("  coded as it is: %zu -> %u vertices (n_r/n_o %.3f), %u triangles\n", input.num_vertices(),
                    rep.vertices, n_o > 0 ? rep.vertices / n_o : 0.0, rep.triangles);
      else
        std::printf("  remeshed: %zu -> %u vertices (n_r/n_o %.3f), grid %.6g (%lld steps), %.1f%% regular triangles "
                    "in %u patches\n",
                    input.num_vertices(), rep.vertices, n_o > 0 ? rep.vertices / n_o : 0.0, g,
                    static_cast<long long>(r.remesh.prm.lattice.A),
                    s.faces ? 100.0 * static_cast<double>(s.regular_faces) / s.faces : 0.0, rep.regular_patches);
      std::printf("  boundary loops: %zu in, %zu out", r.boundary_loops_in, r.boundary_loops_out);
      if (r.repair.holes_filled) std::printf(" (%zu filled: --fill-holes)", r.repair.holes_filled);
      std::printf("\n");
      std::printf("  error of the decoded mesh to the input: RMS %.3e, max %.3e of the diagonal, at %d bits",
                  r.remesh.error.rms, r.remesh.error.max, r.bits);
      if (r.step_scale != 1) std::printf(" with the step x%.3f", r.step_scale);
      if (r.tried.size() > 1) {
        std::printf(" (tried:");
        for (const auto& t : r.tried) {
          std::printf(" %d", t.bits);
          if (t.step_scale != 1) std::printf(" x%.3f", t.step_scale);
          std::printf(": %zu B", t.bytes);
        }
        std::printf(")");
      }
      if (r.codec_options.height_lambda > 0)
        std::printf(", heights chosen by rate and distortion (lambda %.2f)", r.codec_options.height_lambda);
      std::printf("\n");
      std::printf("  stream: connectivity %zu B (%.2f bpv), irregular triangles %zu B (%.2f bpv), geometry %zu B "
                  "(%.2f bpv), header %zu B\n",
                  rep.connectivity_bytes, 8.0 * rep.connectivity_bytes / n_r, rep.irregular_bytes,
                  8.0 * rep.irregular_bytes / n_r, geometry, 8.0 * geometry / n_r, rep.header_bytes + rep.framing_bytes);
      std::printf("  time: repair %.2f s, remesh %.2f s (%zu grids, effort %d), encode %.3f s, general path %.3f s\n",
                  r.seconds_repair, r.seconds_remesh, r.remesh_rounds, opt->effort, r.seconds_encode,
                  r.seconds_general);
    }
  });
}

}  // namespace prm::cli
