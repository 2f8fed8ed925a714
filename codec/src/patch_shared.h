// §8-§9 The patches section, shared by patch_encode.cpp and patch_decode.cpp: models, the lattice propagation over
// a patch (§8.3) and the height coding by recursive difference patches (§9), each written once as a template over
// a "coder" that encodes the truth (encoder) or decodes (decoder), so both sides walk the same steps.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "always_inline.h"
#include "closed_mesh.h"
#include "difference_patch_shared.h"
#include "fan_walk.h"
#include "height_prediction_shared.h"
#include "prm/codec.h"
#include "prm/lattice.h"
#include "regular_patches_shared.h"
#include "signed_int_model.h"

namespace prm::codec {

constexpr int kMaxHeightDepth = 6;  // §9.4 Height_Depth 0..6: difference patches
constexpr int kHeightDepthPredicted = kLinearPredictionDepth;  // §9.7 Height_Depth 7: linear prediction (format 1.2)
constexpr int kGridBits = 21;       // §8.4 Grid_Size: 21 direct bits
// §8.4.2 The grid table (Flags bit 4, format 1.5): Extra_Grid_Count in 3 direct bits, 1..kMaxExtraGrids (prm/lattice.h)
// extra grid sizes after Grid_Size; a patch's Grid_Index is a Symbol8.
constexpr int kExtraGridCountBits = 3;
static_assert(kMaxExtraGrids == (1 << kExtraGridCountBits) - 1, "Extra_Grid_Count's 3 bits hold 1..7");

struct HeightModels {
  SignedIntModel final_[kMaxHeightDepth + 1];
  SignedIntModel base[kMaxHeightDepth];
  SignedIntModel bridge[kMaxHeightDepth];
};

struct PatchModels {
  BitModel axis[8];
  BitModel align[8];
  BitModel grid[8];  // §8.4.2 Grid_Index with Flags bit 4
  SignedIntModel base_i, base_j;
  SignedIntModel base_ref_i, base_ref_j;  // §8.4.1 with Flags bit 3
  HeightModels heights;
  LpModels lp;
};

// §8.4 A symbol 0..7 as three modelled bits, most significant first, with a binary tree of models.
template <typename Coder>
int code_symbol8(BitModel (&tree)[8], int truth, Coder& bit) {
  int node = 1;
  for (int k = 2; k >= 0; --k) node = node << 1 | (bit(tree[node], ((truth >> k) & 1) != 0) ? 1 : 0);
  return node - 8;
}

// §8.4.1 The base reference of a patch (Flags bit 3, format 1.4): the first vertex already placed by an earlier patch
// (known[v]) among the base vertex b itself, then b's neighbours in the order of its fan walk from Vertex_Corner[b]
// (§10.2), then the neighbours of each of those in the same order, the walk ending after kBaseWalk corners in all.
// UINT32_MAX if there is none.
constexpr int kBaseWalk = 64;
inline uint32_t base_reference(const ClosedMesh& mesh, const std::vector<uint32_t>& vertex_corner,
                               const std::vector<uint8_t>& known, uint32_t b) {
  if (known[b]) return b;
  std::array<uint32_t, kBaseWalk> ring;
  int ring_size = 0, steps = 0;
  // One fan walk about v; true when it found a placed vertex (in `found`).
  auto walk = [&](uint32_t v, bool keep, uint32_t& found) {
    const uint32_t c0 = vertex_corner[v];
    if (c0 == UINT32_MAX) return false;
    uint32_t c = c0;
    do {
      if (steps++ == kBaseWalk) return false;
      const uint32_t x = mesh.corner_vertex[corner_next(c)];
      if (known[x]) {
        found = x;
        return true;
      }
      if (keep) ring[static_cast<size_t>(ring_size++)] = x;
      c = fan_next(mesh.opp.data(), c);
    } while (c != c0);
    return false;
  };
  uint32_t found = UINT32_MAX;
  if (walk(b, true, found)) return found;
  for (int k = 0; k < ring_size && steps < kBaseWalk; ++k)
    if (walk(ring[static_cast<size_t>(k)], false, found)) return found;
  return UINT32_MAX;
}

// §8.4.1 The lattice point nearest the base-plane position (u, w): j = floor((2w + C) / 2C), then
// i = floor((2(u - B j) + A) / 2A).
inline std::array<int64_t, 2> nearest_lattice_point(const HexLattice& lc, int64_t u, int64_t w) {
  auto floor_div = [](int64_t a, int64_t d) { return a >= 0 ? a / d : -((-a + d - 1) / d); };
  const int64_t j = floor_div(2 * w + lc.C, 2 * lc.C);
  return {floor_div(2 * (u - lc.B * j) + lc.A, 2 * lc.A), j};
}

// §8.4.1 What the base of patch p of `pair` is coded from, both sides: Nearest(R) if the patch has a base reference R
// (true; q: the positions placed so far, 3 per vertex), otherwise nothing is changed (false).
inline bool base_from_reference(const ClosedMesh& mesh, const PatchSet& ps, size_t p, int pair,
                                const std::vector<uint32_t>& vertex_corner, const std::vector<uint8_t>& known,
                                const uint32_t* q, const HexLattice& lc, std::array<int64_t, 2>& from) {
  const uint32_t r = base_reference(mesh, vertex_corner, known, mesh.corner_vertex[3 * size_t{ps.order[ps.start[p]]}]);
  if (r == UINT32_MAX) return false;
  from = nearest_lattice_point(lc, q[3 * size_t{r} + static_cast<size_t>(pair_u(pair))],
                               q[3 * size_t{r} + static_cast<size_t>(pair_w(pair))]);
  return true;
}

// §8.3 Lattice coordinates of the vertices of one patch: local vertex ids in first-appearance order over the
// patch's triangles (patch order, corners 0, 1, 2), lattice coordinates propagated from the first triangle, where
// corner 0 is at `base` and corner 1 at base + direction `align`. Fills `level` (coordinates, local triangles),
// `global` (local -> mesh vertex) and `local` (mesh vertex -> local id, for the vertices of this patch; the caller
// resets the entries it set). Returns false on a lattice conflict: a vertex reached with two coordinates.
// One pass: a triangle's ids are taken and its third corner placed before the next triangle is read (the placing
// of triangle r depends only on triangles 0..r - 1, so this is the two-pass order's result); a coordinate not yet
// placed holds kUnplaced (no lattice coordinate reaches it: they are bounded by the base, one step per triangle).
// On a conflict, `level` and `global` hold the triangles up to the failing one only.
inline bool propagate_patch(const ClosedMesh& mesh, const PatchSet& ps, size_t p, const std::array<int64_t, 2>& base,
                            int align, bool positive, Level& level, std::vector<uint32_t>& global,
                            std::vector<uint32_t>& local) {
  constexpr uint32_t kNone = UINT32_MAX;
  constexpr int64_t kUnplaced = INT64_MIN;
  const uint32_t* cv = mesh.corner_vertex.data();
  const uint32_t first = ps.start[p], count = ps.start[p + 1] - first;
  level.coord.clear();
  level.tris.resize(count);
  global.clear();
  // A patch's triangles share edges (breadth-first order): at most count + 2 vertices. Sized once, no copies.
  level.coord.reserve(size_t{count} + 2);
  global.reserve(size_t{count} + 2);
  uint32_t* loc = local.data();
  auto id_of = [&](uint32_t v) PRM_WASM_INLINE_LAMBDA {
    uint32_t id = loc[v];
    if (id == kNone) {
      id = static_cast<uint32_t>(global.size());
      loc[v] = id;
      global.push_back(v);
      level.coord.push_back({kUnplaced, 0});
    }
    return id;
  };
  auto assign = [&](uint32_t id, const std::array<int64_t, 2>& c) {
    std::array<int64_t, 2>& at = level.coord[id];
    if (at[0] != kUnplaced) return at[0] == c[0] && at[1] == c[1];  // (std::array's == is a memcmp call)
    at = c;
    return true;
  };
  for (uint32_t r = 0; r < count; ++r) {
    const uint32_t* tc = cv + 3 * size_t{ps.order[first + r]};
    auto& t = level.tris[r];
    t = {id_of(tc[0]), id_of(tc[1]), id_of(tc[2])};
    if (r == 0) {
      const std::array<int64_t, 2> c1 = {base[0] + kDirection[static_cast<size_t>(align)][0],
                                         base[1] + kDirection[static_cast<size_t>(align)][1]};
      assign(t[0], base);
      if (!assign(t[1], c1)) return false;
      if (!assign(t[2], third_corner(base, c1, positive))) return false;
      continue;
    }
    // Breadth-first patch order: every later triangle shares an edge with an earlier one.
    auto placed = [&](uint32_t id) { return level.coord[id][0] != kUnplaced; };
    // The first k in 0, 1, 2 whose edge t[k] -> t[k + 1] has both ends placed.
    const bool p0 = placed(t[0]), p1 = placed(t[1]), p2 = placed(t[2]);
    const int k = p0 && p1 ? 0 : p1 && p2 ? 1 : p2 && p0 ? 2 : 3;
    if (k == 3) return false;
    const uint32_t x = t[k], y = t[(k + 1) % 3], z = t[(k + 2) % 3];
    if (!assign(z, third_corner(level.coord[x], level.coord[y], positive))) return false;
  }
  return true;
}

// §9.2 The levels of one patch, top-down (values are not needed to build them): plans[k] describes level k for
// direction k mod 3 and holds level k + 1 as its child.
// twin0 (optional): level 0's side twins (patch_side_twins).
inline void build_levels(const Level& level0, int depth, std::vector<LevelPlan>& plans,
                         const std::vector<uint32_t>* twin0 = nullptr) {
  plans.resize(static_cast<size_t>(depth));
  const Level* level = &level0;
  for (int k = 0; k < depth; ++k) {
    plan_level(*level, k % 3, plans[static_cast<size_t>(k)], k == 0 ? twin0 : nullptr);
    level = &plans[static_cast<size_t>(k)].child;
  }
}

// Level 0's side twins from the corner table: side 3r + k of the patch's r-th triangle t (edge from corner k to
// corner k + 1, opposite corner k + 2) and the side of the neighbour across it, when that neighbour is in the same
// patch. `tri_pos` (size T, all UINT32_MAX on entry and on return) is scratch.
inline void patch_side_twins(const ClosedMesh& mesh, const PatchSet& ps, size_t p, std::vector<uint32_t>& tri_pos,
                             std::vector<uint32_t>& twin) {
  const uint32_t first = ps.start[p], count = ps.start[p + 1] - first;
  for (uint32_t r = 0; r < count; ++r) tri_pos[ps.order[first + r]] = r;
  twin.resize(size_t{3} * count);
  for (uint32_t r = 0; r < count; ++r) {
    const uint32_t t = ps.order[first + r];
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t oc = static_cast<uint32_t>(mesh.opp[3 * t + (k + 2) % 3]);
      const uint32_t rn = tri_pos[oc / 3];
      twin[3 * r + k] = rn == UINT32_MAX ? UINT32_MAX : 3 * rn + (oc % 3 + 1) % 3;
    }
  }
  for (uint32_t r = 0; r < count; ++r) tri_pos[ps.order[first + r]] = UINT32_MAX;
}

