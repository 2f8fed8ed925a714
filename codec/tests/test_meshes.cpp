#include "test_meshes.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

namespace prm::codec::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

void add_tri(TestMesh& m, uint32_t a, uint32_t b, uint32_t c) {
  m.triangles.push_back(a);
  m.triangles.push_back(b);
  m.triangles.push_back(c);
}

uint32_t add_vertex(TestMesh& m, double x, double y, double z) {
  m.xyz.push_back(x);
  m.xyz.push_back(y);
  m.xyz.push_back(z);
  return static_cast<uint32_t>(m.num_vertices() - 1);
}

}  // namespace

TestMesh icosphere(int subdivisions) {
  TestMesh m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    add_vertex(m, p[0] / n, p[1] / n, p[2] / n);
  }
  const uint32_t f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                             {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& tri : f) add_tri(m, tri[0], tri[1], tri[2]);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      double p[3];
      for (int k = 0; k < 3; ++k) p[k] = (m.xyz[3 * a + k] + m.xyz[3 * b + k]) / 2;
      const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      const uint32_t id = add_vertex(m, p[0] / n, p[1] / n, p[2] / n);
      mid.emplace(key, id);
      return id;
    };
    std::vector<uint32_t> old;
    old.swap(m.triangles);
    for (size_t i = 0; i < old.size(); i += 3) {
      const uint32_t a = old[i], b = old[i + 1], c = old[i + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      add_tri(m, a, ab, ca);
      add_tri(m, b, bc, ab);
      add_tri(m, c, ca, bc);
      add_tri(m, ab, bc, ca);
    }
  }
  return m;
}

TestMesh torus(int n, int mm) {
  TestMesh m;
  const double R = 1.0, r = 0.35;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < mm; ++j) {
      const double u = 2 * kPi * i / n, w = 2 * kPi * j / mm;
      add_vertex(m, (R + r * std::cos(w)) * std::cos(u), (R + r * std::cos(w)) * std::sin(u), r * std::sin(w));
    }
  auto id = [&](int i, int j) { return static_cast<uint32_t>(((i + n) % n) * mm + (j + mm) % mm); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < mm; ++j) {
      add_tri(m, id(i, j), id(i + 1, j), id(i + 1, j + 1));
      add_tri(m, id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return m;
}

TestMesh plate_with_holes(int genus, int refine) {
  const int nx = genus > 0 ? 2 * genus + 1 : 1, ny = genus > 0 ? 3 : 1, nz = 1;
  auto filled = [&](int x, int y, int z) {
    if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz) return false;
    return !(genus > 0 && y == 1 && x % 2 == 1);
  };
  TestMesh m;
  std::map<std::tuple<int, int, int>, uint32_t> ids;
  auto vid = [&](int x, int y, int z) {
    auto key = std::make_tuple(x, y, z);
    auto it = ids.find(key);
    if (it != ids.end()) return it->second;
    const uint32_t v = add_vertex(m, x, y, z);
    ids.emplace(key, v);
    return v;
  };
  for (int x = 0; x < nx; ++x)
    for (int y = 0; y < ny; ++y)
      for (int z = 0; z < nz; ++z) {
        if (!filled(x, y, z)) continue;
        const int cell[3] = {x, y, z};
        for (int a = 0; a < 3; ++a)
          for (int s = 0; s < 2; ++s) {
            int nb[3] = {x, y, z};
            nb[a] += s ? 1 : -1;
            if (filled(nb[0], nb[1], nb[2])) continue;
            const int u = (a + 1) % 3, w = (a + 2) % 3;
            for (int i = 0; i < refine; ++i)
              for (int j = 0; j < refine; ++j) {
                uint32_t q[4];
                const int du[4] = {i, i + 1, i + 1, i}, dw[4] = {j, j, j + 1, j + 1};
                for (int k = 0; k < 4; ++k) {
                  int p[3];
                  p[a] = (cell[a] + s) * refine;
                  p[u] = cell[u] * refine + du[k];
                  p[w] = cell[w] * refine + dw[k];
                  q[k] = vid(p[0], p[1], p[2]);
                }
                if (s == 1) {
                  add_tri(m, q[0], q[1], q[2]);
                  add_tri(m, q[0], q[2], q[3]);
                } else {
                  add_tri(m, q[0], q[2], q[1]);
                  add_tri(m, q[0], q[3], q[2]);
                }
              }
          }
      }
  return m;
}

