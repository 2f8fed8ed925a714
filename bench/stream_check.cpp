// One line per stream for bench/zero_area_sweep.sh: what `prm pack` wrote, decoded and checked against what it
// remeshed (prm/pipeline/stream_check.h).
// Usage: prm_bench_stream_check INPUT_MESH STREAM.prm   prints "zero_area coincident turned vertices triangles"
#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

#include "prm/codec.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/stream_check.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s INPUT_MESH STREAM.prm\n", argv[0]);
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
  return 0;
}
