// libFuzzer target: encode -> decode round trip (§6, §10) on meshes built from the input. Most inputs are not
// manifold and must be refused with a named error; every accepted mesh must decode to itself exactly, and
// re-encoding the decoded mesh must give the same bytes.
#include <cstdint>
#include <cstring>
#include <vector>

#include "prm/codec.h"

using namespace prm::codec;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const uint32_t nv = 3 + data[0] % 61;
  const int bits = 8 + data[1] % 13;
  std::vector<uint32_t> q(3 * nv);
  for (uint32_t i = 0; i < 3 * nv; ++i) q[i] = (i * 2654435761u ^ (size > 2 ? data[2 + i % (size - 2)] : 0)) & ((1u << bits) - 1);
  std::vector<uint32_t> tris;
  for (size_t i = 2; i + 2 < size; i += 3)
    for (int k = 0; k < 3; ++k) tris.push_back(data[i + k] % nv);
  Frame f;
  f.bits = bits;
  EncodeReport rep;
  const auto enc = encode_quantized(q.data(), nv, tris.data(), tris.size() / 3, f, &rep);
  if (!enc.ok()) {
    if (enc.status.error == Error::internal) __builtin_trap();
    return 0;
  }
  DecodeOptions opt;
  opt.positions = PositionOutput::quantized_only;
  const auto dec = decode(enc.value.data(), enc.value.size(), opt);
  if (!dec.ok()) __builtin_trap();
  const auto& d = dec.value;
  if (d.num_triangles() != tris.size() / 3) __builtin_trap();
  std::vector<uint32_t> inverse(nv, UINT32_MAX);
  for (size_t v = 0; v < rep.vertex_order.size(); ++v) inverse[rep.vertex_order[v]] = static_cast<uint32_t>(v);
  for (size_t t = 0; t < d.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      if (d.triangles[3 * t + k] != inverse[tris[3 * rep.triangle_order[t] + (rep.triangle_rotation[t] + k) % 3]])
        __builtin_trap();
  for (size_t v = 0; v < d.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k)
      if (d.quantized[3 * v + k] != q[3 * rep.vertex_order[v] + k]) __builtin_trap();
  // Re-encoding the decoded mesh reproduces the stream: the canonical order is a fixed point.
  const auto again = encode_quantized(d.quantized.data(), d.num_vertices(), d.triangles.data(), d.num_triangles(), d.frame);
  if (!again.ok() || again.value != enc.value) __builtin_trap();
  return 0;
}