TestMesh hex_patch(int radius, bool bumpy) {
  TestMesh m;
  std::map<std::pair<int, int>, uint32_t> ids;
  auto inside = [&](int i, int j) { return std::abs(i) <= radius && std::abs(j) <= radius && std::abs(i + j) <= radius; };
  for (int j = -radius; j <= radius; ++j)
    for (int i = -radius; i <= radius; ++i)
      if (inside(i, j)) {
        const double x = i + 0.5 * j, y = j * std::sqrt(3.0) / 2;
        ids[{i, j}] = add_vertex(m, x, y, bumpy ? 0.8 * std::sin(0.3 * x) * std::cos(0.2 * y) : 0.0);
      }
  for (int j = -radius; j <= radius; ++j)
    for (int i = -radius; i <= radius; ++i) {
      if (inside(i, j) && inside(i + 1, j) && inside(i, j + 1)) add_tri(m, ids[{i, j}], ids[{i + 1, j}], ids[{i, j + 1}]);
      if (inside(i + 1, j) && inside(i + 1, j + 1) && inside(i, j + 1))
        add_tri(m, ids[{i + 1, j}], ids[{i + 1, j + 1}], ids[{i, j + 1}]);
    }
  return m;
}

TestMesh sphere_with_holes(int subdivisions, int holes) {
  TestMesh s = icosphere(subdivisions);
  const double dirs[6][3] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  TestMesh m;
  m.xyz = s.xyz;
  for (size_t t = 0; t < s.num_triangles(); ++t) {
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) c[a] += s.xyz[3 * s.triangles[3 * t + k] + a] / 3;
    const double n = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    bool cut = false;
    for (int h = 0; h < holes && h < 6; ++h)
      cut |= (c[0] * dirs[h][0] + c[1] * dirs[h][1] + c[2] * dirs[h][2]) / n > 0.93;
    if (!cut) add_tri(m, s.triangles[3 * t], s.triangles[3 * t + 1], s.triangles[3 * t + 2]);
  }
  return m;
}

TestMesh concat(const std::vector<TestMesh>& parts) {
  TestMesh m;
  double shift = 0;
  for (const TestMesh& p : parts) {
    const uint32_t base = static_cast<uint32_t>(m.num_vertices());
    double lo = 1e300, hi = -1e300;
    for (size_t i = 0; i < p.num_vertices(); ++i) {
      lo = std::min(lo, p.xyz[3 * i]);
      hi = std::max(hi, p.xyz[3 * i]);
    }
    for (size_t i = 0; i < p.num_vertices(); ++i)
      add_vertex(m, p.xyz[3 * i] - lo + shift, p.xyz[3 * i + 1], p.xyz[3 * i + 2]);
    shift += (hi - lo) + 0.5;
    for (uint32_t v : p.triangles) m.triangles.push_back(v + base);
  }
  return m;
}

TestMesh tetrahedron() {
  TestMesh m;
  add_vertex(m, 0, 0, 0);
  add_vertex(m, 1, 0, 0);
  add_vertex(m, 0, 1, 0);
  add_vertex(m, 0, 0, 1);
  add_tri(m, 0, 2, 1);
  add_tri(m, 0, 1, 3);
  add_tri(m, 1, 2, 3);
  add_tri(m, 2, 0, 3);
  return m;
}

TestMesh single_triangle() {
  TestMesh m;
  add_vertex(m, 0, 0, 0);
  add_vertex(m, 1, 0, 0);
  add_vertex(m, 0, 1, 0);
  add_tri(m, 0, 1, 2);
  return m;
}

// ---------------------------------------------------------------------------------------------------------------
// Loading.

