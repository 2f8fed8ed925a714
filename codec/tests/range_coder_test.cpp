// §5 The range coder: exact worked example, round trips, the §4.2 bound, and hostile blocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "crc32.h"
#include "limits.h"
#include "range_decoder.h"
#include "range_encoder.h"
#include "stream_reader.h"
#include "stream_writer.h"

namespace prm::codec {
namespace {

TEST(RangeCoder, WorkedExample) {  // spec §5.8
  RangeEncoder e;
  BitModel m;
  const int bits[4] = {0, 0, 1, 0};
  const uint16_t p_after[4] = {49152, 53248, 39936, 43136};
  for (int i = 0; i < 4; ++i) {
    e.encode_bit(m, bits[i]);
    EXPECT_EQ(m.p, p_after[i]);
    EXPECT_EQ(m.n, i + 1);
  }
  e.encode_direct(5, 3);
  const std::vector<uint8_t> out = e.finish();
  EXPECT_EQ(out, (std::vector<uint8_t>{0x54, 0xDA, 0x30, 0x00}));
  RangeDecoder d;
  d.init(out.data(), out.size());
  BitModel dm;
  for (int b : bits) EXPECT_EQ(d.decode_bit(dm), b);
  EXPECT_EQ(d.decode_direct(3), 5u);
  EXPECT_TRUE(d.finish());
}

TEST(RangeCoder, RateSchedule) {  // spec §5.2: R = min(1 + floor(log2(N + 1)), 7)
  for (int n = 0; n < 255; ++n) {
    const int expect = std::min(1 + static_cast<int>(std::floor(std::log2(n + 1.0))), 7);
    EXPECT_EQ(kRate[n < kRateSteps ? n : kRateSteps - 1], expect) << n;
  }
}

TEST(RangeCoder, RandomRoundTrips) {
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + static_cast<int>(rng() % 5000);
    const int skew = static_cast<int>(rng() % 100);
    std::vector<int> kind(n), value(n), model(n);
    RangeEncoder e;
    std::vector<BitModel> em(8);
    for (int i = 0; i < n; ++i) {
      kind[i] = rng() % 4 == 0;  // 1: direct bits
      model[i] = rng() % 8;
      if (kind[i]) {
        const int count = static_cast<int>(rng() % 25);
        value[i] = count << 24 | static_cast<int>(rng() & ((1u << count) - 1));
        e.encode_direct(static_cast<uint32_t>(value[i]) & 0xFFFFFF, count);
      } else {
        value[i] = static_cast<int>(rng() % 100) < skew;
        e.encode_bit(em[model[i]], value[i]);
      }
    }
    const std::vector<uint8_t> out = e.finish();
    ASSERT_GE(out.size(), 4u);
    RangeDecoder d;
    d.init(out.data(), out.size());
    std::vector<BitModel> dm(8);
    for (int i = 0; i < n; ++i) {
      if (kind[i]) {
        ASSERT_EQ(d.decode_direct(value[i] >> 24), static_cast<uint32_t>(value[i]) & 0xFFFFFF);
      } else {
        ASSERT_EQ(d.decode_bit(dm[model[i]]), value[i]);
      }
    }
    EXPECT_TRUE(d.finish()) << "trial " << trial;
  }
}

// §4.2: the update of §5.2 never leaves [127, 65409] from its initial state: enumerate every reachable (P, N).
TEST(RangeCoder, ProbabilityFloor) {
  std::vector<uint8_t> seen(size_t{65537} * kRateSteps, 0);
  std::vector<BitModel> todo{BitModel{}};
  seen[size_t{todo[0].p} * kRateSteps] = 1;
  uint32_t lo = kProbOne, hi = 0;
  size_t states = 0;
  while (!todo.empty()) {
    const BitModel m = todo.back();
    todo.pop_back();
    ++states;
    lo = std::min<uint32_t>(lo, m.p);
    hi = std::max<uint32_t>(hi, m.p);
    for (uint32_t bit : {0u, 1u}) {
      BitModel next = m;
      next.update(bit);
      uint8_t& s = seen[size_t{next.p} * kRateSteps + next.n];
      if (!s) {
        s = 1;
        todo.push_back(next);
      }
    }
  }
  EXPECT_EQ(lo, kProbMin);
  EXPECT_EQ(hi, kProbMax);
  EXPECT_EQ(states, 2622375u);
}

// §4.2: the most compressible input (one certain bit, over and over) stays within the bound, and close to it.
TEST(RangeCoder, DecisionsPerByteBound) {
  const uint64_t n = 20000000;
  RangeEncoder e;
  BitModel m;
  for (uint64_t i = 0; i < n; ++i) e.encode_bit(m, 0);
  const std::vector<uint8_t> out = e.finish();
  EXPECT_LE(n, kMaxDecisionsPerByte * (out.size() - 3));
  // The probability settles at the floor 65409/65536: certain bits come close to the bound.
  EXPECT_GT(n, kMaxDecisionsPerByte * (out.size() - 3) * 8 / 10);
}

TEST(RangeCoder, HostileBlocks) {
  // Too short, all 0xFF (Code = 0xFFFFFFFF is invalid), and zero bytes: never reads outside, always terminates.
  for (size_t len = 0; len < 8; ++len) {
    std::vector<uint8_t> ff(len, 0xFF), zero(len, 0);
    RangeDecoder d;
    d.init(ff.data(), ff.size());
    BitModel m;
    // §5.6 A block of at least 4 bytes starting FF FF FF FF is bad_section (bad_start), a shorter one truncated.
    EXPECT_EQ(d.bad_start(), len >= 4);
    EXPECT_TRUE(d.failed());
    for (int i = 0; i < 1000; ++i) d.decode_bit(m);
    EXPECT_TRUE(d.failed());
    RangeDecoder z;
    z.init(zero.data(), zero.size());
    EXPECT_FALSE(z.bad_start());
    for (int i = 0; i < 100000 && !z.failed(); ++i) z.decode_bit(m);
    EXPECT_TRUE(z.failed()) << "zeros must run out: every decision consumes range (§4.2)";
  }
}

TEST(Crc32, KnownValue) {  // spec §3.5
  const char* s = "123456789";
  EXPECT_EQ(crc32(reinterpret_cast<const uint8_t*>(s), 9), 0xCBF43926u);
  EXPECT_EQ(crc32(nullptr, 0), 0u);
}

TEST(StreamReader, VarintRules) {  // spec §1.3
  auto parse = [](std::vector<uint8_t> b, uint32_t* v) {
    StreamReader r(b.data(), b.size());
    *v = r.varint();
    return r.failed() ? r.error() : (r.remaining() ? Error::trailing_bytes : Error::ok);
  };
  uint32_t v;
  EXPECT_EQ(parse({0x00}, &v), Error::ok);
  EXPECT_EQ(v, 0u);
  EXPECT_EQ(parse({0xFF, 0x1F}, &v), Error::ok);
  EXPECT_EQ(v, 4095u);
  EXPECT_EQ(parse({0xFF, 0xFF, 0xFF, 0xFF, 0x0F}, &v), Error::ok);
  EXPECT_EQ(v, 0xFFFFFFFFu);
  EXPECT_EQ(parse({0xFF, 0xFF, 0xFF, 0xFF, 0x1F}, &v), Error::bad_section);  // > 2^32 - 1
  EXPECT_EQ(parse({0x80, 0x00}, &v), Error::bad_section);                    // redundant zero group
  EXPECT_EQ(parse({0x80}, &v), Error::truncated);
  EXPECT_EQ(parse({}, &v), Error::truncated);
  StreamWriter w;
  for (uint32_t x : {0u, 1u, 127u, 128u, 300u, 4095u, 1u << 21, 0xFFFFFFFFu}) w.varint(x);
  StreamReader r(w.buffer().data(), w.size());
  for (uint32_t x : {0u, 1u, 127u, 128u, 300u, 4095u, 1u << 21, 0xFFFFFFFFu}) EXPECT_EQ(r.varint(), x);
  EXPECT_TRUE(r.finish());
}

}  // namespace
}  // namespace prm::codec
