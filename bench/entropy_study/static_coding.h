// hdecode8's schemes (b) and (c): the captured values coded with rans_coding.h's static tables, one rANS symbol per
// value (plus one for a signed integer's sign) instead of today's ~2-20 binary decisions, the low bits raw.
//   CLERS:     the symbol itself (5 letters);
//   residuals: the token of today's zigzag u (2|r| - (r < 0)), the rest raw;
//   signed:    the token of |v| in the model's context, then the sign (2 letters) in the sign model's context.
// Scheme (b) keeps today's contexts; scheme (c) pools them (CLERS by Prev1 only, residuals over the three axes) to
// show what the per-stream tables cost.
#pragma once

#include <cstdint>
#include <vector>

#include "clers_shared.h"
#include "position_shared.h"
#include "rans_coding.h"
#include "trace_capture.h"

namespace entropy_study {

enum class Contexts { today, pooled };

struct StaticStream {
  std::vector<uint16_t> words;  // rANS
  std::vector<uint8_t> raw;     // raw bits
  size_t table_bytes = 0;
  size_t bytes() const { return 2 * words.size() + raw.size() + table_bytes; }
};

inline uint32_t clers_context(const ClersValue& c, Contexts k) {
  using namespace prm::codec;
  const uint32_t prev1 = c.ctx / (kNumClers * (kCountCap + 1) * 2);
  return (k == Contexts::today ? c.ctx : prev1) * 2 + c.s_possible;
}
inline uint32_t residual_context(const ResidualValue& v, Contexts k) {
  return k == Contexts::today ? v.ctx : v.ctx % prm::codec::kResidualContexts;
}
inline uint64_t zigzag(int64_t r) { return r >= 0 ? 2 * static_cast<uint64_t>(r) : 2 * static_cast<uint64_t>(-r) - 1; }

struct ClersCoder {
  StaticTables tables{prm::codec::kNumClers};
  Contexts contexts;
  explicit ClersCoder(Contexts k) : contexts(k) {}
  StaticStream encode(const std::vector<ClersValue>& in) {
    for (const ClersValue& c : in) tables.count(clers_context(c, contexts), c.symbol);
    tables.build();
    RansEncoder rans;
    for (const ClersValue& c : in) rans.queue(tables.freq_cum(tables.dense(clers_context(c, contexts)), c.symbol));
    return {rans.finish(), {}, tables.header_bytes()};
  }
  __attribute__((noinline)) bool decode(const StaticStream& s, const std::vector<ClersValue>& meta, uint8_t* out) const {
    RansDecoder rans(s.words.data(), s.words.size());
    for (size_t i = 0; i < meta.size(); ++i) {
      const uint32_t d = tables.dense(clers_context(meta[i], contexts));
      out[i] = static_cast<uint8_t>(rans.get(i & 1, tables.freq_table(d), tables.slot_table(d)));
    }
    return rans.finish();
  }
};

struct ResidualCoder {
  StaticTables tables{kTokenAlphabet};
  Contexts contexts;
  explicit ResidualCoder(Contexts k) : contexts(k) {}
  StaticStream encode(const std::vector<ResidualValue>& in) {
    int raw_bits;
    for (const ResidualValue& v : in) tables.count(residual_context(v, contexts), magnitude_token(zigzag(v.r), raw_bits));
    tables.build();
    RansEncoder rans;
    BitWriter raw;
    for (const ResidualValue& v : in) {
      const uint64_t u = zigzag(v.r);
      const uint32_t t = magnitude_token(u, raw_bits);
      rans.queue(tables.freq_cum(tables.dense(residual_context(v, contexts)), t));
      put_magnitude_raw(raw, u, raw_bits);
    }
    return {rans.finish(), raw.finish(), tables.header_bytes()};
  }
  __attribute__((noinline)) bool decode(const StaticStream& s, const std::vector<ResidualValue>& meta,
                                        int64_t* out) const {
    RansDecoder rans(s.words.data(), s.words.size());
    BitReader raw(s.raw.data(), s.raw.size());
    for (size_t i = 0; i < meta.size(); ++i) {
      const ResidualValue& v = meta[i];
      const uint32_t d = tables.dense(residual_context(v, contexts));
      const uint64_t u = token_magnitude(rans.get(i & 1, tables.freq_table(d), tables.slot_table(d)), raw);
      const uint64_t magnitude = (u + 1) >> 1;
      if (magnitude > static_cast<uint64_t>((u & 1) ? v.down : v.up)) return false;
      out[i] = (u & 1) ? -static_cast<int64_t>(magnitude) : static_cast<int64_t>(magnitude);
    }
    return rans.finish();
  }
};

struct SignedCoder {
  StaticTables magnitudes{kTokenAlphabet}, signs{2};
  StaticStream encode(const std::vector<SignedValue>& in) {
    int raw_bits;
    for (const SignedValue& v : in) {
      magnitudes.count(v.model, magnitude_token(static_cast<uint64_t>(v.v < 0 ? -v.v : v.v), raw_bits));
      if (v.v != 0) signs.count(v.sign, v.v < 0);
    }
    magnitudes.build();
    signs.build();
    RansEncoder rans;
    BitWriter raw;
    for (const SignedValue& v : in) {
      const uint64_t m = static_cast<uint64_t>(v.v < 0 ? -v.v : v.v);
      rans.queue(magnitudes.freq_cum(magnitudes.dense(v.model), magnitude_token(m, raw_bits)));
      put_magnitude_raw(raw, m, raw_bits);
      if (v.v != 0) rans.queue(signs.freq_cum(signs.dense(v.sign), v.v < 0));
    }
    return {rans.finish(), raw.finish(), magnitudes.header_bytes() + signs.header_bytes()};
  }
  __attribute__((noinline)) bool decode(const StaticStream& s, const std::vector<SignedValue>& meta,
                                        int64_t* out) const {
    RansDecoder rans(s.words.data(), s.words.size());
    BitReader raw(s.raw.data(), s.raw.size());
    uint32_t lane = 0;
    for (size_t i = 0; i < meta.size(); ++i) {
      const SignedValue& v = meta[i];
      const uint32_t d = magnitudes.dense(v.model);
      const uint32_t t = rans.get(lane, magnitudes.freq_table(d), magnitudes.slot_table(d));
      lane ^= 1;
      const uint64_t m = token_magnitude(t, raw);
      if (m >> (v.max_class + 1)) return false;  // §9.5: the class exceeds the caller's bound
      int64_t x = static_cast<int64_t>(m);
      if (m != 0) {
        const uint32_t e = signs.dense(v.sign);
        if (rans.get(lane, signs.freq_table(e), signs.slot_table(e))) x = -x;
        lane ^= 1;
      }
      out[i] = x;
    }
    return rans.finish();
  }
};

}  // namespace entropy_study
