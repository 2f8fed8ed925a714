// §5.7 The range encoder, the exact mirror of RangeDecoder (range_decoder.h): 64-bit Low with LZMA's carry
// handling (a cached byte plus a run of 0xFF bytes), whose first output byte (always 0) is not written.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "adaptive_model.h"

namespace prm::codec {

class RangeEncoder {
 public:
  void encode_bit(BitModel& m, int bit) {
    const uint32_t bound = (range_ >> kProbBits) * m.p;
    if (bit == 0) {
      range_ = bound;
    } else {
      low_ += bound;
      range_ -= bound;
    }
    m.update(static_cast<uint32_t>(bit));
    while (range_ < (1u << 24)) {
      range_ <<= 8;
      shift_low();
    }
  }

  // §5.4 The low `count` bits of v (0..24 bits), most significant first.
  void encode_direct(uint32_t v, int count) {
    for (int i = count - 1; i >= 0; --i) {
      range_ >>= 1;
      if ((v >> i) & 1) low_ += range_;
      while (range_ < (1u << 24)) {
        range_ <<= 8;
        shift_low();
      }
    }
  }

  // The information coded so far, in bits (an encoder statistic, not part of the format): 8 per byte shifted out
  // of Low (the held-back cache byte and pending 0xFF bytes included, the skipped first byte not) plus what the
  // range has shrunk by since its last byte, 32 - log2(Range). finish() adds 24..32 bits to it (§5.6).
  double bits() const {
    const uint64_t shifted = out_.size() + cache_size_ - (skip_first_ ? 1 : 0);
    return 8.0 * static_cast<double>(shifted) + 32.0 - std::log2(static_cast<double>(range_));
  }

  // §5.6 Termination: flushes Low; the returned bytes are the complete coded data.
  std::vector<uint8_t> finish();

 private:
  void shift_low();
  void emit(uint8_t b) {
    if (skip_first_) {
      skip_first_ = false;  // always 0: Low + Range never exceeds 2^32 - 1 (§5.6)
      return;
    }
    out_.push_back(b);
  }

  uint64_t low_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint8_t cache_ = 0;
  uint64_t cache_size_ = 1;
  bool skip_first_ = true;
  std::vector<uint8_t> out_;
};

}  // namespace prm::codec
