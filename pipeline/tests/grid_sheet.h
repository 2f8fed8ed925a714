// An open test sheet: a grid of (n + 1) x (n + 1) vertices of the unit square's parameters, two triangles per cell,
// one boundary loop (the open-boundary and boundary-simplification tests).
#pragma once

#include <cstdint>

#include "prm/mesh.h"

namespace prm::test {

// `position(i, j, x, y)` places grid point (i, j), of parameters (x, y) = (i / n, j / n).
template <typename Position>
Mesh grid_sheet(int n, const Position& position) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.positions.push_back(position(i, j, static_cast<double>(i) / n, static_cast<double>(j) / n));
  auto id = [n](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

}  // namespace prm::test
