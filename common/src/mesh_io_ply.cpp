// PLY, ASCII and binary (little and big endian): vertices (x, y, z and any scalar properties), faces
// (vertex_indices / vertex_index lists, scalar properties) and triangle strips (igea.ply: one list with -1
// restarts). Hand-written: no Debian library reads tristrips and arbitrary typed properties with bounded
// allocation.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "mesh_io_internal.h"
#include "text_scanner.h"

namespace prm::io {
namespace {

enum class Encoding { Ascii, BinaryLittle, BinaryBig };

struct PlyProperty {
  std::string name;
  ScalarType type = ScalarType::Float32;
  bool is_list = false;
  ScalarType count_type = ScalarType::UInt8;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

size_t type_size(ScalarType t) {
  switch (t) {
    case ScalarType::Int8:
    case ScalarType::UInt8:
      return 1;
    case ScalarType::Int16:
    case ScalarType::UInt16:
      return 2;
    case ScalarType::Int32:
    case ScalarType::UInt32:
    case ScalarType::Float32:
      return 4;
    case ScalarType::Float64:
      return 8;
  }
  return 1;
}

bool parse_type(const std::string& s, ScalarType& t) {
  static const struct {
    const char* name;
    ScalarType type;
  } kTypes[] = {
      {"char", ScalarType::Int8},      {"int8", ScalarType::Int8},       {"uchar", ScalarType::UInt8},
      {"uint8", ScalarType::UInt8},    {"short", ScalarType::Int16},     {"int16", ScalarType::Int16},
      {"ushort", ScalarType::UInt16},  {"uint16", ScalarType::UInt16},   {"int", ScalarType::Int32},
      {"int32", ScalarType::Int32},    {"uint", ScalarType::UInt32},     {"uint32", ScalarType::UInt32},
      {"float", ScalarType::Float32},  {"float32", ScalarType::Float32}, {"double", ScalarType::Float64},
      {"float64", ScalarType::Float64}};
  for (const auto& k : kTypes)
    if (s == k.name) {
      t = k.type;
      return true;
    }
  return false;
}

const char* type_name(ScalarType t) {
  switch (t) {
    case ScalarType::Int8:
      return "char";
    case ScalarType::UInt8:
      return "uchar";
    case ScalarType::Int16:
      return "short";
    case ScalarType::UInt16:
      return "ushort";
    case ScalarType::Int32:
      return "int";
    case ScalarType::UInt32:
      return "uint";
    case ScalarType::Float32:
      return "float";
    case ScalarType::Float64:
      return "double";
  }
  return "float";
}

std::string number_text(double v) {
  std::string s;
  append_number(s, v, false);
  return s;
}

// Whether v is a value of type t (integers in range; any float, NaN included, for the float types).
bool fits(ScalarType t, double v) {
  auto in = [&](double lo, double hi) { return v >= lo && v <= hi && v == std::floor(v); };
  switch (t) {
    case ScalarType::Int8:
      return in(-128, 127);
    case ScalarType::UInt8:
      return in(0, 255);
    case ScalarType::Int16:
      return in(-32768, 32767);
    case ScalarType::UInt16:
      return in(0, 65535);
    case ScalarType::Int32:
      return in(-2147483648.0, 2147483647.0);
    case ScalarType::UInt32:
      return in(0, 4294967295.0);
    case ScalarType::Float32:
      return !std::isfinite(v) || std::fabs(v) <= 3.4028234663852886e38;
    case ScalarType::Float64:
      return true;
  }
  return false;
}

// Reads the values of a file body: binary or ASCII, one scalar at a time.
class BodyReader {
 public:
  BodyReader(const std::vector<char>& data, size_t offset, Encoding enc, const std::string& path)
      : data_(data),
        pos_(offset),
        enc_(enc),
        path_(path),
        text_(data.data() + offset, data.data() + data.size(), path) {
    text_.set_eof_hint("truncated, or the header's counts do not match the content");
    text_.set_line(static_cast<size_t>(
                       std::count(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(offset), '\n')) +
                   1);
  }

