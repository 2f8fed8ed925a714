#include "stream_reader.h"

#include <cstring>

namespace prm::codec {

uint32_t StreamReader::u32() {
  const uint8_t* p = bytes(4);
  if (!p) return 0;
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

double StreamReader::f64() {
  const uint8_t* p = bytes(8);
  if (!p) return 0.0;
  uint64_t bits = 0;
  for (int i = 7; i >= 0; --i) bits = bits << 8 | p[i];
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

// §1.3: LEB128 with at most 5 bytes; the 5th byte carries bits 28..31 only; a final byte of 0 after the first is a
// redundant encoding and invalid (so every value has exactly one encoding).
uint32_t StreamReader::varint() {
  uint32_t value = 0;
  for (int i = 0; i < 5; ++i) {
    if (failed()) return 0;
    uint8_t b = u8();
    if (failed()) return 0;
    if (i == 4 && (b & 0xF0) != 0) return fail(Error::bad_section), 0;
    if (i > 0 && b == 0) return fail(Error::bad_section), 0;
    value |= uint32_t{b & 0x7Fu} << (7 * i);
    if ((b & 0x80) == 0) return value;
  }
  return value;  // unreachable: the 5th byte has no continuation bit (checked above)
}

const uint8_t* StreamReader::bytes(size_t n) {
  if (failed()) return nullptr;
  if (n > size_ - pos_) {
    fail(Error::truncated);
    return nullptr;
  }
  const uint8_t* p = data_ + pos_;
  pos_ += n;
  return p;
}

bool StreamReader::finish() {
  if (failed()) return false;
  if (pos_ != size_) {
    fail(Error::trailing_bytes);
    return false;
  }
  return true;
}

}  // namespace prm::codec
