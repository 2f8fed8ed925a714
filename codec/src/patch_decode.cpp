// §8-§9 The patches section, decoder side: the mirror of patch_encode.cpp. Every decoded value is checked before
// it is used: axis and alignment in 0..5, lattice coordinates consistent over the patch and with vertices earlier
// patches placed, positions inside the header's bounding box.
#include <memory>
#include <optional>
#include <string>

#include "patch.h"
#include "patch_shared.h"
#include "range_decoder.h"
#include "status.h"

namespace prm::codec {

Status read_patches(const uint8_t* data, size_t size, uint64_t offset, const ClosedMesh& mesh, int bits,
                    const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi, bool contexts, bool grids,
                    const std::vector<uint8_t>& cls, std::vector<uint32_t>& q, std::vector<uint8_t>& known,
                    std::vector<uint32_t>& vertex_corner_out) {
  q.assign(size_t{3} * mesh.num_vertices, 0);
  known.assign(mesh.num_vertices, 0);
  if (size < 4) return make_status(Error::truncated, "5.6", offset + size, "patch data shorter than 4 bytes");
  RangeDecoder rc;
  rc.init(data, size);
  if (rc.bad_start()) return make_status(Error::bad_section, "5.6", offset, "range-coded data starting with FF FF FF FF");
  auto fail = [&](Error e, const char* section, const std::string& what) {
    return make_status(rc.failed() ? Error::truncated : e, section, offset + rc.consumed(), what);
  };
  // §8.4 Grid_Size and Height_Depth.
  const int64_t grid = rc.decode_direct(kGridBits);
  const int depth = static_cast<int>(rc.decode_direct(3));
  if (!valid_grid_size(grid, bits)) return fail(Error::bad_section, "8.4", "Grid_Size out of range");
  // §8.4.2 The grid table (Flags bit 4): Grid_Size, then 1..7 extra grid sizes, each valid and new.
  std::vector<HexLattice> lattices = {HexLattice::with_grid(grid)};
  if (grids) {
    const int extra = static_cast<int>(rc.decode_direct(kExtraGridCountBits));
    if (extra == 0) return fail(Error::bad_section, "8.4.2", "Extra_Grid_Count 0");
    for (int k = 0; k < extra; ++k) {
      const int64_t g = rc.decode_direct(kGridBits);
      if (!valid_grid_size(g, bits)) return fail(Error::bad_section, "8.4.2", "Extra_Grid out of range");
      for (const HexLattice& l : lattices)
        if (l.A == g) return fail(Error::bad_section, "8.4.2", "Extra_Grid repeats a grid size");
      lattices.push_back(HexLattice::with_grid(g));
    }
  }
  const bool predicted = depth == kHeightDepthPredicted;
  // §9.7.2 Overlap_Depth and the predictor table.
  const int overlap_depth = predicted ? static_cast<int>(rc.decode_direct(3)) : depth;
  if (overlap_depth > kMaxHeightDepth) return fail(Error::bad_section, "9.7.2", "Overlap_Depth above 6");
  const PatchSet ps = build_patches(mesh, cls);
  auto models = std::make_unique<PatchModels>();
  models->lp.sign_context = contexts;
  auto bit = [&](BitModel& m, bool) { return rc.decode_bit(m) != 0; };
  auto value = [&](SignedIntModel& m, int max_class, int64_t, int64_t& out, BitModel* sign = nullptr) {
    return decode_signed(rc, m, max_class, out, sign ? *sign : m.sign);
  };
  auto direct = [&](int n, uint32_t) { return rc.decode_direct(n); };
  LpTable table;
  std::array<bool, kLpSets> fitted{};
  if (predicted && !code_lp_table(table, fitted, models->lp, direct, value))
    return fail(Error::bad_section, "9.7.2", "a weight out of range");
  if (rc.failed()) return fail(Error::truncated, "5.5", "the patch data ends early");
  std::vector<uint32_t> local(mesh.num_vertices, UINT32_MAX), global, queue;
  Level level;
  std::vector<std::vector<int64_t>> f;
  std::vector<LevelPlan> plans;
  std::vector<uint32_t> tri_pos(mesh.num_triangles(), UINT32_MAX), twin;
  std::vector<uint8_t> scratch, placed;
  std::vector<int64_t> h, res;
  LpRaster raster;
  // §9.7.4 For the vertices without a tap set; only linear-prediction streams need it (Vertex_Corner is O(T)).
  std::optional<LpNeighbours> nb;
  if (predicted) nb.emplace(mesh, known, q.data(), local, global);
  // §10.2 Vertex_Corner, for the base references (§8.4.1) and the positions (§10): the one LpNeighbours made, if any.
  std::vector<uint32_t> own_vertex_corner;
  if (!predicted) vertex_corners(mesh, own_vertex_corner);
  const std::vector<uint32_t>& vertex_corner = predicted ? nb->vertex_corner : own_vertex_corner;
  std::array<int64_t, 2> previous{0, 0};
  const int64_t coord_bound = int64_t{1} << (bits + 1);
  for (size_t p = 0; p < ps.size(); ++p) {
    const std::string which = "patch " + std::to_string(p);
    // §8.4 The patch header.
    const int axis = code_symbol8(models->axis, 0, bit);
    const int pair = axis <= 5 ? axis / 2 : 0;  // an axis above 5 is reported below
    // §8.4.2 The patch's lattice: Grid_Index into the grid table (Flags bit 4), else Grid_Size's.
    const int grid_index = grids ? code_symbol8(models->grid, 0, bit) : 0;
    const bool grid_ok = static_cast<size_t>(grid_index) < lattices.size();  // reported below
    const HexLattice& lc = lattices[grid_ok ? static_cast<size_t>(grid_index) : 0];
    // §8.4.1 The base from its reference, if it has one; otherwise from the previous patch's base.
    std::array<int64_t, 2> from = previous;
    const bool referenced = contexts && axis <= 5 && grid_ok &&
                            base_from_reference(mesh, ps, p, pair, vertex_corner, known, q.data(), lc, from);
    SignedIntModel& mi = referenced ? models->base_ref_i : models->base_i;
    SignedIntModel& mj = referenced ? models->base_ref_j : models->base_j;
    int64_t di, dj;
    if (!decode_signed(rc, mi, bits + 2, di) || !decode_signed(rc, mj, bits + 2, dj))
      return fail(Error::bad_section, "8.4", which + ": base vertex out of range");
    const std::array<int64_t, 2> base = {from[0] + di, from[1] + dj};
    const int align = code_symbol8(models->align, 0, bit);
    if (rc.failed()) return fail(Error::truncated, "5.5", "the patch data ends early");
    if (axis > 5 || align > 5) return fail(Error::bad_section, "8.4", which + ": axis or alignment above 5");
    if (!grid_ok) return fail(Error::bad_section, "8.4.2", which + ": Grid_Index beyond the grid table");
    if (base[0] <= -coord_bound || base[0] >= coord_bound || base[1] <= -coord_bound || base[1] >= coord_bound)
      return fail(Error::bad_section, "8.4", which + ": base vertex out of range");
    previous = base;
    const size_t cu = static_cast<size_t>(pair_u(pair)), cw = static_cast<size_t>(pair_w(pair)),
                 ch = static_cast<size_t>(pair);
    // §8.3 Lattice coordinates, then base-plane positions.
    auto release = [&] {
      for (uint32_t v : global) local[v] = UINT32_MAX;
    };
    if (!propagate_patch(mesh, ps, p, base, align, axis % 2 == 0, level, global, local)) {
      release();
      return fail(Error::bad_position, "8.3", which + ": a vertex gets two lattice positions");
    }
    for (uint32_t l = 0; l < level.size(); ++l) {
      const uint32_t v = global[l];
      // |i|, |j| are bounded by the propagation from a bounded base (one step per triangle), so no overflow here.
      const int64_t u = lc.A * level.coord[l][0] + lc.B * level.coord[l][1], w = lc.C * level.coord[l][1];
      if (u < lo[cu] || u > hi[cu] || w < lo[cw] || w > hi[cw])
        return fail(Error::bad_position, "8.3", which + ": vertex " + std::to_string(v) + " outside the bounding box");
      if (known[v] && (q[3 * size_t{v} + cu] != u || q[3 * size_t{v} + cw] != w))
        return fail(Error::bad_position, "8.3", which + ": vertex " + std::to_string(v) + " placed twice, differently");
    }
    // §9.7.4 Method: per patch in a linear-prediction stream.
    const bool lp = predicted && rc.decode_bit(models->lp.method) != 0;
    if (lp) {
      raster.build(level);
      // §9.7.4 Heights by linear prediction; the vertices earlier patches placed are known.
      placed.resize(level.size());
      h.resize(level.size());
      for (uint32_t l = 0; l < level.size(); ++l) {
        placed[l] = known[global[l]];
        h[l] = placed[l] ? int64_t{q[3 * size_t{global[l]} + ch]} : 0;
      }
      nb->height_axis = pair;
      if (!code_lp_heights(level, raster, table, models->lp, bits, lo[ch], hi[ch], placed, h, res, scratch, value, &*nb))
        return fail(Error::bad_position, "9.7.4", which + ": a height outside the bounding box");
    } else {
      // §9.1-§9.3 Heights by difference patches.
      patch_side_twins(mesh, ps, p, tri_pos, twin);
      build_levels(level, overlap_depth, plans, &twin);
      if (!code_heights(level, overlap_depth, bits, models->heights, f, plans, scratch, queue, false, value))
        return fail(Error::bad_position, "9.3", which + ": a height difference out of range");
      h.swap(f[0]);
    }
    release();
    if (rc.failed()) return fail(Error::truncated, "5.5", "the patch data ends early");
    for (uint32_t l = 0; l < level.size(); ++l) {
      const uint32_t v = global[l];
      const int64_t height = h[l];
      if (height < lo[ch] || height > hi[ch])
        return fail(Error::bad_position, "9.3", which + ": vertex " + std::to_string(v) + " height outside the bounding box");
      const int64_t u = lc.A * level.coord[l][0] + lc.B * level.coord[l][1], w = lc.C * level.coord[l][1];
      if (known[v]) {
        if (q[3 * size_t{v} + ch] != height)
          return fail(Error::bad_position, "9.3", which + ": vertex " + std::to_string(v) + " placed twice, differently");
        continue;
      }
      known[v] = 1;
      q[3 * size_t{v} + cu] = static_cast<uint32_t>(u);
      q[3 * size_t{v} + cw] = static_cast<uint32_t>(w);
      q[3 * size_t{v} + ch] = static_cast<uint32_t>(height);
    }
  }
  if (!rc.finish())
    return rc.failed() ? make_status(Error::truncated, "5.5", offset + size, "the patch data ends early")
                       : make_status(Error::trailing_bytes, "5.6", offset + rc.consumed(), "bytes after the last patch");
  vertex_corner_out = predicted ? std::move(nb->vertex_corner) : std::move(own_vertex_corner);
  return ok_status();
}

}  // namespace prm::codec
