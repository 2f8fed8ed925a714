// prm_bench_boundary_distance INPUT DECODED: how far the boundary of DECODED (a mesh file or a .prm stream) lies from
// the boundary of INPUT (issue 22): the RMS and the largest distance of DECODED's boundary vertices to INPUT's
// boundary polyline, in model units and as fractions of INPUT's bounding-box diagonal; and both meshes' boundary
// loops and vertices. Used by bench/open_boundary_table.sh.
#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "prm/boundary_deviation.h"
#include "prm/codec.h"
#include "prm/mesh_io.h"
#include "prm/mesh_validate.h"
#include "prm/pipeline/codec_bridge.h"

namespace {

prm::Mesh read_any(const std::string& path) {
  if (path.size() > 4 && path.compare(path.size() - 4, 4, ".prm") == 0) {
    std::ifstream f(path, std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const auto decoded = prm::codec::decode(bytes.data(), bytes.size());
    if (!decoded.ok()) throw std::runtime_error(path + ": " + decoded.status.message);
    return prm::pipeline::to_mesh(decoded.value);
  }
  return prm::read_mesh(path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s INPUT DECODED(.prm or mesh)\n", argv[0]);
    return 1;
  }
  try {
    const prm::Mesh in = prm::read_mesh(argv[1]), out = read_any(argv[2]);
    const prm::MeshReport a = prm::validate_mesh(in), b = prm::validate_mesh(out);
    const prm::BoundaryDeviation d = prm::boundary_deviation(in, out);
    std::printf("loops %zu -> %zu, boundary edges %zu -> %zu, boundary distance RMS %.3e max %.3e of the diagonal "
                "(%.6g, %.6g model units)\n",
                a.boundary_loops, b.boundary_loops, a.boundary_edges, b.boundary_edges, d.rms / a.diagonal,
                d.max / a.diagonal, d.rms, d.max);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
