// Reading and writing triangle meshes: OBJ, PLY (ASCII and binary), OFF, STL (ASCII and binary), glTF/GLB.
// Every reader is safe on hostile files: a malformed, truncated or lying file throws prm::InputError whose
// message names the file, the problem and where it is (line, element, vertex or face); a missing or
// unreadable file throws prm::IoError. Nothing is allocated for a count before the bytes it needs are seen to
// exist; NaN and infinite coordinates and indices out of range are refused; a file without faces is refused.
//
// What each reader reads:
// - OBJ (tinyobjloader for the faces): v and f lines of every object and group; negative (relative) indices
//   and the v/vt/vn corner forms; every v and f line is first checked by a strict scan, whose correctly
//   rounded doubles are the positions. Texture coordinates, normals and materials are ignored. '#' comments
//   are kept.
// - PLY (hand-written): ASCII, binary little and big endian; x y z of any scalar type; faces from
//   'vertex_indices' or 'vertex_index' lists of element 'face', or triangle strips of element 'tristrips' (-1
//   restarts a strip, parity restarts with it, triangles repeating a vertex are skipped); other scalar
//   vertex/face properties are kept as prm::Property (face properties are copied to every triangle of a
//   polygon); unknown elements are skipped; comments are kept.
// - OFF: OFF and its variants (NOFF, COFF, CNOFF, STOFF...: values after x y z and after a face's indices are
//   ignored); counts on the keyword line or the next; '#' comments are kept; text after the last face is
//   reported.
// - STL: binary when the size is exactly 84 + 50 n for the count n at byte 80 (even if it starts with
//   "solid"), ASCII when it starts with "solid" and looks like text.
// - glTF/GLB (tinygltf, compiled privately): the positions and indices of every TRIANGLES, TRIANGLE_STRIP and
//   TRIANGLE_FAN primitive of every mesh, placed by the node transforms (matrix or TRS, composed down the
//   hierarchy) of the default scene (or scene 0); a mesh used by several nodes appears once per node; a
//   mirroring transform flips its triangles to keep them outward; meshes no node uses are read untransformed.
//   POSITION is float VEC3 or quantized (KHR_mesh_quantization); no Draco or meshopt data (`prm unpack` decodes
//   those). Points and lines are skipped and noted.
// Then, for every format: polygons are triangulated (ear clipping in the polygon's plane; a fan for polygons
// above 256 corners or that cannot be clipped), coincident vertices are welded (see ReadOptions), faces with
// a repeated vertex are dropped and unreferenced vertices removed, all counted in ReadReport.
#pragma once

#include <string>
#include <vector>

#include "prm/mesh.h"

namespace prm {

enum class MeshFormat { Auto, Obj, Ply, Off, Stl, Gltf, Glb };

struct ReadOptions {
  MeshFormat format = MeshFormat::Auto;  // Auto: from the file extension, then from the content
  // Coincident vertices are welded: exact position match when weld_tolerance == 0 (the default), otherwise
  // vertices closer than weld_tolerance (absolute units) are merged. Auto welds the formats that store a
  // vertex per corner or per primitive (STL, glTF/GLB), which need it to be connected, and leaves the indexed
  // formats as they are.
  enum class Weld { Auto, Always, Never };
  Weld weld = Weld::Auto;
  double weld_tolerance = 0.0;
  bool drop_unreferenced = true;  // vertices no face uses are removed (and counted in the report)
  bool keep_properties = true;    // PLY: keep extra per-vertex / per-face scalar properties
};

// What the reader did to the file's content to make it a triangle mesh.
struct ReadReport {
  MeshFormat format = MeshFormat::Auto;
  size_t file_vertices = 0;          // vertex records in the file
  size_t file_faces = 0;             // face records (polygons, strips) in the file
  size_t polygons_triangulated = 0;  // faces with more than three corners, split into triangles
  size_t strip_triangles = 0;        // triangles decoded from triangle strips
  size_t vertices_welded = 0;        // vertices merged into an earlier coincident one
  size_t unreferenced_dropped = 0;   // vertices no face used
  size_t degenerate_dropped = 0;     // faces with a repeated index (e.g. strip restarts), never kept
  std::vector<std::string> notes;    // anything else worth telling the user
};

Mesh read_mesh(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);

struct WriteOptions {
  MeshFormat format = MeshFormat::Auto;  // Auto: from the extension (.obj .ply .off .glb .gltf)
  bool binary = true;                    // PLY: binary little-endian (true) or ASCII
  bool double_positions = false;         // PLY: write positions as double instead of float
  bool write_properties = true;          // PLY: write the mesh's vertex/face properties
};

// Writes OBJ, PLY, OFF, GLB or .gltf (buffer embedded). Text formats write the shortest decimal that reads
// back to the same double (PLY float properties: the same float), so a write/read round trip is exact; GLB
// stores float positions. PLY carries the comments and, with write_properties, every vertex and face property
// (std::invalid_argument if a value does not fit its type); OBJ and OFF carry comments as '#' lines. Throws
// IoError when the file cannot be written, InputError for a format that cannot be written (STL) and
// std::invalid_argument for a triangle index out of range.
void write_mesh(const Mesh& mesh, const std::string& path, const WriteOptions& options = {});

MeshFormat format_from_path(const std::string& path);
const char* format_name(MeshFormat format);

}  // namespace prm
