// §7.1 The encoder's regularity check and §8-§9 the patches section, encoder side (patch headers, heights by
// recursive difference patches). The decoder side is patch_decode.cpp; the shared steps are in patch_shared.h.
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "height_choice.h"
#include "height_prediction_fit.h"
#include "patch.h"
#include "patch_shared.h"
#include "range_encoder.h"
#include "status.h"

namespace prm::codec {
namespace {

// Lattice coordinates of vertex v for pair k, if it is a lattice point.
bool lattice_of(const std::vector<uint32_t>& cq, const HexLattice& lc, int pair, uint32_t v,
                std::array<int64_t, 2>& ij) {
  const int64_t u = cq[3 * size_t{v} + static_cast<size_t>(pair_u(pair))];
  const int64_t w = cq[3 * size_t{v} + static_cast<size_t>(pair_w(pair))];
  return lc.to_lattice(u, w, ij[0], ij[1]);
}

// §7.1 The axis a triangle is regular for, or -1.
int regular_axis(const std::vector<uint32_t>& cq, const HexLattice& lc, const uint32_t* v) {
  for (int pair = 0; pair < 3; ++pair) {
    std::array<int64_t, 2> p[3];
    if (!lattice_of(cq, lc, pair, v[0], p[0]) || !lattice_of(cq, lc, pair, v[1], p[1]) ||
        !lattice_of(cq, lc, pair, v[2], p[2]))
      continue;
    bool unit = true;
    for (int k = 0; k < 3; ++k)
      unit = unit && direction_index(p[(k + 1) % 3][0] - p[k][0], p[(k + 1) % 3][1] - p[k][1]) >= 0;
    if (!unit) continue;
    const int64_t cross = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if (cross == 1) return 2 * pair;
    if (cross == -1) return 2 * pair + 1;
  }
  return -1;
}

// §9.7.4 The reference encoder's choice per patch: linear prediction unless more than 1/64 of the vertices share a
// lattice point with another (a self-overlapping patch, whose sheets the raster order would mix).
bool use_prediction(uint32_t shared, uint32_t vertices, bool always) {
  return always || uint64_t{shared} * 64 <= vertices;
}

// Appendix B.2 The refinement's records of one patch's heights, as code_lp_heights coded them (res, coded: its
// residuals and coded flags). window(l, given): the height's HeightWindow.
template <typename Window>
void record_heights(const Level& level, const LpRaster& raster, const LpTable& table, const LpModels& models,
                    const std::vector<uint8_t>& placed, const std::vector<uint32_t>& global,
                    const std::vector<int64_t>& h, const std::vector<int64_t>& res, const std::vector<uint8_t>& coded,
                    int pair, int64_t lo, int64_t hi, const Window& window, const std::vector<uint32_t>& cq,
                    std::vector<ChosenHeight>& out) {
  std::array<uint32_t, kLpOffsets> id;
  for (uint32_t l : raster.order()) {
    if (placed[l]) continue;
    const int s = table.select(raster.taps(level.coord[l][0], level.coord[l][1], id));
    ChosenHeight c;
    c.vertex = global[l];
    c.pair = static_cast<uint8_t>(pair);
    c.lo = lo;
    c.hi = hi;
    const int group = s == kLpNoSet ? kLpGroups - 1 : lp_group(table.taps[s]);
    int sign = kLpNoSignContext;
    if (models.sign_context) {
      // The prediction as code_lp_heights made it; a height without a tap set keeps kLpNoSignContext's table,
      // which is never used (it is held).
      const int64_t pred = s == kLpNoSet ? lo : std::clamp(lp_predict(table, s, id, h), lo, hi);
      sign = lp_sign_context(id, h, pred);
    }
    c.context = static_cast<uint16_t>(residual_context(group, lp_activity(id, res, coded), sign));
    if (s != kLpNoSet) {
      c.taps = static_cast<uint8_t>(table.taps[s]);
      for (int k = 0; k < table.taps[s]; ++k) {
        c.tap_vertex[static_cast<size_t>(k)] = global[id[table.tap[s][k]]];
        c.weight[static_cast<size_t>(k)] = table.weight[s][k];
      }
    }
    c.window = window(l, static_cast<int64_t>(cq[3 * size_t{c.vertex} + static_cast<size_t>(pair)]));
    c.window.free = c.window.free && c.taps > 0;  // a height predicted without taps is held
    out.push_back(c);
  }
}

}  // namespace

void classify_triangles(const ClosedMesh& mesh, const std::vector<uint32_t>& cq, const std::vector<int64_t>& grids,
                        std::vector<int8_t>& tri_axis, std::vector<uint8_t>& tri_grid) {
  const uint32_t nt = mesh.num_triangles();
  std::vector<HexLattice> lattices;
  for (int64_t g : grids) lattices.push_back(HexLattice::with_grid(g));
  const std::vector<uint8_t> dummy = dummy_triangles(mesh);
  tri_axis.assign(nt, -1);
  tri_grid.assign(nt, 0);
  for (uint32_t t = 0; t < nt; ++t) {
    if (dummy[t] == kDummyTriangle) continue;
    for (size_t g = 0; g < lattices.size() && tri_axis[t] < 0; ++g) {
      tri_axis[t] = static_cast<int8_t>(regular_axis(cq, lattices[g], &mesh.corner_vertex[3 * t]));
      tri_grid[t] = static_cast<uint8_t>(g);
    }
  }
  // §8.2 One axis and one grid per patch: regular neighbours of different axes or grids are both made irregular.
  std::vector<uint8_t> demote(nt, 0);
  for (uint32_t t = 0; t < nt; ++t) {
    if (tri_axis[t] < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = static_cast<uint32_t>(mesh.opp[3 * t + k]) / 3;
      if (tri_axis[n] >= 0 && (tri_axis[n] != tri_axis[t] || tri_grid[n] != tri_grid[t])) demote[t] = 1;
    }
  }
  for (uint32_t t = 0; t < nt; ++t)
    if (demote[t]) tri_axis[t] = -1;
}

namespace {

// §9.7.2 A predictor table and which of its sets carry their weights.
struct FittedTable {
  LpTable table;
  std::array<bool, kLpSets> fitted{};
};

// The encoder's side of the coder the shared steps (patch_shared.h, height_prediction_shared.h) are written over:
// each codes the truth it is given and returns it.
struct EncodeBit {
  RangeEncoder& rc;
  bool operator()(BitModel& m, bool truth) const {
    rc.encode_bit(m, truth ? 1 : 0);
    return truth;
  }
};
struct EncodeValue {
  RangeEncoder& rc;
  bool operator()(SignedIntModel& m, int, int64_t truth, int64_t& out, BitModel* sign = nullptr) const {
    encode_signed(rc, m, truth, sign ? *sign : m.sign);
    out = truth;
    return true;
  }
};
struct EncodeDirect {
  RangeEncoder& rc;
  uint32_t operator()(int n, uint32_t truth) const {
    rc.encode_direct(truth, n);
    return truth;
  }
};

// §8-§9 One writing of the patches section, its steps in the order of the section: the fields (§8.4, §9.7.2), the
// predictor table (§9.7.2), then per patch its header (§8.4, §8.4.1) and its heights, by linear prediction (§9.7.4)
// or by difference patches (§9.1-§9.3).
class PatchSectionWriter {
 public:
  // known: filled with 1 for every vertex of a patch. freedom (optional): as write_patches.
  PatchSectionWriter(const ClosedMesh& mesh, const std::vector<uint32_t>& cq, const std::vector<int8_t>& tri_axis,
                     const PatchCoding& coding, const HeightFreedom* freedom, std::vector<uint8_t>& known)
      : mesh_(mesh), cq_(cq), tri_axis_(tri_axis), coding_(coding), freedom_(freedom), known_(known),
        predicted_(coding.depth == kHeightDepthPredicted),
        free_heights_(freedom && freedom->exact && freedom->tolerance >= 0.5 && freedom->lambda > 0),
        cw_(free_heights_ ? cw_copy_ : cq) {}

