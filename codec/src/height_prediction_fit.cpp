// §9.7.2 The encoder's predictor table (height_prediction_fit.h). The weights of a set minimise the sum of absolute
// residuals (the residuals are coded by magnitude class, so L1 tracks their cost better than L2), under the
// constraint that they sum to one (a constant height is predicted exactly); iteratively reweighted least squares
// from the least-squares start.
#include "height_prediction_fit.h"

#include <algorithm>
#include <cmath>

namespace prm::codec {
namespace {

// Solves the m x m system a x = b (row-major, m <= 11) by Gaussian elimination with partial pivoting; a tiny ridge
// keeps singular systems (taps that always agree) solvable. Returns false if it is still singular.
bool solve(std::vector<double> a, std::vector<double> b, int m, std::vector<double>& x) {
  double trace = 0;
  for (int i = 0; i < m; ++i) trace += a[static_cast<size_t>(i * m + i)];
  const double ridge = 1e-9 * (trace > 0 ? trace / m : 1.0);
  for (int i = 0; i < m; ++i) a[static_cast<size_t>(i * m + i)] += ridge;
  for (int c = 0; c < m; ++c) {
    int p = c;
    for (int r = c + 1; r < m; ++r)
      if (std::fabs(a[static_cast<size_t>(r * m + c)]) > std::fabs(a[static_cast<size_t>(p * m + c)])) p = r;
    if (std::fabs(a[static_cast<size_t>(p * m + c)]) < 1e-300) return false;
    if (p != c) {
      for (int k = 0; k < m; ++k) std::swap(a[static_cast<size_t>(c * m + k)], a[static_cast<size_t>(p * m + k)]);
      std::swap(b[static_cast<size_t>(c)], b[static_cast<size_t>(p)]);
    }
    for (int r = c + 1; r < m; ++r) {
      const double f = a[static_cast<size_t>(r * m + c)] / a[static_cast<size_t>(c * m + c)];
      if (f == 0) continue;
      for (int k = c; k < m; ++k) a[static_cast<size_t>(r * m + k)] -= f * a[static_cast<size_t>(c * m + k)];
      b[static_cast<size_t>(r)] -= f * b[static_cast<size_t>(c)];
    }
  }
  x.assign(static_cast<size_t>(m), 0);
  for (int r = m - 1; r >= 0; --r) {
    double s = b[static_cast<size_t>(r)];
    for (int k = r + 1; k < m; ++k) s -= a[static_cast<size_t>(r * m + k)] * x[static_cast<size_t>(k)];
    x[static_cast<size_t>(r)] = s / a[static_cast<size_t>(r * m + r)];
  }
  return true;
}

// Weights (in 1/256, summing to 256) of set s fitted to its samples; false if the system is singular.
bool fit_set(const std::vector<const LpSample*>& rows, int s, const LpTable& table,
             std::array<int32_t, kLpMaxTaps>& w) {
  const int n = table.taps[s];
  const int m = n - 1;
  const auto& tap = table.tap[s];
  if (m == 0) {
    w.fill(0);
    w[0] = kLpOne;
    return true;
  }
  // y - x0 = sum_{t>=1} c_t (x_t - x0), c_0 = 1 - sum c_t.
  std::vector<double> c(static_cast<size_t>(m), 0.0), row(static_cast<size_t>(m));
  std::vector<double> ata, atb;
  for (int iteration = 0; iteration < 7; ++iteration) {
    ata.assign(static_cast<size_t>(m * m), 0.0);
    atb.assign(static_cast<size_t>(m), 0.0);
    for (const LpSample* r : rows) {
      const double x0 = static_cast<double>(r->tap[static_cast<size_t>(tap[0])]);
      const double y = static_cast<double>(r->h) - x0;
      double pred = 0;
      for (int k = 0; k < m; ++k) {
        row[static_cast<size_t>(k)] = static_cast<double>(r->tap[static_cast<size_t>(tap[k + 1])]) - x0;
        pred += c[static_cast<size_t>(k)] * row[static_cast<size_t>(k)];
      }
      // Iteration 0 is least squares; then weights 1 / |residual| (floored at 0.5) make it least absolute deviations.
      const double weight = iteration == 0 ? 1.0 : 1.0 / std::max(std::fabs(y - pred), 0.5);
      for (int a = 0; a < m; ++a) {
        const double wa = weight * row[static_cast<size_t>(a)];
        atb[static_cast<size_t>(a)] += wa * y;
        for (int b = a; b < m; ++b) ata[static_cast<size_t>(a * m + b)] += wa * row[static_cast<size_t>(b)];
      }
    }
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < a; ++b) ata[static_cast<size_t>(a * m + b)] = ata[static_cast<size_t>(b * m + a)];
    std::vector<double> next;
    if (!solve(ata, atb, m, next)) return iteration > 0;
    c = next;
  }
  const int64_t limit = (int64_t{1} << (kLpMaxWeightClass + 1)) - 1;
  int64_t rest = 0;
  w.fill(0);
  for (int k = 0; k < m; ++k) {
    double q = std::round(c[static_cast<size_t>(k)] * kLpOne);
    if (!(q > -static_cast<double>(limit))) q = -static_cast<double>(limit);  // also NaN
    if (q > static_cast<double>(limit)) q = static_cast<double>(limit);
    w[static_cast<size_t>(k + 1)] = static_cast<int32_t>(q);
    rest += w[static_cast<size_t>(k + 1)];
  }
  w[0] = static_cast<int32_t>(kLpOne - rest);
  return true;
}

}  // namespace

