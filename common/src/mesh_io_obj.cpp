// OBJ through tinyobjloader (MIT; Debian's libtinyobjloader-dev): positions and faces of every group, polygons
// triangulated by read_mesh(); materials and texture coordinates are ignored (no .mtl is opened).
#include <cstdio>

#include <tiny_obj_loader.h>

#include "mesh_io_internal.h"

namespace prm::io {

RawMesh read_obj(const std::string& path) {
  const std::vector<char> data = read_file(path);
  if (data.empty()) fail(path, "the file is empty");
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // read_mesh() triangulates (ear clipping) and counts the polygons
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  const bool ok = reader.ParseFromString(std::string(data.begin(), data.end()), "", config);
  if (!ok) {
    std::string err = reader.Error();
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    fail(path, "malformed OBJ: " + (err.empty() ? std::string("tinyobjloader failed") : err));
  }
  RawMesh raw;
  const auto& attrib = reader.GetAttrib();
  const size_t nv = attrib.vertices.size() / 3;
  raw.positions.resize(nv);
  for (size_t v = 0; v < nv; ++v)
    for (size_t a = 0; a < 3; ++a) raw.positions[v][a] = attrib.vertices[3 * v + a];
  raw.file_vertices = nv;
  std::vector<uint32_t> poly;
  for (const auto& shape : reader.GetShapes()) {
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const size_t n = shape.mesh.num_face_vertices[f];
      poly.clear();
      for (size_t k = 0; k < n; ++k) {
        const int idx = shape.mesh.indices[offset + k].vertex_index;
        if (idx < 0 || static_cast<size_t>(idx) >= nv)
          fail(path, "face " + std::to_string(raw.num_polygons()) + " uses vertex " + std::to_string(idx + 1) +
                         " (1-based), but there are " + std::to_string(nv) + " vertices");
        poly.push_back(static_cast<uint32_t>(idx));
      }
      offset += n;
      if (n < 3) fail(path, "face " + std::to_string(raw.num_polygons()) + " has " + std::to_string(n) + " corners");
      raw.add_polygon(poly.data(), n);
    }
  }
  raw.file_faces = raw.num_polygons();
  if (raw.num_polygons() == 0) fail(path, "the file has no faces");
  const std::string& warn = reader.Warning();
  if (!warn.empty()) raw.notes.push_back("tinyobjloader: " + warn.substr(0, warn.find('\n')));
  return raw;
}

void write_obj(const Mesh& mesh, const std::string& path) {
  std::string out = "# written by prm\n";
  char buf[96];
  for (const Vec3& p : mesh.positions) {
    std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]);
    out += buf;
  }
  for (const Tri& t : mesh.triangles)
    out += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  write_file(path, out);
}

}  // namespace prm::io
