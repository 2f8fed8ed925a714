// The oracle's side of codec/src/entropy_trace.h (compiled with PRM_ENTROPY_ORACLE, namespace prm read prm_oracle).
#include "oracle_decode.h"

#include "entropy_trace.h"
#include "prm/codec.h"

namespace prm::codec::entropy_trace {
const uint8_t* oracle_bits = nullptr;
const uint32_t* oracle_direct = nullptr;
}  // namespace prm::codec::entropy_trace

namespace entropy_study {

bool oracle_decode(const uint8_t* data, size_t size, const Capture& capture, std::vector<float>& positions,
                   std::vector<uint32_t>& triangles) {
  prm::codec::entropy_trace::oracle_bits = capture.bits.data();
  prm::codec::entropy_trace::oracle_direct = capture.directs.data();
  auto decoded = prm::codec::decode(data, size);
  const bool all_used = prm::codec::entropy_trace::oracle_bits == capture.bits.data() + capture.bits.size() &&
                        prm::codec::entropy_trace::oracle_direct == capture.directs.data() + capture.directs.size();
  if (!decoded.ok() || !all_used) return false;
  positions = std::move(decoded.value.positions_f32);
  triangles = std::move(decoded.value.triangles);
  return true;
}

}  // namespace entropy_study
