// Spec Appendix B.2, the encoder's refinement of the chosen heights: it never makes the objective worse, it finds
// the joint optimum where the greedy choice cannot see it, it leaves held heights alone and stays in the windows.
#include <gtest/gtest.h>

#include <random>

#include "height_choice.h"
#include "height_prediction_shared.h"

namespace prm::codec::test {
namespace {

// Residual 0 costs 1 bit, +-1 costs 5, anything else 9, in every context.
ResidualCosts step_costs() {
  ResidualCosts c;
  c.table.resize(kLpGroups * kLpActivities);
  for (auto& t : c.table)
    for (int r = -kCostRange; r <= kCostRange; ++r)
      t[static_cast<size_t>(r + kCostRange)] = r == 0 ? 1.0 : (r == 1 || r == -1) ? 5.0 : 9.0;
  return c;
}

int64_t predicted(const ChosenHeight& c, const std::vector<uint32_t>& q) {
  int64_t sum = 0;
  for (int t = 0; t < c.taps; ++t) sum += int64_t{c.weight[t]} * q[3 * size_t{c.tap_vertex[t]} + c.pair];
  const int64_t p = floor_shift(sum + kLpOne / 2, kLpPrecisionBits);
  return std::clamp(p, c.lo, c.hi);
}

// sum over the records of (h - exact)^2 for the free ones, plus lambda times the bits of every predicted residual.
double objective(const std::vector<ChosenHeight>& hs, const ResidualCosts& costs, double lambda,
                 const std::vector<uint32_t>& q) {
  double j = 0;
  for (const ChosenHeight& c : hs) {
    const int64_t h = q[3 * size_t{c.vertex} + c.pair];
    if (c.window.free) j += (h - c.window.exact) * (h - c.window.exact);
    if (c.taps) j += lambda * costs.bits(c.context, h - predicted(c, q));
  }
  return j;
}

ChosenHeight record(uint32_t v, std::vector<std::pair<uint32_t, int32_t>> taps, double exact, bool free) {
  ChosenHeight c;
  c.vertex = v;
  c.pair = 2;
  c.lo = 0;
  c.hi = 1000;
  c.taps = static_cast<uint8_t>(taps.size());
  for (size_t t = 0; t < taps.size(); ++t) c.tap_vertex[t] = taps[t].first, c.weight[t] = taps[t].second;
  c.window = height_window(static_cast<int64_t>(std::floor(exact + 0.5)), exact, 1.5, 0, 1000, free);
  return c;
}

// A chain: vertex 0 held at 100; 1 (exact 100.6) predicted from 0, 2 (exact 101.6) from 1, 3 (held at 102) from
// 2, each with weight one, at lambda 0.1. One by one (B.1), height 1 keeps 100 (residual 0: 0.36 + 0.1 against
// 0.16 + 0.5 for 101) and height 2 then takes 101 (residual 1), leaving height 3 a residual of 1: in all 1.82. The
// refinement moves height 1 to 101, for residuals 1, 1, 0 and distances 0.16 + 0.16: 1.42, the optimum over the
// windows. The heights it may not move (0 and 3) stay.
TEST(HeightChoice, FindsTheJointOptimumOfAChain) {
  const ResidualCosts costs = step_costs();
  std::vector<uint32_t> q(3 * 4, 0);
  q[3 * 0 + 2] = 100;
  q[3 * 3 + 2] = 102;
  std::vector<ChosenHeight> hs = {record(1, {{0, 256}}, 100.6, true), record(2, {{1, 256}}, 101.6, true),
                                  record(3, {{2, 256}}, 102.0, false)};
  q[3 * 1 + 2] = 100;  // the greedy choice
  q[3 * 2 + 2] = 101;
  const double lambda = 0.1;
  const double before = objective(hs, costs, lambda, q);
  // The optimum over the windows by brute force.
  double best = HUGE_VAL;
  std::array<uint32_t, 2> arg{};
  std::vector<uint32_t> t = q;
  for (int64_t a = hs[0].window.lo; a <= hs[0].window.hi; ++a)
    for (int64_t b = hs[1].window.lo; b <= hs[1].window.hi; ++b) {
      t[3 * 1 + 2] = static_cast<uint32_t>(a);
      t[3 * 2 + 2] = static_cast<uint32_t>(b);
      const double j = objective(hs, costs, lambda, t);
      if (j < best) best = j, arg = {static_cast<uint32_t>(a), static_cast<uint32_t>(b)};
    }
  refine_heights(hs, costs, lambda, 4, q);
  EXPECT_DOUBLE_EQ(objective(hs, costs, lambda, q), best);
  EXPECT_NEAR(before, 1.82, 1e-9);
  EXPECT_NEAR(best, 1.42, 1e-9);
  EXPECT_EQ(q[3 * 1 + 2], arg[0]);
  EXPECT_EQ(q[3 * 2 + 2], arg[1]);
  EXPECT_EQ(q[3 * 0 + 2], 100u);
  EXPECT_EQ(q[3 * 3 + 2], 102u);
  // Zero sweeps or lambda 0: nothing moves.
  std::vector<uint32_t> same = t;
  refine_heights(hs, costs, lambda, 0, same);
  EXPECT_EQ(same, t);
  refine_heights(hs, costs, 0.0, 4, same);
  EXPECT_EQ(same, t);
}

// Random patches of twelve-tap predictions (each vertex predicted from up to 12 earlier ones with weights summing to
// one): the objective never grows, and every free height stays in its window.
TEST(HeightChoice, NeverWorsensTheObjectiveAndStaysInTheWindows) {
  std::mt19937 rng(11);
  const ResidualCosts costs = step_costs();
  for (int trial = 0; trial < 20; ++trial) {
    const uint32_t n = 200;
    std::vector<uint32_t> q(3 * n, 0);
    std::vector<ChosenHeight> hs;
    std::uniform_real_distribution<double> noise(-0.5, 0.5);
    for (uint32_t v = 0; v < n; ++v) {
      const double exact = 300 + 0.05 * v + 3 * std::sin(0.1 * v) + noise(rng);
      q[3 * v + 2] = static_cast<uint32_t>(std::floor(exact + 0.5));
      std::vector<std::pair<uint32_t, int32_t>> taps;
      if (v >= 12) {
        int32_t rest = kLpOne;
        for (uint32_t k = 1; k < 12; ++k) {
          const int32_t w = static_cast<int32_t>(rng() % 61) - 30;
          taps.push_back({v - 1 - k, w});
          rest -= w;
        }
        taps.insert(taps.begin(), {v - 1, rest});
      }
      hs.push_back(record(v, taps, exact, v >= 12 && rng() % 8 != 0));
    }
    const double lambda = 0.05 + 0.1 * trial;
    const double before = objective(hs, costs, lambda, q);
    const std::vector<uint32_t> start = q;
    refine_heights(hs, costs, lambda, 4, q);
    EXPECT_LE(objective(hs, costs, lambda, q), before + 1e-9) << trial;
    for (const ChosenHeight& c : hs) {
      const int64_t h = q[3 * size_t{c.vertex} + 2];
      if (!c.window.free) {
        EXPECT_EQ(h, start[3 * size_t{c.vertex} + 2]);
        continue;
      }
      EXPECT_GE(h, c.window.lo);
      EXPECT_LE(h, c.window.hi);
      EXPECT_LE(std::fabs(h - c.window.exact), 1.5);
    }
  }
}

// B.1 The window: within the tolerance, inside the box but off its faces, always holding the rounded height.
TEST(HeightChoice, WindowStaysOffTheBoxFaces) {
  HeightWindow w = height_window(10, 10.2, 1.5, 0, 100, true);
  EXPECT_TRUE(w.free);
  EXPECT_EQ(w.lo, 9);
  EXPECT_EQ(w.hi, 11);
  w = height_window(1, 0.8, 1.5, 0, 100, true);
  EXPECT_EQ(w.lo, 1);  // 0 is the box's face
  EXPECT_EQ(w.hi, 2);
  EXPECT_FALSE(height_window(0, 0.2, 1.5, 0, 100, true).free);    // on a face: stays
  EXPECT_FALSE(height_window(100, 99.9, 1.5, 0, 100, true).free);
  EXPECT_FALSE(height_window(50, 50.0, 1.5, 0, 100, false).free);  // a lattice coordinate elsewhere
}

// The cost table (built from each decision's cost once per model) is signed_cost_bits entry by entry, to the last
// bit, for models that have seen data (every probability different) with and without the §9.7.4 sign contexts.
TEST(HeightChoice, CostTableIsSignedCostBits) {
  for (bool sign_context : {false, true}) {
    LpModels m;
    m.sign_context = sign_context;
    uint32_t x = 12345;
    auto next = [&x] { return x = x * 1103515245u + 12345u, (x >> 16) & 1; };
    auto train = [&](BitModel& b) {
      for (int k = 0, n = 1 + static_cast<int>(x % 23); k < n; ++k) b.update(next());
    };
    for (auto& row : m.residual)
      for (SignedIntModel& s : row) {
        train(s.zero), train(s.sign);
        for (BitModel& b : s.cls) train(b);
        for (BitModel& b : s.mant) train(b);
      }
    for (auto& row : m.sign)
      for (BitModel& b : row) train(b);
    const ResidualCosts c = ResidualCosts::of(m);
    for (int g = 0; g < kLpGroups; ++g)
      for (int a = 0; a < kLpActivities; ++a)
        for (int s = 0; s < kLpSignContexts; ++s) {
          const BitModel& sign = sign_context ? m.sign[g][s] : m.residual[g][a].sign;
          for (int r = -kCostRange; r <= kCostRange; ++r)
            ASSERT_EQ(c.bits(residual_context(g, a, s), r), signed_cost_bits(m.residual[g][a], r, sign))
                << g << " " << a << " " << s << " " << r;
        }
  }
}

}  // namespace
}  // namespace prm::codec::test
