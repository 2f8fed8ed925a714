#include "prm/pipeline/pack_general.h"

#include <string>
#include <utility>

#include "prm/error.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/remesh/remesh.h"

namespace prm::pipeline {

namespace {

// One bit depth: encode (spec §6, §10), decode, measure against the input.
GeneralPack encode_at(const Mesh& input, const MetroReference& reference, int bits, int max_minor) {
  GeneralPack out;
  auto encoded = encode_general_mesh(input, bits, &out.report, max_minor);
  if (!encoded.ok())
    throw InputError("the general path refuses the input: " + encoded.status.message + " (spec §" +
                     encoded.status.spec_section + ")");
  auto decoded = codec::decode(encoded.value.data(), encoded.value.size());
  if (!decoded.ok()) throw InputError("the encoder's stream does not decode (a codec bug): " + decoded.status.message);
  out.zero_area = count_zero_area_triangles(decoded.value);
  const DistanceReport d = reference.compare(to_mesh(decoded.value));
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
    return g.zero_area == 0 && (target <= 0 || g.rms <= target) && (max_target <= 0 || g.max <= max_target);
  };
  auto missed = [&](const GeneralPack& g) {
    return "the general path at " + std::to_string(g.bits) + " bits " +
           (g.zero_area ? "has " + std::to_string(g.zero_area) + " triangle(s) of zero area"
            : target > 0 && g.rms > target
                ? "has an RMS error of " + std::to_string(g.rms) + ", above the target " + std::to_string(target)
                : "has a maximum error of " + std::to_string(g.max) + ", above the bound " + std::to_string(max_target));
  };
  std::vector<GeneralPack::Trial> tried;
  auto at = [&](int b) {
    GeneralPack g = encode_at(input, reference, b, max_minor);
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
