// Spec Appendix B.2: the encoder's refinement of the chosen heights (height_choice.h).
#include "height_choice.h"

#include <algorithm>
#include <utility>

#include "height_prediction_shared.h"

namespace prm::codec {

static_assert(kLpGroups == 7 && kLpActivities == 9 && kLpSignContexts == 6, "residual_context() is out of date");

ResidualCosts ResidualCosts::of(const LpModels& models) {
  // Each entry is signed_cost_bits(models.residual[g][a], r, sign), summed here in the same order from the cost of
  // each decision, computed once per model rather than once per entry (the table is the same to the last bit;
  // 7 * 9 * 6 contexts of 129 entries made this the encoder's largest cost on small meshes).
  constexpr int kTopClass = 6;  // int_class(kCostRange)
  static_assert(kCostRange >> kTopClass == 1, "kTopClass is the class of kCostRange");
  ResidualCosts c;
  c.table.resize(kResidualContexts);
  for (int g = 0; g < kLpGroups; ++g)
    for (int a = 0; a < kLpActivities; ++a) {
      const SignedIntModel& m = models.residual[g][a];
      double cls_one[kTopClass + 1], cls_zero[kTopClass + 1], mant[kTopClass + 1][2];
      for (int e = 0; e <= kTopClass; ++e) {
        cls_one[e] = bit_cost(m.cls[e], 1);
        cls_zero[e] = bit_cost(m.cls[e], 0);
        mant[e][0] = bit_cost(m.mant[e], 0);
        mant[e][1] = bit_cost(m.mant[e], 1);
      }
      const double zero = bit_cost(m.zero, 1), nonzero = bit_cost(m.zero, 0);
      for (int s = 0; s < kLpSignContexts; ++s) {
        const BitModel& sign = models.sign_context ? models.sign[g][s] : m.sign;
        const double sign_cost[2] = {bit_cost(sign, 0), bit_cost(sign, 1)};
        auto& row = c.table[static_cast<size_t>(residual_context(g, a, s))];
        for (int r = -kCostRange; r <= kCostRange; ++r) {
          double bits = r == 0 ? zero : nonzero;
          if (r != 0) {
            bits += sign_cost[r < 0];
            const uint64_t mag = static_cast<uint64_t>(r < 0 ? -r : r);
            const int e = int_class(mag);
            for (int i = 0; i < e; ++i) bits += cls_one[i];
            bits += cls_zero[e];  // e <= kTopClass < kMaxClass
            if (e > 0) bits += mant[e][(mag >> (e - 1)) & 1] + (e - 1);
          }
          row[static_cast<size_t>(r + kCostRange)] = bits;
        }
      }
    }
  return c;
}

double ResidualCosts::bits(int c, int64_t r) const {
  const auto& t = table[static_cast<size_t>(c)];
  if (r >= -kCostRange && r <= kCostRange) return t[static_cast<size_t>(r + kCostRange)];
  const double edge = t[r < 0 ? 0 : 2 * kCostRange];
  return edge + 2.0 * std::log2(static_cast<double>(r < 0 ? -r : r) / kCostRange);
}

namespace {

// §9.7.4 The clamped prediction from a weighted tap sum.
int64_t predict(int64_t sum, int64_t lo, int64_t hi) {
  const int64_t p = floor_shift(sum + kLpOne / 2, kLpPrecisionBits);
  return p < lo ? lo : p > hi ? hi : p;
}

}  // namespace

void refine_heights(const std::vector<ChosenHeight>& heights, const ResidualCosts& costs, double lambda, int sweeps,
                    std::vector<uint32_t>& q) {
  const size_t n = heights.size();
  if (n == 0 || sweeps <= 0 || lambda <= 0) return;
  auto height = [&](const ChosenHeight& c) -> int64_t { return q[3 * size_t{c.vertex} + c.pair]; };
  // The record of each free vertex; each record's weighted tap sum; per free record, the records it is a tap of
  // (users[start[k] .. start[k + 1]), with the tap's weight).
  std::vector<uint32_t> record_of(q.size() / 3, UINT32_MAX);
  for (size_t k = 0; k < n; ++k)
    if (heights[k].window.free) record_of[heights[k].vertex] = static_cast<uint32_t>(k);
  std::vector<int64_t> sum(n, 0);
  std::vector<uint32_t> start(n + 1, 0);
  for (size_t k = 0; k < n; ++k) {
    const ChosenHeight& c = heights[k];
    for (int t = 0; t < c.taps; ++t) {
      const uint32_t v = c.tap_vertex[static_cast<size_t>(t)];
      sum[k] += int64_t{c.weight[static_cast<size_t>(t)]} * q[3 * size_t{v} + c.pair];
      if (record_of[v] != UINT32_MAX) ++start[record_of[v] + 1];
    }
  }
  for (size_t k = 0; k < n; ++k) start[k + 1] += start[k];
  std::vector<std::pair<uint32_t, int32_t>> users(start[n]);
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (size_t k = 0; k < n; ++k) {
    const ChosenHeight& c = heights[k];
    for (int t = 0; t < c.taps; ++t) {
      const uint32_t r = record_of[c.tap_vertex[static_cast<size_t>(t)]];
      if (r != UINT32_MAX) users[fill[r]++] = {static_cast<uint32_t>(k), c.weight[static_cast<size_t>(t)]};
    }
  }
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    bool moved = false;
    for (size_t k = 0; k < n; ++k) {
      const ChosenHeight& c = heights[k];
      if (!c.window.free) continue;
      const int64_t now = height(c);
      const int64_t own = predict(sum[k], c.lo, c.hi);
      int64_t best = now;
      double best_cost = HUGE_VAL;
      for (int64_t h = c.window.lo; h <= c.window.hi; ++h) {
        const double d = static_cast<double>(h) - c.window.exact;
        double bits = costs.bits(c.context, h - own);
        for (uint32_t u = start[k]; u < start[k + 1]; ++u) {
          const ChosenHeight& user = heights[users[u].first];
          const int64_t s = sum[users[u].first] + int64_t{users[u].second} * (h - now);
          bits += costs.bits(user.context, height(user) - predict(s, user.lo, user.hi));
        }
        const double cost = d * d + lambda * bits;
        if (cost < best_cost) best_cost = cost, best = h;
      }
      if (best == now) continue;
      moved = true;
      for (uint32_t u = start[k]; u < start[k + 1]; ++u) sum[users[u].first] += int64_t{users[u].second} * (best - now);
      q[3 * size_t{c.vertex} + c.pair] = static_cast<uint32_t>(best);
    }
    if (!moved) break;
  }
}

}  // namespace prm::codec
