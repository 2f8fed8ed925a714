#include "prm/pipeline/pack_general.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "prm/error.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/remesh/boundary_polyline.h"
#include "prm/remesh/remesh.h"
#include "prm/vec3.h"

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

// The largest distance between a decoded vertex and the input vertex it codes, when the decoded triangles are the
// input's, one for one (the encoder's vertex_order and triangle_order, corners rotated by triangle_rotation); -1 when
// they are not (then only Metro can tell). The decoded surface is then the input's with every vertex moved by at most
// this much, and a point of a triangle (a convex combination of its corners) by at most this much too, in both
// directions: it bounds both one-sided Metro distances, their maximum and so their RMS.
double vertex_displacement_bound(const Mesh& input, const codec::DecodedMesh& decoded, const codec::EncodeReport& r) {
  const size_t nt = decoded.num_triangles(), nv = decoded.num_vertices();
  if (nt != input.triangles.size() || r.triangle_order.size() != nt || r.triangle_rotation.size() != nt ||
      r.vertex_order.size() != nv)
    return -1;
  std::vector<char> seen(nt, 0);
  for (size_t k = 0; k < nt; ++k) {
    const uint32_t t = r.triangle_order[k];
    if (t >= nt || seen[t] || r.triangle_rotation[k] > 2) return -1;
    seen[t] = 1;
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = decoded.triangles[3 * k + static_cast<size_t>(c)];
      if (v >= nv || r.vertex_order[v] != input.triangles[t][static_cast<size_t>((c + r.triangle_rotation[k]) % 3)])
        return -1;
    }
  }
  double d2 = 0;
  for (size_t k = 0; k < nv; ++k) {
    const uint32_t v = r.vertex_order[k];
    if (v >= input.positions.size()) return -1;
    Vec3 q;
    for (int a = 0; a < 3; ++a)
      q[static_cast<size_t>(a)] = decoded.frame.to_real(decoded.quantized[3 * k + static_cast<size_t>(a)], a);
    d2 = std::max(d2, norm2(q - input.positions[v]));
  }
  return std::sqrt(d2);
}

// The bound above decides a bit depth only with this margin below the target (the Metro distances are computed in
// floating point: a sample's distance may exceed the exact one by a few ulps).
constexpr double kBoundMargin = 1 - 1e-9;

// The Metro distances of g's decoded mesh to the input.
void measure(const MetroReference& reference, const codec::DecodedMesh& decoded, GeneralPack& g) {
  const DistanceReport d = reference.compare(to_mesh(decoded));
  g.measured = true;
  g.rms = d.rel(d.rms);
  g.max = d.rel(d.max);
}
void measure(const MetroReference& reference, GeneralPack& g) {
  auto decoded = codec::decode(g.stream.data(), g.stream.size());
  if (!decoded.ok()) throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
  measure(reference, decoded.value, g);
}

// One bit depth: encode (spec §6, §10), decode, measure the boundary against the input's (`polyline`), and (unless
// `skip_metro` says the depth is decided without it) measure against the input. skip_metro(g) sees g's zero_area,
// boundary RMS and displacement bound.
template <typename SkipMetro>
GeneralPack encode_at(const Mesh& input, const MetroReference& reference, const remesh::BoundaryPolyline& polyline,
                      int bits, int max_minor, const SkipMetro& skip_metro) {
  GeneralPack out;
  auto encoded = encode_general_mesh(input, bits, &out.report, max_minor);
  if (!encoded.ok())
    throw InputError("the general path refuses the input: " + encoded.status.message + " (spec §" +
                     encoded.status.spec_section + ")");
  auto decoded = codec::decode(encoded.value.data(), encoded.value.size());
  if (!decoded.ok()) throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
  out.zero_area = count_zero_area_triangles(decoded.value);
  if (!polyline.empty()) out.boundary_rms = reference.diagonal() > 0
                                                ? boundary_rms(to_mesh(decoded.value), polyline) / reference.diagonal()
                                                : 0;
  out.stream = std::move(encoded.value);
  out.bits = bits;
  // The bound only holds against the mesh that was encoded: the reference must be that very mesh.
  const double bound = &reference.mesh() == &input && reference.diagonal() > 0
                           ? vertex_displacement_bound(input, decoded.value, out.report)
                           : -1;
  out.bound = bound >= 0 ? bound / reference.diagonal() : -1;
  if (!skip_metro(out)) measure(reference, decoded.value, out);
  return out;
}

}  // namespace

