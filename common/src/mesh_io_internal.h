// Shared pieces of the format readers and writers (common/src/mesh_io_*.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prm/error.h"
#include "prm/mesh.h"
#include "prm/mesh_io.h"

namespace prm::io {

// What a reader produces before cleanup: positions and polygons (any corner count >= 3), with per-vertex and
// per-polygon properties, and notes for the report.
struct RawMesh {
  std::vector<Vec3> positions;
  std::vector<uint32_t> corners;        // polygon corners, concatenated
  std::vector<uint32_t> polygon_start;  // polygon k is corners[polygon_start[k] .. polygon_start[k+1])
  std::vector<Property> vertex_properties;
  std::vector<Property> face_properties;  // per polygon
  std::vector<std::string> comments;
  size_t file_vertices = 0, file_faces = 0, strip_triangles = 0;
  std::vector<std::string> notes;

  RawMesh() { polygon_start.push_back(0); }
  size_t num_polygons() const { return polygon_start.size() - 1; }
  void add_polygon(const uint32_t* c, size_t n) {
    corners.insert(corners.end(), c, c + n);
    polygon_start.push_back(static_cast<uint32_t>(corners.size()));
  }
};

// The whole file in memory. Throws IoError when it cannot be opened or read.
std::vector<char> read_file(const std::string& path);
void write_file(const std::string& path, const std::string& bytes);

// The shortest decimal text that reads back to exactly v (as a float when as_float, else as a double): text
// formats round-trip exactly.
void append_number(std::string& out, double v, bool as_float);

// "<path>: <what>" for messages.
[[noreturn]] void fail(const std::string& path, const std::string& what);

// Polygon k of raw: checks indices against the vertex count (names the file, polygon and index on failure).
void check_indices(const RawMesh& raw, const std::string& path);
// Throws when a position is NaN or infinite.
void check_finite(const RawMesh& raw, const std::string& path);

// Triangulates (ear clipping in the polygon's plane; fan for triangles and convex quads), drops triangles
// with a repeated index, welds, drops unreferenced vertices; fills the report.
Mesh finish_mesh(RawMesh raw, const ReadOptions& options, bool weld_auto, ReadReport& report);

RawMesh read_obj(const std::string& path);
RawMesh read_ply(const std::string& path, bool keep_properties);
RawMesh read_off(const std::string& path);
RawMesh read_stl(const std::string& path);
RawMesh read_gltf(const std::string& path);

void write_obj(const Mesh& mesh, const std::string& path);
void write_ply(const Mesh& mesh, const std::string& path, const WriteOptions& options);
void write_off(const Mesh& mesh, const std::string& path);
void write_glb(const Mesh& mesh, const std::string& path, bool binary);

// Limits that keep a lying header from asking for absurd amounts of memory.
constexpr uint64_t kMaxElements = uint64_t{1} << 31;

}  // namespace prm::io
