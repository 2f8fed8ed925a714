// libFuzzer target: the PRM sections (§7-§9) round trip on lattice meshes built from the input: a closed pillow of
// two hexagonal patches (test_meshes.h) whose size, grid, heights and off-lattice vertices come from the bytes.
// Every one must encode (with at least one regular triangle), decode to itself exactly at every height depth and
// with linear prediction (§9.7), and decode identically from the encoder's chosen coding; with the encoder's choice
// of heights (spec Appendix B), unrounded values and lambda from the bytes, it must decode to a mesh within the
// tolerance of them that differs from the input in one coordinate per vertex at most. One of these eleven codings is
// tried per input, chosen by its fourth byte, so that an execution costs one encode and one decode (libFuzzer then
// explores the codings as it explores the meshes; trying all eleven per input made the target eleven times slower).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "prm/codec.h"
#include "test_meshes.h"

using namespace prm::codec;

namespace {

struct Input {
  const uint8_t* data;
  size_t size;
  int64_t at(size_t i) const { return size ? data[i % size] : 0; }
};

int64_t top(int i, int j, const void* user) {
  const Input& in = *static_cast<const Input*>(user);
  return 2048 + 8 * (in.at(static_cast<size_t>(7 * (i + 40) + 13 * (j + 40))) - 128) + 3 * i - 2 * j;
}
int64_t bottom(int i, int j, const void* user) {
  const Input& in = *static_cast<const Input*>(user);
  return 1024 - (in.at(static_cast<size_t>(11 * (i + 40) + 5 * (j + 40))) % 64);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 4) return 0;
  const int variant = data[3] % 11;  // 0..9: height depth -1..8 below; 10: the encoder's choice of heights
  const Input in{data + 4, size - 4};
  const int r = 1 + data[0] % 9;
  const int64_t grid = 2 + data[1] % 30;
  std::vector<std::array<int, 2>> moved;
  for (size_t k = 0; k < data[2] % 8 && k < in.size; ++k)
    moved.push_back({static_cast<int>(in.at(k) % (2 * r + 1)) - r, static_cast<int>(in.at(k + 1) % (2 * r + 1)) - r});
  const prm::codec::test::QuantizedMesh m = prm::codec::test::lattice_pillow(r, grid, top, bottom, &in, moved);
  Frame f;
  f.bits = 12;
  // -1: the encoder's choice; 0..6 difference patches; 7 linear prediction (§9.7), also forced on every patch.
  if (variant < 10) {
    const int depth = variant - 1;
    PrmOptions o;
    o.grid = grid;
    o.height_depth = depth == 8 ? 7 : depth;
    o.predict_every_patch = depth == 8;
    o.patch_contexts = (depth + data[0]) % 2 == 0;  // format 1.4's patch contexts (§8.4.1, §9.7.4) or not
    EncodeReport rep;
    const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), f, o, &rep);
    if (!enc.ok() || rep.regular_triangles == 0) __builtin_trap();
    DecodeOptions opt;
    opt.positions = PositionOutput::quantized_only;
    const auto dec = decode(enc.value.data(), enc.value.size(), opt);
    if (!dec.ok() || dec.value.num_vertices() != m.nv() || dec.value.num_triangles() != m.nt()) __builtin_trap();
    for (size_t k = 0; k < m.nv(); ++k)
      for (int a = 0; a < 3; ++a)
        if (dec.value.quantized[3 * k + a] != m.q[3 * size_t{rep.vertex_order[k]} + a]) __builtin_trap();
    return 0;
  }
  std::vector<double> unrounded(m.q.size());
  for (size_t i = 0; i < m.q.size(); ++i)
    unrounded[i] = static_cast<double>(m.q[i]) + (static_cast<double>(in.at(3 * i + 1)) - 127.5) / 256.0;
  PrmOptions o;
  o.grid = grid;
  o.height_tolerance = 0.5 + static_cast<double>(data[2] >> 3) / 8.0;   // 0.5 .. 4.375 steps
  o.height_lambda = std::ldexp(1.0, data[1] % 12 - 6);                   // 2^-6 .. 2^5
  o.unrounded = unrounded.data();
  o.height_sweeps = data[0] / 9 % 5;  // spec Appendix B.2: 0 (one by one) .. 4 sweeps
  EncodeReport rep;
  const auto enc = encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), f, o, &rep);
  if (!enc.ok()) __builtin_trap();
  DecodeOptions opt;
  opt.positions = PositionOutput::quantized_only;
  const auto dec = decode(enc.value.data(), enc.value.size(), opt);
  if (!dec.ok() || dec.value.num_vertices() != m.nv() || dec.value.num_triangles() != m.nt()) __builtin_trap();
  for (size_t k = 0; k < m.nv(); ++k) {
    int differing = 0;
    for (int a = 0; a < 3; ++a) {
      const size_t i = 3 * size_t{rep.vertex_order[k]} + a;
      const uint32_t got = dec.value.quantized[3 * k + a];
      differing += got != m.q[i];
      if (std::fabs(static_cast<double>(got) - unrounded[i]) > o.height_tolerance + 1e-9) __builtin_trap();
    }
    if (differing > 1) __builtin_trap();
  }
  return 0;
}