void fit_lp_table(const std::vector<LpSample>& samples, LpTable& table, std::array<bool, kLpSets>& fitted) {
  table.enabled.fill(true);
  fitted.fill(false);
  for (int s = 0; s < kLpSets; ++s) table.set_defaults(s);
  // Disable the sets too few samples would select, until the selection is stable (disabling a set only moves its
  // samples to later sets). The rounds look up only the masks the samples have (each with its sample count), not
  // the whole selection table, which the last build below makes once.
  std::vector<std::pair<uint32_t, size_t>> masks;  // (mask, samples with it)
  {
    std::vector<size_t> per_mask(size_t{1} << kLpOffsets, 0);
    for (const LpSample& smp : samples) ++per_mask[smp.mask];
    for (uint32_t m = 0; m < per_mask.size(); ++m)
      if (per_mask[m] != 0) masks.push_back({m, per_mask[m]});
  }
  // The first enabled set inside `mask`, as LpTable::select gives it (kLpNoSet if none).
  const auto first_enabled = [&table](uint32_t mask) {
    for (int s = 0; s < kLpSets; ++s)
      if (table.enabled[s] && (kLpSetMask[s] & ~mask) == 0) return s;
    return int{kLpNoSet};
  };
  std::array<size_t, kLpSets> count{};
  for (int round = 0; round <= kLpSets; ++round) {
    count.fill(0);
    for (const auto& [mask, n] : masks) {
      const int s = first_enabled(mask);
      if (s != kLpNoSet) count[static_cast<size_t>(s)] += n;
    }
    bool changed = false;
    for (int s = 0; s < kLpSets; ++s) {
      if (!table.enabled[s]) continue;
      const bool enough = count[static_cast<size_t>(s)] >= size_t{kLpMinSamplesPerTap} * static_cast<size_t>(table.taps[s]);
      if (count[static_cast<size_t>(s)] == 0 || (s < kLpFirstDefault && !enough)) {
        table.enabled[s] = false;
        changed = true;
      }
    }
    if (!changed) break;
  }
  // Each sample's row is the first enabled set inside its mask, looked up for the masks the samples have only; the
  // whole selection table is built once, at the end, after the fits have settled which sets stay enabled.
  std::vector<uint8_t> set_of_mask(size_t{1} << kLpOffsets, kLpNoSet);
  for (const auto& mn : masks) set_of_mask[mn.first] = static_cast<uint8_t>(first_enabled(mn.first));
  std::vector<std::vector<const LpSample*>> rows(kLpSets);
  for (const LpSample& smp : samples) {
    const int s = set_of_mask[smp.mask];
    if (s != kLpNoSet) rows[static_cast<size_t>(s)].push_back(&smp);
  }
  for (int s = 0; s < kLpSets; ++s) {
    if (!table.enabled[s]) continue;
    const auto& r = rows[static_cast<size_t>(s)];
    if (r.size() < size_t{kLpMinSamplesPerTap} * static_cast<size_t>(table.taps[s])) continue;
    std::array<int32_t, kLpMaxTaps> w;
    if (fit_set(r, s, table, w)) {
      table.weight[s] = w;
      fitted[static_cast<size_t>(s)] = true;
    } else if (s < kLpFirstDefault) {
      table.enabled[s] = false;
    }
  }
  table.build_selection();
}

}  // namespace prm::codec
