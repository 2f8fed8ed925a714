// The oracles' side of codec/src/entropy_trace.h, compiled three times: with PRM_ENTROPY_ORACLE (namespace prm read
// prm_oracle; oracle_decode), with PRM_ENTROPY_VALUE_ORACLE as well (prm_values; value_oracle_decode) and with
// PRM_ENTROPY_RANS on top (prm_rans; rans_in_situ_decode).
#include "oracle_decode.h"

#include "entropy_trace.h"
#include "prm/codec.h"

namespace prm::codec::entropy_trace {
const uint8_t* oracle_bits = nullptr;
const uint32_t* oracle_direct = nullptr;
const uint8_t* oracle_clers = nullptr;
const int64_t* oracle_residual = nullptr;
const int64_t* oracle_signed = nullptr;
}  // namespace prm::codec::entropy_trace

namespace entropy_study {

#if defined(PRM_ENTROPY_RANS)
namespace in_situ {
State g;
}
bool rans_in_situ_decode(const uint8_t* data, size_t size, const Capture& capture, const in_situ::Input& input,
                         std::vector<float>& positions, std::vector<uint32_t>& triangles) {
  in_situ::reset(input);
  const std::vector<uint8_t>& bits = capture.other_bits;
  const std::vector<uint32_t>& directs = capture.other_directs;
#elif defined(PRM_ENTROPY_VALUE_ORACLE)
bool value_oracle_decode(const uint8_t* data, size_t size, const Capture& capture, std::vector<float>& positions,
                         std::vector<uint32_t>& triangles) {
  const std::vector<uint8_t>& bits = capture.other_bits;
  const std::vector<uint32_t>& directs = capture.other_directs;
#else
bool oracle_decode(const uint8_t* data, size_t size, const Capture& capture, std::vector<float>& positions,
                   std::vector<uint32_t>& triangles) {
  const std::vector<uint8_t>& bits = capture.bits;
  const std::vector<uint32_t>& directs = capture.directs;
#endif
  namespace t = prm::codec::entropy_trace;
  t::oracle_bits = bits.data();
  t::oracle_direct = directs.data();
  t::oracle_clers = capture.clers_symbols.data();
  t::oracle_residual = capture.residual_values.data();
  t::oracle_signed = capture.signed_values.data();
  auto decoded = prm::codec::decode(data, size);
  bool all_used = t::oracle_bits == bits.data() + bits.size() && t::oracle_direct == directs.data() + directs.size();
#if defined(PRM_ENTROPY_RANS)
  all_used = all_used && in_situ::g.ctx[0] == input.clers.ctx + capture.clers.size() &&
             in_situ::g.ctx[1] == input.residual.ctx + capture.residuals.size() &&
             in_situ::g.ctx[2] == input.signed_int.ctx + capture.signed_ints.size();
#elif defined(PRM_ENTROPY_VALUE_ORACLE)
  all_used = all_used && t::oracle_clers == capture.clers_symbols.data() + capture.clers_symbols.size() &&
             t::oracle_residual == capture.residual_values.data() + capture.residual_values.size() &&
             t::oracle_signed == capture.signed_values.data() + capture.signed_values.size();
#endif
  if (!decoded.ok() || !all_used) return false;
  positions = std::move(decoded.value.positions_f32);
  triangles = std::move(decoded.value.triangles);
  return true;
}

}  // namespace entropy_study
