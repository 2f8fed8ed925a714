// libFuzzer target: the range decoder alone (§5). The input drives which models and how many direct bits are
// decoded from the same input used as the coded block; nothing may read out of bounds or loop without consuming.
#include <cstdint>
#include <vector>

#include "range_decoder.h"
#include "range_encoder.h"

using namespace prm::codec;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const size_t split = data[0] % size;
  const uint8_t* program = data + 1;
  const size_t program_size = split;
  std::vector<uint8_t> block(data + 1 + split, data + size);
  RangeDecoder d;
  d.init(block.data(), block.size());
  BitModel models[16];
  std::vector<std::pair<int, uint32_t>> decoded;
  for (size_t i = 0; i < program_size && !d.failed(); ++i) {
    const uint8_t op = program[i];
    if (op & 0x80) {
      const int n = op % 25;
      decoded.push_back({-n - 1, d.decode_direct(n)});
    } else {
      decoded.push_back({op & 15, static_cast<uint32_t>(d.decode_bit(models[op & 15]))});
    }
  }
  // Re-encode what was decoded and decode it again: the encoder and decoder must agree (§5.7).
  RangeEncoder e;
  BitModel em[16];
  for (const auto& [kind, v] : decoded) {
    if (kind < 0)
      e.encode_direct(v, -kind - 1);
    else
      e.encode_bit(em[kind], static_cast<int>(v));
  }
  const std::vector<uint8_t> out = e.finish();
  RangeDecoder d2;
  d2.init(out.data(), out.size());
  BitModel dm[16];
  for (const auto& [kind, v] : decoded) {
    const uint32_t w = kind < 0 ? d2.decode_direct(-kind - 1) : static_cast<uint32_t>(d2.decode_bit(dm[kind]));
    if (w != v) __builtin_trap();
  }
  if (!d2.finish()) __builtin_trap();
  return 0;
}
