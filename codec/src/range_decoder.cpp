#include "range_decoder.h"

namespace prm::codec {

// §5.6 Initialisation.
void RangeDecoder::init(const uint8_t* data, size_t size) {
  data_ = data;
  size_ = size;
  pos_ = 0;
  range_ = 0xFFFFFFFFu;
  code_ = 0;
  failed_ = false;
  bad_start_ = false;
  for (int i = 0; i < 4; ++i) code_ = code_ << 8 | next_byte();
  // A valid encoder's first four bytes are below 0xFFFFFFFF (§5.6), so Code < Range holds from the start; a block
  // that starts with FF FF FF FF is bad_section (it fails like a read past the end, and bad_start() tells which).
  if (code_ == 0xFFFFFFFFu) failed_ = bad_start_ = true;
  PRM_ENTROPY_TRACE_CALL(block(size));
#if defined(PRM_ENTROPY_ORACLE)
  pos_ = size_;  // the oracle reads nothing: finish() holds, failed() never turns true
  failed_ = bad_start_ = false;
#endif
}

}  // namespace prm::codec