  // write_patches, with the predictor table `given` instead of one fitted to cq (the refinement's heights are
  // coded with the table they were refined for).
  Status write(const FittedTable* given, std::vector<uint8_t>& payload, PatchStats* stats,
               std::vector<uint32_t>* chosen);

 private:
  void start();
  Status prepare(size_t p);
  void release();
  Status write_table(const FittedTable* given);
  void write_header(size_t p);
  Status write_lp_heights(size_t p);
  Status write_difference_heights(size_t p);

  const ClosedMesh& mesh_;
  const std::vector<uint32_t>& cq_;
  const std::vector<int8_t>& tri_axis_;
  const PatchCoding& coding_;
  const HeightFreedom* freedom_;
  std::vector<uint8_t>& known_;
  std::vector<HexLattice> lattices_;  // §8.4.2 per grid of the table (one without Flags bit 4)
  const bool predicted_;
  // The positions as coded so far: cq, with the heights the encoder chose when it has freedom.
  const bool free_heights_;
  std::vector<uint32_t> cw_copy_;
  const std::vector<uint32_t>& cw_;
  // A vertex in regular triangles of two axis pairs keeps its coordinates: its height for one is a lattice
  // coordinate for the other (§8.3 checks it).
  std::vector<uint8_t> pairs_of_;
  PatchSet ps_;
  RangeEncoder rc_;
  EncodeBit bit_{rc_};
  EncodeValue value_{rc_};
  EncodeDirect direct_{rc_};
  std::unique_ptr<PatchModels> models_ = std::make_unique<PatchModels>();
  std::vector<uint32_t> vertex_corner_;  // §10.2, for the base references (§8.4.1)
  FittedTable own_;                      // §9.7.2 the predictor table
  // One patch: its axis, header fields, level 0 and heights.
  std::vector<uint32_t> local_, global_, queue_;
  Level level_;
  std::vector<std::vector<int64_t>> f_;
  std::vector<LevelPlan> plans_;
  std::vector<uint32_t> tri_pos_, twin_;
  std::vector<uint8_t> scratch_, placed_;
  std::vector<int64_t> h_, res_;
  LpRaster raster_;
  int axis_ = 0, align_ = 0, grid_ = 0;  // grid_: the patch's Grid_Index (§8.4.2)
  std::array<int64_t, 2> c0_;
  std::array<int64_t, 2> previous_{0, 0};
  std::optional<LpNeighbours> nb_;   // §9.7.4 for the vertices without a tap set
  std::vector<ChosenHeight> refine_;  // Appendix B.2 the heights the refinement may move
};

// The patches, the models, and §8.4 Grid_Size and Height_Depth, §9.7.2 Overlap_Depth.
void PatchSectionWriter::start() {
  const uint32_t nt = mesh_.num_triangles();
  std::vector<uint8_t> cls = dummy_triangles(mesh_);
  for (uint32_t t = 0; t < nt; ++t)
    if (cls[t] != kDummyTriangle) cls[t] = tri_axis_[t] >= 0 ? kRegular : kIrregular;
  ps_ = build_patches(mesh_, cls);
  models_->lp.sign_context = coding_.contexts;
  if (coding_.contexts) vertex_corners(mesh_, vertex_corner_);
  lattices_.clear();
  for (int64_t g : coding_.grids) lattices_.push_back(HexLattice::with_grid(g));
  rc_.encode_direct(static_cast<uint32_t>(coding_.grids[0]), kGridBits);
  rc_.encode_direct(static_cast<uint32_t>(coding_.depth), 3);
  if (coding_.grids.size() > 1) {  // §8.4.2 the grid table
    rc_.encode_direct(static_cast<uint32_t>(coding_.grids.size() - 1), kExtraGridCountBits);
    for (size_t k = 1; k < coding_.grids.size(); ++k) rc_.encode_direct(static_cast<uint32_t>(coding_.grids[k]), kGridBits);
  }
  if (predicted_) rc_.encode_direct(static_cast<uint32_t>(coding_.overlap_depth), 3);
  if (free_heights_) {
    cw_copy_ = cq_;
    pairs_of_.assign(mesh_.num_vertices, 0);
    for (uint32_t t = 0; t < nt; ++t)
      if (tri_axis_[t] >= 0)
        for (int k = 0; k < 3; ++k)
          pairs_of_[mesh_.corner_vertex[3 * t + k]] |= static_cast<uint8_t>(1u << (tri_axis_[t] / 2));
  }
  local_.assign(mesh_.num_vertices, UINT32_MAX);
  tri_pos_.assign(nt, UINT32_MAX);
  known_.assign(mesh_.num_vertices, 0);
  // Only linear-prediction streams need the neighbours (Vertex_Corner is O(T)).
  if (predicted_) nb_.emplace(mesh_, known_, cw_.data(), local_, global_);
}

// §8.3 One patch's axis, header fields and level 0 (lattice coordinates), checked against the positions; leaves
// local_[] set for the patch's vertices (release() resets it).
Status PatchSectionWriter::prepare(size_t p) {
  const uint32_t t0 = ps_.order[ps_.start[p]];
  axis_ = tri_axis_[t0];
  grid_ = coding_.tri_grid ? (*coding_.tri_grid)[t0] : 0;
  const HexLattice& lc = lattices_[static_cast<size_t>(grid_)];
  const int pair = axis_ / 2;
  std::array<int64_t, 2> c1;
  if (!lattice_of(cq_, lc, pair, mesh_.corner_vertex[3 * t0], c0_) ||
      !lattice_of(cq_, lc, pair, mesh_.corner_vertex[3 * t0 + 1], c1))
    return make_status(Error::internal, "8.3", 0, "a regular triangle's corner is not a lattice point");
  align_ = direction_index(c1[0] - c0_[0], c1[1] - c0_[1]);
  // The decoder's propagation must find every vertex where it is.
  if (!propagate_patch(mesh_, ps_, p, c0_, align_, axis_ % 2 == 0, level_, global_, local_))
    return make_status(Error::internal, "8.3", 0, "lattice conflict in patch " + std::to_string(p));
  for (uint32_t l = 0; l < level_.size(); ++l) {
    std::array<int64_t, 2> actual;
    if (!lattice_of(cq_, lc, pair, global_[l], actual) || actual != level_.coord[l])
      return make_status(Error::internal, "8.3", 0, "patch " + std::to_string(p) + " propagates off its lattice");
  }
  h_.resize(level_.size());
  for (uint32_t l = 0; l < level_.size(); ++l) h_[l] = cw_[3 * size_t{global_[l]} + static_cast<size_t>(pair)];
  return ok_status();
}

void PatchSectionWriter::release() {
  for (uint32_t v : global_) local_[v] = UINT32_MAX;
}

// §9.7.2 The predictor table: `given`, or fitted to the heights the patches will code (same placement order as
// write()), then coded.
Status PatchSectionWriter::write_table(const FittedTable* given) {
  if (given) {
    own_ = *given;
    code_lp_table(own_.table, own_.fitted, models_->lp, direct_, value_);
    return ok_status();
  }
  std::vector<LpSample> samples;
  std::array<uint32_t, kLpOffsets> id;
  for (size_t p = 0; p < ps_.size(); ++p) {
    PRM_TRY(prepare(p));
    release();
    if (use_prediction(raster_.build(level_), level_.size(), coding_.predict_every_patch))
      for (uint32_t l : raster_.order()) {
        LpSample smp;
        smp.mask = raster_.taps(level_.coord[l][0], level_.coord[l][1], id);
        if (known_[global_[l]]) continue;
        for (int t = 0; t < kLpOffsets; ++t)
          smp.tap[static_cast<size_t>(t)] = id[t] != LpRaster::kNone ? h_[id[t]] : 0;
        smp.h = h_[l];
        samples.push_back(smp);
      }
    for (uint32_t v : global_) known_[v] = 1;
  }
  fit_lp_table(samples, own_.table, own_.fitted);
  code_lp_table(own_.table, own_.fitted, models_->lp, direct_, value_);
  known_.assign(mesh_.num_vertices, 0);
  return ok_status();
}

// §8.4 The patch header; §8.4.1 the base from its reference, if it has one.
void PatchSectionWriter::write_header(size_t p) {
  const int pair = axis_ / 2;
  code_symbol8(models_->axis, axis_, bit_);
  if (coding_.grids.size() > 1) code_symbol8(models_->grid, grid_, bit_);  // §8.4.2 Grid_Index
  std::array<int64_t, 2> near;
  if (coding_.contexts && base_from_reference(mesh_, ps_, p, pair, vertex_corner_, known_, cw_.data(),
                                              lattices_[static_cast<size_t>(grid_)], near)) {
    encode_signed(rc_, models_->base_ref_i, c0_[0] - near[0]);
    encode_signed(rc_, models_->base_ref_j, c0_[1] - near[1]);
  } else {
    encode_signed(rc_, models_->base_i, c0_[0] - previous_[0]);
    encode_signed(rc_, models_->base_j, c0_[1] - previous_[1]);
  }
  code_symbol8(models_->align, align_, bit_);
  previous_ = c0_;
}

// §9.7.4 Heights by linear prediction.
Status PatchSectionWriter::write_lp_heights(size_t p) {
  const int pair = axis_ / 2;
  placed_.resize(level_.size());
  for (uint32_t l = 0; l < level_.size(); ++l) placed_[l] = known_[global_[l]];
  const int64_t lo = coding_.box_lo[static_cast<size_t>(pair)], hi = coding_.box_hi[static_cast<size_t>(pair)];
  nb_->height_axis = pair;
  bool in_range;
  if (free_heights_) {
    // Spec Appendix B. The window around the exact height, inside the box (a height on the box's face stays
    // there: the box remains tight), always holding the rounded height; the choice minimises the squared distance
    // to the exact height plus lambda times the residual's bits under the model's current state.
    const double lambda = freedom_->lambda;
    auto window = [&](uint32_t l, int64_t given) {
      return height_window(given, (*freedom_->exact)[3 * size_t{global_[l]} + static_cast<size_t>(pair)],
                           freedom_->tolerance, lo, hi, pairs_of_[global_[l]] == 1u << pair);
    };
    auto choose = [&](uint32_t l, int64_t pred, int64_t given, const SignedIntModel& model,
                      const BitModel& sign) -> int64_t {
      const HeightWindow w = window(l, given);
      if (!w.free) return given;
      int64_t best = given;
      double best_cost = 1e300;
      for (int64_t q = w.lo; q <= w.hi; ++q) {
        const double d = static_cast<double>(q) - w.exact;
        const double cost = d * d + lambda * signed_cost_bits(model, q - pred, sign);
        if (cost < best_cost) best_cost = cost, best = q;
      }
      return best;
    };
    in_range = code_lp_heights(level_, raster_, own_.table, models_->lp, coding_.bits, lo, hi, placed_, h_, res_,
                               scratch_, value_, &*nb_, choose);
    if (in_range && freedom_->sweeps > 0)
      record_heights(level_, raster_, own_.table, models_->lp, placed_, global_, h_, res_, scratch_, pair, lo, hi,
                     window, cq_, refine_);
    for (uint32_t l = 0; l < level_.size(); ++l)
      cw_copy_[3 * size_t{global_[l]} + static_cast<size_t>(pair)] = static_cast<uint32_t>(h_[l]);
  } else {
    in_range = code_lp_heights(level_, raster_, own_.table, models_->lp, coding_.bits, lo, hi, placed_, h_, res_,
                               scratch_, value_, &*nb_);
  }
  if (!in_range) return make_status(Error::internal, "9.7", 0, "height out of range in patch " + std::to_string(p));
  return ok_status();
}

// §9 Heights by difference patches.
Status PatchSectionWriter::write_difference_heights(size_t p) {
  const int d = predicted_ ? coding_.overlap_depth : coding_.depth;
  f_.assign(1, h_);
  patch_side_twins(mesh_, ps_, p, tri_pos_, twin_);
  build_levels(level_, d, plans_, &twin_);
  if (!code_heights(level_, d, coding_.bits, models_->heights, f_, plans_, scratch_, queue_, true, value_))
    return make_status(Error::internal, "9.3", 0, "height out of range in patch " + std::to_string(p));
  return ok_status();
}

Status PatchSectionWriter::write(const FittedTable* given, std::vector<uint8_t>& payload, PatchStats* stats,
                                 std::vector<uint32_t>* chosen) {
  start();
  if (predicted_) PRM_TRY(write_table(given));
  uint32_t patch_vertices = 0, predicted_patches = 0;
  PatchStats costs;  // the bits of each part (PatchStats), kept when this writing is the one coded
  costs.prologue_bits = rc_.bits();
  costs.vertex_patch.assign(mesh_.num_vertices, UINT32_MAX);
  for (size_t p = 0; p < ps_.size(); ++p) {
    PRM_TRY(prepare(p));
    const double before_header = rc_.bits();
    write_header(p);
    const double before_heights = rc_.bits();
    const bool lp = predicted_ && use_prediction(raster_.build(level_), level_.size(), coding_.predict_every_patch);
    if (predicted_) bit_(models_->lp.method, lp);  // §9.7.4 Method
    if (lp) {
      PRM_TRY(write_lp_heights(p));
      ++predicted_patches;
    } else {
      PRM_TRY(write_difference_heights(p));
    }
    release();
    costs.header_bits.push_back(before_heights - before_header);
    costs.height_bits.push_back(rc_.bits() - before_heights);
    uint32_t carried = 0;
    for (uint32_t l = 0; l < level_.size(); ++l) {
      if (!known_[global_[l]]) costs.vertex_patch[global_[l]] = static_cast<uint32_t>(p), ++carried;
      known_[global_[l]] = 1;
    }
    costs.new_vertices.push_back(carried);
    patch_vertices += carried;
  }
  costs.coded_bits = rc_.bits();
  payload = rc_.finish();
  // Spec Appendix B.2: the chosen heights refined together, then coded as they are.
  if (free_heights_ && freedom_->sweeps > 0 && !refine_.empty()) {
    std::vector<uint32_t> q = cw_;
    refine_heights(refine_, ResidualCosts::of(models_->lp), freedom_->lambda, freedom_->sweeps, q);
    PRM_TRY(PatchSectionWriter(mesh_, q, tri_axis_, coding_, nullptr, known_).write(&own_, payload, stats, nullptr));
    if (chosen) *chosen = q;
    return ok_status();
  }
  if (chosen) *chosen = cw_;
  if (stats) {
    *stats = std::move(costs);
    stats->patches = static_cast<uint32_t>(ps_.size());
    stats->patch_vertices = patch_vertices;
    stats->predicted_patches = predicted_patches;
  }
  return ok_status();
}

}  // namespace

Status write_patches(const ClosedMesh& mesh, const std::vector<uint32_t>& cq, const std::vector<int8_t>& tri_axis,
                     const PatchCoding& coding, std::vector<uint8_t>& payload, std::vector<uint8_t>& known,
                     PatchStats* stats, const HeightFreedom* freedom, std::vector<uint32_t>* chosen) {
  return PatchSectionWriter(mesh, cq, tri_axis, coding, freedom, known).write(nullptr, payload, stats, chosen);
}

}  // namespace prm::codec
