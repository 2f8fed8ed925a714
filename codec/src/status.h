// Building Status values inside the codec, and PRM_TRY (in the spirit of zstd's FORWARD_IF_ERROR).
#pragma once

#include <string>
#include <utility>

#include "prm/codec.h"

namespace prm::codec {

inline Status make_status(Error error, const char* spec_section, uint64_t byte_offset, std::string message) {
  Status s;
  s.error = error;
  s.spec_section = spec_section;
  s.byte_offset = byte_offset;
  s.message = std::move(message);
  return s;
}

inline Status ok_status() { return Status{}; }

}  // namespace prm::codec

#define PRM_TRY(expr)                          \
  do {                                         \
    ::prm::codec::Status prm_try_s_ = (expr);  \
    if (!prm_try_s_.ok()) return prm_try_s_;   \
  } while (0)
