// hdecode8: scheme (b) or (c) inside the real decoder. With PRM_ENTROPY_RANS (and the value oracle's hooks,
// codec/src/entropy_trace.h), the decoder takes each CLERS symbol, position residual and §9.5 integer from a static
// rANS stream (rans_coding.h) instead of today's binarization, the contexts from the capture (already made dense);
// the few other decisions come from the §5 oracle. Compiled in namespace prm_rans (bench/CMakeLists.txt).
#pragma once

#include <cstdint>

#include "rans_coding.h"

namespace entropy_study::in_situ {

// One kind's rANS stream, raw bits, tables and per-value dense contexts.
struct KindStream {
  const uint16_t* words = nullptr;
  size_t num_words = 0;
  const uint8_t* raw = nullptr;
  size_t raw_bytes = 0;
  const StaticTables* tables = nullptr;
  const uint32_t* ctx = nullptr;       // per value
  const StaticTables* signs = nullptr;  // signed integers: the sign's tables and per nonzero value context
  const uint32_t* sign_ctx = nullptr;
};
struct Input {
  KindStream clers, residual, signed_int;
};

struct State {
  RansDecoder rans[3];
  BitReader raw[3];
  const uint32_t* ctx[3];
  const uint32_t* sign_ctx;
  const StaticTables* tables[3];
  const StaticTables* signs;
  uint32_t lane[3];
};
extern State g;

inline void reset(const Input& in) {
  const KindStream* k[3] = {&in.clers, &in.residual, &in.signed_int};
  for (int i = 0; i < 3; ++i) {
    g.rans[i].reset(k[i]->words, k[i]->num_words);
    g.raw[i].reset(k[i]->raw, k[i]->raw_bytes);
    g.ctx[i] = k[i]->ctx;
    g.tables[i] = k[i]->tables;
    g.lane[i] = 0;
  }
  g.sign_ctx = in.signed_int.sign_ctx;
  g.signs = in.signed_int.signs;
}

inline uint32_t next_symbol(int kind) {
  const uint32_t d = *g.ctx[kind]++;
  const uint32_t s = g.rans[kind].get(g.lane[kind], g.tables[kind]->freq_table(d), g.tables[kind]->slot_table(d));
  g.lane[kind] ^= 1;
  return s;
}

inline uint8_t next_clers() { return static_cast<uint8_t>(next_symbol(0)); }

inline int64_t next_residual() {
  const uint64_t u = token_magnitude(next_symbol(1), g.raw[1]);
  const int64_t magnitude = static_cast<int64_t>((u + 1) >> 1);
  return (u & 1) ? -magnitude : magnitude;
}

inline int64_t next_signed() {
  const uint64_t m = token_magnitude(next_symbol(2), g.raw[2]);
  if (m == 0) return 0;
  const uint32_t e = *g.sign_ctx++;
  const uint32_t negative = g.rans[2].get(g.lane[2], g.signs->freq_table(e), g.signs->slot_table(e));
  g.lane[2] ^= 1;
  return negative ? -static_cast<int64_t>(m) : static_cast<int64_t>(m);
}

}  // namespace entropy_study::in_situ
