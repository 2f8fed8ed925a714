// §9.7.2 The encoder's predictor table: which tap sets to enable and their weights, fitted to the stream's heights.
// Encoder only (patch_encode.cpp); the decoder reads the table from the stream.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "height_prediction_shared.h"

namespace prm::codec {

// One height to be coded by linear prediction: which of the 14 offsets hold a vertex of its patch (mask), the
// heights there (0 where none) and its own height.
struct LpSample {
  uint32_t mask = 0;
  std::array<int64_t, kLpOffsets> tap{};
  int64_t h = 0;
};

// Fills table.enabled / table.weight (and starts table.select) and `fitted` (the sets whose weights the stream
// carries): a set without default weights is enabled only when at least kLpMinSamplesPerTap samples per tap select
// it; an enabled set with that many samples gets weights fitted by least absolute deviations, the others keep
// their defaults; sets no sample selects are disabled.
constexpr int kLpMinSamplesPerTap = 32;
void fit_lp_table(const std::vector<LpSample>& samples, LpTable& table, std::array<bool, kLpSets>& fitted);

}  // namespace prm::codec
