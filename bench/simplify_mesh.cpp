// prm_bench_simplify: meshoptimizer's simplifier as the "simplify" of the simplify + Draco baseline of the
// rate-distortion curves (bench/README.md, "Rate-distortion curves"; bench/rd_curves.py drives it).
// Reads any mesh prm reads, simplifies it to at most TRIANGLES triangles with meshopt_simplify (edge collapses under
// a quadric error, no error limit: target_error = 1 of meshoptimizer's scale, no locked borders), and writes the
// result with the unused vertices dropped (.ply binary float positions, .obj or .off by extension). If
// meshopt_simplify stalls above the requested count (it refuses collapses that would flip or pinch the surface), the
// result is simplified further by meshopt_simplifySloppy (vertex clustering) and the tool says so on stderr and in
// its summary line. A TRIANGLES at or above the input's count writes the input unchanged (a plain PLY of any input).
//
// Usage: prm_bench_simplify INPUT TRIANGLES OUTPUT
// Prints one line on stdout: "input_triangles=N output_triangles=M output_vertices=V sloppy=0|1".
// Exit codes: 0 done, 1 usage, 2 unreadable input or unwritable output.
#include <meshoptimizer.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "prm/mesh.h"
#include "prm/mesh_io.h"

namespace {

// The simplified index buffer as a mesh of only the vertices it uses (in first-use order).
prm::Mesh compact(const prm::Mesh& in, const std::vector<unsigned>& indices) {
  prm::Mesh out;
  std::vector<unsigned> remap(in.positions.size(), ~0u);
  out.triangles.reserve(indices.size() / 3);
  for (size_t i = 0; i < indices.size(); i += 3) {
    prm::Tri t;
    for (int c = 0; c < 3; ++c) {
      unsigned& r = remap[indices[i + c]];
      if (r == ~0u) {
        r = static_cast<unsigned>(out.positions.size());
        out.positions.push_back(in.positions[indices[i + c]]);
      }
      t[c] = r;
    }
    out.triangles.push_back(t);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s INPUT TRIANGLES OUTPUT\n", argv[0]);
    return 1;
  }
  char* end = nullptr;
  const long long requested = std::strtoll(argv[2], &end, 10);
  if (*argv[2] == '\0' || *end != '\0' || requested < 1) {
    std::fprintf(stderr, "prm_bench_simplify: TRIANGLES must be a positive integer, not '%s'\n", argv[2]);
    return 1;
  }
  try {
    prm::Mesh mesh = prm::read_mesh(argv[1]);
    mesh.vertex_properties.clear();
    mesh.face_properties.clear();
    mesh.comments.clear();
    const size_t nf = mesh.num_faces();
    std::vector<float> xyz;
    xyz.reserve(3 * mesh.num_vertices());
    for (const prm::Vec3& p : mesh.positions)
      for (double c : p) xyz.push_back(static_cast<float>(c));
    std::vector<unsigned> indices;
    indices.reserve(3 * nf);
    for (const prm::Tri& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());

    bool sloppy = false;
    const size_t target_indices = 3 * static_cast<size_t>(requested);
    if (target_indices < indices.size()) {
      std::vector<unsigned> out(indices.size());
      size_t n = meshopt_simplify(out.data(), indices.data(), indices.size(), xyz.data(), mesh.num_vertices(),
                                  3 * sizeof(float), target_indices, 1.0f, 0, nullptr);
      if (n > target_indices) {
        std::fprintf(stderr, "prm_bench_simplify: meshopt_simplify stalled at %zu triangles (asked %lld): "
                             "finishing with meshopt_simplifySloppy\n", n / 3, requested);
        std::vector<unsigned> coarse(n);
        n = meshopt_simplifySloppy(coarse.data(), out.data(), n, xyz.data(), mesh.num_vertices(), 3 * sizeof(float),
                                   target_indices, 1.0f, nullptr);
        out.assign(coarse.begin(), coarse.begin() + static_cast<std::ptrdiff_t>(n));
        sloppy = true;
      }
      out.resize(n);
      indices.swap(out);
    }
    const prm::Mesh result = compact(mesh, indices);
    prm::write_mesh(result, argv[3]);
    std::printf("input_triangles=%zu output_triangles=%zu output_vertices=%zu sloppy=%d\n", nf,
                result.num_faces(), result.num_vertices(), sloppy ? 1 : 0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prm_bench_simplify: %s\n", e.what());
    return 2;
  }
  return 0;
}
