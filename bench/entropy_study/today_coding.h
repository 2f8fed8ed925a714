// hdecode8's scheme (a): the captured values coded as today's format codes them (§5 range coder, adaptive binary
// models): CLERS by §6.5.1's four decisions, position residuals by §10.4.1's adaptive Rice code, signed integers by
// §9.5's Exp-Golomb binarization. Each kind is one range-coded stream here; models start afresh where the capture's
// block changes, as in the real stream. The decoders take the contexts from the capture (computing them is the
// connectivity's and the prediction's work, not the entropy layer's).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "clers_shared.h"
#include "position_residual_encode.h"
#include "position_shared.h"
#include "range_decoder.h"
#include "range_encoder.h"
#include "signed_int_model.h"
#include "trace_capture.h"

namespace entropy_study {

using prm::codec::BitModel;
using prm::codec::RangeDecoder;
using prm::codec::RangeEncoder;

// §6.5.1 d0: C or not; d1: R or not; d2: S or not (when possible); d3: L (0) or E (1).
inline std::vector<uint8_t> today_encode_clers(const std::vector<ClersValue>& in) {
  using namespace prm::codec;
  RangeEncoder rc;
  auto models = std::make_unique<ClersModels>();
  uint32_t block = in.empty() ? 0 : in[0].block;
  for (const ClersValue& c : in) {
    if (c.block != block) *models = ClersModels{}, block = c.block;
    BitModel* m = models->m[c.ctx];
    rc.encode_bit(m[0], c.symbol != kC);
    if (c.symbol == kC) continue;
    rc.encode_bit(m[1], c.symbol != kR);
    if (c.symbol == kR) continue;
    if (c.s_possible) {
      rc.encode_bit(m[2], c.symbol != kS);
      if (c.symbol == kS) continue;
    }
    rc.encode_bit(m[3], c.symbol == kE);
  }
  return rc.finish();
}

__attribute__((noinline)) inline bool today_decode_clers(const std::vector<uint8_t>& bytes,
                                                         const std::vector<ClersValue>& meta, uint8_t* out) {
  using namespace prm::codec;
  RangeDecoder rc;
  rc.init(bytes.data(), bytes.size());
  auto models = std::make_unique<ClersModels>();
  uint32_t block = meta.empty() ? 0 : meta[0].block;
  for (size_t i = 0; i < meta.size(); ++i) {
    const ClersValue& c = meta[i];
    if (c.block != block) *models = ClersModels{}, block = c.block;
    BitModel* m = models->m[c.ctx];
    uint8_t s;
    if (!rc.decode_bit(m[0]))
      s = kC;
    else if (!rc.decode_bit(m[1]))
      s = kR;
    else if (c.s_possible && !rc.decode_bit(m[2]))
      s = kS;
    else
      s = rc.decode_bit(m[3]) ? kE : kL;
    out[i] = s;
  }
  return rc.finish();
}

// §10.4.1, with the encoder's own encode_residual; decoded as position_decode.cpp's decode_residual does.
inline std::vector<uint8_t> today_encode_residuals(const std::vector<ResidualValue>& in) {
  using namespace prm::codec;
  RangeEncoder rc;
  auto m = std::make_unique<ResidualModels>();
  uint32_t block = in.empty() ? 0 : in[0].block;
  for (const ResidualValue& v : in) {
    if (v.block != block) *m = ResidualModels{}, block = v.block;
    encode_residual(rc, *m, static_cast<int>(v.ctx / kResidualContexts), static_cast<int>(v.ctx % kResidualContexts),
                    v.r, v.up, v.down);
  }
  return rc.finish();
}

__attribute__((noinline)) inline bool today_decode_residuals(const std::vector<uint8_t>& bytes,
                                                             const std::vector<ResidualValue>& meta, int64_t* out) {
  using namespace prm::codec;
  RangeDecoder rc;
  rc.init(bytes.data(), bytes.size());
  auto m = std::make_unique<ResidualModels>();
  uint32_t block = meta.empty() ? 0 : meta[0].block;
  for (size_t i = 0; i < meta.size(); ++i) {
    const ResidualValue& v = meta[i];
    if (v.block != block) *m = ResidualModels{}, block = v.block;
    const int axis = static_cast<int>(v.ctx / kResidualContexts), ctx = static_cast<int>(v.ctx % kResidualContexts);
    RiceState& rice = m->rice[axis][ctx];
    const int k = rice.k();
    BitModel* unary = m->unary[axis][ctx];
    uint32_t q = 0;
    while (q < kUnaryModels - 1 && rc.decode_bit(unary[q])) ++q;
    if (q == kUnaryModels - 1)
      while (q < kUnaryEscape && rc.decode_bit(unary[kUnaryModels - 1])) ++q;
    if (q == kUnaryEscape) q += rc.decode_direct(kEscapeBits);
    uint64_t u = q;
    if (k > 0) {
      u = u << 1 | static_cast<uint64_t>(rc.decode_bit(m->low[axis][k][q < 2 ? q : 2]));
      if (k > 1) u = u << (k - 1) | rc.decode_direct(k - 1);
    }
    const uint64_t magnitude = (u + 1) >> 1;
    if (magnitude > static_cast<uint64_t>((u & 1) ? v.down : v.up)) return false;
    rice.update(static_cast<uint32_t>(magnitude));
    out[i] = (u & 1) ? -static_cast<int64_t>(magnitude) : static_cast<int64_t>(magnitude);
  }
  return rc.finish();
}

// §9.5 with one SignedIntModel per captured model id and one sign model per captured sign id.
struct SignedModels {
  std::vector<prm::codec::SignedIntModel> model;
  std::vector<BitModel> sign;
  BitModel& sign_of(const SignedValue& v) { return v.own_sign ? model[v.model].sign : sign[v.sign]; }
};

inline std::vector<uint8_t> today_encode_signed(const std::vector<SignedValue>& in, uint32_t models, uint32_t signs) {
  RangeEncoder rc;
  SignedModels m{std::vector<prm::codec::SignedIntModel>(models), std::vector<BitModel>(signs)};
  for (const SignedValue& v : in) prm::codec::encode_signed(rc, m.model[v.model], v.v, m.sign_of(v));
  return rc.finish();
}

__attribute__((noinline)) inline bool today_decode_signed(const std::vector<uint8_t>& bytes,
                                                          const std::vector<SignedValue>& meta, uint32_t models,
                                                          uint32_t signs, int64_t* out) {
  RangeDecoder rc;
  rc.init(bytes.data(), bytes.size());
  SignedModels m{std::vector<prm::codec::SignedIntModel>(models), std::vector<BitModel>(signs)};
  for (size_t i = 0; i < meta.size(); ++i) {
    const SignedValue& v = meta[i];
    if (!prm::codec::decode_signed(rc, m.model[v.model], v.max_class, out[i], m.sign_of(v))) return false;
  }
  return rc.finish();
}

}  // namespace entropy_study
