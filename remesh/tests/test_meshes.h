// Generated meshes and small checks shared by the remesher's tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "prm/mesh.h"
#include "prm/vec3.h"

namespace prm::test {

// Icosahedron subdivided `levels` times, projected onto a sphere of radius r (optionally bumped).
inline Mesh icosphere(int levels, double r = 1.0, double bump = 0.0) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.positions.push_back((m.positions[a] + m.positions[b]) * 0.5);
      const uint32_t id = static_cast<uint32_t>(m.positions.size() - 1);
      mid[key] = id;
      return id;
    };
    std::vector<Tri> next;
    for (const Tri& f : m.triangles) {
      const uint32_t a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      next.push_back({f[0], a, c});
      next.push_back({f[1], b, a});
      next.push_back({f[2], c, b});
      next.push_back({a, b, c});
    }
    m.triangles = std::move(next);
  }
  for (Vec3& p : m.positions) {
    const Vec3 u = normalized(p);
    const double rr = r * (1.0 + bump * std::sin(5 * u[0]) * std::sin(4 * u[1]) * std::sin(3 * u[2]));
    p = u * rr;
  }
  return m;
}

// Torus with major radius R and minor radius r, n x m quads split into triangles.
inline Mesh torus(int n, int m, double R = 1.0, double r = 0.35) {
  Mesh mesh;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      mesh.positions.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  auto id = [&](int i, int j) { return static_cast<uint32_t>(((i + n) % n) * m + (j + m) % m); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return mesh;
}

// A thick helical ramp of 1.5 turns around the z axis: its top faces +z and overlaps itself in projection, a
// self-overlapping relief. The cross-section (r0..r1 by thickness) is swept along the helix; the ends are fanned.
inline Mesh helical_ramp(int steps = 360, double turns = 1.5, double r0 = 0.5, double r1 = 1.0, double pitch = 0.32,
                         double thickness = 0.1) {
  Mesh m;
  // Cross-section loop: bottom (r0->r1), outer wall, top (r1->r0), inner wall; 8 points per side.
  std::vector<std::array<double, 2>> loop;  // (r, z offset)
  const int per = 8;
  for (int k = 0; k < per; ++k) loop.push_back({r0 + (r1 - r0) * k / per, 0});
  for (int k = 0; k < per; ++k) loop.push_back({r1, thickness * k / per});
  for (int k = 0; k < per; ++k) loop.push_back({r1 - (r1 - r0) * k / per, thickness});
  for (int k = 0; k < per; ++k) loop.push_back({r0, thickness - thickness * k / per});
  const int n = static_cast<int>(loop.size());
  for (int s = 0; s <= steps; ++s) {
    const double th = 2 * M_PI * turns * s / steps;
    for (const auto& c : loop)
      m.positions.push_back({c[0] * std::cos(th), c[0] * std::sin(th), pitch * th / (2 * M_PI) + c[1]});
  }
  auto id = [&](int s, int k) { return static_cast<uint32_t>(s * n + (k % n)); };
  for (int s = 0; s < steps; ++s)
    for (int k = 0; k < n; ++k) {
      // Outward orientation: the loop runs bottom, outer, top, inner (counter-clockwise seen along +theta).
      m.triangles.push_back({id(s, k), id(s + 1, k), id(s + 1, k + 1)});
      m.triangles.push_back({id(s, k), id(s + 1, k + 1), id(s, k + 1)});
    }
  for (int end = 0; end < 2; ++end) {
    const int s = end == 0 ? 0 : steps;
    Vec3 c{0, 0, 0};
    for (int k = 0; k < n; ++k) c += m.positions[id(s, k)];
    m.positions.push_back(c * (1.0 / n));
    const uint32_t centre = static_cast<uint32_t>(m.positions.size() - 1);
    for (int k = 0; k < n; ++k) {
      if (end == 0)
        m.triangles.push_back({centre, id(s, k), id(s, k + 1)});
      else
        m.triangles.push_back({centre, id(s, k + 1), id(s, k)});
    }
  }
  return m;
}

struct Topology {
  bool closed_manifold = true;  // every directed edge once, its reverse once, one fan per vertex
  int components = 0;
  long euler = 0;
  int genus_sum = 0;
  size_t degenerate = 0;  // faces with a repeated vertex
};

inline Topology topology(const Mesh& m) {
  Topology t;
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (const Tri& f : m.triangles) {
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) ++t.degenerate;
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  }
  for (const auto& [e, c] : directed)
    if (c != 1 || directed.count({e.second, e.first}) == 0) t.closed_manifold = false;
  // Components via union-find on vertices of faces; fans per vertex via face adjacency around the vertex.
  std::vector<uint32_t> parent(m.positions.size());
  for (uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<int> used(m.positions.size(), 0);
  for (const Tri& f : m.triangles)
    for (int k = 0; k < 3; ++k) {
      used[f[k]] = 1;
      parent[find(f[k])] = find(f[(k + 1) % 3]);
    }
  std::set<uint32_t> roots;
  long nv = 0;
  for (uint32_t v = 0; v < parent.size(); ++v)
    if (used[v]) {
      roots.insert(find(v));
      ++nv;
    }
  t.components = static_cast<int>(roots.size());
  const long ne = static_cast<long>(directed.size()) / 2;
  t.euler = nv - ne + static_cast<long>(m.triangles.size());
  t.genus_sum = static_cast<int>((2 * t.components - t.euler) / 2);
  // One fan per vertex: count each vertex's outgoing edges = incident faces in a closed manifold; check a walk.
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> next_around;  // (v, a) -> b for face (v, a, b)
  std::vector<int> faces_at(m.positions.size(), 0);
  for (const Tri& f : m.triangles)
    for (int k = 0; k < 3; ++k) {
      next_around[{f[k], f[(k + 1) % 3]}] = f[(k + 2) % 3];
      ++faces_at[f[k]];
    }
  if (t.closed_manifold)
    for (const Tri& f : m.triangles) {
      const uint32_t v = f[0], start = f[1];
      uint32_t a = start;
      int steps = 0;
      do {
        auto it = next_around.find({v, a});
        if (it == next_around.end()) break;
        a = it->second;
        ++steps;
      } while (a != start && steps <= faces_at[v]);
      if (steps != faces_at[v]) t.closed_manifold = false;
    }
  return t;
}

}  // namespace prm::test
