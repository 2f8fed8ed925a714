// libFuzzer target: the whole decoder (§3-§10) on arbitrary bytes.
//
// Build and run (clang; see codec/fuzz/README.md):
//   cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DPRM_BUILD_FUZZERS=ON \
//         -DPRM_SANITIZE=address,undefined -DPRM_BUILD_BENCH=OFF -DPRM_BUILD_TESTS=OFF
//   cmake --build build-fuzz --target prm_fuzz_decode_fuzzer
//   build-fuzz/codec/prm_fuzz_decode_fuzzer -max_total_time=300 -rss_limit_mb=2048 corpus/
//
// When the first input byte is odd, the fuzzer rewrites the last four bytes as the CRC-32 of the rest (§3.5), so
// that mutations reach the sections instead of stopping at crc_mismatch.
#include <cstdint>
#include <cstring>
#include <vector>

#include "crc32.h"
#include "prm/codec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const bool fix = data[0] & 1;
  std::vector<uint8_t> s(data + 1, data + size);
  if (fix && s.size() >= 10) {
    const uint32_t c = prm::codec::crc32(s.data(), s.size() - 4);
    for (int i = 0; i < 4; ++i) s[s.size() - 4 + i] = static_cast<uint8_t>(c >> (8 * i));
  }
  // The caller's limits (§4.1) scaled to the input, as a caller that knows what it expects would set them: real
  // streams hold at most about 6 closed-mesh triangles per byte (the conformance vectors and the seeds of run.sh:
  // 5.4 at most), so 64 per byte rejects none of them, while a run of E symbols (up to 720 triangles per byte, §4.5)
  // stops at count_exceeds_limit instead of building millions of triangles under the sanitizers.
  prm::codec::DecodeOptions opt;
  opt.limits.max_triangles = 4096 + 64 * uint64_t{size};
  opt.limits.max_vertices = 2048 + 32 * uint64_t{size};
  const auto res = prm::codec::decode(s.data(), s.size(), opt);
  if (res.ok()) {
    const auto& m = res.value;
    for (uint32_t v : m.triangles)
      if (v >= m.num_vertices()) __builtin_trap();
  } else if (res.status.error == prm::codec::Error::internal) {
    __builtin_trap();
  }
  prm::codec::inspect(s.data(), s.size());
  return 0;
}