GeneralPack pack_general(const Mesh& input, const MetroReference& reference, double target, int bits,
                         int max_minor, double max_target) {
  // The depths' decoded meshes share their triangles: Metro refits one candidate tree across them (MetroReference);
  // freed when the depth is chosen, so that the input-sized tree does not stay through the piecewise regular search.
  struct ForgetCandidate {
    const MetroReference& reference;
    ~ForgetCandidate() { reference.forget_candidate(); }
  } forget_candidate{reference};
  // A bit depth is decided without Metro when its decoded mesh has a zero-area triangle (it cannot meet the target)
  // or when the displacement bound is within the target and the bound (it meets it: Metro's RMS and maximum are at
  // most the bound); the depth kept is measured in any case (its distances are reported). Every decision is the one
  // the measured distances would make.
  auto bound_meets = [&](const GeneralPack& g) {
    return g.bound >= 0 && (target <= 0 || g.bound <= kBoundMargin * target) &&
           (max_target <= 0 || g.bound <= kBoundMargin * max_target);
  };
  // A boundary farther than the target from the input's misses whatever Metro says (issue 22: the output's boundary
  // loops lie within the target of the input's; a bound within the target keeps them there too).
  auto boundary_misses = [&](const GeneralPack& g) { return target > 0 && g.boundary_rms > target; };
  auto decided = [&](const GeneralPack& g) { return g.zero_area > 0 || boundary_misses(g) || bound_meets(g); };
  auto meets = [&](const GeneralPack& g) {
    if (g.zero_area > 0 || boundary_misses(g)) return false;
    if (!g.measured) return bound_meets(g);
    return (target <= 0 || g.rms <= target) && (max_target <= 0 || g.max <= max_target);
  };
  auto missed = [&](const GeneralPack& g) {
    return "the general path at " + std::to_string(g.bits) + " bits " +
           (g.zero_area ? "has " + std::to_string(g.zero_area) + " triangle(s) of zero area"
            : boundary_misses(g)
                ? "has its boundary at an RMS distance of " + std::to_string(g.boundary_rms) +
                      " from the input's, above the target " + std::to_string(target)
            : target > 0 && g.rms > target
                ? "has an RMS error of " + std::to_string(g.rms) + ", above the target " + std::to_string(target)
                : "has a maximum error of " + std::to_string(g.max) + ", above the bound " + std::to_string(max_target));
  };
  // The input's boundary, bucketed to reach two steps of the coarsest bit depth (a rounded vertex lies within
  // sqrt(3)/2 step of where it was).
  const remesh::BoundaryPolyline polyline(input, 2.0 * reference.diagonal() / ((1 << kMinGeneralBits) - 1));
  std::vector<GeneralPack::Trial> tried;
  auto at = [&](int b, bool always_measure) {
    GeneralPack g = encode_at(input, reference, polyline, b, max_minor,
                              [&](const GeneralPack& c) { return !always_measure && decided(c); });
    tried.push_back({b, g.stream.size(), g.measured ? g.rms : -1});
    return g;
  };
  GeneralPack best;
  if (bits > 0 || (target <= 0 && max_target <= 0)) {
    best = at(bits > 0 ? bits : 12, true);
    if (!meets(best)) throw remesh::TargetNotReached(missed(best));
  } else {
    // Bisection over [lo, hi]: hi meets the target, every depth below lo does not.
    int lo = kMinGeneralBits, hi = kMaxGeneralBits;
    best = at(hi, false);
    if (!meets(best)) throw remesh::TargetNotReached(missed(best));  // (measured unless it has zero-area triangles)
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      GeneralPack g = at(mid, false);
      if (meets(g)) {
        hi = mid;
        best = std::move(g);
      } else {
        lo = mid + 1;
      }
    }
    // The depth kept: its distances measured (the report's), when the bound decided it.
    if (!best.measured) {
      measure(reference, best);
      for (GeneralPack::Trial& t : tried)
        if (t.bits == best.bits) t.rms = best.rms;
    }
  }
  best.tried = std::move(tried);
  return best;
}

size_t general_floor_bytes(const Mesh& input, int max_minor) {
  codec::EncodeReport report;
  const auto encoded = encode_general_mesh(input, kMinGeneralBits, &report, max_minor);
  if (!encoded.ok())
    throw InputError("the general path refuses the input: " + encoded.status.message + " (spec §" +
                     encoded.status.spec_section + ")");
  return encoded.value.size();
}

}  // namespace prm::pipeline
