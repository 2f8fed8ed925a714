// §6.5 CLERS symbols, their binarization and the context function: one copy, used by the Edgebreaker encoder
// (clers_encode.cpp) and the Spirale Reversi decoder (clers_decode.cpp).
#pragma once

#include <cstdint>

#include "adaptive_model.h"

namespace prm::codec {

// §6.2 Symbol values (also their order in Prev1/Prev2).
enum Clers : uint8_t { kC = 0, kL = 1, kE = 2, kR = 3, kS = 4 };
constexpr int kNumClers = 5;

inline char clers_char(uint8_t s) { return "CLERS"[s < 5 ? s : 0]; }

// §6.5.2 Context: the two previous symbols in decoding order (Prev1, Prev2; E before the first), the number of
// triangles of the decoded part around the start vertex of the top piece's gate, capped at kCountCap (Count), and,
// with the seam context (Flags bit 2, format 1.3), whether a closed vertex of that vertex's decoded fan has a valence
// other than 6 (Seam; 0 without the flag):
//     Ctx = ((Prev1 * 5 + Prev2) * (kCountCap + 1) + min(Count, kCountCap)) * 2 + Seam
constexpr uint32_t kCountCap = 7;
constexpr uint32_t kNumClersContexts = kNumClers * kNumClers * (kCountCap + 1) * 2;
// §6.5.2 The seam walk visits at most this many triangles on each side of the top piece's triangle.
constexpr uint32_t kSeamWalk = 8;

inline uint32_t clers_context(uint32_t prev1, uint32_t prev2, uint32_t gate_start_count, uint32_t seam) {
  const uint32_t c = gate_start_count < kCountCap ? gate_start_count : kCountCap;
  return ((prev1 * kNumClers + prev2) * (kCountCap + 1) + c) * 2 + seam;
}

// §6.5.1 Binarization: four binary decisions, each with its own model per context.
//   d0: C (0) or not (1);  d1: R (0) or not;  d2: S (0) or not (skipped when fewer than two pieces);  d3: L (0) or E (1)
struct ClersModels {
  BitModel m[kNumClersContexts][4];
};

}  // namespace prm::codec
