// The C API (prm/prm.h): what its decoding and encoding halves share. Filling a prm_error from a Status.
#pragma once

#include <algorithm>
#include <cstring>
#include <string>

#include "prm/codec.h"
#include "prm/prm.h"

namespace prm::codec {

inline void copy_truncated(char* dst, size_t capacity, const char* src) {
  const size_t n = std::min(std::strlen(src), capacity - 1);
  std::memcpy(dst, src, n);
  dst[n] = '\0';
}

// §4.4 The error of a call, for the caller (error may be NULL); returns its status.
inline prm_status set_error(prm_error* error, prm_status status, const char* spec_section, uint64_t byte_offset,
                            const char* message) {
  if (error) {
    error->status = status;
    error->name = prm_status_name(status);
    error->byte_offset = byte_offset;
    copy_truncated(error->spec_section, sizeof error->spec_section, spec_section ? spec_section : "");
    copy_truncated(error->message, sizeof error->message, message ? message : "");
  }
  return status;
}

inline prm_status set_error(prm_error* error, const Status& s) {
  return set_error(error, static_cast<prm_status>(s.error), s.spec_section, s.byte_offset, s.message.c_str());
}

inline prm_status set_ok(prm_error* error) { return set_error(error, PRM_OK, "", 0, ""); }

}  // namespace prm::codec
