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
    const int s = table.first_set[raster.taps(level.coord[l][0], level.coord[l][1], id)];
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

void classify_triangles(const ClosedMesh& mesh, const std::vector<uint32_t>& cq, int64_t grid,
                        std::vector<int8_t>& tri_axis) {
  const uint32_t nt = mesh.num_triangles();
  const HexLattice lc = HexLattice::with_grid(grid);
  const std::vector<uint8_t> dummy = dummy_triangles(mesh);
  tri_axis.assign(nt, -1);
  for (uint32_t t = 0; t < nt; ++t)
    if (dummy[t] != kDummyTriangle) tri_axis[t] = static_cast<int8_t>(regular_axis(cq, lc, &mesh.corner_vertex[3 * t]));
  // §8.2 One axis per patch: regular neighbours of different axes are both made irregular.
  std::vector<uint8_t> demote(nt, 0);
  for (uint32_t t = 0; t < nt; ++t) {
    if (tri_axis[t] < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = static_cast<uint32_t>(mesh.opp[3 * t + k]) / 3;
      if (tri_axis[n] >= 0 && tri_axis[n] != tri_axis[t]) demote[t] = 1;
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

// write_patches, with the predictor table `given` instead of one fitted to cq (the refinement's heights are coded
// with the table they were refined for).
Status write_section(const ClosedMesh& mesh, const std::vector<uint32_t>& cq, int bits, int64_t grid,
                     const std::array<uint32_t, 3>& box_lo, const std::array<uint32_t, 3>& box_hi,
                     const std::vector<int8_t>& tri_axis, int depth, int overlap_depth, bool predict_every_patch,
                     bool contexts, std::vector<uint8_t>& payload, std::vector<uint8_t>& known, PatchStats* stats,
                     const HeightFreedom* freedom, std::vector<uint32_t>* chosen, const FittedTable* given) {
  const uint32_t nt = mesh.num_triangles();
  std::vector<uint8_t> cls = dummy_triangles(mesh);
  for (uint32_t t = 0; t < nt; ++t)
    if (cls[t] != kDummyTriangle) cls[t] = tri_axis[t] >= 0 ? kRegular : kIrregular;
  const PatchSet ps = build_patches(mesh, cls);
  const HexLattice lc = HexLattice::with_grid(grid);
  const bool predicted = depth == kHeightDepthPredicted;
  RangeEncoder rc;
  auto models = std::make_unique<PatchModels>();
  models->lp.sign_context = contexts;
  std::vector<uint32_t> vertex_corner;  // §10.2, for the base references (§8.4.1)
  if (contexts) vertex_corners(mesh, vertex_corner);
  // §8.4 Grid_Size and Height_Depth; §9.7.2 Overlap_Depth.
  rc.encode_direct(static_cast<uint32_t>(grid), kGridBits);
  rc.encode_direct(static_cast<uint32_t>(depth), 3);
  if (predicted) rc.encode_direct(static_cast<uint32_t>(overlap_depth), 3);
  auto bit = [&](BitModel& m, bool truth) {
    rc.encode_bit(m, truth ? 1 : 0);
    return truth;
  };
  auto value = [&](SignedIntModel& m, int, int64_t truth, int64_t& out, BitModel* sign = nullptr) {
    encode_signed(rc, m, truth, sign ? *sign : m.sign);
    out = truth;
    return true;
  };
  auto direct = [&](int n, uint32_t truth) {
    rc.encode_direct(truth, n);
    return truth;
  };
  // The positions as coded so far: cq, with the heights the encoder chose when it has freedom.
  const bool free_heights = freedom && freedom->exact && freedom->tolerance >= 0.5 && freedom->lambda > 0;
  std::vector<uint32_t> cw_copy;
  if (free_heights) cw_copy = cq;
  const std::vector<uint32_t>& cw = free_heights ? cw_copy : cq;
  // A vertex in regular triangles of two axis pairs keeps its coordinates: its height for one is a lattice
  // coordinate for the other (§8.3 checks it).
  std::vector<uint8_t> pairs_of;
  if (free_heights) {
    pairs_of.assign(mesh.num_vertices, 0);
    for (uint32_t t = 0; t < mesh.num_triangles(); ++t)
      if (tri_axis[t] >= 0)
        for (int k = 0; k < 3; ++k) pairs_of[mesh.corner_vertex[3 * t + k]] |= static_cast<uint8_t>(1u << (tri_axis[t] / 2));
  }
  std::vector<uint32_t> local(mesh.num_vertices, UINT32_MAX), global, queue;
  Level level;
  std::vector<std::vector<int64_t>> f;
  std::vector<LevelPlan> plans;
  std::vector<uint32_t> tri_pos(mesh.num_triangles(), UINT32_MAX), twin;
  std::vector<uint8_t> scratch, placed;
  std::vector<int64_t> h, res;
  LpRaster raster;
  // §8.3 One patch's axis, header fields and level 0 (lattice coordinates), checked against the positions; leaves
  // local[] set for the patch's vertices (release() resets it).
  int axis = 0, align = 0;
  std::array<int64_t, 2> c0;
  auto prepare = [&](size_t p) -> Status {
    const uint32_t t0 = ps.order[ps.start[p]];
    axis = tri_axis[t0];
    const int pair = axis / 2;
    std::array<int64_t, 2> c1;
    if (!lattice_of(cq, lc, pair, mesh.corner_vertex[3 * t0], c0) ||
        !lattice_of(cq, lc, pair, mesh.corner_vertex[3 * t0 + 1], c1))
      return make_status(Error::internal, "8.3", 0, "a regular triangle's corner is not a lattice point");
    align = direction_index(c1[0] - c0[0], c1[1] - c0[1]);
    // The decoder's propagation must find every vertex where it is.
    if (!propagate_patch(mesh, ps, p, c0, align, axis % 2 == 0, level, global, local))
      return make_status(Error::internal, "8.3", 0, "lattice conflict in patch " + std::to_string(p));
    for (uint32_t l = 0; l < level.size(); ++l) {
      std::array<int64_t, 2> actual;
      if (!lattice_of(cq, lc, pair, global[l], actual) || actual != level.coord[l])
        return make_status(Error::internal, "8.3", 0, "patch " + std::to_string(p) + " propagates off its lattice");
    }
    h.resize(level.size());
    for (uint32_t l = 0; l < level.size(); ++l) h[l] = cw[3 * size_t{global[l]} + static_cast<size_t>(pair)];
    return ok_status();
  };
  auto release = [&] {
    for (uint32_t v : global) local[v] = UINT32_MAX;
  };
  known.assign(mesh.num_vertices, 0);
  // §9.7.4 For the vertices without a tap set; only linear-prediction streams need it (Vertex_Corner is O(T)).
  std::optional<LpNeighbours> nb;
  if (predicted) nb.emplace(mesh, known, cw.data(), local, global);
  // §9.7.2 The predictor table, fitted to the heights the patches will code (same placement order as below).
  FittedTable own;
  LpTable& table = own.table;
  std::array<bool, kLpSets>& fitted = own.fitted;
  if (predicted && given) {
    own = *given;
    code_lp_table(table, fitted, models->lp, direct, value);
  } else if (predicted) {
    std::vector<LpSample> samples;
    std::array<uint32_t, kLpOffsets> id;
    for (size_t p = 0; p < ps.size(); ++p) {
      PRM_TRY(prepare(p));
      release();
      if (use_prediction(raster.build(level), level.size(), predict_every_patch))
        for (uint32_t l : raster.order()) {
          LpSample smp;
          smp.mask = raster.taps(level.coord[l][0], level.coord[l][1], id);
          if (known[global[l]]) continue;
          for (int t = 0; t < kLpOffsets; ++t) smp.tap[static_cast<size_t>(t)] = id[t] != LpRaster::kNone ? h[id[t]] : 0;
          smp.h = h[l];
          samples.push_back(smp);
        }
      for (uint32_t v : global) known[v] = 1;
    }
    fit_lp_table(samples, table, fitted);
    code_lp_table(table, fitted, models->lp, direct, value);
    known.assign(mesh.num_vertices, 0);
  }
  std::vector<ChosenHeight> refine;
  std::array<int64_t, 2> previous{0, 0};
  uint32_t patch_vertices = 0, predicted_patches = 0;
  for (size_t p = 0; p < ps.size(); ++p) {
    PRM_TRY(prepare(p));
    const int pair = axis / 2;
    // §8.4 The patch header; §8.4.1 the base from its reference, if it has one.
    code_symbol8(models->axis, axis, bit);
    std::array<int64_t, 2> near;
    if (contexts && base_from_reference(mesh, ps, p, pair, vertex_corner, known, cw.data(), lc, near)) {
      encode_signed(rc, models->base_ref_i, c0[0] - near[0]);
      encode_signed(rc, models->base_ref_j, c0[1] - near[1]);
    } else {
      encode_signed(rc, models->base_i, c0[0] - previous[0]);
      encode_signed(rc, models->base_j, c0[1] - previous[1]);
    }
    code_symbol8(models->align, align, bit);
    previous = c0;
    const bool lp = predicted && use_prediction(raster.build(level), level.size(), predict_every_patch);
    if (predicted) bit(models->lp.method, lp);  // §9.7.4 Method
    if (lp) {
      // §9.7.4 Heights by linear prediction.
      placed.resize(level.size());
      for (uint32_t l = 0; l < level.size(); ++l) placed[l] = known[global[l]];
      const int64_t lo = box_lo[static_cast<size_t>(pair)], hi = box_hi[static_cast<size_t>(pair)];
      nb->height_axis = pair;
      bool in_range;
      if (free_heights) {
        // Spec Appendix B. The window around the exact height, inside the box (a height on the box's face stays
        // there: the box remains tight), always holding the rounded height; the choice minimises the squared distance
        // to the exact height plus lambda times the residual's bits under the model's current state.
        const double lambda = freedom->lambda;
        auto window = [&](uint32_t l, int64_t given) {
          return height_window(given, (*freedom->exact)[3 * size_t{global[l]} + static_cast<size_t>(pair)],
                               freedom->tolerance, lo, hi, pairs_of[global[l]] == 1u << pair);
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
        in_range = code_lp_heights(level, raster, table, models->lp, bits, lo, hi, placed, h, res, scratch, value,
                                   &*nb, choose);
        if (in_range && freedom->sweeps > 0)
          record_heights(level, raster, table, models->lp, placed, global, h, res, scratch, pair, lo, hi, window, cq,
                         refine);
        for (uint32_t l = 0; l < level.size(); ++l)
          cw_copy[3 * size_t{global[l]} + static_cast<size_t>(pair)] = static_cast<uint32_t>(h[l]);
      } else {
        in_range = code_lp_heights(level, raster, table, models->lp, bits, lo, hi, placed, h, res, scratch, value,
                                   &*nb);
      }
      if (!in_range) return make_status(Error::internal, "9.7", 0, "height out of range in patch " + std::to_string(p));
      ++predicted_patches;
    } else {
      // §9 Heights by difference patches.
      const int d = predicted ? overlap_depth : depth;
      f.assign(1, h);
      patch_side_twins(mesh, ps, p, tri_pos, twin);
      build_levels(level, d, plans, &twin);
      if (!code_heights(level, d, bits, models->heights, f, plans, scratch, queue, true, value))
        return make_status(Error::internal, "9.3", 0, "height out of range in patch " + std::to_string(p));
    }
    release();
    for (uint32_t l = 0; l < level.size(); ++l) {
      patch_vertices += !known[global[l]];
      known[global[l]] = 1;
    }
  }
  payload = rc.finish();
  // Spec Appendix B.2: the chosen heights refined together, then coded as they are.
  if (free_heights && freedom->sweeps > 0 && !refine.empty()) {
    std::vector<uint32_t> q = cw;
    refine_heights(refine, ResidualCosts::of(models->lp), freedom->lambda, freedom->sweeps, q);
    PRM_TRY(write_section(mesh, q, bits, grid, box_lo, box_hi, tri_axis, depth, overlap_depth, predict_every_patch,
                          contexts, payload, known, stats, nullptr, nullptr, &own));
    if (chosen) *chosen = q;
    return ok_status();
  }
  if (chosen) *chosen = cw;
  if (stats) {
    stats->patches = static_cast<uint32_t>(ps.size());
    stats->patch_vertices = patch_vertices;
    stats->predicted_patches = predicted_patches;
  }
  return ok_status();
}

}  // namespace

Status write_patches(const ClosedMesh& mesh, const std::vector<uint32_t>& cq, int bits, int64_t grid,
                     const std::array<uint32_t, 3>& box_lo, const std::array<uint32_t, 3>& box_hi,
                     const std::vector<int8_t>& tri_axis, int depth, int overlap_depth, bool predict_every_patch,
                     bool contexts, std::vector<uint8_t>& payload, std::vector<uint8_t>& known, PatchStats* stats,
                     const HeightFreedom* freedom, std::vector<uint32_t>* chosen) {
  return write_section(mesh, cq, bits, grid, box_lo, box_hi, tri_axis, depth, overlap_depth, predict_every_patch,
                       contexts, payload, known, stats, freedom, chosen, nullptr);
}

}  // namespace prm::codec