// §9.3 Heights of one patch, over levels build_levels() made. f[0] holds the heights (encoder: input; decoder:
// output). `value(model, max_class, truth, out)` codes one signed integer. Returns false when a decoded value breaks
// a bound (§9.3: |f_k| < 2^(bits+k+1)).
template <typename Value>
bool code_heights(const Level& level0, int depth, int bits, HeightModels& m, std::vector<std::vector<int64_t>>& f,
                  const std::vector<LevelPlan>& plans, std::vector<uint8_t>& known, std::vector<uint32_t>& queue,
                  bool encoder, Value& value) {
  f.resize(static_cast<size_t>(depth) + 1);
  auto level_size = [&](int k) { return k == 0 ? level0.size() : plans[static_cast<size_t>(k - 1)].child.size(); };
  for (int k = 0; k <= depth; ++k) f[static_cast<size_t>(k)].resize(level_size(k));
  if (encoder)  // f_{k+1} on the d-edges of level k: f_k(end) - f_k(start)
    for (int k = 0; k < depth; ++k) {
      const auto& dedge = plans[static_cast<size_t>(k)].dedge;
      for (size_t e = 0; e < dedge.size(); ++e)
        f[static_cast<size_t>(k) + 1][e] = f[static_cast<size_t>(k)][dedge[e][1]] - f[static_cast<size_t>(k)][dedge[e][0]];
    }
  auto bound = [&](int k) { return int64_t{1} << (bits + k + 1); };
  auto in_bound = [&](int k, int64_t v) { return v > -bound(k) && v < bound(k); };
  // §9.3 The deepest level's values, explicitly.
  {
    std::vector<int64_t>& fd = f[static_cast<size_t>(depth)];
    for (size_t v = 0; v < fd.size(); ++v) {
      int64_t out;
      if (!value(m.final_[depth], bits + depth + 1, fd[v], out) || !in_bound(depth, out)) return false;
      fd[v] = out;
    }
  }
  // §9.3 Each level from the one below: base values, bridges, chains.
  for (int k = depth - 1; k >= 0; --k) {
    const LevelPlan& pl = plans[static_cast<size_t>(k)];
    std::vector<int64_t>& fk = f[static_cast<size_t>(k)];
    const std::vector<int64_t>& below = f[static_cast<size_t>(k) + 1];
    const uint32_t n = static_cast<uint32_t>(fk.size());
    known.assign(n, 0);
    queue.clear();
    // The chain through v (whose value is set): values along it from the differences, vertices queued in order.
    auto chain = [&](uint32_t v) {
      uint32_t s = v;
      while (pl.in_edge[s] != UINT32_MAX) {
        const uint32_t e = pl.in_edge[s];
        const uint32_t a = pl.dedge[e][0];
        fk[a] = fk[s] - below[e];
        if (!in_bound(k, fk[a])) return false;
        s = a;
      }
      for (uint32_t u = s;;) {
        known[u] = 1;
        queue.push_back(u);
        const uint32_t e = pl.out_edge[u];
        if (e == UINT32_MAX) break;
        const uint32_t b = pl.dedge[e][1];
        if (b != v) {
          fk[b] = fk[u] + below[e];
          if (!in_bound(k, fk[b])) return false;
        }
        u = b;
      }
      return true;
    };
    for (uint32_t v0 = 0; v0 < n; ++v0) {
      if (known[v0]) continue;
      int64_t out;
      if (!value(m.base[k], bits + k + 1, fk[v0], out) || !in_bound(k, out)) return false;
      fk[v0] = out;
      size_t head = queue.size();
      if (!chain(v0)) return false;
      while (head < queue.size()) {
        const uint32_t u = queue[head++];
        for (uint32_t r = pl.nbr_start[u]; r < pl.nbr_start[u + 1]; ++r) {
          const uint32_t w = pl.nbr[r];
          if (known[w]) continue;
          if (!value(m.bridge[k], bits + k + 2, fk[w] - fk[u], out)) return false;
          fk[w] = fk[u] + out;
          if (!in_bound(k, fk[w])) return false;
          if (!chain(w)) return false;
        }
      }
    }
  }
  return true;
}

}  // namespace prm::codec
