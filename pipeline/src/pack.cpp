#include "prm/pipeline/pack.h"

#include <chrono>
#include <iterator>

#include "prm/error.h"
#include "prm/mesh_validate.h"
#include "prm/metro_distance.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/remesh/lattice.h"

namespace prm::pipeline {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// One bit depth and step scale: repair (done by the caller), remesh, encode.
PackResult pack_at(const Mesh& source, const MetroReference& reference, const PackOptions& options, int bits,
                   double step_scale, double initial_grid) {
  PackResult out;
  auto t0 = std::chrono::steady_clock::now();
  remesh::RemeshOptions ro;
  ro.bits = bits;
  ro.step_scale = step_scale;
  ro.reliefs.tau = options.tau;
  ro.reliefs.parallel = options.parallel;
  ro.parallel = options.parallel;
  ro.fit_heights = options.fit_heights;
  ro.error_flip_weight = options.error_flip_weight;
  ro.grid_size = options.grid_size;
  ro.grid_fraction = options.grid_fraction;
  ro.initial_grid_size = initial_grid;
  ro.target_error = kQuantizationMargin * options.target_error;
  // The search measures what the decoder will output: the candidate quantized to the stream's frame (its lattice
  // vertices are exact already; the heights and the other vertices round to the nearest step), or, when the
  // encoder may choose the heights, the candidate encoded and decoded.
  const remesh::QuantFrame frame = remesh::frame_of_mesh(source, bits, step_scale);
  codec::PrmOptions po;
  if (options.height_lambda > 0) {
    po.height_tolerance = kHeightTolerance;
    po.height_lambda = options.height_lambda;
  }
  po.height_sweeps = options.height_sweeps;
  po.seam_context = options.max_minor >= codec::kFormatMinorSeam ? -1 : 0;
  po.patch_contexts = options.max_minor >= codec::kFormatMinorPatchContexts;
  // The stream of a candidate with options o, and the error of its decoded mesh.
  // zero_area: the decoded mesh's triangles of zero area (the chosen heights can put a corner on a line).
  auto encode_and_measure = [&](const remesh::PrmMesh& prm, const codec::PrmOptions& o, codec::EncodeReport* report,
                                std::vector<uint8_t>* stream, size_t* zero_area = nullptr) {
    auto encoded = encode_prm_mesh(prm, report, o);
    if (!encoded.ok())
      throw InputError("the piecewise regular mesh could not be encoded (a remesher or codec bug): " +
                       encoded.status.message + " (spec §" + encoded.status.spec_section + ")");
    auto decoded = codec::decode(encoded.value.data(), encoded.value.size());
    if (!decoded.ok()) throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
    if (zero_area) *zero_area = count_zero_area_triangles(decoded.value);
    const DistanceReport d = reference.compare(to_mesh(decoded.value));
    if (stream) *stream = std::move(encoded.value);
    return remesh::ErrorEstimate{d.rel(d.rms), d.rel(d.max)};
  };
  auto error = [&](const remesh::PrmMesh& prm) {
    if (po.height_lambda > 0) return encode_and_measure(prm, po, nullptr, nullptr);
    const Mesh& candidate = prm.mesh;
    Mesh q;
    q.triangles = candidate.triangles;
    q.positions.resize(candidate.positions.size());
    for (size_t v = 0; v < q.positions.size(); ++v)
      for (int a = 0; a < 3; ++a)
        q.positions[v][static_cast<size_t>(a)] =
            frame.to_real(frame.quantize(candidate.positions[v][static_cast<size_t>(a)], a), a);
    const DistanceReport d = reference.compare(q);
    return remesh::ErrorEstimate{d.rel(d.rms), d.rel(d.max)};
  };
  out.remesh = remesh::remesh(source, ro, error);
  out.seconds_remesh = seconds_since(t0);
  out.bits = bits;
  out.step_scale = step_scale;

  t0 = std::chrono::steady_clock::now();
  auto encoded = encode_prm_mesh(out.remesh.prm, &out.report, po);
  out.seconds_encode = seconds_since(t0);
  if (!encoded.ok())
    throw InputError("the piecewise regular mesh could not be encoded (a remesher or codec bug): " +
                     encoded.status.message + " (spec §" + encoded.status.spec_section + ")");
  out.stream = std::move(encoded.value);
  out.codec_options = po;
  // The error left below the target buys smaller residuals: the largest lambda that still meets it.
  if (options.optimize_heights && options.height_lambda <= 0 && options.target_error > 0) {
    const auto t1 = std::chrono::steady_clock::now();
    // The error grows with lambda: bisection for the last one that meets the target.
    int lo = -1, hi = static_cast<int>(std::size(kHeightLambdas));  // lo meets (-1: rounding), hi does not
    while (hi - lo > 1) {
      const int mid = (lo + hi) / 2;
      codec::PrmOptions o = po;
      o.height_tolerance = kHeightTolerance;
      o.height_lambda = kHeightLambdas[mid];
      o.height_sweeps = options.height_sweeps;
      // Only linear prediction takes the freedom; the difference depths would code the same heights as above.
      if (out.report.height_depth == codec::kLinearPredictionDepth) {
        o.height_depth = out.report.height_depth;
        o.overlap_depth = out.report.overlap_depth;
      }
      codec::EncodeReport report;
      std::vector<uint8_t> stream;
      size_t zero_area = 0;
      const remesh::ErrorEstimate e = encode_and_measure(out.remesh.prm, o, &report, &stream, &zero_area);
      if (e.rms > ro.target_error || zero_area > 0) {
        hi = mid;
        continue;
      }
      lo = mid;
      if (stream.size() < out.stream.size()) {
        out.stream = std::move(stream);
        out.report = report;
        out.remesh.error = e;
        out.codec_options = o;
      }
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
    zero_area = zero_area_of(out.stream);
  }
  if (zero_area > 0)
    throw remesh::TargetNotReached(std::to_string(zero_area) + " triangle(s) of the piecewise regular mesh have zero "
                                   "area once quantized to " + std::to_string(bits) + " bits (step scale " +
                                   std::to_string(step_scale) + "): vertices too close to separate");
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

}  // namespace

PackResult pack(const Mesh& input, const PackOptions& options) {
  auto t0 = std::chrono::steady_clock::now();
  check_remesh_range(input);  // before anything squares a length
  // Paper §2: the remesher needs a closed, consistently oriented manifold; the bunny's holes are closed by fans first.
  const MeshReport check = validate_mesh(input);
  Mesh closed;
  RepairReport repair;
  const bool repaired = !check.ready_for_remesh();
  if (repaired) closed = repair_mesh(input, &repair);  // throws InputError when it cannot be made a closed manifold
  const Mesh& source = repaired ? closed : input;
  const double seconds_repair = seconds_since(t0);
  MetroOptions mo;
  mo.samples = options.metro_samples;  // 0: Metro's ten per face, as `prm compare` measures
  const MetroReference reference(source, mo);

  PackResult out;
  const double fixed_scale = options.step_scale > 0 ? options.step_scale : 1.0;
  if (options.bits > 0 || options.target_error <= 0) {
    out = pack_at(source, reference, options, options.bits > 0 ? options.bits : 12, fixed_scale, 0);
    out.tried.push_back({out.bits, out.step_scale, out.stream.size()});
  } else {
    // The bit depth is part of the search: fewer bits make every height cheaper and add quantization error, which a
    // finer grid must buy back. From 12 bits down while the stream shrinks (up from 12 while the target is out of
    // reach), each grid search starting from the previous grid size.
    double grid = 0, seconds = 0;
    bool have = false;
    enum class Outcome { unreachable, smaller, larger };
    auto attempt = [&](int bits, double scale) {
      PackResult r;
      try {
        r = pack_at(source, reference, options, bits, scale, grid);
      } catch (const remesh::VertexBudgetExceeded&) {
        if (!have) throw;  // more bits would not make the grid it needs coarser
        return Outcome::unreachable;
      } catch (const remesh::TargetNotReached&) {
        return Outcome::unreachable;
      }
      seconds += r.seconds_remesh + r.seconds_encode;
      out.tried.push_back({bits, scale, r.stream.size()});
      grid = static_cast<double>(r.remesh.prm.lattice.A) * r.remesh.prm.frame.step;
      if (have && r.stream.size() >= out.stream.size()) return Outcome::larger;
      auto tried = std::move(out.tried);
      out = std::move(r);
      out.tried = std::move(tried);
      have = true;
      return Outcome::smaller;
    };
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
    }
    if (!have)
      throw remesh::TargetNotReached("no grid size reached the target error " + std::to_string(options.target_error) +
                                     " at 12 to " + std::to_string(kMaxPackBits) + " bits");
    out.seconds_remesh = seconds - out.seconds_encode;  // the whole search
  }
  out.seconds_repair = seconds_repair;
  out.repaired = repaired;
  out.repair = repair;
  if (repaired) out.repaired_input = std::move(closed);
  return out;
}

}  // namespace prm::pipeline
