// The encoding entry points of prm/codec.h: make_frame, encode, encode_quantized, encode_prm (prm_codec only; the
// decoder's are in codec_api_decode.cpp). Nothing throws out of here.
#include <algorithm>
#include <cmath>
#include <new>
#include <string>

#include "clers.h"
#include "container.h"
#include "lers.h"
#include "limits.h"
#include "patch.h"
#include "patch_shared.h"
#include "position.h"
#include "prm/codec.h"
#include "status.h"

namespace prm::codec {

namespace {

Status check_frame(const Frame& f) {
  if (f.bits < kMinPositionBits || f.bits > kMaxPositionBits)
    return make_status(Error::invalid_argument, "10.1", 0, "position bits must be 8..20");
  for (double o : f.origin)
    if (!std::isfinite(o)) return make_status(Error::invalid_argument, "10.1", 0, "frame origin not finite");
  if (!std::isfinite(f.step) || !(f.step > 0))
    return make_status(Error::invalid_argument, "10.1", 0, "frame step must be finite and positive");
  return ok_status();
}

Status encode_impl(const uint32_t* q, size_t nv, const uint32_t* tris, size_t nt, const Frame& frame,
                   std::vector<uint8_t>& out, EncodeReport* report, const PrmOptions* prm = nullptr,
                   int seam_context = -1) {
  PRM_TRY(check_frame(frame));
  if (prm) seam_context = prm->seam_context;
  if (seam_context < -1 || seam_context > 1)
    return make_status(Error::invalid_argument, "6.5.2", 0, "seam context must be -1 (the smaller), 0 or 1");
  if (prm) {
    if (!valid_grid_size(prm->grid, frame.bits))
      return make_status(Error::invalid_argument, "8.4", 0, "grid size must be 2..2^bits quantization steps");
    if (prm->extra_grids.size() > static_cast<size_t>(kMaxExtraGrids))
      return make_status(Error::invalid_argument, "8.4.2", 0, "at most 7 extra grid sizes");
    for (size_t k = 0; k < prm->extra_grids.size(); ++k) {
      const int64_t g = prm->extra_grids[k];
      if (!valid_grid_size(g, frame.bits))
        return make_status(Error::invalid_argument, "8.4.2", 0, "extra grid size must be 2..2^bits quantization steps");
      if (g == prm->grid || std::find(prm->extra_grids.begin(), prm->extra_grids.begin() + static_cast<long>(k), g) !=
                                prm->extra_grids.begin() + static_cast<long>(k))
        return make_status(Error::invalid_argument, "8.4.2", 0, "grid sizes must be distinct");
    }
    if (prm->height_depth < -1 || prm->height_depth > kHeightDepthPredicted)
      return make_status(Error::invalid_argument, "9.4", 0, "height depth must be 0..7 (or -1: best)");
    if (prm->overlap_depth < -1 || prm->overlap_depth > kMaxHeightDepth)
      return make_status(Error::invalid_argument, "9.7.2", 0, "overlap depth must be 0..6 (or -1: 3)");
    if (!(prm->height_tolerance >= 0 && prm->height_tolerance <= 16) || !(prm->height_lambda >= 0 && prm->height_lambda <= 1e6))
      return make_status(Error::invalid_argument, "9.7", 0, "height tolerance must be 0..16 steps and lambda 0..1e6");
    if (prm->height_sweeps < 0 || prm->height_sweeps > 16)
      return make_status(Error::invalid_argument, "9.7", 0, "height sweeps must be 0..16");
    if (prm->unrounded && prm->height_tolerance >= 0.5 && prm->height_lambda > 0)
      for (size_t i = 0; i < 3 * nv; ++i)
        if (!(std::fabs(prm->unrounded[i] - static_cast<double>(q[i])) <= 1.0))
          return make_status(Error::invalid_argument, "9.7", 0,
                             "unrounded coordinate of vertex " + std::to_string(i / 3) +
                                 " is not finite or more than a step from its quantized value");
  }
  const uint32_t qmax = (uint32_t{1} << frame.bits) - 1;
  for (size_t i = 0; i < 3 * nv; ++i)
    if (q[i] > qmax)
      return make_status(Error::invalid_argument, "10.1", 0,
                         "quantized coordinate of vertex " + std::to_string(i / 3) + " exceeds 2^bits - 1");
  ConnectivityPlan plan;
  PRM_TRY(plan_connectivity(tris, nt, nv, plan));
  const ClosedMesh& mesh = plan.mesh;
  // Quantized positions in canonical order, and their bounding box (§3.3).
  std::vector<uint32_t> cq(size_t{3} * mesh.num_vertices, 0);
  Header h;
  h.frame = frame;
  h.bbox_min = {qmax, qmax, qmax};
  h.bbox_max = {0, 0, 0};
  uint32_t real = 0;
  for (uint32_t v = 0; v < mesh.num_vertices; ++v) {
    const uint32_t in = plan.vertex_input[v];
    if (in == UINT32_MAX) continue;
    ++real;
    for (int k = 0; k < 3; ++k) {
      cq[3 * v + k] = q[3 * size_t{in} + k];
      h.bbox_min[k] = std::min(h.bbox_min[k], cq[3 * v + k]);
      h.bbox_max[k] = std::max(h.bbox_max[k], cq[3 * v + k]);
    }
  }
  if (real == 0) h.bbox_min = h.bbox_max = {0, 0, 0};
  h.vertices = real;
  h.triangles = static_cast<uint32_t>(nt);
  std::vector<uint8_t> conn, pos, irregular_payload, patch_payload;
  // §6.5.2 The seam context (Flags bit 2, format 1.3): with it, without it, or the smaller of the two (ties: without).
  bool seam = seam_context == 1;
  PRM_TRY(write_connectivity(plan, seam, conn));
  if (seam_context == -1) {
    std::vector<uint8_t> with;
    PRM_TRY(write_connectivity(plan, true, with));
    if (with.size() < conn.size()) {
      conn = std::move(with);
      seam = true;
    }
  }
  if (seam) h.flags |= kFlagClersSeam;
  // §7-§9 A PRM: regular triangles found by the encoder's own check; none: the general path.
  std::vector<int8_t> tri_axis;
  std::vector<uint8_t> tri_grid;  // §8.4.2 index into `grids`
  std::vector<int64_t> grids;     // §8.4, §8.4.2 Grid_Size and the extra grids the regular triangles use
  std::vector<uint8_t> known;
  PatchStats patch_stats;
  uint32_t regular = 0;
  int depth_used = -1, overlap_used = -1;
  if (prm) {
    grids = {prm->grid};
    if (prm->patch_grids) grids.insert(grids.end(), prm->extra_grids.begin(), prm->extra_grids.end());
    classify_triangles(mesh, cq, grids, tri_axis, tri_grid);
    // §8.4.2 The table holds the extra grids in use, renumbered in their order.
    std::vector<uint8_t> used(grids.size(), 0), renumber(grids.size(), 0);
    for (uint32_t t = 0; t < mesh.num_triangles(); ++t)
      if (tri_axis[t] >= 0) used[tri_grid[t]] = 1, ++regular;
    std::vector<int64_t> kept = {prm->grid};
    for (size_t g = 1; g < grids.size(); ++g)
      if (used[g]) renumber[g] = static_cast<uint8_t>(kept.size()), kept.push_back(grids[g]);
    for (uint8_t& g : tri_grid) g = renumber[g];
    grids = std::move(kept);
  }
  if (regular > 0) {
    std::vector<uint8_t> irregular(mesh.num_triangles(), 0);
    const std::vector<uint8_t> dummy = dummy_triangles(mesh);
    for (uint32_t t = 0; t < mesh.num_triangles(); ++t) irregular[t] = dummy[t] != kDummyTriangle && tri_axis[t] < 0;
    h.flags |= kFlagLersValence;  // §7.3 the valence context
    if (prm->patch_contexts) h.flags |= kFlagPatchContexts;  // §8.4.1, §9.7.4 (format 1.4)
    if (grids.size() > 1) h.flags |= kFlagPatchGrids;        // §8.4.2 (format 1.5)
    write_irregular_triangles(mesh, irregular, true, irregular_payload);
    // The encoder's freedom in the heights (spec Appendix B, PrmOptions::height_lambda), in canonical vertex order.
    std::vector<double> exact;
    HeightFreedom freedom;
    if (prm->unrounded && prm->height_tolerance >= 0.5 && prm->height_lambda > 0) {
      exact.assign(cq.size(), 0.0);
      for (uint32_t v = 0; v < mesh.num_vertices; ++v) {
        const uint32_t in = plan.vertex_input[v];
        if (in == UINT32_MAX) continue;
        // PrmOptions::rounded_heights: no exact height (NaN), so the height stays q's (height_window).
        const bool held = prm->rounded_heights && prm->rounded_heights[in];
        for (int k = 0; k < 3; ++k)
          exact[3 * size_t{v} + k] = held ? std::nan("") : prm->unrounded[3 * size_t{in} + k];
      }
      freedom.exact = &exact;
      freedom.tolerance = prm->height_tolerance;
      freedom.lambda = prm->height_lambda;
      freedom.sweeps = prm->height_sweeps;
    }
    std::vector<uint32_t> coded_positions;
    // §9.4 The height coding: the caller's, or the one giving the smallest section: every difference depth, then
    // linear prediction (§9.7) with the best of them for the self-overlapping patches.
    auto patch_coding = [&](int d, int overlap) {
      PatchCoding c;
      c.bits = frame.bits;
      c.grids = grids;
      c.tri_grid = &tri_grid;
      c.box_lo = h.bbox_min;
      c.box_hi = h.bbox_max;
      c.depth = d;
      c.overlap_depth = overlap;
      c.predict_every_patch = prm->predict_every_patch;
      c.contexts = prm->patch_contexts;
      return c;
    };
    auto attempt = [&](int d, int overlap) -> Status {
      std::vector<uint8_t> payload, k;
      std::vector<uint32_t> chosen;
      PatchStats st;
      const bool free = freedom.exact && d == kHeightDepthPredicted;
      PRM_TRY(write_patches(mesh, cq, tri_axis, patch_coding(d, overlap), payload, k, &st, free ? &freedom : nullptr,
                            free ? &chosen : nullptr));
      if (depth_used < 0 || payload.size() < patch_payload.size()) {
        coded_positions = std::move(chosen);
        patch_payload = std::move(payload);
        known = std::move(k);
        patch_stats = st;
        depth_used = d;
        overlap_used = d == kHeightDepthPredicted ? overlap : -1;
      }
      return ok_status();
    };
    if (prm->height_depth == kHeightDepthPredicted) {
      PRM_TRY(attempt(kHeightDepthPredicted, prm->overlap_depth >= 0 ? prm->overlap_depth : 3));
    } else if (prm->height_depth >= 0) {
      PRM_TRY(attempt(prm->height_depth, 0));
    } else {
      for (int d = 0; d <= kMaxHeightDepth; ++d) PRM_TRY(attempt(d, 0));
      PRM_TRY(attempt(kHeightDepthPredicted, prm->overlap_depth >= 0 ? prm->overlap_depth : depth_used));
    }
    if (!coded_positions.empty()) {
      // The predictor table was fitted to the rounded heights; fitted again to the chosen ones, the same heights
      // may cost less.
      std::vector<uint8_t> payload, k;
      PatchStats st;
      PRM_TRY(write_patches(mesh, coded_positions, tri_axis, patch_coding(kHeightDepthPredicted, overlap_used),
                            payload, k, &st));
      if (payload.size() < patch_payload.size()) {
        patch_payload = std::move(payload);
        known = std::move(k);
        patch_stats = st;
      }
    }
    h.version_minor = kFormatMinorPredicted;  // §3.2 1.2: the valence context, whatever the height coding (1.3 below)
    if (!coded_positions.empty()) cq = std::move(coded_positions);  // the heights the patches section holds
    PRM_TRY(write_positions(mesh, cq, h.bbox_min, h.bbox_max, pos, &known));
  } else {
    PRM_TRY(write_positions(mesh, cq, h.bbox_min, h.bbox_max, pos));
  }
  if (h.flags & kFlagClersSeam) h.version_minor = kFormatMinorSeam;  // §3.2 1.3
  if (h.flags & kFlagPatchContexts) h.version_minor = kFormatMinorPatchContexts;  // §3.2 1.4
  if (h.flags & kFlagPatchGrids) h.version_minor = kFormatMinorPatchGrids;  // §3.2 1.5
  size_t header_bytes = 0;
  if (regular > 0)
    out = write_container(h,
                          {{kSectionConnectivity, &conn},
                           {kSectionPositions, &pos},
                           {kSectionIrregular, &irregular_payload},
                           {kSectionPatches, &patch_payload}},
                          &header_bytes);
  else
    out = write_container(h, {{kSectionConnectivity, &conn}, {kSectionPositions, &pos}}, &header_bytes);
  if (report) {
    EncodeReport& r = *report;
    r = EncodeReport{};
    r.total_bytes = out.size();
    r.header_bytes = header_bytes;
    r.connectivity_bytes = conn.size();
    r.position_bytes = pos.size();
    r.irregular_bytes = irregular_payload.size();
    r.patch_bytes = patch_payload.size();
    r.framing_bytes = out.size() - header_bytes - conn.size() - pos.size() - r.irregular_bytes - r.patch_bytes;
    r.regular_triangles = regular;
    r.regular_patches = patch_stats.patches;
    r.patch_vertices = patch_stats.patch_vertices;
    r.height_depth = depth_used;
    r.overlap_depth = overlap_used;
    r.predicted_patches = patch_stats.predicted_patches;
    r.grid_sizes = static_cast<uint32_t>(grids.size());
    r.vertices = real;
    r.triangles = static_cast<uint32_t>(nt);
    r.components = static_cast<uint32_t>(plan.component_sizes.size());
    r.holes = static_cast<uint32_t>(plan.dummies.size());
    r.handles = static_cast<uint32_t>(plan.handles.size() / 2);
    r.unreferenced_dropped = plan.unreferenced;
    r.patch_prologue_bits = patch_stats.prologue_bits;
    for (size_t p = 0; p < patch_stats.header_bits.size(); ++p)
      r.patch_costs.push_back({patch_stats.header_bits[p], patch_stats.height_bits[p], patch_stats.new_vertices[p]});
    if (!patch_stats.vertex_patch.empty()) {
      r.vertex_patch.assign(nv, UINT32_MAX);
      for (uint32_t v = 0; v < mesh.num_vertices; ++v)
        if (plan.vertex_input[v] != UINT32_MAX) r.vertex_patch[plan.vertex_input[v]] = patch_stats.vertex_patch[v];
    }
    r.vertex_order.reserve(real);
    for (uint32_t v = 0; v < mesh.num_vertices; ++v)
      if (plan.vertex_input[v] != UINT32_MAX) r.vertex_order.push_back(plan.vertex_input[v]);
    for (size_t t = 0; t < plan.triangle_input.size(); ++t)
      if (plan.triangle_input[t] != UINT32_MAX) {
        r.triangle_order.push_back(plan.triangle_input[t]);
        r.triangle_rotation.push_back(plan.triangle_rotation[t]);
      }
  }
  return ok_status();
}

template <typename T>
Result<std::vector<uint8_t>> encode_float(const T* xyz, size_t nv, const uint32_t* tris, size_t nt,
                                          const EncodeOptions& options, EncodeReport* report) {
  Result<std::vector<uint8_t>> res;
  try {
    if (options.position_bits < kMinPositionBits || options.position_bits > kMaxPositionBits) {
      res.status = make_status(Error::invalid_argument, "10.1", 0, "position bits must be 8..20");
      return res;
    }
    for (size_t i = 0; i < 3 * nv; ++i)
      if (!std::isfinite(static_cast<double>(xyz[i]))) {
        res.status = make_status(Error::invalid_argument, "10.1", 0,
                                 "vertex " + std::to_string(i / 3) + " has a non-finite coordinate");
        return res;
      }
    const Frame frame = frame_of_points(xyz, nv, options.position_bits);
    std::vector<uint32_t> q(3 * nv);
    for (size_t i = 0; i < 3 * nv; ++i)
      q[i] = quantize(static_cast<double>(xyz[i]), frame.origin[i % 3], frame.step, frame.bits);
    res.status = encode_impl(q.data(), nv, tris, nt, frame, res.value, report, nullptr, options.seam_context);
  } catch (const std::bad_alloc&) {
    res.status = make_status(Error::out_of_memory, "", 0, "out of memory");
  } catch (...) {
    res.status = make_status(Error::internal, "", 0, "unexpected exception");
  }
  if (!res.ok()) res.value.clear();
  return res;
}

}  // namespace

Frame make_frame(const double* xyz, size_t n, int bits) { return frame_of_points(xyz, n, bits); }
Frame make_frame(const float* xyz, size_t n, int bits) { return frame_of_points(xyz, n, bits); }

Result<std::vector<uint8_t>> encode(const float* xyz, size_t nv, const uint32_t* tris, size_t nt,
                                    const EncodeOptions& options, EncodeReport* report) {
  return encode_float(xyz, nv, tris, nt, options, report);
}

Result<std::vector<uint8_t>> encode(const double* xyz, size_t nv, const uint32_t* tris, size_t nt,
                                    const EncodeOptions& options, EncodeReport* report) {
  return encode_float(xyz, nv, tris, nt, options, report);
}

Result<std::vector<uint8_t>> encode_quantized(const uint32_t* q, size_t nv, const uint32_t* tris, size_t nt,
                                              const Frame& frame, EncodeReport* report, int seam_context) {
  Result<std::vector<uint8_t>> res;
  try {
    res.status = encode_impl(q, nv, tris, nt, frame, res.value, report, nullptr, seam_context);
  } catch (const std::bad_alloc&) {
    res.status = make_status(Error::out_of_memory, "", 0, "out of memory");
  } catch (...) {
    res.status = make_status(Error::internal, "", 0, "unexpected exception");
  }
  if (!res.ok()) res.value.clear();
  return res;
}

Result<std::vector<uint8_t>> encode_prm(const uint32_t* q, size_t nv, const uint32_t* tris, size_t nt,
                                        const Frame& frame, const PrmOptions& options, EncodeReport* report) {
  Result<std::vector<uint8_t>> res;
  try {
    res.status = encode_impl(q, nv, tris, nt, frame, res.value, report, &options);
  } catch (const std::bad_alloc&) {
    res.status = make_status(Error::out_of_memory, "", 0, "out of memory");
  } catch (...) {
    res.status = make_status(Error::internal, "", 0, "unexpected exception");
  }
  if (!res.ok()) res.value.clear();
  return res;
}

}  // namespace prm::codec
