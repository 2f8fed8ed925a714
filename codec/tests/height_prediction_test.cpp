// §9.7 Linear prediction of the heights: the tap-set tables, the raster order and lookup (dense and sparse alike,
// overlapping patches), the worked example of §9.7.5 exactly, the table's coding, and the encoder's fit.
#include <gtest/gtest.h>

#include <random>

#include "height_prediction_shared.h"
#include "height_prediction_fit.h"

namespace prm::codec::test {
namespace {

Level six_vertex_patch() {
  Level level;
  level.coord = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 0}, {2, 1}};
  level.tris = {{0, 1, 2}, {2, 1, 3}, {1, 4, 3}, {3, 4, 5}};
  return level;
}

// The table of the §9.7.5 example: only the sets with default weights (20..37), with those weights.
LpTable defaults_only() {
  LpTable table;
  for (int s = 0; s < kLpSets; ++s) {
    table.enabled[s] = s >= kLpFirstDefault;
    table.set_defaults(s);
  }
  table.build_selection();
  return table;
}

TEST(HeightPrediction, TapSetsAreCausalAndOrdered) {
  for (const auto& o : kLpOffset) EXPECT_TRUE(o[1] < 0 || (o[1] == 0 && o[0] < 0));
  LpTable table;
  EXPECT_EQ(table.taps[0], 12);
  for (int s = 1; s < kLpSets; ++s) EXPECT_LE(table.taps[s], table.taps[s - 1]) << s;  // larger sets first
  for (int s = kLpFirstDefault; s < kLpSets; ++s) {
    table.set_defaults(s);
    int32_t sum = 0;
    for (int k = 0; k < table.taps[s]; ++k) sum += table.weight[s][k];
    EXPECT_EQ(sum, kLpOne) << s;  // a constant is predicted exactly
  }
}

TEST(HeightPrediction, WorkedExampleOfTheSpec) {
  // §9.7.5: sets 20..37 with their defaults, heights 10 12 11 13 15 16, bounds [0, 4095].
  const Level level = six_vertex_patch();
  const LpTable table = defaults_only();
  LpRaster raster;
  EXPECT_EQ(raster.build(level), 0u);
  EXPECT_EQ(raster.order(), (std::vector<uint32_t>{0, 1, 4, 2, 3, 5}));
  std::vector<int64_t> h = {10, 12, 11, 13, 15, 16}, res;
  std::vector<uint8_t> placed(6, 0), coded;
  LpModels models;
  std::vector<int64_t> residuals;
  std::vector<std::pair<int, int>> contexts;
  auto record = [&](SignedIntModel& m, int, int64_t truth, int64_t& out, BitModel*) {
    for (int g = 0; g < kLpGroups; ++g)
      for (int a = 0; a < kLpActivities; ++a)
        if (&models.residual[g][a] == &m) contexts.push_back({g, a});
    residuals.push_back(truth);
    out = truth;
    return true;
  };
  ASSERT_TRUE(code_lp_heights(level, raster, table, models, 12, 0, 4095, placed, h, res, coded, record));
  EXPECT_EQ(residuals, (std::vector<int64_t>{-2037, 2, 1, 0, -1, 0}));
  const std::vector<std::pair<int, int>> expect = {{6, 8}, {5, 7}, {4, 7}, {4, 7}, {3, 7}, {3, 2}};
  EXPECT_EQ(contexts, expect);
  // The decoder's side: the same residuals give the heights back.
  std::vector<int64_t> decoded(6, 0);
  size_t next = 0;
  auto replay = [&](SignedIntModel&, int, int64_t, int64_t& out, BitModel*) {
    out = residuals[next++];
    return true;
  };
  LpModels fresh;
  ASSERT_TRUE(code_lp_heights(level, raster, table, fresh, 12, 0, 4095, placed, decoded, res, coded, replay));
  EXPECT_EQ(decoded, (std::vector<int64_t>{10, 12, 11, 13, 15, 16}));
}

TEST(HeightPrediction, PlacedVerticesAreNotCoded) {
  const Level level = six_vertex_patch();
  const LpTable table = defaults_only();
  LpRaster raster;
  raster.build(level);
  std::vector<int64_t> h = {10, 12, 11, 13, 15, 16}, res;
  std::vector<uint8_t> placed = {1, 0, 0, 1, 0, 0}, coded;
  LpModels models;
  int count = 0;
  auto value = [&](SignedIntModel&, int, int64_t truth, int64_t& out, BitModel*) {
    ++count;
    out = truth;
    return true;
  };
  ASSERT_TRUE(code_lp_heights(level, raster, table, models, 12, 0, 4095, placed, h, res, coded, value));
  EXPECT_EQ(count, 4);
}

