// read_mesh / write_mesh: format dispatch and the cleanup every reader shares (triangulation, welding,
// dropping unreferenced vertices).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <numeric>
#include <unordered_map>

#include "mesh_io_internal.h"
#include "prm/vec3.h"

namespace prm {

namespace io {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw InputError(path + ": " + what);
}

std::vector<char> read_file(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw IoError(path + ": cannot open (" + std::strerror(errno) + ")");
  std::vector<char> data;
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) data.insert(data.end(), buf, buf + n);
  const bool err = std::ferror(f);
  std::fclose(f);
  if (err) throw IoError(path + ": read error");
  return data;
}

void write_file(const std::string& path, const std::string& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw IoError(path + ": cannot create (" + std::strerror(errno) + ")");
  const size_t n = std::fwrite(bytes.data(), 1, bytes.size(), f);
  const bool err = std::fclose(f) != 0;
  if (n != bytes.size() || err) throw IoError(path + ": write error");
}

void append_number(std::string& out, double v, bool as_float) {
  char buf[32];
  const std::to_chars_result r = as_float ? std::to_chars(buf, buf + sizeof buf, static_cast<float>(v))
                                          : std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void check_indices(const RawMesh& raw, const std::string& path) {
  const size_t nv = raw.positions.size();
  for (size_t k = 0; k < raw.num_polygons(); ++k) {
    const uint32_t b = raw.polygon_start[k], e = raw.polygon_start[k + 1];
    if (e - b < 3)
      fail(path, "face " + std::to_string(k) + " has " + std::to_string(e - b) + " corners (at least 3)");
    for (uint32_t c = b; c < e; ++c)
      if (raw.corners[c] >= nv)
        fail(path, "face " + std::to_string(k) + " uses vertex " + std::to_string(raw.corners[c]) +
                       ", but there are only " + std::to_string(nv) + " vertices");
  }
}

void check_finite(const RawMesh& raw, const std::string& path) {
  for (size_t v = 0; v < raw.positions.size(); ++v)
    for (double c : raw.positions[v])
      if (!std::isfinite(c))
        fail(path, "vertex " + std::to_string(v) + " has a non-finite coordinate (NaN or inf)");
}

namespace {

// Ear clipping in the plane of the polygon (Newell normal), walking a cursor round the ring so that a polygon
// of n corners costs O(n^2). Falls back to a fan when no ear is found (corners nearly collinear,
// self-intersecting polygon), for polygons above kMaxEarClipCorners and once the file has used up its work
// budget (a hostile file could otherwise ask for O(n^3) work per polygon).
constexpr size_t kMaxEarClipCorners = 256;

struct Triangulator {
  size_t budget = size_t{1} << 28;  // ear tests times ring size, over the whole file
  size_t fan_fallbacks = 0;
};

void triangulate(const std::vector<Vec3>& pos, const uint32_t* c, size_t n, std::vector<Tri>& out,
                 Triangulator& tr) {
  if (n == 3) {
    out.push_back({c[0], c[1], c[2]});
    return;
  }
  std::vector<uint32_t> ring(c, c + n);
  if (n <= kMaxEarClipCorners && tr.budget > 0) {
    Vec3 normal{0, 0, 0};
    for (size_t i = 0; i < n; ++i) {
      const Vec3& a = pos[c[i]];
      const Vec3& b = pos[c[(i + 1) % n]];
      normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
      normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
      normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    auto convex = [&](uint32_t a, uint32_t b, uint32_t d) {
      return dot(cross(pos[b] - pos[a], pos[d] - pos[b]), normal) > 0;
    };
    auto inside = [&](uint32_t p, uint32_t a, uint32_t b, uint32_t d) {
      const Vec3& x = pos[p];
      return dot(cross(pos[b] - pos[a], x - pos[a]), normal) >= 0 &&
             dot(cross(pos[d] - pos[b], x - pos[b]), normal) >= 0 &&
             dot(cross(pos[a] - pos[d], x - pos[d]), normal) >= 0;
    };
    auto is_ear = [&](size_t i) {
      const size_t m = ring.size();
      tr.budget -= std::min(tr.budget, m);
      const uint32_t a = ring[(i + m - 1) % m], b = ring[i], d = ring[(i + 1) % m];
      if (!convex(a, b, d)) return false;
      for (uint32_t p : ring)
        if (p != a && p != b && p != d && pos[p] != pos[a] && pos[p] != pos[b] && pos[p] != pos[d] &&
            inside(p, a, b, d))
          return false;
      return true;
    };
    size_t i = 0, misses = 0;
    while (ring.size() > 3 && misses < ring.size() && tr.budget > 0) {
      if (!is_ear(i)) {
        i = (i + 1) % ring.size();
        ++misses;
        continue;
      }
      const size_t m = ring.size();
      out.push_back({ring[(i + m - 1) % m], ring[i], ring[(i + 1) % m]});
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
      if (i >= ring.size()) i = 0;
      misses = 0;
    }
    if (ring.size() > 3) ++tr.fan_fallbacks;
  } else {
    ++tr.fan_fallbacks;
  }
  for (size_t i = 1; i + 1 < ring.size(); ++i) out.push_back({ring[0], ring[i], ring[i + 1]});
}

struct PositionHash {
  size_t operator()(const Vec3& p) const {
    uint64_t h = 1469598103934665603ull;
    for (double c : p) {
      const double z = c == 0 ? 0.0 : c;  // -0 and +0 weld
      uint64_t bits;
      std::memcpy(&bits, &z, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
    return static_cast<size_t>(h);
  }
};

// Representative of each vertex after welding (vertices map to the first coincident one).
std::vector<uint32_t> weld_map(const std::vector<Vec3>& pos, double tol) {
  std::vector<uint32_t> rep(pos.size());
  if (tol <= 0) {
    std::unordered_map<Vec3, uint32_t, PositionHash> first;
    first.reserve(pos.size());
    for (uint32_t v = 0; v < pos.size(); ++v) {
      Vec3 key = pos[v];
      for (double& c : key)
        if (c == 0) c = 0.0;
      rep[v] = first.emplace(key, v).first->second;
    }
    return rep;
  }
  // Tolerance: a hash grid of cell size tol; each vertex joins the first earlier vertex within tol, looking
  // in its own cell and the 26 around it. Where |x| / tol exceeds 4e18 (a tiny tolerance on large coordinates),
  // tol is below the spacing of doubles there (|x| 2^-53 > 400 tol), so two coordinates within tol are equal: the
  // cell is then the value itself, folded into the int64 range above the grid's. (Clamping them to one cell, as
  // before, put every such vertex in the same cell: with --weld-tolerance 1e-3, a 1 MB binary STL of distinct
  // coordinates near 1e17 took 3.5 s, quadratic in the vertex count.)
  struct Cell {
    int64_t x, y, z;
    bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct CellHash {
    size_t operator()(const Cell& c) const {
      const uint64_t h = static_cast<uint64_t>(c.x) * 73856093u ^ static_cast<uint64_t>(c.y) * 19349663u ^
                         static_cast<uint64_t>(c.z) * 83492791u;
      return static_cast<size_t>(h ^ (h >> 29));
    }
  };
  std::unordered_map<Cell, std::vector<uint32_t>, CellHash> grid;
  auto coord = [&](double x) -> int64_t {
    const double q = std::floor(x / tol);
    constexpr double kLimit = 4e18;
    if (std::fabs(q) <= kLimit) return static_cast<int64_t>(q);
    constexpr uint64_t kFold = 4'000'000'000'000'000'000u;
    constexpr int64_t kBase = 4'100'000'000'000'000'000;  // beyond the grid's cells and their neighbours
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const int64_t folded = kBase + static_cast<int64_t>(bits % kFold);  // at most 5 values share one
    return q > 0 ? folded : -folded;
  };
  for (uint32_t v = 0; v < pos.size(); ++v) {
    const Cell c{coord(pos[v][0]), coord(pos[v][1]), coord(pos[v][2])};
    rep[v] = v;
    for (int64_t dx = -1; dx <= 1 && rep[v] == v; ++dx)
      for (int64_t dy = -1; dy <= 1 && rep[v] == v; ++dy)
        for (int64_t dz = -1; dz <= 1 && rep[v] == v; ++dz) {
          const auto it = grid.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == grid.end()) continue;
          for (uint32_t w : it->second)
            if (norm(pos[w] - pos[v]) <= tol) {
              rep[v] = w;
              break;
            }
        }
    if (rep[v] == v) grid[c].push_back(v);
  }
  return rep;
}

}  // namespace

Mesh finish_mesh(RawMesh raw, const ReadOptions& options, bool weld_auto, ReadReport& report) {
  Mesh mesh;
  report.file_vertices = raw.file_vertices ? raw.file_vertices : raw.positions.size();
  report.file_faces = raw.file_faces ? raw.file_faces : raw.num_polygons();
  report.strip_triangles = raw.strip_triangles;
  report.notes.insert(report.notes.end(), raw.notes.begin(), raw.notes.end());
  const size_t nv = raw.positions.size();

  // Welding.
  const bool weld =
      options.weld == ReadOptions::Weld::Always || (options.weld == ReadOptions::Weld::Auto && weld_auto);
  std::vector<uint32_t> rep(nv);
  std::iota(rep.begin(), rep.end(), 0u);
  if (weld) {
    rep = weld_map(raw.positions, options.weld_tolerance);
    for (uint32_t v = 0; v < nv; ++v) report.vertices_welded += rep[v] != v;
  }

  // Triangles; a polygon's properties go to each of its triangles.
  std::vector<uint32_t> tri_polygon;
  std::vector<Tri> tris;
  Triangulator triangulator;
  for (size_t k = 0; k < raw.num_polygons(); ++k) {
    const uint32_t b = raw.polygon_start[k], e = raw.polygon_start[k + 1];
    triangulate(raw.positions, raw.corners.data() + b, e - b, tris, triangulator);
    if (e - b > 3) ++report.polygons_triangulated;
    tri_polygon.resize(tris.size(), static_cast<uint32_t>(k));
  }
  if (triangulator.fan_fallbacks)
    report.notes.push_back(
        std::to_string(triangulator.fan_fallbacks) +
        " polygon(s) could not be ear-clipped (self-intersecting, collinear or huge) and were "
        "split as fans");
  // Drop triangles that use a vertex twice (after welding).
  std::vector<Tri> kept;
  std::vector<uint32_t> kept_polygon;
  kept.reserve(tris.size());
  for (size_t t = 0; t < tris.size(); ++t) {
    Tri x = {rep[tris[t][0]], rep[tris[t][1]], rep[tris[t][2]]};
    if (x[0] == x[1] || x[1] == x[2] || x[0] == x[2]) {
      ++report.degenerate_dropped;
      continue;
    }
    kept.push_back(x);
    kept_polygon.push_back(tri_polygon[t]);
  }

  // Unreferenced vertices.
  std::vector<uint32_t> new_id(nv, UINT32_MAX);
  std::vector<uint32_t> old_of;
  if (options.drop_unreferenced) {
    std::vector<uint8_t> used(nv, 0);
    for (const Tri& t : kept)
      for (uint32_t v : t) used[v] = 1;
    for (uint32_t v = 0; v < nv; ++v)
      if (used[v]) {
        new_id[v] = static_cast<uint32_t>(old_of.size());
        old_of.push_back(v);
      } else if (rep[v] == v) {
        ++report.unreferenced_dropped;
      }
  } else {
    for (uint32_t v = 0; v < nv; ++v)
      if (rep[v] == v) {
        new_id[v] = static_cast<uint32_t>(old_of.size());
        old_of.push_back(v);
      }
  }
  mesh.positions.reserve(old_of.size());
  for (uint32_t v : old_of) mesh.positions.push_back(raw.positions[v]);
  mesh.triangles.reserve(kept.size());
  for (const Tri& t : kept) mesh.triangles.push_back({new_id[t[0]], new_id[t[1]], new_id[t[2]]});
  if (options.keep_properties) {
    for (Property& p : raw.vertex_properties) {
      std::vector<double> vals(old_of.size());
      for (size_t i = 0; i < old_of.size(); ++i) vals[i] = p.values[old_of[i]];
      mesh.vertex_properties.push_back({p.name, p.type, std::move(vals)});
    }
    for (Property& p : raw.face_properties) {
      std::vector<double> vals(kept.size());
      for (size_t i = 0; i < kept.size(); ++i) vals[i] = p.values[kept_polygon[i]];
      mesh.face_properties.push_back({p.name, p.type, std::move(vals)});
    }
  }
  mesh.comments = std::move(raw.comments);
  return mesh;
}

}  // namespace io

MeshFormat format_from_path(const std::string& path) {
  std::string ext;
  const size_t dot = path.find_last_of('.');
  if (dot != std::string::npos && path.find_first_of("/\\", dot) == std::string::npos)
    ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "obj") return MeshFormat::Obj;
  if (ext == "ply") return MeshFormat::Ply;
  if (ext == "off") return MeshFormat::Off;
  if (ext == "stl") return MeshFormat::Stl;
  if (ext == "gltf") return MeshFormat::Gltf;
  if (ext == "glb") return MeshFormat::Glb;
  return MeshFormat::Auto;
}

const char* format_name(MeshFormat f) {
  switch (f) {
    case MeshFormat::Obj:
      return "OBJ";
    case MeshFormat::Ply:
      return "PLY";
    case MeshFormat::Off:
      return "OFF";
    case MeshFormat::Stl:
      return "STL";
    case MeshFormat::Gltf:
      return "glTF";
    case MeshFormat::Glb:
      return "GLB";
    case MeshFormat::Auto:
      break;
  }
  return "unknown";
}

namespace {

// The format from the first bytes (and the size, for binary STL), for files whose extension says nothing.
MeshFormat sniff(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw IoError(path + ": cannot open (" + std::strerror(errno) + ")");
  char head[256] = {0};
  const size_t n = std::fread(head, 1, sizeof head, f);
  long size = -1;
  if (std::fseek(f, 0, SEEK_END) == 0) size = std::ftell(f);
  std::fclose(f);
  const std::string s(head, n);
  if (s.rfind("ply", 0) == 0) return MeshFormat::Ply;
  if (s.rfind("glTF", 0) == 0) return MeshFormat::Glb;
  if (n >= 84 && size >= 84) {
    uint32_t count;
    std::memcpy(&count, head + 80, 4);
    if (static_cast<uint64_t>(size) == 84 + 50 * uint64_t{count}) return MeshFormat::Stl;
  }
  if (s.rfind("solid", 0) == 0) return MeshFormat::Stl;
  const size_t first = s.find_first_not_of(" \t\r\n");
  if (first != std::string::npos) {
    const size_t end = s.find_first_of(" \t\r\n", first);
    const std::string word = s.substr(first, end == std::string::npos ? std::string::npos : end - first);
    if (word.size() >= 3 && word.size() <= 6 && word.compare(word.size() - 3, 3, "OFF") == 0)
      return MeshFormat::Off;
    if (s[first] == '{') return MeshFormat::Gltf;
    if (word == "v" || word == "vn" || word == "vt" || word == "o" || word == "g" || word == "mtllib" ||
        word[0] == '#')
      return MeshFormat::Obj;
  }
  return MeshFormat::Auto;
}

}  // namespace

Mesh read_mesh(const std::string& path, const ReadOptions& options, ReadReport* report) {
  ReadReport local;
  ReadReport& r = report ? *report : local;
  r = ReadReport{};
  MeshFormat f = options.format != MeshFormat::Auto ? options.format : format_from_path(path);
  if (f == MeshFormat::Auto) f = sniff(path);
  if (f == MeshFormat::Auto)
    throw InputError(path + ": unknown mesh format (expected .obj, .ply, .off, .stl, .gltf or .glb)");
  r.format = f;
  io::RawMesh raw;
  bool weld_auto = false;
  switch (f) {
    case MeshFormat::Obj:
      raw = io::read_obj(path);
      break;
    case MeshFormat::Ply:
      raw = io::read_ply(path, options.keep_properties);
      break;
    case MeshFormat::Off:
      raw = io::read_off(path);
      break;
    case MeshFormat::Stl:
      raw = io::read_stl(path);
      weld_auto = true;
      break;
    case MeshFormat::Gltf:
    case MeshFormat::Glb:
      raw = io::read_gltf(path);
      weld_auto = true;
      break;
    case MeshFormat::Auto:
      break;
  }
  if (raw.num_polygons() == 0)
    io::fail(path, raw.positions.empty()
                       ? std::string("the file has no vertices and no faces (not a mesh file?)")
                       : "the file has no faces (only " + std::to_string(raw.positions.size()) +
                             " vertices: a point cloud is not a mesh)");
  io::check_indices(raw, path);
  io::check_finite(raw, path);
  return io::finish_mesh(std::move(raw), options, weld_auto, r);
}

void write_mesh(const Mesh& mesh, const std::string& path, const WriteOptions& options) {
  MeshFormat f = options.format != MeshFormat::Auto ? options.format : format_from_path(path);
  for (const Tri& t : mesh.triangles)
    for (uint32_t v : t)
      if (v >= mesh.positions.size()) throw std::invalid_argument("write_mesh: triangle index out of range");
  switch (f) {
    case MeshFormat::Obj:
      io::write_obj(mesh, path);
      return;
    case MeshFormat::Ply:
      io::write_ply(mesh, path, options);
      return;
    case MeshFormat::Off:
      io::write_off(mesh, path);
      return;
    case MeshFormat::Glb:
      io::write_glb(mesh, path, true);
      return;
    case MeshFormat::Gltf:
      io::write_glb(mesh, path, false);
      return;
    case MeshFormat::Stl:
    case MeshFormat::Auto:
      break;
  }
  throw InputError(path + ": cannot write this format (use .obj, .ply, .off, .glb or .gltf)");
}

}  // namespace prm
