// `prm pack --target-bytes N` (issue 23): the largest quality whose stream fits a byte budget. pack() meets an RMS
// target; this searches the target over a ladder of errors (kBytesLadderSteps per octave) until two neighbouring rungs
// bracket the budget, and keeps the lowest-RMS stream of at most N bytes among every rung it packed.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "prm/mesh.h"
#include "prm/pipeline/pack.h"

namespace prm::pipeline {

// The target errors tried are 2^(k / kBytesLadderSteps), k an integer, within [kBytesMinError, kBytesMaxError]
// (the range `prm pack --target-error` accepts). A rung is about 4.4% of the error, so about 4-5% of the bytes, from
// the next: the stream kept is within about that of the budget where the bytes follow the error.
constexpr int kBytesLadderSteps = 16;
constexpr double kBytesMinError = 1e-7;
constexpr double kBytesMaxError = 0.1;
// The first rung: this error (the middle of the range of issue 23's targets, 5e-5..5e-4), then the rung the last
// points predict (log bytes linear in log error; with one point, bytes ~ 1 / error: bench/README.md "Rate-distortion
// curves", the slope is 0.9-1.3 between 5e-5 and 5e-4 on the paper's models).
constexpr double kBytesFirstError = 2e-4;
constexpr double kBytesFirstSlope = -1.0;
// A guard: at most this many packs (the bracketing needs about log2 of the rungs between the first guess and the
// answer; 8 octaves of error are 128 rungs, 7 bisections).
constexpr int kBytesMaxPacks = 14;

// Even the coarsest stream (the pack at kBytesMaxError, where the remesher's coarsest grid sets a floor on the
// bytes) is larger than the budget.
class BudgetTooSmall : public std::runtime_error {
 public:
  BudgetTooSmall(const std::string& what, size_t smallest) : std::runtime_error(what), smallest_bytes(smallest) {}
  size_t smallest_bytes;  // the smallest stream the search made (0: none could be made)
};

struct BytesSearchStep {
  double target_error = 0;  // the rung's PackOptions::target_error
  bool made = false;        // false: no stream met that error (remesh::TargetNotReached), counted as too large
  size_t bytes = 0;
  double rms = 0, max = 0;  // of the decoded stream, fractions of the diagonal
  double seconds = 0;       // wall-clock seconds of the pack
};

struct PackToBytesResult {
  PackResult result;         // the stream kept: at most `budget` bytes, the lowest RMS of the rungs packed
  double target_error = 0;   // the rung it was packed at
  std::vector<BytesSearchStep> steps;  // every rung packed, in order
  bool finest = false;       // the budget holds even the finest rung tried (kBytesMinError or the vertex budget)
};

// options.target_error and the grid options must be 0 (the search sets the target error); everything else (mode,
// effort, adaptive, max_error, ...) applies to every pack. Throws BudgetTooSmall, std::invalid_argument (budget 0
// or a grid given), and what pack() throws other than remesh::TargetNotReached (a rung that cannot be met counts as
// larger than the budget).
PackToBytesResult pack_to_bytes(const Mesh& input, size_t budget, const PackOptions& options);

}  // namespace prm::pipeline
