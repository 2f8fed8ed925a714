// Generated meshes with known geometry for the distance tests.
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <utility>

#include "prm/mesh.h"
#include "prm/vec3.h"

namespace prm::test {

// Icosahedron subdivided `levels` times (each triangle into four), vertices on the sphere of the given radius and
// centre. 10·4^levels + 2 vertices, 20·4^levels faces, counter-clockwise seen from outside.
inline Mesh icosphere(int levels, double radius = 1.0, Vec3 centre = {0, 0, 0}) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& p : m.positions) p = normalized(p);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const uint32_t id = static_cast<uint32_t>(m.positions.size());
      m.positions.push_back(normalized(m.positions[a] + m.positions[b]));
      mid.emplace(key, id);
      return id;
    };
    std::vector<Tri> next;
    next.reserve(4 * m.triangles.size());
    for (const Tri& f : m.triangles) {
      const uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    m.triangles = std::move(next);
  }
  for (Vec3& p : m.positions) p = centre + p * radius;
  return m;
}

// A rectangular patch of the plane z = height: [0, sx] × [0, sy] cut into nx × ny cells, two triangles each.
inline Mesh grid_patch(int nx, int ny, double sx, double sy, double height = 0.0) {
  Mesh m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.positions.push_back({sx * i / nx, sy * j / ny, height});
  auto id = [&](int i, int j) { return static_cast<uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

inline Mesh translated(Mesh m, const Vec3& t) {
  for (Vec3& p : m.positions) p += t;
  return m;
}

// Every vertex moved by a uniform random vector of the cube [-amplitude, amplitude]^3.
inline Mesh jittered(Mesh m, double amplitude, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (Vec3& p : m.positions) p = p + Vec3{u(rng), u(rng), u(rng)};
  return m;
}

// Random triangle soup in the unit cube (for brute-force comparisons of the tree).
inline Mesh random_soup(size_t triangles, uint64_t seed, double size = 0.2) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), s(-size, size);
  Mesh m;
  for (size_t t = 0; t < triangles; ++t) {
    const Vec3 c{u(rng), u(rng), u(rng)};
    for (int k = 0; k < 3; ++k) m.positions.push_back(c + Vec3{s(rng), s(rng), s(rng)});
    const uint32_t b = static_cast<uint32_t>(3 * t);
    m.triangles.push_back({b, b + 1, b + 2});
  }
  return m;
}

}  // namespace prm::test