TEST(HeightPrediction, OutOfBoundsHeightIsRejected) {
  const Level level = six_vertex_patch();
  const LpTable table = defaults_only();
  LpRaster raster;
  raster.build(level);
  std::vector<int64_t> h(6, 0), res;
  std::vector<uint8_t> placed(6, 0), coded;
  LpModels models;
  auto hostile = [&](SignedIntModel&, int, int64_t, int64_t& out, BitModel*) {
    out = 5000;  // beyond Hi = 4095
    return true;
  };
  EXPECT_FALSE(code_lp_heights(level, raster, table, models, 12, 0, 4095, placed, h, res, coded, hostile));
}

// Dense and sparse lookups agree, on a compact patch and on a long thin diagonal one (sparse), and both count the
// vertices sharing a lattice point.
TEST(HeightPrediction, DenseAndSparseRastersAgree) {
  std::mt19937 rng(3);
  for (int shape = 0; shape < 2; ++shape) {
    Level level;
    if (shape == 0) {
      for (int j = 0; j < 30; ++j)
        for (int i = 0; i < 30; ++i)
          if (rng() % 5) level.coord.push_back({i, j});
    } else {
      for (int k = 0; k < 3000; ++k) level.coord.push_back({k, -k + static_cast<int64_t>(rng() % 2)});
    }
    level.coord.push_back(level.coord[7]);  // one shared lattice point
    LpRaster raster;
    EXPECT_EQ(raster.build(level), 1u);
    const auto& order = raster.order();
    ASSERT_EQ(order.size(), level.size());
    for (size_t r = 1; r < order.size(); ++r) {
      const auto &a = level.coord[order[r - 1]], &b = level.coord[order[r]];
      EXPECT_TRUE(a[1] < b[1] || (a[1] == b[1] && (a[0] < b[0] || (a[0] == b[0] && order[r - 1] < order[r]))));
    }
    // Against a brute-force At().
    std::array<uint32_t, kLpOffsets> id;
    for (uint32_t l = 0; l < level.size(); l += 7) {
      const uint32_t mask = raster.taps(level.coord[l][0], level.coord[l][1], id);
      for (int t = 0; t < kLpOffsets; ++t) {
        uint32_t expect = LpRaster::kNone;
        for (uint32_t m = 0; m < level.size() && expect == LpRaster::kNone; ++m)
          if (level.coord[m][0] == level.coord[l][0] + kLpOffset[t][0] &&
              level.coord[m][1] == level.coord[l][1] + kLpOffset[t][1])
            expect = m;
        EXPECT_EQ(id[t], expect);
        EXPECT_EQ((mask >> t) & 1, expect != LpRaster::kNone ? 1u : 0u);
      }
    }
  }
}

// The fit recovers a known predictor: heights of a plane plus a known second-order term are predicted by the
// parallelogram set almost exactly; the fitted weights sum to 256.
TEST(HeightPrediction, FitRecoversAPlane) {
  std::vector<LpSample> samples;
  std::mt19937 rng(5);
  auto height = [](int64_t i, int64_t j) { return 1000 + 7 * i - 3 * j; };
  for (int n = 0; n < 4000; ++n) {
    const int64_t i = static_cast<int64_t>(rng() % 200), j = static_cast<int64_t>(rng() % 200);
    LpSample s;
    s.mask = 0x0FFF;
    for (int t = 0; t < kLpOffsets; ++t) s.tap[t] = height(i + kLpOffset[t][0], j + kLpOffset[t][1]);
    s.h = height(i, j) + static_cast<int64_t>(rng() % 3) - 1;
    samples.push_back(s);
  }
  LpTable table;
  std::array<bool, kLpSets> fitted;
  fit_lp_table(samples, table, fitted);
  EXPECT_TRUE(table.enabled[0]);
  EXPECT_TRUE(fitted[0]);
  for (int s = 1; s < kLpSets; ++s) EXPECT_FALSE(table.enabled[s]) << s;  // nothing else is selected
  int32_t sum = 0;
  for (int k = 0; k < 12; ++k) sum += table.weight[0][k];
  EXPECT_EQ(sum, kLpOne);
  // Mean absolute residual of the fitted predictor on the samples: the noise's (2/3), not more.
  double total = 0;
  for (const LpSample& s : samples) {
    int64_t sum_w = 0;
    for (int k = 0; k < 12; ++k) sum_w += int64_t{table.weight[0][k]} * s.tap[table.tap[0][k]];
    total += std::abs(static_cast<double>(s.h - floor_shift(sum_w + 128, 8)));
  }
  EXPECT_LT(total / samples.size(), 0.9);
}

