// The study's side of codec/src/entropy_trace.h: compiled with PRM_ENTROPY_TRACE into the traced decoder's objects
// (where namespace prm reads prm_traced), it records what the decoder hands to the hooks.
#include "trace_capture.h"

#include <unordered_map>

#include "entropy_trace.h"
#include "prm/codec.h"
#include "signed_int_model.h"

namespace {

struct State {
  entropy_study::Capture* out = nullptr;
  uint16_t block = 0;
  bool inside = false;  // within a captured value's decoding
  std::unordered_map<const void*, uint32_t> models, signs;  // per block: a model's address to its id
};
State g_state;

uint32_t id_of(std::unordered_map<const void*, uint32_t>& ids, const void* p, uint32_t& next) {
  const auto it = ids.emplace(p, next);
  if (it.second) ++next;
  return it.first->second;
}

}  // namespace

namespace prm::codec::entropy_trace {

void block(size_t size) {
  if (!g_state.out) return;
  g_state.out->block_sizes.push_back(size);
  g_state.block = static_cast<uint16_t>(g_state.out->block_sizes.size() - 1);
  g_state.models.clear();
  g_state.signs.clear();
}

void value_begin() { g_state.inside = true; }

void clers(uint32_t ctx, uint32_t symbol, int s_possible) {
  g_state.inside = false;
  if (!g_state.out) return;
  g_state.out->clers.push_back(
      {ctx, static_cast<uint8_t>(symbol), static_cast<uint8_t>(s_possible != 0), g_state.block});
}

void residual(uint32_t ctx, int64_t r, int64_t up, int64_t down) {
  g_state.inside = false;
  if (!g_state.out) return;
  g_state.out->residuals.push_back({ctx, g_state.block, r, up, down});
}

void signed_int(const void* model, const void* sign, int max_class, int64_t v) {
  g_state.inside = false;
  if (!g_state.out) return;
  entropy_study::Capture& c = *g_state.out;
  const bool own = sign == &static_cast<const SignedIntModel*>(model)->sign;
  c.signed_ints.push_back({id_of(g_state.models, model, c.signed_models), id_of(g_state.signs, sign, c.sign_models),
                           static_cast<uint8_t>(own), static_cast<int8_t>(max_class), g_state.block, v});
}

void bit(uint32_t b) {
  if (!g_state.out) return;
  ++g_state.out->decisions;
  g_state.out->bits.push_back(static_cast<uint8_t>(b));
  if (!g_state.inside) g_state.out->other_bits.push_back(static_cast<uint8_t>(b));
}

void direct(int count, uint32_t v) {
  if (!g_state.out) return;
  g_state.out->direct_bits += static_cast<uint64_t>(count);
  g_state.out->directs.push_back(v);
  if (!g_state.inside) g_state.out->other_directs.push_back(v);
}

}  // namespace prm::codec::entropy_trace

namespace entropy_study {

bool capture_stream(const uint8_t* data, size_t size, Capture& out, std::string& error) {
  out = Capture{};
  g_state = State{};
  g_state.out = &out;
  const auto decoded = prm::codec::decode(data, size);
  g_state.out = nullptr;
  if (!decoded.ok()) {
    error = decoded.status.message;
    return false;
  }
  for (const ClersValue& c : out.clers) out.clers_symbols.push_back(c.symbol);
  for (const ResidualValue& r : out.residuals) out.residual_values.push_back(r.r);
  for (const SignedValue& s : out.signed_ints) out.signed_values.push_back(s.v);
  out.vertices = decoded.value.positions_f32.size() / 3;
  out.triangles = decoded.value.triangles.size() / 3;
  return true;
}

}  // namespace entropy_study
