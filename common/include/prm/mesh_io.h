// Reading and writing triangle meshes: OBJ, PLY (ASCII and binary), OFF, STL (ASCII and binary), glTF/GLB.
// Every reader is safe on hostile files: a malformed, truncated or lying file throws prm::InputError whose message
// names the file, the problem and where it is; nothing is allocated before the data is seen to exist.
#pragma once

#include <string>
#include <vector>

#include "prm/mesh.h"

namespace prm {

enum class MeshFormat { Auto, Obj, Ply, Off, Stl, Gltf, Glb };

struct ReadOptions {
  MeshFormat format = MeshFormat::Auto;  // Auto: from the file extension, then from the content
  // Coincident vertices are welded: exact position match when weld_tolerance == 0 (the default), otherwise
  // vertices closer than weld_tolerance (absolute units) are merged. Auto welds the formats that store a vertex per
  // corner or per primitive (STL, glTF/GLB), which need it to be connected, and leaves the indexed formats as they are.
  enum class Weld { Auto, Always, Never };
  Weld weld = Weld::Auto;
  double weld_tolerance = 0.0;
  bool drop_unreferenced = true;  // vertices no face uses are removed (and counted in the report)
  bool keep_properties = true;    // PLY: keep extra per-vertex / per-face scalar properties
};

// What the reader did to the file's content to make it a triangle mesh.
struct ReadReport {
  MeshFormat format = MeshFormat::Auto;
  size_t file_vertices = 0;           // vertex records in the file
  size_t file_faces = 0;              // face records (polygons, strips) in the file
  size_t polygons_triangulated = 0;   // faces with more than three corners, split into triangles
  size_t strip_triangles = 0;         // triangles decoded from triangle strips
  size_t vertices_welded = 0;         // vertices merged into an earlier coincident one
  size_t unreferenced_dropped = 0;    // vertices no face used
  size_t degenerate_dropped = 0;      // faces with a repeated index (e.g. strip restarts), never kept
  std::vector<std::string> notes;     // anything else worth telling the user
};

Mesh read_mesh(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);

struct WriteOptions {
  MeshFormat format = MeshFormat::Auto;  // Auto: from the extension (.obj .ply .off .glb .gltf)
  bool binary = true;                    // PLY: binary little-endian (true) or ASCII
  bool double_positions = false;         // PLY: write positions as double instead of float
  bool write_properties = true;          // PLY: write the mesh's vertex/face properties
};

void write_mesh(const Mesh& mesh, const std::string& path, const WriteOptions& options = {});

MeshFormat format_from_path(const std::string& path);
const char* format_name(MeshFormat format);

}  // namespace prm
