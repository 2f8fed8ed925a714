// §7.1 The encoder's regularity check and §8-§9 the patches section, encoder side (patch headers, heights by
// recursive difference patches). The decoder side is patch_decode.cpp; the shared steps are in patch_shared.h.
#include <memory>
#include <string>

#include "patch_shared.h"
#include "patches.h"
#include "range_encoder.h"
#include "status.h"

namespace prm::codec {
namespace {

// Lattice coordinates of vertex v for pair k, if it is a lattice point.
bool lattice_of(const std::vector<uint32_t>& cq, const LatticeConstants& lc, int pair, uint32_t v,
                std::array<int64_t, 2>& ij) {
  const int64_t u = cq[3 * size_t{v} + static_cast<size_t>(pair_u(pair))];
  const int64_t w = cq[3 * size_t{v} + static_cast<size_t>(pair_w(pair))];
  return lc.to_lattice(u, w, ij[0], ij[1]);
}

// §7.1 The axis a triangle is regular for, or -1.
int regular_axis(const std::vector<uint32_t>& cq, const LatticeConstants& lc, const uint32_t* v) {
  for (int pair = 0; pair < 3; ++pair) {
    std::array<int64_t, 2> p[3];
    if (!lattice_of(cq, lc, pair, v[0], p[0]) || !lattice_of(cq, lc, pair, v[1], p[1]) ||
        !lattice_of(cq, lc, pair, v[2], p[2]))
      continue;
    bool unit = true;
    for (int k = 0; k < 3; ++k)
      unit = unit && direction_index(p[(k + 1) % 3][0] - p[k][0], p[(k + 1) % 3][1] - p[k][1]) >= 0;
    if (!unit) continue;
    const int64_t cross = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if (cross == 1) return 2 * pair;
    if (cross == -1) return 2 * pair + 1;
  }
  return -1;
}

}  // namespace

void classify_triangles(const ClosedMesh& mesh, const std::vector<uint32_t>& cq, int64_t grid,
                        std::vector<int8_t>& tri_axis) {
  const uint32_t nt = mesh.num_triangles();
  const LatticeConstants lc = LatticeConstants::of(grid);
  const std::vector<uint8_t> dummy = dummy_triangles(mesh);
  tri_axis.assign(nt, -1);
  for (uint32_t t = 0; t < nt; ++t)
    if (dummy[t] != kDummyTriangle) tri_axis[t] = static_cast<int8_t>(regular_axis(cq, lc, &mesh.corner_vertex[3 * t]));
  // §8.2 One axis per patch: regular neighbours of different axes are both made irregular.
  std::vector<uint8_t> demote(nt, 0);
  for (uint32_t t = 0; t < nt; ++t) {
    if (tri_axis[t] < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = static_cast<uint32_t>(mesh.opp[3 * t + k]) / 3;
      if (tri_axis[n] >= 0 && tri_axis[n] != tri_axis[t]) demote[t] = 1;
    }
  }
  for (uint32_t t = 0; t < nt; ++t)
    if (demote[t]) tri_axis[t] = -1;
}

Status write_patches(const ClosedMesh& mesh, const std::vector<uint32_t>& cq, int bits, int64_t grid,
                     const std::vector<int8_t>& tri_axis, int depth, std::vector<uint8_t>& payload,
                     std::vector<uint8_t>& known, PatchStats* stats) {
  const uint32_t nt = mesh.num_triangles();
  std::vector<uint8_t> cls = dummy_triangles(mesh);
  for (uint32_t t = 0; t < nt; ++t)
    if (cls[t] != kDummyTriangle) cls[t] = tri_axis[t] >= 0 ? kRegular : kIrregular;
  const PatchSet ps = build_patches(mesh, cls);
  const LatticeConstants lc = LatticeConstants::of(grid);
  RangeEncoder rc;
  auto models = std::make_unique<PatchModels>();
  // §8.4 Grid_Size and Height_Depth.
  rc.encode_direct(static_cast<uint32_t>(grid), kGridBits);
  rc.encode_direct(static_cast<uint32_t>(depth), 3);
  auto bit = [&](BitModel& m, bool truth) {
    rc.encode_bit(m, truth ? 1 : 0);
    return truth;
  };
  auto value = [&](SignedIntModel& m, int, int64_t truth, int64_t& out) {
    encode_signed(rc, m, truth);
    out = truth;
    return true;
  };
  known.assign(mesh.num_vertices, 0);
  std::vector<uint32_t> local(mesh.num_vertices, UINT32_MAX), global, queue;
  Level level;
  std::vector<std::vector<int64_t>> f;
  std::vector<LevelPlan> plans;
  std::vector<uint32_t> tri_pos(mesh.num_triangles(), UINT32_MAX), twin;
  std::vector<uint8_t> scratch;
  std::array<int64_t, 2> previous{0, 0};
  uint32_t patch_vertices = 0;
  for (size_t p = 0; p < ps.size(); ++p) {
    const uint32_t t0 = ps.order[ps.start[p]];
    const int axis = tri_axis[t0];
    const int pair = axis / 2;
    std::array<int64_t, 2> c0, c1;
    if (!lattice_of(cq, lc, pair, mesh.corner_vertex[3 * t0], c0) ||
        !lattice_of(cq, lc, pair, mesh.corner_vertex[3 * t0 + 1], c1))
      return make_status(Error::internal, "8.3", 0, "a regular triangle's corner is not a lattice point");
    const int align = direction_index(c1[0] - c0[0], c1[1] - c0[1]);
    // §8.4 The patch header.
    code_symbol8(models->axis, axis, bit);
    encode_signed(rc, models->base_i, c0[0] - previous[0]);
    encode_signed(rc, models->base_j, c0[1] - previous[1]);
    code_symbol8(models->align, align, bit);
    previous = c0;
    // §8.3 The decoder's propagation must find every vertex where it is.
    if (!propagate_patch(mesh, ps, p, c0, align, axis % 2 == 0, level, global, local))
      return make_status(Error::internal, "8.3", 0, "lattice conflict in patch " + std::to_string(p));
    for (uint32_t l = 0; l < level.size(); ++l) {
      std::array<int64_t, 2> actual;
      if (!lattice_of(cq, lc, pair, global[l], actual) || actual != level.coord[l])
        return make_status(Error::internal, "8.3", 0, "patch " + std::to_string(p) + " propagates off its lattice");
    }
    // §9 Heights.
    f.assign(1, std::vector<int64_t>(level.size()));
    for (uint32_t l = 0; l < level.size(); ++l) f[0][l] = cq[3 * size_t{global[l]} + static_cast<size_t>(pair)];
    patch_side_twins(mesh, ps, p, tri_pos, twin);
    build_levels(level, depth, plans, &twin);
    if (!code_heights(level, depth, bits, models->heights, f, plans, scratch, queue, true, value))
      return make_status(Error::internal, "9.3", 0, "height out of range in patch " + std::to_string(p));
    for (uint32_t l = 0; l < level.size(); ++l) {
      patch_vertices += !known[global[l]];
      known[global[l]] = 1;
      local[global[l]] = UINT32_MAX;
    }
  }
  payload = rc.finish();
  if (stats) {
    stats->patches = static_cast<uint32_t>(ps.size());
    stats->patch_vertices = patch_vertices;
  }
  return ok_status();
}

}  // namespace prm::codec
