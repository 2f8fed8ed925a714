#include "prm/pipeline/pack_general.h"

#include <cmath>
#include <string>
#include <utility>

#include "prm/error.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/remesh/boundary_polyline.h"
#include "prm/remesh/remesh.h"

namespace prm::pipeline {

namespace {

// The RMS distance of `decoded`'s boundary vertices to the input's boundary (`polyline`), model units; 0 if closed.
double boundary_rms(const Mesh& decoded, const remesh::BoundaryPolyline& polyline) {
  if (polyline.empty()) return 0;
  const std::vector<uint8_t> on_boundary = remesh::boundary_vertex_flags(decoded);
  double sum2 = 0;
  size_t n = 0;
  for (size_t v = 0; v < decoded.positions.size(); ++v)
    if (on_boundary[v]) {
      const double d = polyline.distance(decoded.positions[v]);
      sum2 += d * d;
      ++n;
    }
  return n ? std::sqrt(sum2 / static_cast<double>(n)) : 0;
}

// One bit depth: encode (spec §6, §10), decode, measure against the input.
GeneralPack encode_at(const Mesh& input, const MetroReference& reference, const remesh::BoundaryPolyline& polyline,
                      int bits, int max_minor) {
  GeneralPack out;
  auto encoded = encode_general_mesh(input, bits, &out.report, max_minor);
  if (!encoded.ok())
    throw InputError("the general path refuses the input: " + encoded.status.message + " (spec §" +
                     encoded.status.spec_section + ")");
  auto decoded = codec::decode(encoded.value.data(), encoded.value.size());
  if (!decoded.ok()) throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
  out.zero_area = count_zero_area_triangles(decoded.value);
  const Mesh out_mesh = to_mesh(decoded.value);
  const DistanceReport d = reference.compare(out_mesh);
  out.boundary_rms = d.rel(boundary_rms(out_mesh, polyline));
  out.stream = std::move(encoded.value);
  out.bits = bits;
  out.rms = d.rel(d.rms);
  out.max = d.rel(d.max);
  return out;
}

}  // namespace

GeneralPack pack_general(const Mesh& input, const MetroReference& reference, double target, int bits,
                         int max_minor, double max_target) {
  auto meets = [&](const GeneralPack& g) {
    return g.zero_area == 0 && (target <= 0 || (g.rms <= target && g.boundary_rms <= target)) &&
           (max_target <= 0 || g.max <= max_target);
  };
  auto missed = [&](const GeneralPack& g) {
    return "the general path at " + std::to_string(g.bits) + " bits " +
           (g.zero_area ? "has " + std::to_string(g.zero_area) + " triangle(s) of zero area"
            : target > 0 && g.rms > target
                ? "has an RMS error of " + std::to_string(g.rms) + ", above the target " + std::to_string(target)
            : target > 0 && g.boundary_rms > target
                ? "has its boundary at an RMS distance of " + std::to_string(g.boundary_rms) +
                      " from the input's, above the target " + std::to_string(target)
                : "has a maximum error of " + std::to_string(g.max) + ", above the bound " + std::to_string(max_target));
  };
  // The input's boundary, bucketed to reach two steps of the coarsest bit depth (a rounded vertex lies within
  // sqrt(3)/2 step of where it was).
  const remesh::BoundaryPolyline polyline(input, 2.0 * reference.diagonal() / ((1 << kMinGeneralBits) - 1));
  std::vector<GeneralPack::Trial> tried;
  auto at = [&](int b) {
    GeneralPack g = encode_at(input, reference, polyline, b, max_minor);
    tried.push_back({b, g.stream.size(), g.rms});
    return g;
  };
  GeneralPack best;
  if (bits > 0 || (target <= 0 && max_target <= 0)) {
    best = at(bits > 0 ? bits : 12);
    if (!meets(best)) throw remesh::TargetNotReached(missed(best));
  } else {
    // Bisection over [lo, hi]: hi meets the target, every depth below lo does not.
    int lo = kMinGeneralBits, hi = kMaxGeneralBits;
    best = at(hi);
    if (!meets(best)) throw remesh::TargetNotReached(missed(best));
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      GeneralPack g = at(mid);
      if (meets(g)) {
        hi = mid;
        best = std::move(g);
      } else {
        lo = mid + 1;
      }
    }
  }
  best.tried = std::move(tried);
  return best;
}

}  // namespace prm::pipeline
