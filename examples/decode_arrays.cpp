// Decodes a .prm stream into flat arrays with the C++ API (prm/codec.h) and prints what it got.
#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

#include "prm/codec.h"

int main(int argc, char** argv) {
  if (argc != 2) return std::fprintf(stderr, "usage: decode_arrays FILE.prm\n"), 1;
  std::ifstream in(argv[1], std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const prm::codec::Result<prm::codec::DecodedMesh> r = prm::codec::decode(bytes.data(), bytes.size());
  if (!r.ok())
    return std::fprintf(stderr, "%s: %s (byte %llu, spec section %s)\n", prm::codec::error_name(r.status.error),
                        r.status.message.c_str(), static_cast<unsigned long long>(r.status.byte_offset),
                        r.status.spec_section), 2;
  const std::vector<float>& xyz = r.value.positions_f32;     // 3 per vertex
  const std::vector<uint32_t>& tris = r.value.triangles;     // 3 per triangle
  std::printf("prm %s: %zu vertices, %zu triangles, first vertex %g %g %g\n", prm::codec::library_version_string(),
              xyz.size() / 3, tris.size() / 3, xyz[0], xyz[1], xyz[2]);
  return 0;
}
