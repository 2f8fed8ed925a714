// OBJ through tinyobjloader (MIT; Debian's libtinyobjloader-dev): positions and faces of every group,
// polygons triangulated by read_mesh(); materials, normals and texture coordinates are ignored (no .mtl is
// opened). Relative (negative) indices and the v/vt/vn corner forms are resolved by tinyobjloader.
#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "mesh_io_internal.h"
#include "text_scanner.h"

namespace prm::io {
namespace {

// tinyobjloader turns what it cannot parse into zeros ("v nan 0 0", "v 1 2" and "v abc 0 0" all give 0),
// wraps indices that overflow an int, and parses numbers into floats (or, in its double build, not correctly
// rounded), so every v and f line is checked here first and a bad one is refused with its line named. The
// positions are taken from this pass (correctly rounded doubles: a written OBJ reads back exactly);
// tinyobjloader resolves the faces. Also collects the '#' comments.
void scan_obj_text(const std::vector<char>& data, const std::string& path, RawMesh& raw) {
  TextScanner in(data.data(), data.data() + data.size(), path, '#');
  in.collect_comments(&raw.comments);
  int64_t vertices = 0;
  while (!in.at_end()) {
    const std::string_view key = in.token("a keyword");
    if (key == "v") {
      int n = 0;
      Vec3 p{0, 0, 0};
      while (!in.at_line_end()) {
        const double x = in.parse_double(in.token("a coordinate"), "a vertex coordinate");
        if (!std::isfinite(x))
          in.fail("vertex " + std::to_string(vertices + 1) + " has a non-finite coordinate (NaN or inf)");
        if (n < 3) p[static_cast<size_t>(n)] = x;
        ++n;
      }
      if (n < 3)
        in.fail("vertex " + std::to_string(vertices + 1) + " has " + std::to_string(n) +
                " coordinates (3 needed)");
      raw.positions.push_back(p);
      ++vertices;
    } else if (key == "f") {
      int64_t corners = 0;
      while (!in.at_line_end()) {
        const std::string_view t = in.token("a face corner");
        const int64_t i = in.parse_int(t.substr(0, t.find('/')), "a vertex index");
        if (i == 0) in.fail("vertex index 0 (OBJ indices start at 1)");
        if (i > INT32_MAX || i < -INT32_MAX)
          in.fail("vertex index " + std::to_string(i) + " is out of range");
        if (i < 0 && -i > vertices)
          in.fail("relative vertex index " + std::to_string(i) + " reaches before the first vertex (" +
                  std::to_string(vertices) + " vertices so far)");
        ++corners;
      }
      if (corners < 3) in.fail("a face has " + std::to_string(corners) + " corners (at least 3)");
    } else {
      in.skip_line();
    }
  }
}

}  // namespace

RawMesh read_obj(const std::string& path) {
  const std::vector<char> data = read_file(path);
  if (data.empty()) fail(path, "the file is empty");
  RawMesh raw;
  scan_obj_text(data, path, raw);
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
  const size_t nv = raw.positions.size();
  if (reader.GetAttrib().vertices.size() != 3 * nv)
    fail(path, "tinyobjloader found " + std::to_string(reader.GetAttrib().vertices.size() / 3) +
                   " vertices, the " + "line scan " + std::to_string(nv) +
                   " (a line form neither reads the same way)");
  raw.file_vertices = nv;
  std::vector<uint32_t> poly;
  for (const auto& shape : reader.GetShapes()) {
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const size_t n = shape.mesh.num_face_vertices[f];
      if (offset + n > shape.mesh.indices.size()) fail(path, "tinyobjloader returned inconsistent face data");
      poly.clear();
      for (size_t k = 0; k < n; ++k) {
        const int idx = shape.mesh.indices[offset + k].vertex_index;
        if (idx < 0 || static_cast<size_t>(idx) >= nv)
          fail(path, "face " + std::to_string(raw.num_polygons() + 1) + " uses vertex " +
                         std::to_string(idx + 1) + ", but there are only " + std::to_string(nv) +
                         " vertices");
        poly.push_back(static_cast<uint32_t>(idx));
      }
      offset += n;
      if (n < 3)
        fail(path,
             "face " + std::to_string(raw.num_polygons() + 1) + " has " + std::to_string(n) + " corners");
      raw.add_polygon(poly.data(), n);
    }
  }
  raw.file_faces = raw.num_polygons();
  // Index warnings are covered by the checks above; keep the others (e.g. a missing material library).
  std::string warn = reader.Warning();
  for (size_t b = 0; b < warn.size();) {
    size_t e = warn.find('\n', b);
    if (e == std::string::npos) e = warn.size();
    const std::string w = warn.substr(b, e - b);
    if (!w.empty() && w != "." && w.find("indices out of bounds") == std::string::npos)
      raw.notes.push_back("tinyobjloader: " + w);
    b = e + 1;
  }
  return raw;
}

void write_obj(const Mesh& mesh, const std::string& path) {
  std::string out;
  for (const std::string& c : mesh.comments)
    if (c.find('\n') == std::string::npos) out += "# " + c + "\n";
  for (const Vec3& p : mesh.positions) {
    out += 'v';
    for (double x : p) {
      out += ' ';
      append_number(out, x, false);  // shortest exact text: a write/read round trip is lossless
    }
    out += '\n';
  }
  for (const Tri& t : mesh.triangles)
    out += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) +
           "\n";
  write_file(path, out);
}

}  // namespace prm::io
