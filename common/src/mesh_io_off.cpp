// OFF (ASCII): "OFF" (or NOFF, COFF, CNOFF, STOFF...) then "V F E", V vertex lines and F face lines
// "n i1 .. in [colour]". Values after the first three coordinates of a vertex line and after a face's indices
// are ignored (normals, colours, texture coordinates). '#' starts a comment.
#include <cstdio>

#include "mesh_io_internal.h"
#include "text_scanner.h"

namespace prm::io {

RawMesh read_off(const std::string& path) {
  const std::vector<char> data = read_file(path);
  if (data.empty()) fail(path, "the file is empty");
  TextScanner in(data.data(), data.data() + data.size(), path, '#');
  RawMesh raw;
  in.collect_comments(&raw.comments);
  in.set_eof_hint("truncated, or the header's counts do not match the content");
  std::string_view head = in.token("the OFF keyword");
  // The keyword may carry prefixes (ST, C, N, 4, n) and may be followed by the counts on the same line.
  if (head.size() < 3 || head.substr(head.size() - 3) != "OFF")
    fail(path, "not an OFF file: it does not start with OFF");
  for (char c : head.substr(0, head.size() - 3)) {
    if (c == '4' || c == 'n')
      fail(path, "only 3-dimensional OFF files are supported ('" + std::string(head) + "')");
    if (c != 'S' && c != 'T' && c != 'C' && c != 'N')
      fail(path, "unknown OFF variant '" + std::string(head) + "'");
  }
  const int64_t nv = in.integer("the vertex count");
  const int64_t nf = in.integer("the face count");
  in.integer("the edge count");
  if (nv < 0 || nf < 0) in.fail("negative vertex or face count");
  if (static_cast<uint64_t>(nv) > kMaxElements || static_cast<uint64_t>(nf) > kMaxElements)
    in.fail("the counts (" + std::to_string(nv) + " vertices, " + std::to_string(nf) + " faces) exceed 2^31");
  // A vertex takes at least 6 characters ("0 0 0\n"), a face at least 8: a lying count is caught before
  // allocating.
  if (static_cast<uint64_t>(nv) * 6 + static_cast<uint64_t>(nf) * 8 > in.remaining())
    in.fail("the header claims " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
            " faces, but only " + std::to_string(in.remaining()) +
            " bytes follow (truncated or lying header)");
  raw.positions.resize(static_cast<size_t>(nv));
  raw.file_vertices = static_cast<size_t>(nv);
  for (int64_t v = 0; v < nv; ++v) {
    for (size_t a = 0; a < 3; ++a)
      raw.positions[static_cast<size_t>(v)][a] = in.number("a vertex coordinate");
    while (!in.at_line_end()) in.token("vertex extras");
  }
  std::vector<uint32_t> poly;
  for (int64_t f = 0; f < nf; ++f) {
    const int64_t n = in.integer("a face's corner count");
    if (n < 3) in.fail("face " + std::to_string(f) + " has " + std::to_string(n) + " corners (at least 3)");
    if (static_cast<uint64_t>(n) * 2 > in.remaining())
      in.fail("face " + std::to_string(f) + " runs past the end of the file");
    poly.resize(static_cast<size_t>(n));
    for (int64_t k = 0; k < n; ++k) {
      const int64_t i = in.integer("a vertex index");
      if (i < 0 || i >= nv)
        in.fail("face " + std::to_string(f) + " uses vertex " + std::to_string(i) + ", but there are " +
                std::to_string(nv) + " vertices");
      poly[static_cast<size_t>(k)] = static_cast<uint32_t>(i);
    }
    while (!in.at_line_end()) in.token("face extras");
    raw.add_polygon(poly.data(), poly.size());
  }
  raw.file_faces = static_cast<size_t>(nf);
  if (!in.at_end())
    raw.notes.push_back("text after the last of the " + std::to_string(nf) +
                        " faces the header announces was ignored (line " + std::to_string(in.line()) + ")");
  return raw;
}

void write_off(const Mesh& mesh, const std::string& path) {
  std::string out = "OFF\n";
  for (const std::string& c : mesh.comments)
    if (c.find('\n') == std::string::npos) out += "# " + c + "\n";
  out += std::to_string(mesh.positions.size()) + " " + std::to_string(mesh.triangles.size()) + " 0\n";
  for (const Vec3& p : mesh.positions) {
    for (size_t a = 0; a < 3; ++a) {
      if (a) out += ' ';
      append_number(out, p[a], false);  // shortest exact text: a write/read round trip is lossless
    }
    out += '\n';
  }
  for (const Tri& t : mesh.triangles)
    out += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
  write_file(path, out);
}

}  // namespace prm::io
