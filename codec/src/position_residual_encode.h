// §10.4.1 a position residual's encoding, shared by the encoder (position_encode.cpp) and the bench's entropy study
// (bench/entropy_study/today_coding.h), which must code exactly as the format does. The decoder side is
// position_decode.cpp's decode_residual.
#pragma once

#include <cstdint>

#include "position_shared.h"
#include "range_encoder.h"

namespace prm::codec {

// §10.4.1 Residual r of one axis: nothing when the box leaves no room (up + down = 0); otherwise its zigzag value
// u = 2r (r >= 0) or -2r - 1 (r < 0), Rice coded with parameter k: q = u >> k in unary (modelled), then the highest
// of the k low bits (modelled) and the others (direct).
inline void encode_residual(RangeEncoder& rc, ResidualModels& m, int axis, int ctx, int64_t r, int64_t up,
                            int64_t down) {
  if (up + down == 0) return;
  RiceState& rice = m.rice[axis][ctx];
  const int k = rice.k();
  const uint64_t magnitude = static_cast<uint64_t>(r < 0 ? -r : r);
  const uint64_t u = r >= 0 ? 2 * magnitude : 2 * magnitude - 1;
  const uint64_t q = u >> k;
  BitModel* unary = m.unary[axis][ctx];
  const uint64_t ones = q < kUnaryEscape ? q : kUnaryEscape;
  for (uint64_t i = 0; i < ones; ++i) rc.encode_bit(unary[i < kUnaryModels ? i : kUnaryModels - 1], 1);
  if (q < kUnaryEscape)
    rc.encode_bit(unary[q < kUnaryModels ? q : kUnaryModels - 1], 0);
  else
    rc.encode_direct(static_cast<uint32_t>(q - kUnaryEscape), kEscapeBits);
  if (k > 0) {
    rc.encode_bit(m.low[axis][k][q < 2 ? q : 2], static_cast<int>((u >> (k - 1)) & 1));
    if (k > 1) rc.encode_direct(static_cast<uint32_t>(u), k - 1);
  }
  rice.update(static_cast<uint32_t>(magnitude));
}


}  // namespace prm::codec
