// The heights' guard of --local-refinement (pack.cpp finish_at, h22max6): the encoder's rate-distortion heights are
// chosen for the RMS target only, and may undo the refinement's worst case (venus: 1.37e-3 of the diagonal with
// rounded heights, 1.65e-3 decoded). When the chosen stream's max passes the aim, smaller lambdas are tried.
#pragma once

namespace prm::pipeline {

// Lambdas tried below the chosen one before the rounded heights (h22max6: uncapped, up to 16 tries, about 4 s CPU on
// the horse when none met the aim).
constexpr int kHeightGuardTries = 4;
// The guard is skipped when the rounded heights' max, the search's sparser estimate, passes the aim by more than
// this factor (they are the guard's last try, so nothing could help); within it, they are measured at full density
// first. That estimate can be over the full-density max: the camel's rounded heights, 1.69e-3 of the diagonal
// sparse, 1.50e-3 at full density (8x: 1.6e-3; hrefine3).
constexpr double kHeightGuardSparseMargin = 1.1;
// height_guard_choice: no lambda met both.
constexpr int kHeightGuardNone = -2;

// k: the chosen lambda's index in kHeightLambdas. try_lambda(j) encodes with lambda j (-1: the rounded heights),
// measures, and returns true (keeping that stream) when it meets both the RMS target and the aim. Tries j = k - 1
// down, at most kHeightGuardTries of them, then -1; returns the first j that meets, or kHeightGuardNone (the caller's
// stream stays as it was).
template <class Try>
int height_guard_choice(int k, Try&& try_lambda) {
  for (int j = k - 1, tries = 0; j >= 0 && tries < kHeightGuardTries; --j, ++tries)
    if (try_lambda(j)) return j;
  return try_lambda(-1) ? -1 : kHeightGuardNone;
}

}  // namespace prm::pipeline