// §9.7.4 The activity context against its definition, min(bit length of floor(3 * sum / count), 7) over the coded
// residuals at the activity offsets (8 with none), for every count and sums around each class boundary.
TEST(HeightPrediction, ActivityContextMatchesItsDefinition) {
  std::array<int64_t, kLpOffsets> activity{};
  std::array<int64_t, kLpOffsets> height{};
  std::array<int64_t, kLpOffsets> delta{};
  for (int t = 0; t < kLpOffsets; ++t) delta[static_cast<size_t>(t)] = t;
  const LpCellView view{height.data(), activity.data(), delta.data()};
  std::mt19937 rng(7);
  for (int count = 0; count <= 6; ++count) {
    for (int64_t sum = 0; sum < 3000; sum += sum < 600 ? 1 : 37) {
      activity.fill(-1);
      // `count` of the six activity offsets hold residuals summing to `sum`, the first holding the rest.
      int64_t rest = count ? sum : 0;
      for (int k = count - 1; k >= 0; --k) {
        const int64_t a = k == 0 ? rest : static_cast<int64_t>(rng() % static_cast<uint32_t>(rest + 1));
        activity[static_cast<size_t>(kLpActivityTap[k])] = a;
        rest -= a;
      }
      const int64_t used = count ? sum : 0;
      int want = 8;
      if (count > 0) {
        const int64_t x = 3 * used / count;
        int bits = 0;
        while (bits < 63 && (x >> bits) != 0) ++bits;
        want = std::min(bits, 7);
      }
      EXPECT_EQ(lp_activity(view), want) << count << " " << sum;
    }
  }
  activity.fill(-1);
  for (int k = 0; k < 6; ++k) activity[static_cast<size_t>(kLpActivityTap[k])] = int64_t{1} << 41;  // |r| < 2^41
  EXPECT_EQ(lp_activity(view), 7);
}

// The table's fields round-trip through the shared coder, enabled and fitted flags included.
TEST(HeightPrediction, TableRoundTrip) {
  LpTable table;
  std::array<bool, kLpSets> fitted{};
  std::mt19937 rng(9);
  for (int s = 0; s < kLpSets; ++s) {
    table.enabled[s] = rng() % 3 != 0;
    fitted[s] = table.enabled[s] && (s < kLpFirstDefault || rng() % 2);
    if (fitted[s])
      for (int k = 1; k < table.taps[s]; ++k) table.weight[s][k] = static_cast<int32_t>(rng() % 2001) - 1000;
    else
      table.set_defaults(s);
  }
  std::vector<uint32_t> bits;
  std::vector<int64_t> values;
  LpModels m;
  auto put_direct = [&](int, uint32_t truth) {
    bits.push_back(truth);
    return truth;
  };
  auto put_value = [&](SignedIntModel&, int, int64_t truth, int64_t& out) {
    values.push_back(truth);
    out = truth;
    return true;
  };
  LpTable sent = table;
  std::array<bool, kLpSets> sent_fitted = fitted;
  ASSERT_TRUE(code_lp_table(sent, sent_fitted, m, put_direct, put_value));
  size_t nb = 0, nv = 0;
  auto get_direct = [&](int, uint32_t) { return bits[nb++]; };
  auto get_value = [&](SignedIntModel&, int, int64_t, int64_t& out) {
    out = values[nv++];
    return true;
  };
  LpTable got;
  std::array<bool, kLpSets> got_fitted{};
  ASSERT_TRUE(code_lp_table(got, got_fitted, m, get_direct, get_value));
  EXPECT_EQ(nb, bits.size());
  EXPECT_EQ(nv, values.size());
  EXPECT_EQ(got.enabled, sent.enabled);
  EXPECT_EQ(got.weight, sent.weight);
  for (uint32_t mask = 0; mask < (1u << kLpOffsets); ++mask) ASSERT_EQ(got.select(mask), sent.select(mask)) << mask;
}

}  // namespace
}  // namespace prm::codec::test
