// Byte-level reading of a stream (§1.3): little-endian integers, LEB128 varints, IEEE doubles.
//
// Sticky error (dav1d/libjxl style): a read past the end returns 0 and marks the reader failed; later reads keep
// returning 0. Callers check failed() once per field group or per loop iteration, and end every section with
// finish(), which also rejects unread bytes (§3.4).
#pragma once

#include <cstddef>
#include <cstdint>

#include "prm/codec.h"

namespace prm::codec {

class StreamReader {
 public:
  // `base_offset` is the absolute stream offset of data[0], so that errors report stream offsets.
  StreamReader(const uint8_t* data, size_t size, uint64_t base_offset = 0)
      : data_(data), size_(size), base_(base_offset) {}

  uint8_t u8() {
    if (pos_ >= size_) return fail(Error::truncated), 0;
    return data_[pos_++];
  }
  uint32_t u32();
  double f64();
  // §1.3 Varint: LEB128, at most 5 bytes, value < 2^32, no redundant trailing zero groups.
  uint32_t varint();
  // Advances over n bytes and returns a pointer to them, or nullptr (and fails) when fewer remain.
  const uint8_t* bytes(size_t n);

  bool failed() const { return error_ != Error::ok; }
  Error error() const { return error_; }
  uint64_t error_offset() const { return error_offset_; }
  uint64_t offset() const { return base_ + pos_; }
  size_t position() const { return pos_; }
  size_t remaining() const { return pos_ <= size_ ? size_ - pos_ : 0; }
  // True when no read failed and every byte was consumed; otherwise fails with trailing_bytes.
  bool finish();

  void fail(Error e) {
    if (error_ == Error::ok) {
      error_ = e;
      error_offset_ = base_ + pos_;
    }
  }

 private:
  const uint8_t* data_;
  size_t size_;
  uint64_t base_;
  size_t pos_ = 0;
  Error error_ = Error::ok;
  uint64_t error_offset_ = 0;
};

}  // namespace prm::codec
