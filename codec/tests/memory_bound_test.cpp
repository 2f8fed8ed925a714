// §4.5 The decoder's memory follows what it decodes, not what a stream claims. Streams crafted as an attacker would:
// a valid header and CRC, one component claiming the most triangles §4.3 lets its bytes claim (2,880 per byte of
// CLERS data), over zero, random or "all E" data; the peak of live heap bytes during decode is counted by this
// binary's operator new (which ASan's allocator serves as well, so the counts hold under the sanitizers).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <random>
#include <string>

#include "clers_shared.h"
#include "crc32.h"
#include "limits.h"
#include "prm/codec.h"
#include "range_encoder.h"
#include "spirale_reversi.h"
#include "stream_writer.h"

// The peak of live heap bytes since the last reset.
namespace {
size_t g_live = 0, g_peak = 0;
void* counted_alloc(size_t n) {
  void* p = std::malloc(n + 16);
  if (!p) throw std::bad_alloc();
  *static_cast<size_t*>(p) = n;
  g_live += n;
  if (g_live > g_peak) g_peak = g_live;
  return static_cast<char*>(p) + 16;
}
void counted_free(void* p) {
  if (!p) return;
  char* base = static_cast<char*>(p) - 16;
  g_live -= *reinterpret_cast<size_t*>(base);
  std::free(base);
}
}  // namespace
void* operator new(size_t n) { return counted_alloc(n); }
void* operator new[](size_t n) { return counted_alloc(n); }
void* operator new(size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted_alloc(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted_alloc(n);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, size_t) noexcept { counted_free(p); }
void operator delete[](void* p, size_t) noexcept { counted_free(p); }

namespace prm::codec::test {
namespace {

constexpr size_t kMB = size_t{1} << 20;

// A stream of `total` bytes (give or take a few) whose connectivity section is one component of the most triangles
// §4.3 allows for its CLERS_Data (`clers`, padded with `pad` to fill the size), no handle, no hole; the header's
// counts agree with the section (V = T / 2 + 2), and the CRC is right. The positions section is 4 zero bytes.
constexpr size_t kOverhead = 80;  // the header, the framing and the counts take about 70 bytes
uint32_t most_triangles(size_t total) {
  return static_cast<uint32_t>(kMaxDecisionsPerByte * (total - kOverhead - 3) + 2);
}

std::vector<uint8_t> crafted(size_t total, std::vector<uint8_t> clers, uint8_t pad, uint32_t* claimed = nullptr) {
  const size_t length = total - kOverhead;
  if (clers.size() < length) clers.resize(length, pad);
  const uint32_t triangles = most_triangles(total);
  if (claimed) *claimed = triangles;
  StreamWriter conn;
  conn.varint(1);          // Component_Count
  conn.varint(triangles);  // Component_Size
  conn.varint(0);          // Handle_Count
  conn.varint(0);          // Dummy_Count
  conn.bytes(clers);
  StreamWriter w;
  w.bytes(std::vector<uint8_t>{'P', 'R', 'M', 0x1A, 1, 4});
  w.u8(0);   // Flags
  w.u8(12);  // Position_Bits
  w.varint(triangles / 2 + 2);
  w.varint(triangles);
  for (int k = 0; k < 3; ++k) w.f64(0.0);
  w.f64(1.0);
  for (int k = 0; k < 3; ++k) w.varint(0);
  for (int k = 0; k < 3; ++k) w.varint(4095);
  w.u8(1);
  w.varint(static_cast<uint32_t>(conn.size()));
  w.bytes(conn.buffer());
  w.u8(2);
  w.varint(4);
  w.bytes(std::vector<uint8_t>(4, 0));
  w.u32(crc32(w.buffer().data(), w.size()));
  return w.buffer();
}

// CLERS data that codes `count` E symbols for a component of `triangles` triangles, the decoder's contexts
// (§6.5.2) tracked by Spirale Reversi as the encoder does: a prefix that is valid as far as it goes, at the
// probability floor's rate (about 720 E per byte).
std::vector<uint8_t> e_run(uint32_t triangles, uint32_t count) {
  SpiraleReversi sr;
  sr.init(triangles, triangles / 2 + 2);
  RangeEncoder rc;
  auto models = std::make_unique<ClersModels>();
  uint32_t prev1 = kE, prev2 = kE;
  for (uint32_t i = triangles - 1, k = 0; k < count; --i, ++k) {
    const uint32_t depth = sr.stack_depth();
    if (depth > 0) {
      BitModel* m = models->m[clers_context(prev1, prev2, sr.gate_start_count(), 0)];
      rc.encode_bit(m[0], 1);
      rc.encode_bit(m[1], 1);
      if (depth >= 2) rc.encode_bit(m[2], 1);
      rc.encode_bit(m[3], 1);
    }
    EXPECT_TRUE(sr.apply(i, kE));
    prev2 = prev1;
    prev1 = kE;
  }
  return rc.finish();
}

struct Outcome {
  Status status;
  size_t peak = 0;
};

Outcome decode_counted(const std::vector<uint8_t>& s) {
  Outcome o;
  const size_t before = g_live;
  g_peak = g_live;
  auto res = decode(s.data(), s.size(), {});
  o.peak = g_peak - before;
  o.status = res.status;
  return o;
}

// The claimed count passes §4.1 and §4.3 (the error comes from decoding the symbols), is named, and the peak stays
// under `bound`.
void expect_rejected_within(const std::vector<uint8_t>& s, uint32_t claimed, size_t bound, const std::string& what) {
  ASSERT_LE(claimed, DecodeLimits{}.max_triangles) << what;
  const Outcome o = decode_counted(s);
  EXPECT_FALSE(o.status.ok()) << what;
  EXPECT_TRUE(o.status.error == Error::bad_connectivity || o.status.error == Error::truncated ||
              o.status.error == Error::non_manifold_result)
      << what << ": " << error_name(o.status.error) << " §" << o.status.spec_section << ": " << o.status.message;
  const std::string section = o.status.spec_section ? o.status.spec_section : "";
  EXPECT_TRUE(section.rfind('6', 0) == 0 || section.rfind('5', 0) == 0)
      << what << ": rejected in §" << o.status.spec_section << ", not while decoding the symbols";
  EXPECT_LT(o.peak, bound) << what << ": " << claimed << " triangles claimed, peak " << o.peak << " bytes";
  std::printf("  %s: %u triangles claimed; %s at byte %llu (§%s); peak %zu bytes\n", what.c_str(), claimed,
              error_name(o.status.error), static_cast<unsigned long long>(o.status.byte_offset), section.c_str(),
              o.peak);
}

TEST(MemoryBound, ZeroDataClaimingTheMostTriangles) {
  for (size_t total : {size_t{1000}, size_t{16} << 10, size_t{46000}}) {
    uint32_t claimed = 0;
    const std::vector<uint8_t> s = crafted(total, {}, 0x00, &claimed);
    EXPECT_LT(s.size(), total + 8);
    // Before §4.5 the decoder allocated 24 bytes per claimed triangle before reading a symbol: 71 MB for 1 KB.
    expect_rejected_within(s, claimed, total < 1024 ? 16 * kMB : 64 * kMB,
                           std::to_string(s.size()) + " bytes of zeros");
  }
}

TEST(MemoryBound, RandomDataClaimingTheMostTriangles) {
  std::mt19937 rng(17);
  for (size_t total : {size_t{1000}, size_t{16} << 10, size_t{46000}})
    for (int trial = 0; trial < 4; ++trial) {
      std::vector<uint8_t> clers(total - kOverhead);
      for (auto& b : clers) b = static_cast<uint8_t>(rng());
      clers[0] = 0;  // §5.6 an initial Code of 0xFFFFFFFF is invalid by itself
      uint32_t claimed = 0;
      const std::vector<uint8_t> s = crafted(total, clers, 0, &claimed);
      expect_rejected_within(s, claimed, total < 1024 ? 16 * kMB : 64 * kMB,
                             std::to_string(s.size()) + " random bytes, trial " + std::to_string(trial));
    }
}

// A prefix that decodes: the memory follows the triangles decoded before the error, not the claimed count.
TEST(MemoryBound, ValidPrefixCostsWhatItDecodes) {
  const uint32_t decoded = 20000;
  uint32_t claimed = 0;
  const size_t total = size_t{16} << 10;
  const std::vector<uint8_t> s = crafted(total, e_run(most_triangles(total), decoded), 0x00, &claimed);
  // About 70 bytes per E triangle (opposites, records, stack), doubled by the tables' growth.
  expect_rejected_within(s, claimed, kMB + 160 * size_t{decoded}, "20,000 E symbols, then zeros");
}

// The bound per decoded triangle holds for valid streams too: a closed mesh decodes within a constant plus a fixed
// number of bytes per triangle, whatever the stream's size.
TEST(MemoryBound, ValidStreamPerTriangle) {
  // An n x n torus grid: the regular mesh for which a stream is smallest per triangle.
  const int n = 200;
  std::vector<float> xyz;
  std::vector<uint32_t> tris;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = 2 * 3.141592653589793 * i / n, v = 2 * 3.141592653589793 * j / n;
      xyz.push_back(static_cast<float>((2 + std::cos(v)) * std::cos(u)));
      xyz.push_back(static_cast<float>((2 + std::cos(v)) * std::sin(u)));
      xyz.push_back(static_cast<float>(std::sin(v)));
      const uint32_t a = static_cast<uint32_t>(i * n + j), b = static_cast<uint32_t>(((i + 1) % n) * n + j),
                     c = static_cast<uint32_t>(((i + 1) % n) * n + (j + 1) % n),
                     d = static_cast<uint32_t>(i * n + (j + 1) % n);
      tris.insert(tris.end(), {a, b, c, a, c, d});
    }
  auto enc = encode(xyz.data(), xyz.size() / 3, tris.data(), tris.size() / 3, {});
  ASSERT_TRUE(enc.ok());
  const Outcome o = decode_counted(enc.value);
  ASSERT_TRUE(o.status.ok()) << o.status.message;
  const size_t t = tris.size() / 3;
  EXPECT_LT(o.peak, kMB + 200 * t) << o.peak << " bytes for " << t << " triangles";
  std::printf("  %zu triangles in %zu bytes: peak %zu bytes\n", t, enc.value.size(), o.peak);
}

}  // namespace
}  // namespace prm::codec::test
