#include "prm/pipeline/pack_to_bytes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <map>
#include <optional>

#include "prm/remesh/remesh.h"

namespace prm::pipeline {

namespace {

double rung_error(int k) { return std::exp2(static_cast<double>(k) / kBytesLadderSteps); }

}  // namespace

PackToBytesResult pack_to_bytes(const Mesh& input, size_t budget, const PackOptions& options) {
  if (budget == 0) throw std::invalid_argument("--target-bytes must be at least 1");
  if (options.target_error > 0 || options.grid_size > 0 || options.grid_fraction > 0)
    throw std::invalid_argument("--target-bytes searches the target error: no --target-error, --grid or "
                                "--grid-fraction with it");
  const int k_min = static_cast<int>(std::ceil(kBytesLadderSteps * std::log2(kBytesMinError)));
  const int k_max = static_cast<int>(std::floor(kBytesLadderSteps * std::log2(kBytesMaxError)));
  const double log_budget = std::log2(static_cast<double>(budget));

  PackToBytesResult out;
  std::map<int, BytesSearchStep> seen;  // rung -> its pack
  std::optional<int> best;              // the rung of out.result
  auto pack_rung = [&](int k) {
    PackOptions o = options;
    o.target_error = rung_error(k);
    BytesSearchStep step;
    step.target_error = o.target_error;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      PackResult r = pack(input, o);
      step.made = true;
      step.bytes = r.stream.size();
      step.rms = r.remesh.error.rms;
      step.max = r.remesh.error.max;
      if (step.bytes <= budget && (!best || step.rms < seen.at(*best).rms)) {
        out.result = std::move(r);
        out.target_error = o.target_error;
        best = k;
      }
    } catch (const remesh::TargetNotReached&) {
      step.made = false;  // too fine for the remesher (vertex budget) and the general path: more than the budget
    }
    step.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    seen[k] = step;
    out.steps.push_back(step);
  };
  auto fits = [&](int k) { return seen.at(k).made && seen.at(k).bytes <= budget; };
  // The rung where log bytes, linear in the rung through two made points (a and b), meets the budget; nullopt when
  // the bytes do not fall with the error between them.
  auto predict = [&](int a, int b) -> std::optional<double> {
    const double ya = std::log2(static_cast<double>(seen.at(a).bytes));
    const double yb = std::log2(static_cast<double>(seen.at(b).bytes));
    const double slope = (yb - ya) / (b - a);  // per rung
    if (!(slope < 0)) return std::nullopt;
    return a + (log_budget - ya) / slope;
  };
  auto predict_from_one = [&](int a) {
    const double ya = std::log2(static_cast<double>(seen.at(a).bytes));
    return a + (log_budget - ya) / (kBytesFirstSlope / kBytesLadderSteps);
  };

  int k = std::clamp(static_cast<int>(std::lround(kBytesLadderSteps * std::log2(kBytesFirstError))), k_min, k_max);
  // Unbracketed steps in a row: each moves at least 2^(that many - 1) rungs, so that a plateau of the bytes (the
  // general path's bit depths, the remesher's coarsest grid) is crossed in a few packs.
  int unbracketed = 0;
  for (int packs = 0; packs < kBytesMaxPacks; ++packs) {
    pack_rung(k);
    const int stride = 1 << std::min(unbracketed, 6);
    // The bracket: the finest rung that fits and the coarsest finer one that does not.
    std::optional<int> fit, over;
    for (const auto& [r, s] : seen)
      if (fits(r) && !fit) fit = r;
    for (const auto& [r, s] : seen)
      if (!fits(r) && (!fit || r < *fit)) over = r;
    auto made_points = [&](int from, int to) {  // the made rungs in [from, to], in order
      std::vector<int> m;
      for (const auto& [r, s] : seen)
        if (s.made && r >= from && r <= to) m.push_back(r);
      return m;
    };
    std::optional<double> guess;
    int lo = k_min - 1, hi = k_max + 1;  // the next rung lies strictly between
    if (fit && over) {
      if (*fit - *over <= 1) break;
      lo = *over;
      hi = *fit;
      if (seen.at(*over).made) guess = predict(*over, *fit);
      const int w = hi - lo;
      const int margin = std::max(1, w / 4);  // the bracket shrinks by a quarter at least
      const int next = guess ? static_cast<int>(std::lround(*guess)) : (lo + hi) / 2;
      k = std::clamp(next, lo + margin, hi - margin);
      unbracketed = 0;
      continue;
    }
    if (fit) {  // everything fits so far: finer
      if (*fit == k_min) {
        out.finest = true;
        break;
      }
      const std::vector<int> m = made_points(*fit, k_max);
      guess = m.size() >= 2 ? predict(m[0], m[1]) : std::nullopt;
      if (!guess) guess = predict_from_one(*fit);
      // A finer target the finest stream already meets would most likely give that stream again: below its RMS.
      const double rms = seen.at(*fit).rms;
      const int below_rms = rms > 0 ? static_cast<int>(std::floor(kBytesLadderSteps * std::log2(rms))) - 1 : k_min;
      k = std::clamp(std::min({static_cast<int>(std::floor(*guess)), *fit - stride, below_rms}), k_min, *fit - 1);
      ++unbracketed;
      continue;
    }
    // Nothing fits so far: coarser.
    const int coarsest = std::prev(seen.end())->first;
    if (coarsest >= k_max) break;
    const std::vector<int> m = made_points(k_min, k_max);
    if (m.size() >= 2) guess = predict(m[m.size() - 2], m.back());
    if (!guess && m.size() == 1) guess = predict_from_one(m.back());
    // Two made rungs whose bytes do not fall: the coarsest rung decides (the floor of the remesher's coarsest grid).
    if (!guess && m.size() >= 2) guess = k_max;
    k = std::clamp(std::max(guess ? static_cast<int>(std::ceil(*guess)) : coarsest + kBytesLadderSteps, coarsest + stride),
                   coarsest + 1, k_max);
    ++unbracketed;
  }
  if (!best) {
    size_t smallest = 0;
    for (const BytesSearchStep& s : out.steps)
      if (s.made && (smallest == 0 || s.bytes < smallest)) smallest = s.bytes;
    const double coarsest = rung_error(std::prev(seen.end())->first);
    throw BudgetTooSmall("no stream fits " + std::to_string(budget) + " bytes: the smallest made is " +
                             (smallest ? std::to_string(smallest) + " bytes" : std::string("none")) +
                             " (target errors up to " + std::to_string(coarsest) + " of the diagonal, " +
                             std::to_string(out.steps.size()) + " packs)",
                         smallest);
  }
  return out;
}

}  // namespace prm::pipeline
