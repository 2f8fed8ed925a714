// §5 The range decoder: LZMA-style binary arithmetic decoding with 32-bit range and code, adaptive bit models
// (adaptive_model.h) and equiprobable "direct" bits.
//
// Reads past the end of the data return 0 and make failed() true (sticky); decoding loops check failed() once per
// symbol, so zero-filled reads can never spin. finish() also rejects unread bytes (§5.6).
#pragma once

#include <cstddef>
#include <cstdint>

#include "adaptive_model.h"
#include "always_inline.h"
#include "entropy_trace.h"

namespace prm::codec {

class RangeDecoder {
 public:
  // §5.6 Initialisation: Range = 0xFFFFFFFF, Code = the first 4 bytes, big-endian. Code = 0xFFFFFFFF is invalid
  // (bad_section): the decoder is then failed() from the start and bad_start() is true.
  void init(const uint8_t* data, size_t size);

  // §5.3 One bit with model m.
  PRM_ALWAYS_INLINE int decode_bit(BitModel& m) {
    PRM_ENTROPY_ORACLE_BIT();
    // Written without data-dependent branches: the bit is as unpredictable as the data.
    const uint32_t p = m.p;
    const uint32_t bound = (range_ >> kProbBits) * p;
    const uint32_t bit = code_ >= bound ? 1u : 0u;
    const uint32_t mask = 0u - bit;
    code_ -= bound & mask;
    range_ = bit ? range_ - bound : bound;
    m.update(bit);
    normalize();
    PRM_ENTROPY_TRACE_CALL(bit(bit));
    return static_cast<int>(bit);
  }

  // §5.4 `count` (0..24) equiprobable bits, most significant first.
  PRM_ALWAYS_INLINE uint32_t decode_direct(int count) {
    PRM_ENTROPY_ORACLE_DIRECT();
    uint32_t v = 0;
    for (int i = 0; i < count; ++i) {
      range_ >>= 1;
      uint32_t bit = code_ >= range_ ? 1u : 0u;
      code_ -= range_ & (0u - bit);
      v = v << 1 | bit;
      normalize();
    }
    PRM_ENTROPY_TRACE_CALL(direct(count, v));
    return v;
  }

  bool failed() const { return failed_; }
  // §5.6 True when the block starts with FF FF FF FF (bad_section, not truncated).
  bool bad_start() const { return bad_start_; }
  // Bytes consumed so far (including the 4 of the initialisation).
  size_t consumed() const { return pos_; }
  // §5.6 True when nothing failed and every byte was consumed.
  bool finish() const { return !failed_ && pos_ == size_; }

 private:
  // §5.5 Renormalisation.
  PRM_ALWAYS_INLINE void normalize() {
    // After one decision Range >= 2^24 / 2^16 * kProbMin > 2^14, so at most two bytes are needed.
    if (range_ < (1u << 24)) {
      range_ <<= 8;
      code_ = code_ << 8 | next_byte();
      if (range_ < (1u << 24)) {
        range_ <<= 8;
        code_ = code_ << 8 | next_byte();
      }
    }
  }
  uint32_t next_byte() {
    if (pos_ < size_) return data_[pos_++];
    failed_ = true;
    return 0;
  }

  // §5.1 Decoder state.
  const uint8_t* data_ = nullptr;
  size_t size_ = 0;
  size_t pos_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint32_t code_ = 0;
  bool failed_ = false;
  bool bad_start_ = false;
};

}  // namespace prm::codec
