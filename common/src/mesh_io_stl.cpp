// STL, binary (80-byte header, uint32 count, 50 bytes per triangle) and ASCII ("solid ... facet ... vertex x
// y z"). A file is binary when its size is exactly 84 + 50 n for the count n it states, even if it starts
// with "solid". STL stores every corner separately: read_mesh() welds coincident corners (exactly, by
// default).
#include <algorithm>
#include <cctype>
#include <cstring>

#include "mesh_io_internal.h"
#include "text_scanner.h"

namespace prm::io {

RawMesh read_stl(const std::string& path) {
  const std::vector<char> data = read_file(path);
  if (data.empty()) fail(path, "the file is empty");
  RawMesh raw;
  uint32_t count = 0;
  if (data.size() >= 84) std::memcpy(&count, data.data() + 80, 4);
  const bool binary = data.size() >= 84 && data.size() == 84 + 50 * static_cast<uint64_t>(count);
  // Binary files often start with "solid" too: one whose first bytes are not text is binary whatever its
  // header says.
  bool text = true;
  for (size_t i = 0; i < std::min<size_t>(data.size(), 512) && text; ++i) {
    const unsigned char c = static_cast<unsigned char>(data[i]);
    text = c >= 32 ? c < 127 : (c == '\n' || c == '\r' || c == '\t' || c == '\f' || c == '\v');
  }
  const bool starts_solid = data.size() >= 5 && std::memcmp(data.data(), "solid", 5) == 0 && text;
  if (binary) {
    raw.positions.reserve(size_t{3} * count);
    for (uint32_t t = 0; t < count; ++t) {
      const char* rec = data.data() + 84 + 50 * static_cast<size_t>(t) + 12;  // skip the normal
      uint32_t c[3];
      for (int k = 0; k < 3; ++k) {
        float xyz[3];
        std::memcpy(xyz, rec + 12 * k, 12);
        c[k] = static_cast<uint32_t>(raw.positions.size());
        raw.positions.push_back({xyz[0], xyz[1], xyz[2]});
      }
      raw.add_polygon(c, 3);
    }
    raw.file_faces = count;
  } else if (starts_solid) {
    TextScanner in(data.data(), data.data() + data.size(), path);
    in.token("solid");
    // The name runs to the end of the line.
    in.skip_line();
    std::vector<uint32_t> loop;
    bool ended = false;
    while (!in.at_end()) {
      const std::string_view t = in.token("a keyword");
      if (t == "facet" || t == "normal") {
        if (t == "facet") loop.clear();
        continue;
      }
      if (t == "outer" || t == "loop") continue;
      if (t == "vertex") {
        Vec3 p;
        for (double& c : p) c = in.number("a vertex coordinate");
        loop.push_back(static_cast<uint32_t>(raw.positions.size()));
        raw.positions.push_back(p);
        continue;
      }
      if (t == "endloop") {
        if (loop.size() != 3)
          in.fail("a facet has " + std::to_string(loop.size()) + " vertices (STL facets have 3)");
        raw.add_polygon(loop.data(), 3);
        loop.clear();
        continue;
      }
      if (t == "endfacet") continue;
      if (t == "endsolid") {
        ended = true;
        in.skip_line();
        continue;
      }
      if (t == "solid") {  // several solids in one file
        in.skip_line();
        continue;
      }
      // Facet normals are numbers after "normal"; anything else is malformed.
      if (!t.empty() &&
          (std::isdigit(static_cast<unsigned char>(t[0])) || t[0] == '-' || t[0] == '+' || t[0] == '.'))
        continue;
      in.fail("unexpected '" + std::string(t.substr(0, 40)) + "' in an ASCII STL file");
    }
    if (!ended) fail(path, "the ASCII STL has no endsolid (truncated)");
    raw.file_faces = raw.num_polygons();
  } else {
    if (data.size() >= 84)
      fail(path, "binary STL size is " + std::to_string(data.size()) + " bytes, but its header states " +
                     std::to_string(count) + " triangles (" + std::to_string(84 + 50 * uint64_t{count}) +
                     " bytes): truncated or not an STL file");
    fail(path, "not an STL file (" + std::to_string(data.size()) +
                   " bytes: too short for binary STL, no 'solid' keyword)");
  }
  raw.file_vertices = raw.positions.size();
  return raw;
}

}  // namespace prm::io
