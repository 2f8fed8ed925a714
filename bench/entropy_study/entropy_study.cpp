// prm_bench_entropy_study (hdecode8, bench/README.md "hdecode8: entropy-layer study"): what a faster entropy layer
// would save. For each stream, the values its range-coded sections yield (CLERS symbols, position residuals, §9.5
// signed integers: heights, patch headers, LERS) are captured from a traced copy of the decoder, then coded by
//   today   scheme (a): today's format (range coder, adaptive binary models; today_coding.h)
//   static  scheme (b): static per-stream tables, interleaved rANS, raw low bits, today's contexts (static_coding.h)
//   pooled  scheme (c): as (b) with pooled CLERS and residual contexts
// and each scheme's decoders are timed (CPU time of the thread, rounds alternating the schemes, best kept) on exactly
// those values, with the contexts taken from the capture. Every decode is checked against the capture.
// Second table: the whole decode (prm::codec::decode, the library's objects) against the same decoder with an oracle
// for §5 (oracle_decode.h: the captured decisions handed out with no arithmetic) and with a value oracle (CLERS
// symbols, residuals and §9.5 integers handed out whole, the other decisions as before), alternating: what the range
// coder's arithmetic and model updates, and what the whole entropy layer, cost inside the real decode; and with the
// values decoded by schemes (b) and (c) inside the decoder (rans_in_situ.h; the few other decisions from the oracle).
//
//   prm_bench_entropy_study [--rounds=N] FILE.prm...   table (markdown) of bytes and decode time per kind and scheme
//   prm_bench_entropy_study --check FILE.prm...        round trips only; exit 1 if a scheme mis-decodes a value
//   prm_bench_entropy_study --profile=WHAT:N FILE...   no timing, for callgrind: WHAT today, static or pooled decodes
//                                                      every kind N times with that scheme; real, oracle, values,
//                                                      static-in-decoder or pooled-in-decoder decodes the whole
//                                                      stream N times
// Exit codes: 0 ok, 1 a scheme mis-decoded (or a capture's own replay did not match), 2 bad usage or unreadable stream.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../cpu_time.h"
#include "oracle_decode.h"
#include "prm/codec.h"
#include "static_coding.h"
#include "today_coding.h"
#include "trace_capture.h"

namespace entropy_study {
namespace {

// CPU seconds of the thread natively; emscripten has no thread CPU clock, so the wasm build (bench/README.md,
// "hdecode8") reads the monotonic wall clock.
double seconds() {
#if defined(__EMSCRIPTEN__)
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
#else
  return prm::bench::thread_cpu_seconds();
#endif
}

enum Kind { kClers, kResiduals, kSigned, kKinds };
const char* const kKindName[kKinds] = {"CLERS", "residuals", "signed ints"};
enum Scheme { kToday, kStatic, kPooled, kSchemes };
const char* const kSchemeName[kSchemes] = {"(a) today", "(b) static rANS", "(c) static rANS, pooled"};
const char* const kSchemeArg[kSchemes] = {"today", "static", "pooled"};

// Today's modelled decisions and direct bits for the captured values (§6.5.1, §10.4.1, §9.5).
struct Work {
  uint64_t decisions = 0, direct = 0;
};
Work today_work(const Capture& c, Kind kind) {
  using namespace prm::codec;
  Work w;
  if (kind == kClers) {
    for (const ClersValue& v : c.clers)
      w.decisions += v.symbol == kC ? 1 : v.symbol == kR ? 2 : v.symbol == kS ? 3 : 3 + v.s_possible;
  } else if (kind == kResiduals) {
    std::vector<RiceState> rice(3 * kResidualContexts);
    uint32_t block = c.residuals.empty() ? 0 : c.residuals[0].block;
    for (const ResidualValue& v : c.residuals) {
      if (v.block != block) rice.assign(rice.size(), RiceState{}), block = v.block;
      const int k = rice[v.ctx].k();
      const uint64_t q = zigzag(v.r) >> k;
      w.decisions += (q < kUnaryEscape ? q + 1 : kUnaryEscape) + (k > 0);
      w.direct += (q >= kUnaryEscape ? kEscapeBits : 0) + (k > 1 ? k - 1 : 0);
      rice[v.ctx].update(static_cast<uint32_t>(v.r < 0 ? -v.r : v.r));
    }
  } else {
    for (const SignedValue& v : c.signed_ints) {
      ++w.decisions;
      if (v.v == 0) continue;
      const int e = int_class(static_cast<uint64_t>(v.v < 0 ? -v.v : v.v));
      w.decisions += 1 + e + (e < kMaxClass) + (e > 0);
      w.direct += e > 1 ? e - 1 : 0;
    }
  }
  return w;
}

// One stream's three kinds coded by the three schemes, with decoders that can be timed and checked.
struct Study {
  const Capture& c;
  std::vector<uint8_t> today[kKinds];
  ClersCoder clers_b{Contexts::today}, clers_c{Contexts::pooled};
  ResidualCoder residual_b{Contexts::today}, residual_c{Contexts::pooled};
  SignedCoder signed_b, signed_c;
  StaticStream stat[2][kKinds];
  std::vector<uint32_t> dense[2][kKinds + 1];  // per value, the dense context of (b), (c); last: the signs'
  in_situ::Input in_situ_input[2];              // (b), (c) inside the decoder (rans_in_situ.h)
  std::vector<uint8_t> out_clers;
  std::vector<int64_t> out_values;