namespace {

void add_polygon(TestMesh& m, const std::vector<int64_t>& poly, size_t nv, const std::string& path) {
  for (int64_t v : poly)
    if (v < 0 || static_cast<size_t>(v) >= nv) throw std::runtime_error(path + ": face index out of range");
  for (size_t k = 1; k + 1 < poly.size(); ++k)
    add_tri(m, static_cast<uint32_t>(poly[0]), static_cast<uint32_t>(poly[k]), static_cast<uint32_t>(poly[k + 1]));
}

// Next token, skipping '#' comments.
struct Tokens {
  std::istream& in;
  bool next(std::string& tok) {
    while (in >> tok) {
      if (tok[0] == '#') {
        std::string rest;
        std::getline(in, rest);
        continue;
      }
      return true;
    }
    return false;
  }
};

TestMesh load_off(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot open");
  Tokens t{f};
  std::string tok;
  if (!t.next(tok) || tok.find("OFF") == std::string::npos) throw std::runtime_error(path + ": not OFF");
  const bool has_dim = tok.find('n') != std::string::npos;
  std::string sv, sf, se;
  if (has_dim) t.next(tok);
  if (!t.next(sv) || !t.next(sf) || !t.next(se)) throw std::runtime_error(path + ": bad counts");
  const size_t nv = std::stoul(sv), nf = std::stoul(sf);
  // Vertex lines may carry colours/normals: read whole lines.
  TestMesh m;
  std::string line;
  std::getline(f, line);
  size_t read = 0;
  while (read < nv && std::getline(f, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t\r")] == '#') continue;
    std::istringstream ls(line);
    double x, y, z;
    if (!(ls >> x >> y >> z)) throw std::runtime_error(path + ": bad vertex");
    add_vertex(m, x, y, z);
    ++read;
  }
  if (read != nv) throw std::runtime_error(path + ": missing vertices");
  size_t faces = 0;
  while (faces < nf && std::getline(f, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t\r")] == '#') continue;
    std::istringstream ls(line);
    size_t n;
    if (!(ls >> n)) throw std::runtime_error(path + ": bad face");
    std::vector<int64_t> poly(n);
    for (auto& v : poly)
      if (!(ls >> v)) throw std::runtime_error(path + ": bad face");
    add_polygon(m, poly, nv, path);
    ++faces;
  }
  if (faces != nf) throw std::runtime_error(path + ": missing faces");
  return m;
}

TestMesh load_obj(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot open");
  TestMesh m;
  std::string line;
  std::vector<std::vector<int64_t>> faces;
  while (std::getline(f, line)) {
    std::istringstream ls(line);
    std::string kw;
    if (!(ls >> kw)) continue;
    if (kw == "v") {
      double x, y, z;
      ls >> x >> y >> z;
      add_vertex(m, x, y, z);
    } else if (kw == "f") {
      std::vector<int64_t> poly;
      std::string tok;
      while (ls >> tok) {
        int64_t v = std::stoll(tok.substr(0, tok.find('/')));
        poly.push_back(v < 0 ? static_cast<int64_t>(m.num_vertices()) + v : v - 1);
      }
      faces.push_back(poly);
    }
  }
  for (auto& p : faces) add_polygon(m, p, m.num_vertices(), path);
  return m;
}

struct PlyProperty {
  std::string name, type, list_count_type;
  bool is_list = false;
};
struct PlyElement {
  std::string name;
  size_t count = 0;
  std::vector<PlyProperty> props;
};

size_t ply_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  throw std::runtime_error("ply: unknown type " + t);
}

double ply_read_binary(const uint8_t* p, const std::string& t) {
  if (t == "char" || t == "int8") return static_cast<int8_t>(p[0]);
  if (t == "uchar" || t == "uint8") return p[0];
  if (t == "short" || t == "int16") { int16_t v; std::memcpy(&v, p, 2); return v; }
  if (t == "ushort" || t == "uint16") { uint16_t v; std::memcpy(&v, p, 2); return v; }
  if (t == "int" || t == "int32") { int32_t v; std::memcpy(&v, p, 4); return v; }
  if (t == "uint" || t == "uint32") { uint32_t v; std::memcpy(&v, p, 4); return v; }
  if (t == "float" || t == "float32") { float v; std::memcpy(&v, p, 4); return v; }
  double v; std::memcpy(&v, p, 8); return v;
}

TestMesh load_ply(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error(path + ": cannot open");
  std::string line, format;
  std::vector<PlyElement> elements;
  std::getline(f, line);
  if (line.rfind("ply", 0) != 0) throw std::runtime_error(path + ": not PLY");
  while (std::getline(f, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw == "format") ls >> format;
    else if (kw == "element") {
      PlyElement e;
      ls >> e.name >> e.count;
      elements.push_back(e);
    } else if (kw == "property") {
      PlyProperty p;
      std::string t;
      ls >> t;
      if (t == "list") {
        p.is_list = true;
        ls >> p.list_count_type >> p.type >> p.name;
      } else {
        p.type = t;
        ls >> p.name;
      }
      elements.back().props.push_back(p);
    } else if (kw == "end_header") break;
  }
  const bool ascii = format == "ascii";
  if (!ascii && format != "binary_little_endian") throw std::runtime_error(path + ": unsupported PLY format");
  std::vector<uint8_t> data((std::istreambuf_iterator<char>(f)), {});
  size_t pos = 0;
  std::istringstream text(ascii ? std::string(data.begin(), data.end()) : std::string());
  auto read_value = [&](const std::string& type) -> double {
    if (ascii) {
      double v;
      if (!(text >> v)) throw std::runtime_error(path + ": truncated");
      return v;
    }
    const size_t s = ply_size(type);
    if (pos + s > data.size()) throw std::runtime_error(path + ": truncated");
    const double v = ply_read_binary(&data[pos], type);
    pos += s;
    return v;
  };
  TestMesh m;
  for (const PlyElement& e : elements) {
    for (size_t i = 0; i < e.count; ++i) {
      double xyz[3] = {0, 0, 0};
      std::vector<int64_t> list;
      for (const PlyProperty& p : e.props) {
        if (p.is_list) {
          const size_t n = static_cast<size_t>(read_value(p.list_count_type));
          std::vector<int64_t> values(n);
          for (auto& v : values) v = static_cast<int64_t>(read_value(p.type));
          if (p.name == "vertex_indices" || p.name == "vertex_index") list = values;
        } else {
          const double v = read_value(p.type);
          if (e.name == "vertex") {
            if (p.name == "x") xyz[0] = v;
            if (p.name == "y") xyz[1] = v;
            if (p.name == "z") xyz[2] = v;
          }
        }
      }
      if (e.name == "vertex") add_vertex(m, xyz[0], xyz[1], xyz[2]);
      if (e.name == "face") add_polygon(m, list, m.num_vertices(), path);
      if (e.name == "tristrips") {
        // Runs separated by -1; odd triangles flipped; triangles repeating a vertex skipped.
        size_t k = 0;
        while (k < list.size()) {
          size_t end = k;
          while (end < list.size() && list[end] >= 0) ++end;
          for (size_t t = k; t + 2 < end; ++t) {
            int64_t a = list[t], b = list[t + 1], c = list[t + 2];
            if ((t - k) % 2) std::swap(a, b);
            if (a == b || b == c || a == c) continue;
            add_polygon(m, {a, b, c}, m.num_vertices(), path);
          }
          k = end + 1;
        }
      }
    }
  }
  return m;
}

}  // namespace

TestMesh load_mesh(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  if (ext == ".off") return load_off(path);
  if (ext == ".obj") return load_obj(path);
  if (ext == ".ply") return load_ply(path);
  throw std::runtime_error(path + ": unsupported extension");
}

std::string manifold_problem(const TestMesh& m) {
  const size_t nt = m.num_triangles(), nv = m.num_vertices();
  std::unordered_map<uint64_t, std::vector<std::pair<uint32_t, bool>>> edges;  // key min,max -> (tri, forward)
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* f = &m.triangles[3 * t];
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) return "degenerate triangle " + std::to_string(t);
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = f[k], b = f[(k + 1) % 3];
      const uint64_t key = uint64_t{std::min(a, b)} << 32 | std::max(a, b);
      edges[key].push_back({static_cast<uint32_t>(t), a < b});
    }
  }
  for (auto& e : edges) {
    if (e.second.size() > 2) return "edge with three or more triangles";
    if (e.second.size() == 2 && e.second[0].second == e.second[1].second) return "inconsistent orientation";
  }
  // Vertex fans: union the triangles around v that share an edge (v, w).
  std::vector<std::vector<uint32_t>> around(nv);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) around[m.triangles[3 * t + k]].push_back(static_cast<uint32_t>(t));
  for (size_t v = 0; v < nv; ++v) {
    auto& tris = around[v];
    if (tris.size() < 2) continue;
    std::vector<size_t> parent(tris.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<size_t(size_t)> find = [&](size_t x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
    std::map<uint32_t, size_t> by_neighbour;
    for (size_t i = 0; i < tris.size(); ++i) {
      const uint32_t* f = &m.triangles[3 * tris[i]];
      for (int k = 0; k < 3; ++k) {
        if (f[k] == v) continue;
        auto it = by_neighbour.find(f[k]);
        if (it == by_neighbour.end())
          by_neighbour.emplace(f[k], i);
        else
          parent[find(i)] = find(it->second);
      }
    }
    size_t roots = 0;
    for (size_t i = 0; i < tris.size(); ++i) roots += find(i) == i;
    if (roots > 1) return "vertex " + std::to_string(v) + " has more than one fan";
  }
  return "";
}

std::vector<std::string> list_files(const std::string& dir, const std::vector<std::string>& extensions) {
  std::vector<std::string> out;
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (std::find(extensions.begin(), extensions.end(), ext) != extensions.end()) out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

QuantizedMesh lattice_pillow(int r, int64_t grid, int64_t (*top)(int, int, const void*),
                             int64_t (*bottom)(int, int, const void*), const void* user,
                             const std::vector<std::array<int, 2>>& moved) {
  // Lattice constants of spec §8.1; indices shifted so that every coordinate is positive.
  const int64_t A = grid, B = grid / 2;
  int64_t s3 = 0;
  while ((s3 + 1) * (s3 + 1) <= 3 * grid * grid) ++s3;
  const int64_t C = (s3 + 1) / 2, shift = r + 1;
  QuantizedMesh m;
  std::map<std::pair<int, int>, uint32_t> up, down;
  auto inside = [&](int i, int j) { return std::abs(i) <= r && std::abs(j) <= r && std::abs(i + j) <= r; };
  auto add = [&](int i, int j, int64_t h) {
    const int64_t ii = i + shift, jj = j + shift;
    m.q.push_back(static_cast<uint32_t>(A * ii + B * jj));
    m.q.push_back(static_cast<uint32_t>(C * jj));
    m.q.push_back(static_cast<uint32_t>(h));
    return static_cast<uint32_t>(m.nv() - 1);
  };
  for (int j = -r; j <= r; ++j)
    for (int i = -r; i <= r; ++i)
      if (inside(i, j)) {
        up[{i, j}] = add(i, j, top(i, j, user));
        down[{i, j}] = add(i, j, bottom(i, j, user));
      }
  auto tri = [&](uint32_t a, uint32_t b, uint32_t c) { m.tris.insert(m.tris.end(), {a, b, c}); };
  for (int j = -r; j <= r; ++j)
    for (int i = -r; i <= r; ++i) {
      if (inside(i, j) && inside(i + 1, j) && inside(i, j + 1)) {
        tri(up[{i, j}], up[{i + 1, j}], up[{i, j + 1}]);
        tri(down[{i, j}], down[{i, j + 1}], down[{i + 1, j}]);
      }
      if (inside(i + 1, j) && inside(i + 1, j + 1) && inside(i, j + 1)) {
        tri(up[{i + 1, j}], up[{i + 1, j + 1}], up[{i, j + 1}]);
        tri(down[{i + 1, j}], down[{i, j + 1}], down[{i + 1, j + 1}]);
      }
    }
  // The rim, counter-clockwise from (r, -r), and the band: outward-facing quads split in two.
  const int dir[6][2] = {{1, 0}, {0, 1}, {-1, 1}, {-1, 0}, {0, -1}, {1, -1}};
  std::vector<std::pair<int, int>> ring;
  int ci = r, cj = -r;
  for (int side = 1; side < 7; ++side)
    for (int s = 0; s < r; ++s) {
      ring.push_back({ci, cj});
      ci += dir[side % 6][0];
      cj += dir[side % 6][1];
    }
  for (size_t k = 0; k < ring.size(); ++k) {
    const auto a = ring[k], b = ring[(k + 1) % ring.size()];
    tri(up[b], up[a], down[a]);
    tri(up[b], down[a], down[b]);
  }
  for (const auto& ij : moved)
    if (inside(ij[0], ij[1])) m.q[3 * size_t{up[{ij[0], ij[1]}]}] += 1;
  return m;
}

uint64_t fnv1a64_words(const std::vector<uint32_t>& words, uint64_t h) {
  for (uint32_t x : words)
    for (int i = 0; i < 4; ++i) {
      h ^= (x >> (8 * i)) & 0xFF;
      h *= 1099511628211ull;
    }
  return h;
}

}  // namespace prm::codec::test
