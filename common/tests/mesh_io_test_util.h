// Helpers shared by the mesh I/O, validation and repair tests: paths of the test data and small generated
// meshes.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "prm/mesh.h"

namespace prm::test {

inline std::string data_path(const std::string& name) {
  return std::string(PRM_SOURCE_DIR) + "/common/tests/data/" + name;
}
inline std::string shared_mesh(const std::string& name) {
  return std::string(PRM_SHARED_MESHES) + "/" + name;
}
// A scratch file in the build tree, unique per test name.
inline std::string temp_path(const std::string& name) {
  return std::string(PRM_BINARY_DIR) + "/mesh_io_test_" + name;
}

// A tetrahedron with outward faces, placed at `offset`.
inline Mesh tetrahedron(double offset = 0) {
  Mesh m;
  m.positions = {{offset, 0, 0}, {offset + 1, 0, 0}, {offset, 1, 0}, {offset, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

// Appends b's vertices and faces to a.
inline void append(Mesh& a, const Mesh& b) {
  const uint32_t base = static_cast<uint32_t>(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (Tri t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

// A torus of n x m quads split into triangles, outward-oriented: genus 1, Euler characteristic 0.
inline Mesh torus(uint32_t n = 12, uint32_t m = 8, double big = 2, double small = 0.5) {
  Mesh t;
  const double pi = std::acos(-1.0);
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = 0; j < m; ++j) {
      const double u = 2 * pi * i / n, v = 2 * pi * j / m;
      t.positions.push_back({(big + small * std::cos(v)) * std::cos(u),
                             (big + small * std::cos(v)) * std::sin(u), small * std::sin(v)});
    }
  auto id = [&](uint32_t i, uint32_t j) { return (i % n) * m + (j % m); };
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = 0; j < m; ++j) {
      t.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return t;
}

// An open cylinder (a tube of n x m quads): two boundary loops of n edges each, genus 0.
inline Mesh open_cylinder(uint32_t n = 16, uint32_t m = 4) {
  Mesh c;
  const double pi = std::acos(-1.0);
  for (uint32_t j = 0; j <= m; ++j)
    for (uint32_t i = 0; i < n; ++i)
      c.positions.push_back({std::cos(2 * pi * i / n), std::sin(2 * pi * i / n), static_cast<double>(j)});
  auto id = [&](uint32_t i, uint32_t j) { return j * n + (i % n); };
  for (uint32_t j = 0; j < m; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      c.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      c.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return c;
}

// Signed volume (positive for an outward-oriented closed mesh).
inline double signed_volume(const Mesh& m) {
  double v = 0;
  for (const Tri& t : m.triangles) {
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return v / 6;
}

inline double area(const Mesh& m) {
  double s = 0;
  for (const Tri& t : m.triangles) {
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Vec3 x{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    s += 0.5 * std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  }
  return s;
}

}  // namespace prm::test
