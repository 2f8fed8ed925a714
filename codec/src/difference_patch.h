// §9 Heights by recursive difference patches (paper §3.3): the construction of the levels, shared by the encoder
// and the decoder (heights_encode.cpp, heights_decode.cpp). Everything is combinatorial: lattice coordinates only
// tell an edge's direction, so self-overlapping patches work like any other.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "prm_lattice.h"

namespace prm::codec {

// §9.1 A level: vertices with lattice coordinates, triangles over them (local ids).
struct Level {
  std::vector<std::array<int64_t, 2>> coord;
  std::vector<std::array<uint32_t, 3>> tris;
  uint32_t size() const { return static_cast<uint32_t>(coord.size()); }
};

// §9.2 What a level yields for direction d (0, 1, 2: e0, e1, e2 of §8.1):
//   - its edges, in order of first appearance over the triangles (triangle order, then edges (c0, c1), (c1, c2),
//     (c2, c0));
//   - the d-edges: edges whose lattice difference is +e_d or -e_d, oriented so that end = start + e_d;
//   - per vertex, the d-edge that starts at it and the one that ends at it (chains);
//   - per vertex, its other neighbours (non-d edges) in edge order (bridges);
//   - the next level: one vertex per d-edge (in edge order; coordinates of its start vertex), one triangle per
//     triangle T whose d-edge exists and whose two other edges each have exactly one other triangle with a d-edge:
//     (d-edge(T), d-edge(across T's next edge), d-edge(across T's previous edge)).
struct LevelPlan {
  std::vector<std::array<uint32_t, 2>> dedge;     // (start, end) per d-edge = per vertex of the next level
  std::vector<uint32_t> out_edge, in_edge;        // per vertex: d-edge starting / ending there, or UINT32_MAX
  std::vector<uint32_t> nbr_start, nbr;           // CSR: non-d neighbours per vertex
  Level child;
};

inline void plan_level(const Level& level, int d, LevelPlan& out) {
  const uint32_t nv = level.size();
  const uint32_t nt = static_cast<uint32_t>(level.tris.size());
  constexpr uint32_t kNone = UINT32_MAX;
  // Unique edges with their first appearance; per triangle side its edge id.
  struct Side {
    uint64_t key;
    uint32_t first;  // 3 * t + k
  };
  std::vector<Side> sides;
  sides.reserve(size_t{3} * nt);
  for (uint32_t t = 0; t < nt; ++t)
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t a = level.tris[t][k], b = level.tris[t][(k + 1) % 3];
      const uint64_t key = uint64_t{std::min(a, b)} << 32 | std::max(a, b);
      sides.push_back({key, 3 * t + k});
    }
  std::vector<uint32_t> by_key(sides.size());
  for (uint32_t s = 0; s < by_key.size(); ++s) by_key[s] = s;
  std::sort(by_key.begin(), by_key.end(), [&](uint32_t x, uint32_t y) {
    return sides[x].key != sides[y].key ? sides[x].key < sides[y].key : sides[x].first < sides[y].first;
  });
  // side -> edge (numbered by first appearance), edge -> its sides (up to 2 recorded; more marks it crowded).
  std::vector<uint32_t> side_edge(sides.size(), kNone);
  std::vector<uint32_t> edge_first_side;  // per edge (numbered in key order for now)
  std::vector<uint32_t> key_edge(by_key.size());
  for (size_t r = 0; r < by_key.size(); ++r) {
    if (r == 0 || sides[by_key[r]].key != sides[by_key[r - 1]].key) edge_first_side.push_back(sides[by_key[r]].first);
    key_edge[r] = static_cast<uint32_t>(edge_first_side.size() - 1);
  }
  // Renumber edges by first appearance.
  const uint32_t ne = static_cast<uint32_t>(edge_first_side.size());
  std::vector<uint32_t> rank(ne);
  {
    std::vector<uint32_t> idx(ne);
    for (uint32_t e = 0; e < ne; ++e) idx[e] = e;
    std::sort(idx.begin(), idx.end(), [&](uint32_t x, uint32_t y) { return edge_first_side[x] < edge_first_side[y]; });
    for (uint32_t r = 0; r < ne; ++r) rank[idx[r]] = r;
  }
  std::vector<std::array<uint32_t, 2>> edge_sides(ne, {kNone, kNone});
  std::vector<uint8_t> edge_count(ne, 0);
  for (size_t r = 0; r < by_key.size(); ++r) {
    const uint32_t e = rank[key_edge[r]];
    const uint32_t s = sides[by_key[r]].first;
    side_edge[s] = e;
    if (edge_count[e] < 2) edge_sides[e][edge_count[e]] = s;
    if (edge_count[e] < 3) ++edge_count[e];
  }
  // Edge endpoints and directions.
  std::vector<std::array<uint32_t, 2>> ends(ne);
  for (uint32_t e = 0; e < ne; ++e) {
    const uint32_t s = edge_sides[e][0];
    ends[e] = {level.tris[s / 3][s % 3], level.tris[s / 3][(s % 3 + 1) % 3]};
  }
  const auto& step = kDirection[static_cast<size_t>(d)];
  std::vector<uint32_t> edge_dnum(ne, kNone);  // d-edge number of an edge
  out.dedge.clear();
  out.out_edge.assign(nv, kNone);
  out.in_edge.assign(nv, kNone);
  std::vector<uint32_t> nbr_count(nv, 0);
  for (uint32_t e = 0; e < ne; ++e) {
    uint32_t a = ends[e][0], b = ends[e][1];
    const int64_t di = level.coord[b][0] - level.coord[a][0], dj = level.coord[b][1] - level.coord[a][1];
    bool is_d = false;
    if (di == -step[0] && dj == -step[1]) {
      std::swap(a, b);
      is_d = true;
    } else if (di == step[0] && dj == step[1]) {
      is_d = true;
    }
    // A chain is a path: a vertex starts and ends at most one d-edge (a second one is not a d-edge).
    if (is_d && out.out_edge[a] == kNone && out.in_edge[b] == kNone) {
      edge_dnum[e] = static_cast<uint32_t>(out.dedge.size());
      out.out_edge[a] = edge_dnum[e];
      out.in_edge[b] = edge_dnum[e];
      out.dedge.push_back({a, b});
    } else {
      ++nbr_count[ends[e][0]];
      ++nbr_count[ends[e][1]];
    }
  }
  out.nbr_start.assign(size_t{nv} + 1, 0);
  for (uint32_t v = 0; v < nv; ++v) out.nbr_start[v + 1] = out.nbr_start[v] + nbr_count[v];
  out.nbr.assign(out.nbr_start[nv], 0);
  std::vector<uint32_t> fill(out.nbr_start.begin(), out.nbr_start.end() - 1);
  for (uint32_t e = 0; e < ne; ++e) {
    if (edge_dnum[e] != kNone) continue;
    out.nbr[fill[ends[e][0]]++] = ends[e][1];
    out.nbr[fill[ends[e][1]]++] = ends[e][0];
  }
  // The next level.
  Level& child = out.child;
  child.coord.resize(out.dedge.size());
  for (size_t k = 0; k < out.dedge.size(); ++k) child.coord[k] = level.coord[out.dedge[k][0]];
  child.tris.clear();
  auto d_of_triangle = [&](uint32_t t) -> uint32_t {
    for (uint32_t k = 0; k < 3; ++k)
      if (edge_dnum[side_edge[3 * t + k]] != kNone) return edge_dnum[side_edge[3 * t + k]];
    return kNone;
  };
  auto across = [&](uint32_t s) -> uint32_t {  // the other triangle of side s's edge, if exactly one
    const uint32_t e = side_edge[s];
    if (edge_count[e] != 2) return kNone;
    const uint32_t other = edge_sides[e][0] == s ? edge_sides[e][1] : edge_sides[e][0];
    return other / 3;
  };
  for (uint32_t t = 0; t < nt; ++t) {
    uint32_t k = 0;
    while (k < 3 && edge_dnum[side_edge[3 * t + k]] == kNone) ++k;
    if (k == 3) continue;
    const uint32_t n1 = across(3 * t + (k + 1) % 3), n2 = across(3 * t + (k + 2) % 3);
    if (n1 == kNone || n2 == kNone) continue;
    const uint32_t a = edge_dnum[side_edge[3 * t + k]], b = d_of_triangle(n1), c = d_of_triangle(n2);
    if (b == kNone || c == kNone || a == b || b == c || a == c) continue;
    child.tris.push_back({a, b, c});
  }
}

}  // namespace prm::codec