  explicit Study(const Capture& capture) : c(capture) {
    today[kClers] = today_encode_clers(c.clers);
    today[kResiduals] = today_encode_residuals(c.residuals);
    today[kSigned] = today_encode_signed(c.signed_ints, c.signed_models, c.sign_models);
    stat[0][kClers] = clers_b.encode(c.clers);
    stat[1][kClers] = clers_c.encode(c.clers);
    stat[0][kResiduals] = residual_b.encode(c.residuals);
    stat[1][kResiduals] = residual_c.encode(c.residuals);
    stat[0][kSigned] = signed_b.encode(c.signed_ints);
    stat[1][kSigned] = signed_c.encode(c.signed_ints);
    for (int s = 0; s < 2; ++s) {
      const Contexts k = s == 0 ? Contexts::today : Contexts::pooled;
      const ClersCoder& cc = s == 0 ? clers_b : clers_c;
      const ResidualCoder& rc = s == 0 ? residual_b : residual_c;
      const SignedCoder& sc = s == 0 ? signed_b : signed_c;
      for (const ClersValue& v : c.clers) dense[s][kClers].push_back(cc.tables.dense(clers_context(v, k)));
      for (const ResidualValue& v : c.residuals) dense[s][kResiduals].push_back(rc.tables.dense(residual_context(v, k)));
      for (const SignedValue& v : c.signed_ints) {
        dense[s][kSigned].push_back(sc.magnitudes.dense(v.model));
        if (v.v != 0) dense[s][kKinds].push_back(sc.signs.dense(v.sign));
      }
      in_situ::KindStream* ks[kKinds] = {&in_situ_input[s].clers, &in_situ_input[s].residual,
                                         &in_situ_input[s].signed_int};
      const StaticTables* tables[kKinds] = {&cc.tables, &rc.tables, &sc.magnitudes};
      for (int kind = 0; kind < kKinds; ++kind) {
        const StaticStream& st = stat[s][kind];
        *ks[kind] = {st.words.data(), st.words.size(), st.raw.data(), st.raw.size(), tables[kind],
                     dense[s][kind].data(), nullptr, nullptr};
      }
      in_situ_input[s].signed_int.signs = &sc.signs;
      in_situ_input[s].signed_int.sign_ctx = dense[s][kKinds].data();
    }
    out_clers.resize(c.clers.size());
    out_values.resize(std::max(c.residuals.size(), c.signed_ints.size()));
  }
  size_t values(Kind k) const {
    return k == kClers ? c.clers.size() : k == kResiduals ? c.residuals.size() : c.signed_ints.size();
  }
  size_t bytes(Scheme s, Kind k) const { return s == kToday ? today[k].size() : stat[s - 1][k].bytes(); }
  size_t table_bytes(Scheme s, Kind k) const { return s == kToday ? 0 : stat[s - 1][k].table_bytes; }
  bool decode(Scheme s, Kind k) {
    if (values(k) == 0) return true;
    if (s == kToday) {
      if (k == kClers) return today_decode_clers(today[k], c.clers, out_clers.data());
      if (k == kResiduals) return today_decode_residuals(today[k], c.residuals, out_values.data());
      return today_decode_signed(today[k], c.signed_ints, c.signed_models, c.sign_models, out_values.data());
    }
    const StaticStream& st = stat[s - 1][k];
    if (k == kClers) return (s == kStatic ? clers_b : clers_c).decode(st, c.clers, out_clers.data());
    if (k == kResiduals) return (s == kStatic ? residual_b : residual_c).decode(st, c.residuals, out_values.data());
    return (s == kStatic ? signed_b : signed_c).decode(st, c.signed_ints, out_values.data());
  }
  // Decodes and compares with the capture.
  bool check(Scheme s, Kind k) {
    if (!decode(s, k)) return false;
    for (size_t i = 0; i < values(k); ++i) {
      const bool same = k == kClers ? out_clers[i] == c.clers[i].symbol
                        : k == kResiduals ? out_values[i] == c.residuals[i].r
                                          : out_values[i] == c.signed_ints[i].v;
      if (!same) return false;
    }
    return true;
  }
};

std::vector<uint8_t> read_file(const std::string& path, bool& ok) {
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ok = static_cast<bool>(in) || in.eof();
  return bytes;
}

std::string base_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The whole decode: the library's, with the §5 oracle, with the value oracle, with schemes (b) and (c) inside
// (oracle_decode.h).
enum Whole { kReal, kOracle, kValues, kRansB, kRansC, kWholes };
const char* const kWholeArg[kWholes] = {"real", "oracle", "values", "static-in-decoder", "pooled-in-decoder"};
bool whole_decode(Whole w, const std::vector<uint8_t>& bytes, const Study& st, std::vector<float>& positions,
                  std::vector<uint32_t>& triangles) {
  const Capture& c = st.c;
  if (w == kOracle) return oracle_decode(bytes.data(), bytes.size(), c, positions, triangles);
  if (w == kValues) return value_oracle_decode(bytes.data(), bytes.size(), c, positions, triangles);
  if (w == kRansB || w == kRansC)
    return rans_in_situ_decode(bytes.data(), bytes.size(), c, st.in_situ_input[w == kRansB ? 0 : 1], positions,
                               triangles);
  auto decoded = prm::codec::decode(bytes.data(), bytes.size());
  if (!decoded.ok()) return false;
  positions = std::move(decoded.value.positions_f32);
  triangles = std::move(decoded.value.triangles);
  return true;
}

int run(int argc, char** argv) {
  int rounds = 15, profile = 0;
  bool check_only = false;
  int profile_what = kToday;  // a Scheme, or kSchemes + a Whole
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--rounds=", 0) == 0) {
      rounds = std::max(1, std::atoi(a.c_str() + 9));
    } else if (a == "--check") {
      check_only = true;
    } else if (a.rfind("--profile=", 0) == 0) {
      const std::string v = a.substr(10);
      const size_t colon = v.find(':');
      const std::string what = v.substr(0, colon);
      int s = 0;
      while (s < kSchemes && what != kSchemeArg[s]) ++s;
      if (s == kSchemes)
        while (s < kSchemes + kWholes && what != kWholeArg[s - kSchemes]) ++s;
      if (colon == std::string::npos || s == kSchemes + kWholes) {
        std::fprintf(stderr, "--profile=WHAT:N: see --help\n");
        return 2;
      }
      profile_what = s;
      profile = std::max(1, std::atoi(v.c_str() + colon + 1));
    } else if (!a.empty() && a[0] != '-') {
      files.push_back(a);
    } else {
      std::fprintf(a == "--help" || a == "-h" ? stdout : stderr,
                   "usage: %s [--rounds=N | --check | --profile=WHAT:N] FILE.prm...\n"
                   "  WHAT: today, static, pooled (the entropy values alone), real, oracle, values, static-in-decoder,\n"
                   "  pooled-in-decoder (the whole decode)\n"
                   "exit codes: 0 ok, 1 a scheme mis-decoded, 2 bad usage or unreadable stream\n",
                   argv[0]);
      return a == "--help" || a == "-h" ? 0 : 2;
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "no stream given (--help)\n");
    return 2;
  }
  int status = 0;
  std::vector<std::string> oracle_rows;
  if (!check_only && !profile)
    std::printf("| stream | V | kind | values | decisions + direct bits today | scheme | bytes | of which tables | "
                "ns/value | ns/vertex |\n|---|---:|---|---:|---:|---|---:|---:|---:|---:|\n");
  for (const std::string& file : files) {
    bool ok = false;
    const std::vector<uint8_t> bytes = read_file(file, ok);
    Capture cap;
    std::string error;
    if (!ok || !capture_stream(bytes.data(), bytes.size(), cap, error)) {
      std::fprintf(stderr, "%s: %s\n", file.c_str(), ok ? error.c_str() : "cannot read");
      status = std::max(status, 2);
      continue;
    }
    Study st(cap);
    bool exact = true;
    for (int s = 0; s < kSchemes; ++s)
      for (int k = 0; k < kKinds; ++k)
        if (!st.check(static_cast<Scheme>(s), static_cast<Kind>(k))) {
          std::fprintf(stderr, "%s: %s mis-decodes the %s\n", file.c_str(), kSchemeName[s], kKindName[k]);
          exact = false;
        }
    std::vector<float> real_p, oracle_p;
    std::vector<uint32_t> real_t, oracle_t;
    if (!whole_decode(kReal, bytes, st, real_p, real_t)) exact = false;
    for (Whole w : {kOracle, kValues, kRansB, kRansC})
      if (!whole_decode(w, bytes, st, oracle_p, oracle_t) || real_p != oracle_p || real_t != oracle_t) {
        std::fprintf(stderr, "%s: the %s oracle's decode differs from the real one\n", file.c_str(), kWholeArg[w]);
        exact = false;
      }
    if (!exact) status = 1;
    Work all;
    for (int k = 0; k < kKinds; ++k) {
      const Work w = today_work(cap, static_cast<Kind>(k));
      all.decisions += w.decisions;
      all.direct += w.direct;
    }
    std::fprintf(stderr,
                 "%s: %zu bytes, V %zu, T %zu; %zu CLERS, %zu residuals, %zu signed (%u models, %u sign models); decode: "
                 "%llu decisions, %llu "
                 "direct bits (of which the captured values %llu, %llu); range-coded blocks:",
                 base_name(file).c_str(), bytes.size(), cap.vertices, cap.triangles, cap.clers.size(),
                 cap.residuals.size(), cap.signed_ints.size(), cap.signed_models, cap.sign_models,
                 static_cast<unsigned long long>(cap.decisions),
                 static_cast<unsigned long long>(cap.direct_bits), static_cast<unsigned long long>(all.decisions),
                 static_cast<unsigned long long>(all.direct));
    for (size_t b : cap.block_sizes) std::fprintf(stderr, " %zu", b);
    std::fprintf(stderr, "; today's replay: %zu, %zu, %zu bytes%s\n", st.today[kClers].size(),
                 st.today[kResiduals].size(), st.today[kSigned].size(), exact ? "" : " (MIS-DECODED)");
    if (check_only) continue;
    if (profile) {
      for (int r = 0; r < profile; ++r) {
        if (profile_what >= kSchemes)
          whole_decode(static_cast<Whole>(profile_what - kSchemes), bytes, st, oracle_p, oracle_t);
        else
          for (int k = 0; k < kKinds; ++k) st.decode(static_cast<Scheme>(profile_what), static_cast<Kind>(k));
      }
      continue;
    }
    // Rounds alternate the schemes (the starting one rotates); each timing runs the decoder for >= 20 ms.
    double best[kSchemes][kKinds];
    int inner[kSchemes][kKinds];
    for (auto& row : best) std::fill(row, row + kKinds, 1e30);
    for (auto& row : inner) std::fill(row, row + kKinds, 1);
    for (int r = 0; r < rounds; ++r)
      for (int i = 0; i < kSchemes; ++i) {
        const Scheme s = static_cast<Scheme>((i + r) % kSchemes);
        for (int k = 0; k < kKinds; ++k) {
          if (st.values(static_cast<Kind>(k)) == 0) continue;
          const double t0 = seconds();
          for (int n = 0; n < inner[s][k]; ++n) st.decode(s, static_cast<Kind>(k));
          const double t = (seconds() - t0) / inner[s][k];
          best[s][k] = std::min(best[s][k], t);
          inner[s][k] = static_cast<int>(std::clamp(0.02 / std::max(t, 1e-9), 1.0, 1e5));
        }
      }
    // The whole decode, real and with the two oracles, alternating (the first one rotates).
    double best_whole[kWholes];
    int inner_whole[kWholes];
    std::fill(best_whole, best_whole + kWholes, 1e30);
    std::fill(inner_whole, inner_whole + kWholes, 1);
    for (int r = 0; r < rounds; ++r)
      for (int i = 0; i < kWholes; ++i) {
        const Whole w = static_cast<Whole>((i + r) % kWholes);
        const double t0 = seconds();
        for (int n = 0; n < inner_whole[w]; ++n) (void)whole_decode(w, bytes, st, oracle_p, oracle_t);
        const double t = (seconds() - t0) / inner_whole[w];
        best_whole[w] = std::min(best_whole[w], t);
        inner_whole[w] = static_cast<int>(std::clamp(0.05 / std::max(t, 1e-9), 1.0, 1e5));
      }
    const double nv = static_cast<double>(cap.vertices);
    double ns[kWholes];
    for (int w = 0; w < kWholes; ++w) ns[w] = best_whole[w] * 1e9 / nv;
    const double real = ns[kReal];
    char row[512];
    std::snprintf(row, sizeof row,
                  "| %s | %zu | %llu + %llu | %.1f | %.1f (%.0f%%) | %.1f (%.0f%%) | %.1f (%.0f%%) | %.1f (%.0f%%) |\n",
                  base_name(file).c_str(), cap.vertices, static_cast<unsigned long long>(cap.decisions),
                  static_cast<unsigned long long>(cap.direct_bits), real, ns[kOracle],
                  100.0 * (real - ns[kOracle]) / real, ns[kValues], 100.0 * (real - ns[kValues]) / real, ns[kRansB],
                  100.0 * (real - ns[kRansB]) / real, ns[kRansC], 100.0 * (real - ns[kRansC]) / real);
    oracle_rows.push_back(row);
    for (int s = 0; s < kSchemes; ++s) {
      double total_ns = 0;
      size_t total_bytes = 0, total_tables = 0;
      for (int k = 0; k < kKinds; ++k) {
        const Kind kind = static_cast<Kind>(k);
        const size_t n = st.values(kind);
        const double ns = n ? best[s][k] * 1e9 : 0;
        total_ns += ns;
        total_bytes += st.bytes(static_cast<Scheme>(s), kind);
        total_tables += st.table_bytes(static_cast<Scheme>(s), kind);
        const Work w = today_work(cap, kind);
        std::printf("| %s | %zu | %s | %zu | %llu + %llu | %s | %zu | %zu | %.2f | %.1f |\n", base_name(file).c_str(),
                    cap.vertices, kKindName[k], n, static_cast<unsigned long long>(w.decisions),
                    static_cast<unsigned long long>(w.direct), kSchemeName[s], st.bytes(static_cast<Scheme>(s), kind),
                    st.table_bytes(static_cast<Scheme>(s), kind), n ? ns / static_cast<double>(n) : 0.0, ns / nv);
      }
      std::printf("| %s | %zu | **all three** | | | %s | %zu | %zu | | **%.1f** |\n", base_name(file).c_str(),
                  cap.vertices, kSchemeName[s], total_bytes, total_tables, total_ns / nv);
    }
    std::fflush(stdout);
  }
  if (!oracle_rows.empty()) {
    std::printf("\n| stream | V | decisions + direct bits | decode ns/vertex | with the §5 oracle (saved) | with the value "
                "oracle (saved) | with (b) inside (saved) | with (c) inside (saved) |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const std::string& row : oracle_rows) std::printf("%s", row.c_str());
  }
  return status;
}

}  // namespace
}  // namespace entropy_study

int main(int argc, char** argv) { return entropy_study::run(argc, argv); }
