// prm_bench_decode: decode speed per vertex of PRM streams against Draco's decoder on the same mesh (bench/README.md,
// "Decode speed per vertex"). For each .prm file: our decoder (prm::codec::decode, float positions out) and Draco
// 1.5.5 (edgebreaker) at compression level 10 (Table 1's setting, its smallest streams) and at level 7
// (draco_encoder's default, whose decoder is faster: hweb2 measured 1.8x on feline_5k) decoding the mesh our stream
// decodes to, quantized at the stream's bit depth on the stream's own grid (explicit quantization with our origin and (2^b - 1) x our step, as Table 1's S_r: Draco then
// reproduces the decoded mesh exactly). Times are CPU seconds of the thread (cpu_time.h: this 2-core machine is shared),
// interleaved rounds (PRM, Draco 10, Draco 7, PRM, ...), best round kept; per vertex of the decoded mesh.
//
//   prm_bench_decode [--rounds=N] FILE.prm...
//   prm_bench_decode --profile=N FILE.prm...   only our decoder, N times per file, no timing (for callgrind or perf)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cpu_time.h"
#include "draco_codec.h"
#include "prm/codec.h"
#include "prm/mesh.h"

int main(int argc, char** argv) {
  int rounds = 15, profile = 0;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--rounds=", 0) == 0)
      rounds = std::max(1, std::atoi(a.c_str() + 9));
    else if (a.rfind("--profile=", 0) == 0)
      profile = std::max(1, std::atoi(a.c_str() + 10));
    else if (!a.empty() && a[0] != '-')
      files.push_back(a);
    else {
      std::fprintf(stderr, "usage: %s [--rounds=N | --profile=N] FILE.prm...\n", argv[0]);
      return a == "--help" || a == "-h" ? 0 : 1;
    }
  }
  std::printf("| stream | bytes | V | T | bits | PRM ms | PRM ns/vertex | Draco B (cl 10) | Draco ms | Draco ns/vertex | "
              "vertices/s PRM/Draco | Draco B (cl 7) | Draco cl 7 ms | Draco cl 7 ns/vertex | vertices/s PRM/Draco cl 7 "
              "|\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  int status = 0;
  for (const std::string& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto decoded = prm::codec::decode(bytes.data(), bytes.size());
    if (!in || !decoded.ok()) {
      std::fprintf(stderr, "%s: %s\n", file.c_str(), in ? decoded.status.message.c_str() : "cannot read");
      status = 2;
      continue;
    }
    if (profile > 0) {
      for (int k = 0; k < profile; ++k) (void)prm::codec::decode(bytes.data(), bytes.size());
      continue;
    }
    const prm::codec::DecodedMesh& d = decoded.value;
    prm::Mesh mesh;
    const size_t nv = d.positions_f32.size() / 3, nt = d.triangles.size() / 3;
    mesh.positions.resize(nv);
    for (size_t v = 0; v < nv; ++v)
      for (size_t k = 0; k < 3; ++k) mesh.positions[v][k] = d.positions_f32[3 * v + k];
    mesh.triangles.resize(nt);
    for (size_t t = 0; t < nt; ++t)
      for (size_t k = 0; k < 3; ++k) mesh.triangles[t][k] = d.triangles[3 * t + k];
    prm::bench::DracoGrid grid;
    for (size_t a = 0; a < 3; ++a) grid.origin[a] = static_cast<float>(d.frame.origin[a]);
    grid.range = static_cast<float>(d.frame.step * static_cast<double>((1 << d.frame.bits) - 1));
    std::string why;
    auto draco = prm::bench::DracoCodec(10, d.frame.bits, grid).start(mesh, &why);
    auto draco7 = prm::bench::DracoCodec(7, d.frame.bits, grid).start(mesh, &why);
    if (!draco || !draco->encode() || !draco->decode() || !draco7 || !draco7->encode() || !draco7->decode()) {
      std::fprintf(stderr, "%s: Draco: %s\n", file.c_str(), why.c_str());
      status = 3;
      continue;
    }
    double ours = HUGE_VAL, theirs = HUGE_VAL, theirs7 = HUGE_VAL;
    for (int r = 0; r < rounds; ++r) {
      ours = std::min(ours, prm::bench::best_cpu_time([&] { (void)prm::codec::decode(bytes.data(), bytes.size()); }, 2));
      theirs = std::min(theirs, prm::bench::best_cpu_time([&] { (void)draco->decode(); }, 2));
      theirs7 = std::min(theirs7, prm::bench::best_cpu_time([&] { (void)draco7->decode(); }, 2));
    }
    const double per_v = 1e9 / static_cast<double>(nv);
    std::printf("| %s | %zu | %zu | %zu | %d | %.3f | %.1f | %zu | %.3f | %.1f | %.2f | %zu | %.3f | %.1f | %.2f |\n",
                file.c_str(), bytes.size(), nv, nt, d.frame.bits, 1e3 * ours, ours * per_v, draco->stream_bytes(),
                1e3 * theirs, theirs * per_v, theirs / ours, draco7->stream_bytes(), 1e3 * theirs7, theirs7 * per_v,
                theirs7 / ours);
    std::fflush(stdout);
  }
  return status;
}
