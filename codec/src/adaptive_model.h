// §5.2 The adaptive binary model shared by the range encoder and decoder.
//
// P is the probability that the next bit is 0, in units of 2^-16. A model starts at P = 32768 with N = 0
// observations. After coding a bit, with R = min(1 + floor(log2(N + 1)), 7):
//     bit 0: P += (65536 - P) >> R        bit 1: P -= P >> R
// then P is clamped to [kProbMin, 65536 - kProbMin] and N = min(N + 1, 255). The rate starts fast (close to a
// count-based estimate while few bits have been seen) and settles at 7 after 63 bits.
//
// The clamp is the probability floor of §4.2: no bit ever costs less than -log2(1 - kProbMin / 65536) bits, so a
// section of L bytes holds at most kMaxDecisionsPerByte * (L - 3) decisions.
#pragma once

#include <cstdint>

namespace prm::codec {

constexpr uint32_t kProbBits = 16;
constexpr uint32_t kProbOne = 1u << kProbBits;
constexpr uint32_t kProbMin = 64;                     // §4.2 probability floor: 2^-10
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
  uint8_t n = 0;

  void update(int bit) {
    const uint32_t r = kRate[n < kRateSteps ? n : kRateSteps - 1];
    uint32_t q = p;
    if (bit == 0)
      q += (kProbOne - q) >> r;
    else
      q -= q >> r;
    if (q < kProbMin) q = kProbMin;
    if (q > kProbMax) q = kProbMax;
    p = static_cast<uint16_t>(q);
    if (n < 255) ++n;
  }

  // The same update, in a form that compiles to conditional moves.
  void update_branchless(uint32_t bit) {
    const uint32_t r = kRate[n < kRateSteps ? n : kRateSteps - 1];
    const uint32_t q = p;
    const uint32_t up = q + ((kProbOne - q) >> r), down = q - (q >> r);
    uint32_t v = bit ? down : up;
    v = v < kProbMin ? kProbMin : v;
    v = v > kProbMax ? kProbMax : v;
    p = static_cast<uint16_t>(v);
    n = static_cast<uint8_t>(n + (n < 255));
  }
};

}  // namespace prm::codec
