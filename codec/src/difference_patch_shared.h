// §9 Heights by recursive difference patches (paper §3.3): the construction of the levels, shared by the encoder
// and the decoder (patch_shared.h, patch_encode.cpp, patch_decode.cpp). Everything is combinatorial: lattice coordinates only
// tell an edge's direction, so self-overlapping patches work like any other.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "prm/lattice.h"

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
  // Scratch, kept between calls to spare allocations.
  std::vector<uint32_t> side_edge, bucket_start, bucket, group_first, fill, side_lo, side_hi, edge_dnum;
  std::vector<std::array<uint32_t, 2>> ends;
  std::vector<uint8_t> tri_dside;
  std::vector<std::array<uint32_t, 2>> edge_sides;
  std::vector<uint8_t> edge_count;
};

// `twin` (optional): per side, the other side of its edge or UINT32_MAX; level 0 knows it from the mesh's corner
// table (§6.1), which on a valid stream groups the sides exactly as the vertex pairs do (§6.8: no two edges join
// the same pair). Without it the pairs are grouped here.
inline void plan_level(const Level& level, int d, LevelPlan& out, const std::vector<uint32_t>* twin = nullptr) {
  const uint32_t nv = level.size();
  const uint32_t nt = static_cast<uint32_t>(level.tris.size());
  constexpr uint32_t kNone = UINT32_MAX;
  // Unique edges (unordered vertex pairs) numbered by first appearance over the sides 3t + k; per side its edge;
  // per edge its first two sides and how many sides it has (capped at 3). Sides are bucketed by their smaller
  // vertex (a stable counting sort), then grouped by the larger one inside each bucket: linear in the sides.
  const size_t num_sides = size_t{3} * nt;
  auto& side_edge = out.side_edge;
  auto& edge_sides = out.edge_sides;
  auto& edge_count = out.edge_count;
  auto& bucket_start = out.bucket_start;
  auto& bucket = out.bucket;
  auto& group_first = out.group_first;
  side_edge.resize(num_sides);
  group_first.assign(num_sides, kNone);
  if (twin) {
    for (uint32_t s = 0; s < num_sides; ++s) {
      const uint32_t o = (*twin)[s];
      group_first[s] = o != kNone && o < s ? o : s;
    }
  } else {
  bucket_start.assign(size_t{nv} + 1, 0);
  auto& side_lo = out.side_lo;
  auto& side_hi = out.side_hi;
  side_lo.resize(num_sides);
  side_hi.resize(num_sides);
  for (uint32_t t = 0; t < nt; ++t) {
    const auto& tri = level.tris[t];
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t a = tri[k], b = tri[k == 2 ? 0 : k + 1];
      side_lo[3 * t + k] = a < b ? a : b;
      side_hi[3 * t + k] = a < b ? b : a;
    }
  }
  auto lo_of = [&](uint32_t s) { return side_lo[s]; };
  auto hi_of = [&](uint32_t s) { return side_hi[s]; };
  for (uint32_t s = 0; s < num_sides; ++s) ++bucket_start[lo_of(s) + 1];
  for (uint32_t v = 0; v < nv; ++v) bucket_start[v + 1] += bucket_start[v];
  bucket.resize(num_sides);
  {
    std::vector<uint32_t>& fill = out.fill;
    fill.assign(bucket_start.begin(), bucket_start.end() - 1);
    for (uint32_t s = 0; s < num_sides; ++s) bucket[fill[lo_of(s)]++] = s;
  }
  for (uint32_t v = 0; v < nv; ++v) {
    const uint32_t b0 = bucket_start[v], b1 = bucket_start[v + 1];
    if (b1 - b0 > 64)  // a crowded vertex (hostile input): sort its bucket by the other end, stably
      std::stable_sort(bucket.begin() + b0, bucket.begin() + b1, [&](uint32_t x, uint32_t y) { return hi_of(x) < hi_of(y); });
    for (uint32_t r = b0; r < b1; ++r) {
      const uint32_t s = bucket[r];
      if (group_first[s] != kNone) continue;
      group_first[s] = s;  // the smallest side of its group: buckets keep increasing side order
      const uint32_t other = hi_of(s);
      for (uint32_t r2 = r + 1; r2 < b1; ++r2) {
        const uint32_t o = hi_of(bucket[r2]);
        if (o == other) group_first[bucket[r2]] = s;
        else if (b1 - b0 > 64 && o > other) break;  // sorted bucket: no more of this group
      }
    }
  }
  }
  uint32_t ne = 0;
  for (uint32_t s = 0; s < num_sides; ++s) ne += group_first[s] == s;
  edge_sides.resize(ne);
  edge_count.resize(ne);
  for (uint32_t s = 0, next = 0; s < num_sides; ++s) {
    const uint32_t g = group_first[s];
    if (g == s) {
      side_edge[s] = next;
      edge_sides[next][0] = s;
      edge_sides[next][1] = kNone;
      edge_count[next] = 1;
      ++next;
    } else {
      const uint32_t e = side_edge[g];
      side_edge[s] = e;
      if (edge_count[e] < 2) edge_sides[e][1] = s;
      if (edge_count[e] < 3) ++edge_count[e];
    }
  }
  // Edge endpoints and directions.
  auto& ends = out.ends;
  ends.resize(ne);
  for (uint32_t e = 0; e < ne; ++e) {
    const uint32_t s = edge_sides[e][0];
    ends[e] = {level.tris[s / 3][s % 3], level.tris[s / 3][(s % 3 + 1) % 3]};
  }
  const auto& step = kDirection[static_cast<size_t>(d)];
  auto& edge_dnum = out.edge_dnum;  // d-edge number of an edge
  edge_dnum.assign(ne, kNone);
  out.dedge.resize(ne);  // at most one d-edge per edge; trimmed below
  uint32_t num_d = 0;
  out.out_edge.assign(nv, kNone);
  out.in_edge.assign(nv, kNone);
  auto& nbr_count = out.fill;
  nbr_count.assign(nv, 0);
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
      edge_dnum[e] = num_d;
      out.out_edge[a] = num_d;
      out.in_edge[b] = num_d;
      out.dedge[num_d][0] = a;
      out.dedge[num_d][1] = b;
      ++num_d;
    } else {
      ++nbr_count[ends[e][0]];
      ++nbr_count[ends[e][1]];
    }
  }
  out.dedge.resize(num_d);
  out.nbr_start.assign(size_t{nv} + 1, 0);
  for (uint32_t v = 0; v < nv; ++v) out.nbr_start[v + 1] = out.nbr_start[v] + nbr_count[v];
  out.nbr.assign(out.nbr_start[nv], 0);
  auto& fill = out.fill;
  fill.assign(out.nbr_start.begin(), out.nbr_start.end() - 1);
  for (uint32_t e = 0; e < ne; ++e) {
    if (edge_dnum[e] != kNone) continue;
    out.nbr[fill[ends[e][0]]++] = ends[e][1];
    out.nbr[fill[ends[e][1]]++] = ends[e][0];
  }
  // The next level.
  Level& child = out.child;
  child.coord.resize(out.dedge.size());
  for (size_t k = 0; k < out.dedge.size(); ++k) child.coord[k] = level.coord[out.dedge[k][0]];
  child.tris.resize(nt);  // at most one per triangle; trimmed below
  uint32_t num_child = 0;
  // Per triangle: the side of its d-edge (0..2), or 3.
  auto& tri_dside = out.tri_dside;
  tri_dside.resize(nt);
  for (uint32_t t = 0; t < nt; ++t) {
    uint8_t k = 0;
    while (k < 3 && edge_dnum[side_edge[3 * t + k]] == kNone) ++k;
    tri_dside[t] = k;
  }
  auto d_of_triangle = [&](uint32_t t) -> uint32_t {
    return tri_dside[t] < 3 ? edge_dnum[side_edge[3 * t + tri_dside[t]]] : kNone;
  };
  auto across = [&](uint32_t s) -> uint32_t {  // the other triangle of side s's edge, if exactly one
    const uint32_t e = side_edge[s];
    if (edge_count[e] != 2) return kNone;
    const uint32_t other = edge_sides[e][0] == s ? edge_sides[e][1] : edge_sides[e][0];
    return other / 3;
  };
  for (uint32_t t = 0; t < nt; ++t) {
    const uint32_t k = tri_dside[t];
    if (k == 3) continue;
    const uint32_t n1 = across(3 * t + (k + 1) % 3), n2 = across(3 * t + (k + 2) % 3);
    if (n1 == kNone || n2 == kNone) continue;
    const uint32_t a = edge_dnum[side_edge[3 * t + k]], b = d_of_triangle(n1), c = d_of_triangle(n2);
    if (b == kNone || c == kNone || a == b || b == c || a == c) continue;
    child.tris[num_child][0] = a;
    child.tris[num_child][1] = b;
    child.tris[num_child][2] = c;
    ++num_child;
  }
  child.tris.resize(num_child);
}

}  // namespace prm::codec
