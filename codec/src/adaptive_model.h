// §5.2 The adaptive binary model shared by the range encoder and decoder.
//
// P is the probability that the next bit is 0, in units of 2^-16. A model starts at P = 32768 with N = 0
// observations. After coding a bit, with R = min(1 + floor(log2(N + 1)), 7):
//     bit 0: P += (65536 - P) >> R        bit 1: P -= P >> R
// and N = min(N + 1, 63). The rate starts fast (close to a count-based estimate while few bits have been seen) and
// settles at 7 after 63 bits.
//
// §4.2 probability floor: from the initial state this update only reaches P in [kProbMin, kProbMax] = [127, 65409]
// (all 2,622,375 reachable (P, N) states were enumerated; test RangeCoder.ProbabilityFloor), so no decision costs
// less than -log2(65409 / 65536) bits and a block of L bytes holds at most kMaxDecisionsPerByte * (L - 3) decisions.
#pragma once

#include <cstdint>

namespace prm::codec {

constexpr uint32_t kProbBits = 16;
constexpr uint32_t kProbOne = 1u << kProbBits;
constexpr uint32_t kProbMin = 127;  // §4.2 the probability floor (reached, never crossed)
constexpr uint32_t kProbMax = kProbOne - kProbMin;
constexpr uint32_t kProbInit = kProbOne / 2;

// §5.2 Adaptation rate by observation count N: min(1 + floor(log2(N + 1)), kMaxRate), tabulated up to N = 63.
constexpr int kMaxRate = 7;
constexpr int kRateSteps = 64;
constexpr uint8_t kRate[kRateSteps] = {1, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 5, 5, 5, 5,
                                       5, 5, 5, 5, 5, 5, 5, 5, 5, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6,
                                       6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 6, 7};

struct BitModel {
  uint16_t p = kProbInit;
  uint16_t n = 0;  // not a char type: a char store may alias the coder state and force reloads

#if defined(__GNUC__) || defined(__clang__)
  __attribute__((always_inline))
#endif
  inline void update(uint32_t bit) {
    const uint32_t r = kRate[n];
    const uint32_t q = p;
    // Written with conditional moves: the bit is as unpredictable as the data.
    const uint32_t up = q + ((kProbOne - q) >> r), down = q - (q >> r);
    p = static_cast<uint16_t>(bit ? down : up);
    n = static_cast<uint16_t>(n + (n < kRateSteps - 1));
  }
};

}  // namespace prm::codec
