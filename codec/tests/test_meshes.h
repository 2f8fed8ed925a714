// Meshes for the codec tests: generators (exact, integer-friendly positions) and a small loader for the real
// meshes (OFF, OBJ, PLY; polygons fan-triangulated), independent of prm_common so the codec tests build alone.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

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

// Loads OFF/OBJ/PLY (ASCII or binary little-endian; PLY tristrips too). Throws std::runtime_error on failure.
TestMesh load_mesh(const std::string& path);

// Independent manifold check: returns "" when every edge has one or two triangles with opposite orientations,
// no triangle repeats a vertex and every vertex has one fan; otherwise what is wrong.
std::string manifold_problem(const TestMesh& mesh);

std::vector<std::string> list_files(const std::string& dir, const std::vector<std::string>& extensions);

}  // namespace prm::codec::test
