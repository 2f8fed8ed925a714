// Issue 17's awkward inputs for pack, shared by the pack tests: a bowtie and a box as thin as one likes.
#pragma once

#include <array>
#include <cstdint>
#include <map>

#include "prm/mesh.h"

namespace prm::test {

// Two triangles sharing one vertex: repair splits the pinch and closes each triangle into a flat two-sided shape.
inline Mesh bowtie() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0.5, 0}, {1, -0.5, 0}, {-1, 0.5, 0}, {-1, -0.5, 0}};
  m.triangles = {{0, 1, 2}, {0, 3, 4}};
  return m;
}

// The surface of an sx x sy x sz box, each side an n x n grid of quads split in two, outward.
inline Mesh box(double sx, double sy, double sz, int n) {
  Mesh m;
  std::map<std::array<int, 3>, uint32_t> id;
  auto vertex = [&](std::array<int, 3> g) {
    auto [it, added] = id.emplace(g, static_cast<uint32_t>(m.positions.size()));
    if (added) m.positions.push_back({sx * g[0] / n, sy * g[1] / n, sz * g[2] / n});
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto at = [&](int u, int w) {
            std::array<int, 3> g{};
            g[static_cast<size_t>(axis)] = side * n;
            g[static_cast<size_t>((axis + 1) % 3)] = u;
            g[static_cast<size_t>((axis + 2) % 3)] = w;
            return vertex(g);
          };
          const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
          if (side) {
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
          } else {
            m.triangles.push_back({a, c, b});
            m.triangles.push_back({a, d, c});
          }
        }
  return m;
}

}  // namespace prm::test
