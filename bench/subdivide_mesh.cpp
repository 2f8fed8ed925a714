// Large test meshes for the scale bench (bench/README.md, "Scale"): midpoint subdivision, each level splitting every
// triangle into four at its edge midpoints. The surface does not change (every new vertex lies on an input edge),
// so a remesh at one target error has the same output size at every level: only the input grows, 4x per level.
// Usage: prm_bench_subdivide INPUT_MESH LEVELS OUTPUT.ply   (binary PLY, float positions; prints V and F per level)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <utility>
#include <vector>

#include "prm/mesh.h"
#include "prm/mesh_io.h"

namespace {

// One level: the new vertex of an edge is numbered once, by sorting the 3F half-edges by their (lower, higher) key.
prm::Mesh subdivide_midpoints(const prm::Mesh& in) {
  const size_t nf = in.triangles.size();
  std::vector<std::pair<uint64_t, uint32_t>> half_edges(3 * nf);  // (edge key, 3 * face + corner)
  for (size_t f = 0; f < nf; ++f) {
    for (int c = 0; c < 3; ++c) {
      const uint64_t a = in.triangles[f][c], b = in.triangles[f][(c + 1) % 3];
      half_edges[3 * f + c] = {(std::min(a, b) << 32) | std::max(a, b), static_cast<uint32_t>(3 * f + c)};
    }
  }
  std::sort(half_edges.begin(), half_edges.end());
  prm::Mesh out;
  out.positions = in.positions;
  std::vector<uint32_t> midpoint(3 * nf);
  for (size_t i = 0; i < half_edges.size(); ++i) {
    if (i == 0 || half_edges[i].first != half_edges[i - 1].first) {
      const prm::Vec3& p = in.positions[half_edges[i].first >> 32];
      const prm::Vec3& q = in.positions[half_edges[i].first & 0xffffffffu];
      out.positions.push_back({(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2});
    }
    midpoint[half_edges[i].second] = static_cast<uint32_t>(out.positions.size() - 1);
  }
  out.triangles.reserve(4 * nf);
  for (size_t f = 0; f < nf; ++f) {
    const prm::Tri& t = in.triangles[f];
    const uint32_t m0 = midpoint[3 * f], m1 = midpoint[3 * f + 1], m2 = midpoint[3 * f + 2];  // edges 01, 12, 20
    out.triangles.push_back({t[0], m0, m2});
    out.triangles.push_back({t[1], m1, m0});
    out.triangles.push_back({t[2], m2, m1});
    out.triangles.push_back({m0, m1, m2});
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s INPUT_MESH LEVELS OUTPUT.ply\n", argv[0]);
    return 1;
  }
  try {
    prm::Mesh mesh = prm::read_mesh(argv[1]);
    mesh.vertex_properties.clear();
    mesh.face_properties.clear();
    std::printf("level 0: V %zu F %zu\n", mesh.num_vertices(), mesh.num_faces());
    const int levels = std::atoi(argv[2]);
    for (int level = 1; level <= levels; ++level) {
      mesh = subdivide_midpoints(mesh);
      std::printf("level %d: V %zu F %zu\n", level, mesh.num_vertices(), mesh.num_faces());
    }
    prm::write_mesh(mesh, argv[3]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prm_bench_subdivide: %s\n", e.what());
    return 2;
  }
  return 0;
}
