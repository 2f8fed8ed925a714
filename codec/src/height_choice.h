// Spec Appendix B, encoder only: the heights the encoder chooses to code (PrmOptions::height_lambda).
//
// B.1, the first choice (patch_encode.cpp), is greedy: each height in turn, in coding order, takes the value in its
// window that minimises its own squared distance to the exact height plus lambda times its residual's bits under the
// models' current state. But a height is also a tap of up to twelve later predictions, so moving it changes their
// residuals too. B.2, the refinement here, minimises the sum over all of them,
//     sum (h - exact)^2 + lambda * sum bits(residual),
// by coordinate descent (iterated conditional modes): in coding order, each free height takes the value in its
// window that minimises its own term plus the bits of every residual it predicts, all others held. The bits come
// from static tables per residual context (the models' states at the end of the first choice) and the contexts are
// those of the first choice. The decoder sees only the heights.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace prm::codec {

struct LpModels;

// B.1 The heights a vertex may take: the integers within `tolerance` of the exact height, inside the bounding box
// and never on its faces (a height on a face stays there, so the box stays tight), always holding the rounded height
// `given`. `movable`: the vertex is in regular triangles of one axis pair only (otherwise its height is a lattice
// coordinate elsewhere). Not free: the height stays `given`; so does one without an exact height (NaN: the caller's
// PrmOptions::rounded_heights).
struct HeightWindow {
  int64_t lo = 0, hi = 0;
  double exact = 0;  // in quantization steps
  bool free = false;
};
inline HeightWindow height_window(int64_t given, double exact, double tolerance, int64_t box_lo, int64_t box_hi,
                                  bool movable) {
  HeightWindow w;
  w.exact = exact;
  w.free = movable && !std::isnan(exact) && given > box_lo && given < box_hi;
  w.lo = w.hi = given;
  if (!w.free) return w;
  w.lo = std::min(given, std::max(box_lo + 1, static_cast<int64_t>(std::ceil(exact - tolerance))));
  w.hi = std::max(given, std::min(box_hi - 1, static_cast<int64_t>(std::floor(exact + tolerance))));
  return w;
}

// One height coded by linear prediction (§9.7.4), in coding order.
struct ChosenHeight {
  uint32_t vertex = 0;   // closed-mesh vertex
  uint8_t pair = 0;      // the coordinate that is its height
  uint8_t taps = 0;      // 0: predicted without a tap set (then never free)
  uint16_t context = 0;  // its residual's context (§9.7.4): residual_context(group, activity, sign context)
  int64_t lo = 0, hi = 0;  // the clamp of its prediction: the bounding box (§9.7.4)
  HeightWindow window;
  std::array<uint32_t, 12> tap_vertex{};
  std::array<int32_t, 12> weight{};
};

// The index of a residual's context (§9.7.4): its model's group and activity, and its sign context
// (kLpNoSignContext when the stream has none).
inline int residual_context(int group, int activity, int sign) { return (group * 9 + activity) * 6 + sign; }
constexpr int kResidualContexts = 7 * 9 * 6;

// The bits of residual r in context c: tabulated for |r| <= kCostRange, beyond it the edge's cost plus two bits per
// doubling (the Exp-Golomb binarization of §9.5).
constexpr int kCostRange = 64;
struct ResidualCosts {
  std::vector<std::array<double, 2 * kCostRange + 1>> table;
  static ResidualCosts of(const LpModels& models);  // signed_cost_bits of each residual model's state
  double bits(int c, int64_t r) const;
};

// B.2 Refines the heights in q (3 per closed-mesh vertex) in place.
void refine_heights(const std::vector<ChosenHeight>& heights, const ResidualCosts& costs, double lambda, int sweeps,
                    std::vector<uint32_t>& q);

}  // namespace prm::codec
