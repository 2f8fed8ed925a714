// Round-trip checking shared by the codec tests.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "prm/codec.h"
#include "test_meshes.h"

namespace prm::codec::test {

// Encodes `m` with `bits`, decodes, and checks: the triangles are the input's (through the report's vertex and
// triangle order and corner rotation), and the positions are the quantized input exactly.
inline ::testing::AssertionResult round_trip(const TestMesh& m, int bits = 12, EncodeReport* report_out = nullptr,
                                             std::vector<uint8_t>* stream_out = nullptr, int seam_context = -1) {
  EncodeOptions opt;
  opt.position_bits = bits;
  opt.seam_context = seam_context;
  EncodeReport rep;
  auto enc = encode(m.xyz.data(), m.num_vertices(), m.triangles.data(), m.num_triangles(), opt, &rep);
  if (!enc.ok())
    return ::testing::AssertionFailure() << "encode: " << error_name(enc.status.error) << " §"
                                         << enc.status.spec_section << ": " << enc.status.message;
  DecodeOptions dopt;
  dopt.positions = PositionOutput::float64;
  auto dec = decode(enc.value.data(), enc.value.size(), dopt);
  if (!dec.ok())
    return ::testing::AssertionFailure() << "decode: " << error_name(dec.status.error) << " §"
                                         << dec.status.spec_section << " at " << dec.status.byte_offset << ": "
                                         << dec.status.message;
  const DecodedMesh& d = dec.value;
  if (d.num_triangles() != m.num_triangles())
    return ::testing::AssertionFailure() << "triangles " << d.num_triangles() << " != " << m.num_triangles();
  if (d.num_vertices() != rep.vertex_order.size() || rep.triangle_order.size() != m.num_triangles())
    return ::testing::AssertionFailure() << "report sizes";
  std::vector<uint32_t> inverse(m.num_vertices(), UINT32_MAX);
  for (size_t v = 0; v < rep.vertex_order.size(); ++v) {
    if (rep.vertex_order[v] >= m.num_vertices() || inverse[rep.vertex_order[v]] != UINT32_MAX)
      return ::testing::AssertionFailure() << "vertex_order is not a permutation of the used vertices";
    inverse[rep.vertex_order[v]] = static_cast<uint32_t>(v);
  }
  std::vector<uint8_t> seen(m.num_triangles(), 0);
  for (size_t t = 0; t < d.num_triangles(); ++t) {
    const uint32_t in = rep.triangle_order[t];
    if (in >= m.num_triangles() || seen[in]++) return ::testing::AssertionFailure() << "triangle_order";
    for (int k = 0; k < 3; ++k) {
      const uint32_t expect = inverse[m.triangles[3 * in + (rep.triangle_rotation[t] + k) % 3]];
      if (d.triangles[3 * t + k] != expect)
        return ::testing::AssertionFailure() << "triangle " << t << " corner " << k << ": " << d.triangles[3 * t + k]
                                             << " != " << expect;
    }
  }
  const Frame f = make_frame(m.xyz.data(), m.num_vertices(), bits);
  for (int k = 0; k < 3; ++k)
    if (d.frame.origin[k] != f.origin[k]) return ::testing::AssertionFailure() << "frame origin";
  if (d.frame.step != f.step || d.frame.bits != bits) return ::testing::AssertionFailure() << "frame step/bits";
  for (size_t v = 0; v < d.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) {
      const uint32_t q = quantize(m.xyz[3 * rep.vertex_order[v] + k], f.origin[k], f.step, bits);
      if (d.quantized[3 * v + k] != q)
        return ::testing::AssertionFailure() << "vertex " << v << " axis " << k << ": " << d.quantized[3 * v + k]
                                             << " != " << q;
      if (d.positions_f64[3 * v + k] != dequantize(q, f.origin[k], f.step))
        return ::testing::AssertionFailure() << "dequantized position";
    }
  if (report_out) *report_out = rep;
  if (stream_out) *stream_out = enc.value;
  return ::testing::AssertionSuccess();
}

}  // namespace prm::codec::test
