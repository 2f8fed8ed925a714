// §9.5 Signed integers with adaptive models (an adaptive Exp-Golomb binarization), shared by the encoder and the
// decoder of the PRM sections: patch headers (§8), heights (§9) and LERS gaps (§7).
//
// v = 0: one modelled bit "zero" = 1. Otherwise "zero" = 0, a modelled sign bit (1 = negative), then the class
// e = floor(log2 |v|) in unary with modelled bits cls[0..e] (e ones then a zero; no zero after kMaxClass ones), then
// the e low bits of |v| below its leading one: the highest one modelled (mant[e]), the others direct.
#pragma once

#include <cmath>
#include <cstdint>

#include "adaptive_model.h"
#include "entropy_trace.h"
#include "range_decoder.h"
#include "range_encoder.h"

namespace prm::codec {

constexpr int kMaxClass = 40;  // |v| < 2^41

struct SignedIntModel {
  BitModel zero;
  BitModel sign;
  BitModel cls[kMaxClass + 1];
  BitModel mant[kMaxClass + 1];
};

inline int int_class(uint64_t m) {
#if defined(__GNUC__) || defined(__clang__)
  return 63 - __builtin_clzll(m);
#else
  int e = -1;
  while (m) {
    ++e;
    m >>= 1;
  }
  return e;
#endif
}

// |v| < 2^(kMaxClass + 1) is the caller's promise. `sign`: the model of the sign bit (m.sign unless a context
// chooses another, §9.7.4).
inline void encode_signed(RangeEncoder& rc, SignedIntModel& m, int64_t v, BitModel& sign) {
  rc.encode_bit(m.zero, v == 0);
  if (v == 0) return;
  rc.encode_bit(sign, v < 0);
  const uint64_t mag = static_cast<uint64_t>(v < 0 ? -v : v);
  const int e = int_class(mag);
  for (int i = 0; i < e; ++i) rc.encode_bit(m.cls[i], 1);
  if (e < kMaxClass) rc.encode_bit(m.cls[e], 0);
  if (e > 0) {
    rc.encode_bit(m.mant[e], static_cast<int>((mag >> (e - 1)) & 1));
    for (int done = 0, rest = e - 1; rest > 0; rest -= done) {  // direct bits, at most 24 at a time
      done = rest > 24 ? 24 : rest;
      rc.encode_direct(static_cast<uint32_t>((mag >> (rest - done)) & ((1u << done) - 1)), done);
    }
  }
}

inline void encode_signed(RangeEncoder& rc, SignedIntModel& m, int64_t v) { encode_signed(rc, m, v, m.sign); }

// The encoder's estimate of what encode_signed(v) costs now, in bits (-log2 of each modelled decision's probability,
// one bit per direct bit); the models are not changed.
inline double bit_cost(const BitModel& b, int one) {
  const double p0 = static_cast<double>(b.p) / kProbOne;
  return -std::log2(one ? 1.0 - p0 : p0);
}

inline double signed_cost_bits(const SignedIntModel& m, int64_t v, const BitModel& sign) {
  const auto bit = bit_cost;
  double bits = bit(m.zero, v == 0);
  if (v == 0) return bits;
  bits += bit(sign, v < 0);
  const uint64_t mag = static_cast<uint64_t>(v < 0 ? -v : v);
  const int e = int_class(mag);
  for (int i = 0; i < e; ++i) bits += bit(m.cls[i], 1);
  if (e < kMaxClass) bits += bit(m.cls[e], 0);
  if (e > 0) bits += bit(m.mant[e], static_cast<int>((mag >> (e - 1)) & 1)) + (e - 1);
  return bits;
}

inline double signed_cost_bits(const SignedIntModel& m, int64_t v) { return signed_cost_bits(m, v, m.sign); }

// Returns false (and leaves v = 0) when the class exceeds max_class: the caller's bound on the magnitude.
PRM_WASM_INLINE bool decode_signed(RangeDecoder& rc, SignedIntModel& m, int max_class, int64_t& v, BitModel& sign) {
  v = 0;
  PRM_ENTROPY_TRACE_CALL(value_begin());
  PRM_ENTROPY_RETURN_VALUE(signed, v);
  if (rc.decode_bit(m.zero)) {
    PRM_ENTROPY_TRACE_CALL(signed_int(&m, &sign, max_class, 0));
    return true;
  }
  const bool negative = rc.decode_bit(sign) != 0;
  int e = 0;
  while (e < kMaxClass && rc.decode_bit(m.cls[e])) ++e;
  if (e > max_class) return false;
  uint64_t mag = 1;
  if (e > 0) {
    mag = mag << 1 | static_cast<uint64_t>(rc.decode_bit(m.mant[e]));
    for (int done = 0, rest = e - 1; rest > 0; rest -= done) {
      done = rest > 24 ? 24 : rest;
      mag = mag << done | rc.decode_direct(done);
    }
  }
  v = negative ? -static_cast<int64_t>(mag) : static_cast<int64_t>(mag);
  PRM_ENTROPY_TRACE_CALL(signed_int(&m, &sign, max_class, v));
  return true;
}

inline bool decode_signed(RangeDecoder& rc, SignedIntModel& m, int max_class, int64_t& v) {
  return decode_signed(rc, m, max_class, v, m.sign);
}

}  // namespace prm::codec
