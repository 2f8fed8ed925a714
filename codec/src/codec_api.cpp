// The public entry points of prm/codec.h: encode, decode, inspect, frames. Nothing throws out of here.
#include <algorithm>
#include <cmath>
#include <new>
#include <string>

#include "clers.h"
#include "container.h"
#include "lers.h"
#include "limits.h"
#include "patch_shared.h"
#include "patches.h"
#include "positions.h"
#include "prm/codec.h"
#include "status.h"

namespace prm::codec {

// §4.4 Error names.
const char* error_name(Error error) {
  switch (error) {
    case Error::ok: return "ok";
    case Error::invalid_argument: return "invalid_argument";
    case Error::degenerate_triangle: return "degenerate_triangle";
    case Error::non_manifold_edge: return "non_manifold_edge";
    case Error::inconsistent_orientation: return "inconsistent_orientation";
    case Error::non_manifold_vertex: return "non_manifold_vertex";
    case Error::truncated: return "truncated";
    case Error::bad_magic: return "bad_magic";
    case Error::unsupported_version: return "unsupported_version";
    case Error::bad_header: return "bad_header";
    case Error::bad_section: return "bad_section";
    case Error::unsupported_feature: return "unsupported_feature";
    case Error::count_exceeds_limit: return "count_exceeds_limit";
    case Error::count_exceeds_stream: return "count_exceeds_stream";
    case Error::bad_connectivity: return "bad_connectivity";
    case Error::non_manifold_result: return "non_manifold_result";
    case Error::bad_position: return "bad_position";
    case Error::trailing_bytes: return "trailing_bytes";
    case Error::crc_mismatch: return "crc_mismatch";
    case Error::out_of_memory: return "out_of_memory";
    case Error::internal: return "internal";
  }
  return "unknown";
}

// §10.1 Quantization.
uint32_t quantize(double p, double origin, double step, int bits) {
  const double qmax = static_cast<double>((uint64_t{1} << bits) - 1);
  double x = std::floor((p - origin) / step + 0.5);
  if (!(x >= 0)) x = 0;  // also NaN
  if (x > qmax) x = qmax;
  return static_cast<uint32_t>(x);
}

namespace {

template <typename T>
Frame make_frame_t(const T* xyz, size_t n, int bits) {
  Frame f;
  f.bits = bits;
  if (n == 0) return f;
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = static_cast<double>(xyz[k]);
  for (size_t i = 1; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const double v = static_cast<double>(xyz[3 * i + k]);
      lo[k] = std::min(lo[k], v);
      hi[k] = std::max(hi[k], v);
    }
  double extent = 0;
  for (int k = 0; k < 3; ++k) {
    f.origin[k] = lo[k];
    extent = std::max(extent, hi[k] - lo[k]);
  }
  const double qmax = static_cast<double>((uint64_t{1} << bits) - 1);
  f.step = extent > 0 ? extent / qmax : 1.0;
  return f;
}

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
    if (prm->grid < 2 || prm->grid > (int64_t{1} << frame.bits))
      return make_status(Error::invalid_argument, "8.4", 0, "grid size must be 2..2^bits quantization steps");
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
  std::vector<uint8_t> known;
  PatchStats patch_stats;
  uint32_t regular = 0;
  int depth_used = -1, overlap_used = -1;
  if (prm) {
    classify_triangles(mesh, cq, prm->grid, tri_axis);
    for (int8_t a : tri_axis) regular += a >= 0;
  }
  if (regular > 0) {
    std::vector<uint8_t> irregular(mesh.num_triangles(), 0);
    const std::vector<uint8_t> dummy = dummy_triangles(mesh);
    for (uint32_t t = 0; t < mesh.num_triangles(); ++t) irregular[t] = dummy[t] != kDummyTriangle && tri_axis[t] < 0;
    h.flags |= kFlagLersValence;  // §7.3 the valence context
    if (prm->patch_contexts) h.flags |= kFlagPatchContexts;  // §8.4.1, §9.7.4 (format 1.4)
    write_irregular_triangles(mesh, irregular, true, irregular_payload);
    // The encoder's freedom in the heights (spec Appendix B, PrmOptions::height_lambda), in canonical vertex order.
    std::vector<double> exact;
    HeightFreedom freedom;
    if (prm->unrounded && prm->height_tolerance >= 0.5 && prm->height_lambda > 0) {
      exact.assign(cq.size(), 0.0);
      for (uint32_t v = 0; v < mesh.num_vertices; ++v) {
        const uint32_t in = plan.vertex_input[v];
        if (in == UINT32_MAX) continue;
        for (int k = 0; k < 3; ++k) exact[3 * size_t{v} + k] = prm->unrounded[3 * size_t{in} + k];
      }
      freedom.exact = &exact;
      freedom.tolerance = prm->height_tolerance;
      freedom.lambda = prm->height_lambda;
      freedom.sweeps = prm->height_sweeps;
    }
    std::vector<uint32_t> coded_positions;
    // §9.4 The height coding: the caller's, or the one giving the smallest section: every difference depth, then
    // linear prediction (§9.7) with the best of them for the self-overlapping patches.
    auto attempt = [&](int d, int overlap) -> Status {
      std::vector<uint8_t> payload, k;
      std::vector<uint32_t> chosen;
      PatchStats st;
      const bool free = freedom.exact && d == kHeightDepthPredicted;
      PRM_TRY(write_patches(mesh, cq, frame.bits, prm->grid, h.bbox_min, h.bbox_max, tri_axis, d, overlap,
                            prm->predict_every_patch, prm->patch_contexts, payload, k, &st, free ? &freedom : nullptr,
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
      PRM_TRY(write_patches(mesh, coded_positions, frame.bits, prm->grid, h.bbox_min, h.bbox_max, tri_axis,
                            kHeightDepthPredicted, overlap_used, prm->predict_every_patch, prm->patch_contexts, payload,
                            k, &st));
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
    r.vertices = real;
    r.triangles = static_cast<uint32_t>(nt);
    r.components = static_cast<uint32_t>(plan.component_sizes.size());
    r.holes = static_cast<uint32_t>(plan.dummies.size());
    r.handles = static_cast<uint32_t>(plan.handles.size() / 2);
    r.unreferenced_dropped = plan.unreferenced;
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
    const Frame frame = make_frame_t(xyz, nv, options.position_bits);
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

Frame make_frame(const double* xyz, size_t n, int bits) { return make_frame_t(xyz, n, bits); }
Frame make_frame(const float* xyz, size_t n, int bits) { return make_frame_t(xyz, n, bits); }

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

Result<DecodedMesh> decode(const uint8_t* data, size_t size, const DecodeOptions& options) {
  Result<DecodedMesh> res;
  try {
    Container c;
    res.status = read_container(data, size, c);
    if (!res.ok()) return res;
    const Header& h = c.header;
    // §4.1 The header's counts against the caller's limits, before anything is allocated.
    if (h.vertices > options.limits.max_vertices || h.triangles > options.limits.max_triangles) {
      res.status = make_status(Error::count_exceeds_limit, "4.1", 8,
                               "the stream has " + std::to_string(h.vertices) + " vertices and " +
                                   std::to_string(h.triangles) + " triangles, beyond the caller's limits");
      return res;
    }
    const Section* cs = c.find(kSectionConnectivity);
    const Section* ps = c.find(kSectionPositions);
    ClosedMesh mesh;
    res.status = read_connectivity(data + cs->offset, cs->size, cs->offset, options.limits, h.vertices,
                                   h.triangles, (h.flags & kFlagClersSeam) != 0, mesh);
    if (!res.ok()) return res;
    std::vector<uint32_t> q;
    const Section* is = c.find(kSectionIrregular);
    const Section* pts = c.find(kSectionPatches);
    if (is && pts) {  // §2 a PRM: irregular triangles, patches, then the other vertices
      std::vector<uint8_t> cls, known;
      res.status = read_irregular_triangles(data + is->offset, is->size, is->offset, mesh,
                                            (h.flags & kFlagLersValence) != 0, cls);
      if (!res.ok()) return res;
      res.status = read_patches(data + pts->offset, pts->size, pts->offset, mesh, h.frame.bits, h.bbox_min,
                                h.bbox_max, (h.flags & kFlagPatchContexts) != 0, cls, q, known);
      if (!res.ok()) return res;
      res.status = read_positions(data + ps->offset, ps->size, ps->offset, mesh, h.bbox_min, h.bbox_max, q, &known);
    } else {
      res.status = read_positions(data + ps->offset, ps->size, ps->offset, mesh, h.bbox_min, h.bbox_max, q);
    }
    if (!res.ok()) return res;
    DecodedMesh& out = res.value;
    out.frame = h.frame;
    if (mesh.num_vertices == h.vertices) {  // no dummies: the closed mesh is the output (§6.7)
      out.triangles = std::move(mesh.corner_vertex);
      out.quantized = std::move(q);
    } else {
      out.triangles = std::move(mesh.output_triangles);
      out.quantized.resize(size_t{3} * h.vertices);
      for (uint32_t v = 0; v < mesh.num_vertices; ++v) {
        const uint32_t n = mesh.old_to_new[v];
        if (n == UINT32_MAX) continue;
        for (int k = 0; k < 3; ++k) out.quantized[3 * size_t{n} + k] = q[3 * size_t{v} + k];
      }
    }
    // §10.5 Output positions: o + q * s in double, rounded to float for float32 output.
    if (options.positions == PositionOutput::float32) {
      out.positions_f32.resize(out.quantized.size());
      for (size_t i = 0; i < out.quantized.size(); ++i)
        out.positions_f32[i] = static_cast<float>(dequantize(out.quantized[i], h.frame.origin[i % 3], h.frame.step));
    } else if (options.positions == PositionOutput::float64) {
      out.positions_f64.resize(out.quantized.size());
      for (size_t i = 0; i < out.quantized.size(); ++i)
        out.positions_f64[i] = dequantize(out.quantized[i], h.frame.origin[i % 3], h.frame.step);
    }
  } catch (const std::bad_alloc&) {
    res.status = make_status(Error::out_of_memory, "4", 0, "out of memory");
  } catch (...) {
    res.status = make_status(Error::internal, "", 0, "unexpected exception");
  }
  if (!res.ok()) res.value = DecodedMesh{};
  return res;
}

Result<StreamInfo> inspect(const uint8_t* data, size_t size) {
  Result<StreamInfo> res;
  try {
    Container c;
    res.status = read_container(data, size, c);
    if (!res.ok()) return res;
    StreamInfo& s = res.value;
    s.version_major = c.header.version_major;
    s.version_minor = c.header.version_minor;
    s.flags = c.header.flags;
    s.vertices = c.header.vertices;
    s.triangles = c.header.triangles;
    s.frame = c.header.frame;
    s.bbox_min = c.header.bbox_min;
    s.bbox_max = c.header.bbox_max;
    s.header_bytes = c.header_bytes;
    for (const Section& sec : c.sections) s.sections.push_back({sec.id, section_name(sec.id), sec.offset, sec.size});
    s.crc = c.crc;
    s.total_bytes = size;
  } catch (const std::bad_alloc&) {
    res.status = make_status(Error::out_of_memory, "4", 0, "out of memory");
  } catch (...) {
    res.status = make_status(Error::internal, "", 0, "unexpected exception");
  }
  return res;
}

}  // namespace prm::codec
