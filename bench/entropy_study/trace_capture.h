// hdecode8's entropy-layer study: the values a real stream's range-coded sections yield, captured from the decoder
// through codec/src/entropy_trace.h. The capture links its own copy of the decoder objects, compiled with
// PRM_ENTROPY_TRACE and in namespace prm_traced (bench/CMakeLists.txt), so nothing here changes the library.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace entropy_study {

// §6.5.1 one CLERS symbol (prm::codec::Clers) with its context; s_possible: the S decision was coded.
struct ClersValue {
  uint32_t ctx;
  uint8_t symbol;
  uint8_t s_possible;
  uint16_t block;
};

// §10.4.1 one position residual; ctx = axis * kResidualContexts + context; up, down: its bounds.
struct ResidualValue {
  uint32_t ctx;
  uint16_t block;
  int64_t r, up, down;
};

// §9.5 one signed integer: model and sign are ids of the SignedIntModel and of the sign model (own_sign: the model's
// own), numbered from 0 in order of first use over the stream (a new range-coded block never reuses a model).
struct SignedValue {
  uint32_t model, sign;
  uint8_t own_sign;
  int8_t max_class;
  uint16_t block;
  int64_t v;
};

struct Capture {
  std::vector<ClersValue> clers;
  std::vector<ResidualValue> residuals;
  std::vector<SignedValue> signed_ints;
  std::vector<size_t> block_sizes;     // bytes of each range-coded block, in decoding order
  uint64_t decisions = 0;              // §5.3 modelled decisions of the whole decode
  uint64_t direct_bits = 0;            // §5.4 direct bits of the whole decode
  std::vector<uint8_t> bits;           // every decision, in decoding order (for the oracle, oracle_decode.h)
  std::vector<uint32_t> directs;       // every decode_direct's value, in decoding order
  std::vector<uint8_t> other_bits;     // the same outside the captured values (for the value oracle)
  std::vector<uint32_t> other_directs;
  std::vector<uint8_t> clers_symbols;  // the captured values alone (for the value oracle)
  std::vector<int64_t> residual_values, signed_values;
  uint32_t signed_models = 0, sign_models = 0;
  size_t vertices = 0, triangles = 0;  // of the decoded mesh
};

// Decodes the stream with the traced decoder; false (and `error`) if it does not decode.
bool capture_stream(const uint8_t* data, size_t size, Capture& out, std::string& error);

}  // namespace entropy_study