  double read(ScalarType t, const char* what) {
    if (enc_ == Encoding::Ascii) {
      const std::string_view tok = text_.token(what);
      // A float property holds float values: the text of one is rounded as the binary form would be.
      if (t == ScalarType::Float32) {
        const double v = text_.parse_double(tok, what);
        if (!fits(t, v))
          text_.fail("'" + std::string(tok.substr(0, 40)) + "' does not fit a float (" + what + ")");
        return static_cast<float>(v);
      }
      if (t == ScalarType::Float64) return text_.parse_double(tok, what);
      const double v = static_cast<double>(text_.parse_int(tok, what));
      if (!fits(t, v))
        text_.fail(std::to_string(text_.parse_int(tok, what)) + " does not fit a " + type_name(t) + " (" +
                   what + ")");
      return v;
    }
    const size_t n = type_size(t);
    if (pos_ + n > data_.size())
      fail(path_, std::string("the file ends inside ") + what +
                      " (truncated, or the header's counts do not match the content)");
    unsigned char b[8];
    std::memcpy(b, data_.data() + pos_, n);
    pos_ += n;
    if (enc_ == Encoding::BinaryBig) std::reverse(b, b + n);
    switch (t) {
      case ScalarType::Int8: {
        int8_t v;
        std::memcpy(&v, b, 1);
        return v;
      }
      case ScalarType::UInt8:
        return b[0];
      case ScalarType::Int16: {
        int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case ScalarType::UInt16: {
        uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case ScalarType::Int32: {
        int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case ScalarType::UInt32: {
        uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case ScalarType::Float32: {
        float v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case ScalarType::Float64: {
        double v;
        std::memcpy(&v, b, 8);
        return v;
      }
    }
    return 0;
  }
  size_t remaining() const { return enc_ == Encoding::Ascii ? text_.remaining() : data_.size() - pos_; }
  bool ascii() const { return enc_ == Encoding::Ascii; }
  bool at_end() { return enc_ == Encoding::Ascii ? text_.at_end() : pos_ >= data_.size(); }

 private:
  const std::vector<char>& data_;
  size_t pos_;
  Encoding enc_;
  const std::string& path_;
  TextScanner text_;
};

// The fewest bytes an element can take: lists may be empty, ASCII values take at least two characters.
uint64_t min_element_bytes(const PlyElement& e, Encoding enc) {
  uint64_t n = 0;
  for (const PlyProperty& p : e.properties)
    n += enc == Encoding::Ascii ? 2 : type_size(p.is_list ? p.count_type : p.type);
  return std::max<uint64_t>(n, 1);
}

}  // namespace

RawMesh read_ply(const std::string& path, bool keep_properties) {
  const std::vector<char> data = read_file(path);
  RawMesh raw;
  // Header.
  size_t line_start = 0;
  auto next_line = [&](std::string& line) {
    if (line_start >= data.size())
      fail(path, "the header has no end_header line (truncated or not a PLY file)");
    size_t e = line_start;
    while (e < data.size() && data[e] != '\n') ++e;
    line.assign(data.data() + line_start, e - line_start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    line_start = std::min(e + 1, data.size());  // a last line without a line break ends at the end
    if (line.size() > 4096) fail(path, "a header line is longer than 4096 characters (not a PLY header)");
  };
  std::string line;
  next_line(line);
  if (line != "ply") fail(path, "not a PLY file: the first line is not 'ply'");
  Encoding enc = Encoding::Ascii;
  bool have_format = false;
  std::vector<PlyElement> elements;
  size_t header_lines = 0;
  for (;;) {
    next_line(line);
    if (++header_lines > 100000) fail(path, "the header has more than 100000 lines");
    std::istringstream in(line);
    std::string key;
    in >> key;
    if (key.empty()) continue;
    if (key == "end_header") break;
    if (key == "format") {
      std::string f, v;
      in >> f >> v;
      if (f == "ascii")
        enc = Encoding::Ascii;
      else if (f == "binary_little_endian")
        enc = Encoding::BinaryLittle;
      else if (f == "binary_big_endian")
        enc = Encoding::BinaryBig;
      else
        fail(path, "unknown PLY format '" + f + "'");
      have_format = true;
    } else if (key == "comment" || key == "obj_info") {
      if (key == "comment") raw.comments.push_back(line.size() > 8 ? line.substr(8) : std::string());
    } else if (key == "element") {
      PlyElement e;
      std::string count;
      in >> e.name >> count;
      if (count.empty() || count[0] == '-')
        fail(path, "element '" + e.name + "' has a negative or missing count");
      char* end = nullptr;
      const unsigned long long c = std::strtoull(count.c_str(), &end, 10);
      if (*end != '\0') fail(path, "element '" + e.name + "' has count '" + count + "', not a number");
      if (c > kMaxElements)
        fail(path, "element '" + e.name + "' claims " + count + " entries (at most 2^31)");
      e.count = c;
      // One element of each kind the reader uses: a second 'vertex' or 'face' (or 'face' with 'tristrips') would give
      // the polygons or vertices properties of another length (found by common/fuzz/mesh_read_fuzzer.cpp).
      for (const PlyElement& o : elements) {
        const bool face_like = e.name == "face" || e.name == "tristrips";
        if ((e.name == "vertex" || face_like) && o.name == e.name)
          fail(path, "element '" + e.name + "' appears twice in the header");
        if (face_like && (o.name == "face" || o.name == "tristrips"))
          fail(path, "elements 'face' and 'tristrips' together: the faces are one or the other");
      }
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) fail(path, "a property comes before any element");
      PlyProperty p;
      std::string t;
      in >> t;
      if (t == "list") {
        std::string ct, it;
        in >> ct >> it >> p.name;
        if (!parse_type(ct, p.count_type) || !parse_type(it, p.type))
          fail(path, "unknown type in 'property list " + ct + " " + it + "'");
        if (p.count_type == ScalarType::Float32 || p.count_type == ScalarType::Float64)
          fail(path, "a list count must be an integer type");
        p.is_list = true;
      } else {
        in >> p.name;
        if (!parse_type(t, p.type)) fail(path, "unknown property type '" + t + "'");
      }
      if (p.name.empty()) fail(path, "a property has no name");
      elements.back().properties.push_back(p);
    } else {
      fail(path, "unknown header keyword '" + key + "'");
    }
  }
  if (!have_format) fail(path, "the header has no format line");

  BodyReader body(data, line_start, enc, path);
  bool have_vertices = false;
  size_t strip_skipped = 0;
  for (const PlyElement& e : elements) {
    // A lying count: the bytes left cannot hold it. Checked before anything is allocated.
    const uint64_t need = e.count * min_element_bytes(e, enc);
    if (need > body.remaining())
      fail(path, "element '" + e.name + "' claims " + std::to_string(e.count) + " entries but only " +
                     std::to_string(body.remaining()) + " bytes follow (truncated or lying header)");
    const bool is_vertex = e.name == "vertex";
    const bool is_face = e.name == "face";
    const bool is_strips = e.name == "tristrips";
    int ix = -1, iy = -1, iz = -1, ilist = -1;
    for (size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      if (is_vertex && !p.is_list) {
        if (p.name == "x") ix = static_cast<int>(k);
        if (p.name == "y") iy = static_cast<int>(k);
        if (p.name == "z") iz = static_cast<int>(k);
      }
      if ((is_face || is_strips) && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index"))
        ilist = static_cast<int>(k);
    }
    if (is_vertex) {
      if (have_vertices) fail(path, "the header has two vertex elements");
      if (ix < 0 || iy < 0 || iz < 0) fail(path, "the vertex element has no x, y and z properties");
      raw.positions.resize(e.count);
      raw.file_vertices = e.count;
      have_vertices = true;
    }
    if ((is_face || is_strips) && ilist < 0)
      fail(path, "element '" + e.name + "' has no vertex_indices list");
    // Extra scalar properties kept per vertex / per face.
    std::vector<int> keep_slot(e.properties.size(), -1);
    std::vector<Property>* props = is_vertex ? &raw.vertex_properties
                                   : is_face ? &raw.face_properties
                                             : nullptr;
    if (keep_properties && props)
      for (size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        if (p.is_list || static_cast<int>(k) == ix || static_cast<int>(k) == iy || static_cast<int>(k) == iz)
          continue;
        keep_slot[k] = static_cast<int>(props->size());
        props->push_back(Property{p.name, p.type, {}});
        props->back().values.reserve(e.count);
      }
    std::vector<uint32_t> poly;
    for (uint64_t i = 0; i < e.count; ++i) {
      for (size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        if (p.is_list) {
          const double cnt = body.read(p.count_type, "a list count");
          if (cnt < 0) fail(path, e.name + " " + std::to_string(i) + " has a negative list count");
          const uint64_t n = static_cast<uint64_t>(cnt);
          if (n * (body.ascii() ? 2 : type_size(p.type)) > body.remaining())
            fail(path, e.name + " " + std::to_string(i) + " claims a list of " + std::to_string(n) +
                           " entries beyond the end of the file (truncated)");
          if (static_cast<int>(k) == ilist) {
            poly.clear();
            for (uint64_t j = 0; j < n; ++j) {
              const double v = body.read(p.type, "a vertex index");
              if (is_strips && v == -1) {
                poly.push_back(UINT32_MAX);
                continue;
              }
              if (v < 0 || v >= 4294967295.0 || v != std::floor(v))
                fail(path, e.name + " " + std::to_string(i) + " has vertex index " + number_text(v) +
                               " (negative or not an integer)");
              poly.push_back(static_cast<uint32_t>(v));
            }
          } else {
            for (uint64_t j = 0; j < n; ++j) body.read(p.type, "a list entry");
          }
        } else {
          const double v = body.read(p.type, "a property value");
          if (is_vertex) {
            if (static_cast<int>(k) == ix) raw.positions[i][0] = v;
            if (static_cast<int>(k) == iy) raw.positions[i][1] = v;
            if (static_cast<int>(k) == iz) raw.positions[i][2] = v;
          }
          if (keep_slot[k] >= 0) (*props)[static_cast<size_t>(keep_slot[k])].values.push_back(v);
        }
      }
      if (is_face) {
        if (poly.size() < 3)
          fail(path,
               "face " + std::to_string(i) + " has " + std::to_string(poly.size()) + " corners (at least 3)");
        raw.add_polygon(poly.data(), poly.size());
        ++raw.file_faces;
      } else if (is_strips) {
        // A strip's triangle k is (s[k], s[k+1], s[k+2]) for even k and (s[k+1], s[k], s[k+2]) for odd k;
        // parity restarts after each -1; triangles that repeat a vertex are skipped.
        ++raw.file_faces;
        size_t run = 0;
        for (size_t j = 0; j < poly.size(); ++j) {
          if (poly[j] == UINT32_MAX) {
            run = 0;
            continue;
          }
          ++run;
          if (run < 3) continue;
          const size_t k = run - 3;
          uint32_t t[3] = {poly[j - 2], poly[j - 1], poly[j]};
          if (k % 2) std::swap(t[0], t[1]);
          if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
            ++strip_skipped;
            continue;
          }
          raw.add_polygon(t, 3);
          ++raw.strip_triangles;
        }
      }
    }
    // Faces of a tristrips-only file keep no per-face properties (strips have none per triangle).
  }
  if (!have_vertices) fail(path, "the file has no vertex element");
  if (strip_skipped)
    raw.notes.push_back(std::to_string(strip_skipped) +
                        " strip triangles that repeat a vertex (strip joins) were skipped");
  if (raw.strip_triangles && !raw.face_properties.empty()) raw.face_properties.clear();
  if (!body.at_end())
    raw.notes.push_back(std::to_string(body.remaining()) +
                        " bytes after the last element the header announces were ignored");
  return raw;
}

namespace {

void put(std::string& out, double v, ScalarType t, bool binary, const std::string& name) {
  if (!fits(t, v))
    throw std::invalid_argument("write_ply: property '" + name + "' holds " + std::to_string(v) +
                                ", which a " + type_name(t) + " cannot represent");
  if (!binary) {
    if (t == ScalarType::Float32 || t == ScalarType::Float64) {
      append_number(out, v, t == ScalarType::Float32);  // shortest exact text
    } else {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(v));
      out += buf;
    }
    return;
  }
  unsigned char b[8];
  switch (t) {
    case ScalarType::Int8: {
      int8_t x = static_cast<int8_t>(v);
      std::memcpy(b, &x, 1);
      break;
    }
    case ScalarType::UInt8: {
      uint8_t x = static_cast<uint8_t>(v);
      std::memcpy(b, &x, 1);
      break;
    }
    case ScalarType::Int16: {
      int16_t x = static_cast<int16_t>(v);
      std::memcpy(b, &x, 2);
      break;
    }
    case ScalarType::UInt16: {
      uint16_t x = static_cast<uint16_t>(v);
      std::memcpy(b, &x, 2);
      break;
    }
    case ScalarType::Int32: {
      int32_t x = static_cast<int32_t>(v);
      std::memcpy(b, &x, 4);
      break;
    }
    case ScalarType::UInt32: {
      uint32_t x = static_cast<uint32_t>(v);
      std::memcpy(b, &x, 4);
      break;
    }
    case ScalarType::Float32: {
      float x = static_cast<float>(v);
      std::memcpy(b, &x, 4);
      break;
    }
    case ScalarType::Float64:
      std::memcpy(b, &v, 8);
      break;
  }
  out.append(reinterpret_cast<const char*>(b), type_size(t));  // little-endian hosts only (x86-64, arm64)
}

}  // namespace

void write_ply(const Mesh& mesh, const std::string& path, const WriteOptions& options) {
  const bool binary = options.binary;
  const ScalarType pt = options.double_positions ? ScalarType::Float64 : ScalarType::Float32;
  std::string out;
  out += "ply\n";
  out += binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n";
  for (const std::string& c : mesh.comments) {
    if (c.find('\n') != std::string::npos)
      throw std::invalid_argument("write_ply: a comment contains a line break");
    out += "comment " + c + "\n";
  }
  out += "element vertex " + std::to_string(mesh.positions.size()) + "\n";
  for (const char* n : {"x", "y", "z"}) out += std::string("property ") + type_name(pt) + " " + n + "\n";
  const bool props = options.write_properties;
  if (props)
    for (const Property& p : mesh.vertex_properties)
      out += std::string("property ") + type_name(p.type) + " " + p.name + "\n";
  out += "element face " + std::to_string(mesh.triangles.size()) + "\n";
  out += "property list uchar int vertex_indices\n";
  if (props)
    for (const Property& p : mesh.face_properties)
      out += std::string("property ") + type_name(p.type) + " " + p.name + "\n";
  out += "end_header\n";
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    for (int a = 0; a < 3; ++a) {
      if (!binary && a) out += ' ';
      put(out, mesh.positions[v][static_cast<size_t>(a)], pt, binary, "position");
    }
    if (props)
      for (const Property& p : mesh.vertex_properties) {
        if (!binary) out += ' ';
        put(out, p.values.at(v), p.type, binary, p.name);
      }
    if (!binary) out += '\n';
  }
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (binary) {
      out += static_cast<char>(3);
      for (uint32_t v : mesh.triangles[f]) put(out, v, ScalarType::Int32, true, "vertex_indices");
    } else {
      out += "3 " + std::to_string(mesh.triangles[f][0]) + " " + std::to_string(mesh.triangles[f][1]) + " " +
             std::to_string(mesh.triangles[f][2]);
    }
    if (props)
      for (const Property& p : mesh.face_properties) {
        if (!binary) out += ' ';
        put(out, p.values.at(f), p.type, binary, p.name);
      }
    if (!binary) out += '\n';
  }
  write_file(path, out);
}

}  // namespace prm::io
