// Hostile streams (§3-§6, §10): every byte flipped, every truncation, random bytes, counts inflated to 2^32 - 1.
// Each decode must return either a valid mesh or a named error, never crash or hang (run under ASan+UBSan), and never
// allocate beyond what the caller's limits and the stream's length allow (§4).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <new>
#include <random>

#include "crc32.h"
#include "roundtrip_util.h"
#include "stream_writer.h"

// Allocation accounting for this test binary: the peak of live bytes since reset_peak().
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
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, size_t) noexcept { counted_free(p); }
void operator delete[](void* p, size_t) noexcept { counted_free(p); }

namespace prm::codec::test {
namespace {

std::vector<uint8_t> small_stream() {
  // Components, a handle, holes: every part of §6.3 is present.
  const TestMesh m = concat({plate_with_holes(1, 1), sphere_with_holes(1, 2), tetrahedron()});
  EncodeReport rep;
  auto enc = encode(m.xyz.data(), m.num_vertices(), m.triangles.data(), m.num_triangles(), {}, &rep);
  EXPECT_TRUE(enc.ok());
  EXPECT_EQ(rep.handles, 1u);
  EXPECT_EQ(rep.holes, 2u);
  EXPECT_EQ(rep.components, 3u);
  return enc.value;
}

void fix_crc(std::vector<uint8_t>& s) {
  if (s.size() < 4) return;
  const uint32_t c = crc32(s.data(), s.size() - 4);
  for (int i = 0; i < 4; ++i) s[s.size() - 4 + i] = static_cast<uint8_t>(c >> (8 * i));
}

// Decodes a copy in a fresh, exactly sized heap buffer (so ASan sees any overread) and checks the outcome.
Status decode_checked(const std::vector<uint8_t>& s, size_t max_peak, const DecodeOptions& opt = {}) {
  std::unique_ptr<uint8_t[]> buf(new uint8_t[s.size() ? s.size() : 1]);
  if (!s.empty()) std::memcpy(buf.get(), s.data(), s.size());
  const size_t before = g_live;
  g_peak = g_live;
  auto res = decode(buf.get(), s.size(), opt);
  EXPECT_LE(g_peak - before, max_peak) << "decode allocated beyond its bound";
  if (!res.ok()) {
    EXPECT_NE(res.status.error, Error::internal);
    EXPECT_NE(res.status.error, Error::out_of_memory);
    EXPECT_STRNE(error_name(res.status.error), "unknown");
    EXPECT_FALSE(res.status.message.empty());
    EXPECT_LE(res.status.byte_offset, s.size());
  } else {
    // A mesh that decodes must be a valid one.
    const DecodedMesh& d = res.value;
    for (uint32_t v : d.triangles) EXPECT_LT(v, d.num_vertices());
  }
  return res.status;
}

// Bytes a stream of `size` bytes may make the decoder allocate: the §4.2 bound on triangles, ~80 bytes each.
size_t allowance(size_t size) { return 80 * 5700 * size + (1 << 20); }

TEST(Hostile, EveryByteFlipped) {
  const std::vector<uint8_t> s = small_stream();
  ASSERT_TRUE(decode_checked(s, allowance(s.size())).ok());
  size_t ok_after_fix = 0;
  for (size_t i = 0; i < s.size(); ++i)
    for (uint8_t x : {0x01, 0x80, 0xFF}) {
      std::vector<uint8_t> t = s;
      t[i] ^= x;
      const Status raw = decode_checked(t, allowance(t.size()));
      EXPECT_FALSE(raw.ok()) << "byte " << i;  // the CRC (or magic/version) catches every flip
      if (i >= s.size() - 4) continue;
      fix_crc(t);
      ok_after_fix += decode_checked(t, allowance(t.size())).ok();
    }
  // Some flips give another valid stream (a different origin, a different residual); most must be rejected.
  EXPECT_LT(ok_after_fix, s.size());
}

TEST(Hostile, EveryTruncation) {
  const std::vector<uint8_t> s = small_stream();
  for (size_t len = 0; len < s.size(); ++len) {
    std::vector<uint8_t> t(s.begin(), s.begin() + static_cast<long>(len));
    EXPECT_FALSE(decode_checked(t, allowance(len)).ok()) << len;
    if (len >= 10 && len < s.size() - 4) {  // a prefix with a valid CRC appended: the framing must catch it
      std::vector<uint8_t> u(s.begin(), s.begin() + static_cast<long>(len));
      u.resize(len + 4);
      fix_crc(u);
      const Status st = decode_checked(u, allowance(u.size()));
      EXPECT_FALSE(st.ok()) << len;
    }
  }
  // A trailing byte, inside the CRC'd region.
  std::vector<uint8_t> t = s;
  t.insert(t.end() - 4, 0x00);
  fix_crc(t);
  EXPECT_FALSE(decode_checked(t, allowance(t.size())).ok());
}

TEST(Hostile, RandomBytes) {
  std::mt19937 rng(7);
  const std::vector<uint8_t> s = small_stream();
  for (int trial = 0; trial < 20000; ++trial) {
    const size_t len = rng() % 300;
    std::vector<uint8_t> t(len);
    for (auto& b : t) b = static_cast<uint8_t>(rng());
    if (trial % 2 && len >= 10) {  // valid magic, version and CRC around random content
      std::memcpy(t.data(), s.data(), 6);
      fix_crc(t);
    }
    if (trial % 4 == 3 && len > 60) {  // a valid header, random sections
      std::memcpy(t.data(), s.data(), 51);
      fix_crc(t);
    }
    decode_checked(t, allowance(len));
  }
}

// Builds a stream from parts, with a valid CRC.
std::vector<uint8_t> build(uint32_t vertices, uint32_t triangles, const std::vector<uint8_t>& conn,
                           const std::vector<uint8_t>& pos) {
  StreamWriter w;
  for (uint8_t b : std::initializer_list<uint8_t>{'P', 'R', 'M', 0x1A, 1, 0, 0, 12}) w.u8(b);
  w.varint(vertices);
  w.varint(triangles);
  for (int k = 0; k < 3; ++k) w.f64(0.0);
  w.f64(1.0);
  for (int k = 0; k < 6; ++k) w.varint(k < 3 ? 0 : 4095);
  w.u8(1);
  w.varint(static_cast<uint32_t>(conn.size()));
  w.bytes(conn);
  w.u8(2);
  w.varint(static_cast<uint32_t>(pos.size()));
  w.bytes(pos);
  w.u32(0);
  std::vector<uint8_t> s = w.buffer();
  fix_crc(s);
  return s;
}

std::vector<uint8_t> varints(std::initializer_list<uint32_t> v) {
  StreamWriter w;
  for (uint32_t x : v) w.varint(x);
  return w.buffer();
}

TEST(Hostile, InflatedCounts) {
  const uint32_t big = 0xFFFFFFFFu;
  const std::vector<uint8_t> clers = {0x7F, 0xFF, 0x80, 0x00};
  auto with_clers = [&](std::vector<uint8_t> head) {
    head.insert(head.end(), clers.begin(), clers.end());
    return head;
  };
  const size_t cap = 4 << 20;  // nothing here may allocate more than a few MB
  // Header counts beyond the caller's limits.
  EXPECT_EQ(decode_checked(build(big, 4, with_clers(varints({1, 4, 0, 0})), {}), cap).error,
            Error::count_exceeds_limit);
  EXPECT_EQ(decode_checked(build(4, big, with_clers(varints({1, 4, 0, 0})), {}), cap).error,
            Error::count_exceeds_limit);
  // Component_Count, Handle_Count, Dummy_Count larger than the section's bytes.
  EXPECT_EQ(decode_checked(build(4, 4, with_clers(varints({big})), {}), cap).error, Error::count_exceeds_stream);
  EXPECT_EQ(decode_checked(build(4, 4, with_clers(varints({1, 4, big})), {}), cap).error,
            Error::count_exceeds_stream);
  EXPECT_EQ(decode_checked(build(4, 4, with_clers(varints({1, 4, 0, big})), {}), cap).error,
            Error::count_exceeds_stream);
  // A component of 2^32 - 2 triangles: beyond the limits.
  EXPECT_EQ(decode_checked(build(4, 4, with_clers(varints({1, big - 1, 0, 0})), {}), cap).error,
            Error::count_exceeds_limit);
  // Within generous caller limits, 2^26 triangles cannot be coded in 4 bytes (§4.2).
  DecodeOptions generous;
  generous.limits.max_triangles = uint64_t{1} << 29;
  generous.limits.max_vertices = uint64_t{1} << 28;
  EXPECT_EQ(decode_checked(build((1u << 25) + 2, 1u << 26, with_clers(varints({1, 1u << 26, 0, 0})), {}), cap,
                           generous)
                .error,
            Error::count_exceeds_stream);
  // Odd component size, impossible handle counts, bad dummy ids.
  EXPECT_EQ(decode_checked(build(4, 4, with_clers(varints({1, 5, 0, 0})), {}), cap).error, Error::bad_connectivity);
  EXPECT_EQ(decode_checked(build(4, 4, with_clers(varints({1, 4, 1, 1, 0, 0})), {}), cap).error,
            Error::bad_connectivity);
  EXPECT_EQ(decode_checked(build(3, 4, with_clers(varints({1, 4, 0, 1, 7})), {}), cap).error,
            Error::bad_connectivity);
  // Vertex_Count inconsistent with the components.
  EXPECT_EQ(decode_checked(build(5, 4, with_clers(varints({1, 4, 0, 0})), {}), cap).error, Error::bad_connectivity);
}

TEST(Hostile, HeaderFields) {
  const std::vector<uint8_t> s = small_stream();
  auto patched = [&](size_t at, uint8_t value) {
    std::vector<uint8_t> t = s;
    t[at] = value;
    fix_crc(t);
    return decode_checked(t, allowance(t.size())).error;
  };
  EXPECT_EQ(patched(0, 'X'), Error::bad_magic);
  EXPECT_EQ(patched(4, 2), Error::unsupported_version);
  // Flags: bits 0 (the LERS valence context, §7.3), 2 (the CLERS seam context, §6.5.2), 3 (the patch contexts,
  // §8.4.1, §9.7.4) and 4 (the patch grids, §8.4.2) are defined (§3.3).
  const uint8_t seam = s[6] & 0x04;
  for (uint8_t flags : {2, 0x20, 0x40, 0x80, 0xE2})
    EXPECT_EQ(patched(6, static_cast<uint8_t>(flags | seam)), Error::unsupported_feature) << int{flags};
  // A general-path stream with bit 0, 3 or 4: nothing to apply them to.
  EXPECT_EQ(patched(6, static_cast<uint8_t>(1 | seam)), Error::ok);
  EXPECT_EQ(patched(6, static_cast<uint8_t>(8 | seam)), Error::ok);
  EXPECT_EQ(patched(6, static_cast<uint8_t>(0x10 | seam)), Error::ok);
  // Bit 2 toggled: the symbols decode with other contexts; whatever comes out, it is checked (§6.8), not trusted.
  const Error toggled = patched(6, static_cast<uint8_t>(seam ^ 0x04));
  EXPECT_NE(toggled, Error::internal);
  EXPECT_EQ(patched(7, 7), Error::bad_header);           // Position_Bits
  EXPECT_EQ(patched(7, 21), Error::bad_header);
  std::vector<uint8_t> t = s;
  t.back() ^= 1;
  EXPECT_EQ(decode_checked(t, allowance(t.size())).error, Error::crc_mismatch);
}

TEST(Hostile, ReservedAndUnknownSections) {
  const std::vector<uint8_t> conn = varints({0, 0, 0});
  for (uint8_t id : {0, 3, 4, 5, 9, 15, 16, 200}) {
    StreamWriter w;
    for (uint8_t b : std::initializer_list<uint8_t>{'P', 'R', 'M', 0x1A, 1, 0, 0, 12}) w.u8(b);
    w.varint(0);
    w.varint(0);
    for (int k = 0; k < 4; ++k) w.f64(k < 3 ? 0.0 : 1.0);
    for (int k = 0; k < 6; ++k) w.varint(0);
    w.u8(1);
    w.varint(3);
    w.bytes(conn);
    w.u8(id);
    w.varint(0);
    w.u32(0);
    std::vector<uint8_t> s = w.buffer();
    fix_crc(s);
    const Error e = decode_checked(s, 1 << 20).error;
    // 3 and 4 (the PRM sections) without the positions section, or alone, are bad; 5..15 are reserved.
    EXPECT_EQ(e, id >= 5 && id <= 15 ? Error::unsupported_feature : Error::bad_section) << int(id);
  }
  // The empty mesh decodes.
  EXPECT_TRUE(decode_checked(build(0, 0, conn, {}), 1 << 20).ok());
}

}  // namespace
}  // namespace prm::codec::test
