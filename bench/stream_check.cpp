// One line per stream for bench/zero_area_sweep.sh: what `prm pack` wrote, decoded and checked against what it
// remeshed (prm/pipeline/stream_check.h).
// Usage: prm_bench_stream_check INPUT_MESH STREAM.prm [--list]
//   prints "zero_area coincident turned vertices triangles"; --list then prints one line per turned triangle: its
//   index, its corners (decoded, quantized), its unit normal, and the unit normal of the reference's nearest triangle.
#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

#include <cmath>
#include <cstring>

#include "prm/aabb_tree.h"
#include "prm/codec.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/vec3.h"
#include "prm/pipeline/stream_check.h"

using prm::operator*;
using prm::operator+;

int main(int argc, char** argv) {
  const bool list = argc == 4 && std::strcmp(argv[3], "--list") == 0;
  if (argc != 3 && !list) {
    std::fprintf(stderr, "usage: %s INPUT_MESH STREAM.prm [--list]\n", argv[0]);
    return 1;
  }
  std::ifstream in(argv[2], std::ios::binary);
  const std::vector<uint8_t> stream((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto decoded = prm::codec::decode(stream.data(), stream.size());
  if (!decoded.ok()) {
    std::printf("does not decode: %s\n", decoded.status.message.c_str());
    return 2;
  }
  const prm::Mesh reference = prm::pipeline::pack_reference(prm::read_mesh(argv[1]));
  const prm::pipeline::StreamCheck c = prm::pipeline::check_decoded(decoded.value, &reference);
  std::printf("%zu %zu %zu %zu %zu\n", c.zero_area, c.coincident, c.turned, decoded.value.num_vertices(),
              decoded.value.num_triangles());
  if (!list) return 0;
  // The same test as check_decoded's, each turned triangle printed.
  const prm::Mesh m = prm::pipeline::to_mesh(decoded.value);
  const prm::AabbTree tree(reference);
  auto unit = [](const prm::Vec3& v) {
    const double l = std::sqrt(prm::dot(v, v));
    return l > 0 ? v * (1.0 / l) : v;
  };
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    const prm::Tri& t = m.triangles[f];
    const prm::Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &d = m.positions[t[2]];
    const auto hit = tree.closest((a + b + d) * (1.0 / 3.0));
    const prm::Tri& s = reference.triangles[hit.face];
    const prm::Vec3 sn = prm::triangle_normal_area2(reference.positions[s[0]], reference.positions[s[1]],
                                                    reference.positions[s[2]]);
    const prm::Vec3 n = prm::triangle_normal_area2(a, b, d);
    if (prm::dot(n, sn) > 0) continue;
    std::printf("turned %zu:", f);
    for (uint32_t v : t)
      std::printf(" (%u %u %u)", decoded.value.quantized[3 * size_t{v}], decoded.value.quantized[3 * size_t{v} + 1],
                  decoded.value.quantized[3 * size_t{v} + 2]);
    const prm::Vec3 un = unit(n), us = unit(sn);
    std::printf(" normal (%.3f %.3f %.3f) reference face %u normal (%.3f %.3f %.3f)\n", un[0], un[1], un[2],
                static_cast<unsigned>(hit.face), us[0], us[1], us[2]);
  }
  return 0;
}
