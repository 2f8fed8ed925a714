// Meshes for the codec tests: generators (exact, integer-friendly positions) and a small loader for the real
// meshes (OFF, OBJ, PLY; polygons fan-triangulated), independent of prm_common so the codec tests build alone.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "prm/codec.h"

namespace prm::codec::test {

struct TestMesh {
  std::vector<double> xyz;         // 3 per vertex
  std::vector<uint32_t> triangles; // 3 per triangle
  size_t num_vertices() const { return xyz.size() / 3; }
  size_t num_triangles() const { return triangles.size() / 3; }
};

TestMesh icosphere(int subdivisions);                 // subdivided icosahedron (regular: valence 6 but 12)
TestMesh torus(int n, int m);                         // n x m grid on a torus, all valence 6
TestMesh plate_with_holes(int genus, int refine);     // closed polycube plate with `genus` square holes
TestMesh hex_patch(int radius, bool bumpy);           // hexagon of the triangular lattice (one boundary loop)
TestMesh sphere_with_holes(int subdivisions, int holes);
TestMesh concat(const std::vector<TestMesh>& parts);  // several components
TestMesh tetrahedron();
TestMesh single_triangle();

// A mesh with quantized positions, for the PRM sections (§7-§9).
struct QuantizedMesh {
  std::vector<uint32_t> q;     // 3 per vertex
  std::vector<uint32_t> tris;  // 3 per triangle
  size_t nv() const { return q.size() / 3; }
  size_t nt() const { return tris.size() / 3; }
};

// A closed "pillow" on the lattice of axis pair 2 (height z) with grid size `grid` (>= 2): a hexagon of radius r of
// lattice points facing +z on top (heights top(i, j)), the same hexagon facing -z below (heights bottom(i, j)) and a
// band of side triangles between their rims. Every top and bottom triangle is regular (§7.1), the band is not.
// Each (i, j) listed in `moved` has its top vertex moved one step along x, off the lattice.
// The frame of lattice meshes coded as they are: 12 bits, origin 0, step 1 (a quantized value is the position).
inline Frame unit_frame() {
  Frame f;
  f.bits = 12;
  f.origin = {0, 0, 0};
  f.step = 1;
  return f;
}

QuantizedMesh lattice_pillow(int r, int64_t grid, int64_t (*top)(int, int, const void*),
                             int64_t (*bottom)(int, int, const void*), const void* user,
                             const std::vector<std::array<int, 2>>& moved);

// Loads OFF/OBJ/PLY (ASCII or binary little-endian; PLY tristrips too). Throws std::runtime_error on failure.
TestMesh load_mesh(const std::string& path);

// Independent manifold check: returns "" when every edge has one or two triangles with opposite orientations,
// no triangle repeats a vertex and every vertex has one fan; otherwise what is wrong.
std::string manifold_problem(const TestMesh& mesh);

// FNV-1a 64 of uint32 words taken as their little-endian bytes, chained from `h` (the golden streams' and the
// conformance vectors' hash of the triangles, then the quantized positions).
uint64_t fnv1a64_words(const std::vector<uint32_t>& words, uint64_t h = 1469598103934665603ull);

std::vector<std::string> list_files(const std::string& dir, const std::vector<std::string>& extensions);

}  // namespace prm::codec::test
