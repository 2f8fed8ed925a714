// §9.7 Heights by linear prediction (Height_Depth 7, format 1.2), shared by patch_encode.cpp and patch_decode.cpp:
// the tap sets and their default weights, the predictor table, the raster order of a patch and the coding of its
// heights, written once as a template over a "coder" that encodes the truth (encoder) or decodes (decoder).
//
// A patch whose vertices have distinct lattice coordinates is coded in raster order (increasing j, then i); each
// height is predicted from already coded heights of the same patch at fixed lattice offsets (a "tap set", the first
// one of the table whose offsets are all present), with integer weights in 1/256 that the stream carries (fitted by
// the encoder) or that the spec fixes, and the residual is coded with a context from the set's size and the
// residuals around it. Per patch the encoder may instead use the difference patches of §9.1-§9.3 (it does for
// self-overlapping patches, where two vertices share a lattice point).
#pragma once

#include <algorithm>
#include <array>
#include <utility>
#include <cstdint>
#include <vector>

#include "always_inline.h"
#include "closed_mesh.h"
#include "difference_patch_shared.h"
#include "fan_walk.h"
#include "signed_int_model.h"

namespace prm::codec {

// §9.7.1 The tap offsets (Δi, Δj), all before (0, 0) in raster order.
constexpr int kLpOffsets = 14;
constexpr std::array<std::array<int8_t, 2>, kLpOffsets> kLpOffset = {{{{0, -1}},
                                                                      {{1, -1}},
                                                                      {{-1, 0}},
                                                                      {{1, -2}},
                                                                      {{-1, -1}},
                                                                      {{2, -1}},
                                                                      {{0, -2}},
                                                                      {{2, -2}},
                                                                      {{-2, 0}},
                                                                      {{1, -3}},
                                                                      {{2, -3}},
                                                                      {{-1, -2}},
                                                                      {{-2, -1}},
                                                                      {{-3, 0}}}};

// §9.7.1 The tap sets, in selection order, as masks over the offsets (bit t = offset t); a set's taps are its
// offsets in increasing t.
constexpr int kLpSets = 38;
constexpr uint16_t kLpSetMask[kLpSets] = {
    0x0FFF, 0x0FDF, 0x0EFF, 0x07FF, 0x0BFF, 0x09FF, 0x06FF, 0x0F5F, 0x0EFB, 0x0B5F, 0x06EF, 0x06EB, 0x0B5D,
    0x06AB, 0x0137, 0x0955, 0x003F, 0x00EB, 0x04AA, 0x1115, 0x0007, 0x000B, 0x0015, 0x2104, 0x0041, 0x0082,
    0x0104, 0x0005, 0x0003, 0x0004, 0x0001, 0x0002, 0x0020, 0x0010, 0x0080, 0x0100, 0x0008, 0x0040};

// §9.7.1 Weights are in units of 2^-kLpPrecisionBits; the first tap's weight is 256 minus the others' sum.
constexpr int kLpPrecisionBits = 8;
constexpr int32_t kLpOne = 1 << kLpPrecisionBits;
constexpr int kLpMaxWeightClass = 12;  // |w_t| < 2^13 for the coded weights (t >= 1)
constexpr int kLpMaxTaps = 12;

// §9.7.1 Default weights of the sets 20..37, in tap order (the others have none: they are used only when the
// stream gives their weights).
constexpr int kLpFirstDefault = 20;
constexpr int16_t kLpDefault[kLpSets - kLpFirstDefault][3] = {
    {-256, 256, 256}, {256, 256, -256}, {256, 256, -256}, {768, -768, 256}, {512, -256, 0}, {512, -256, 0},
    {512, -256, 0},   {128, 128, 0},    {128, 128, 0},    {256, 0, 0},      {256, 0, 0},    {256, 0, 0},
    {256, 0, 0},      {256, 0, 0},      {256, 0, 0},      {256, 0, 0},      {256, 0, 0},    {256, 0, 0}};

// The taps of set s: its offsets in increasing order; returns their number.
inline int lp_set_taps(int s, std::array<int, kLpMaxTaps>& tap) {
  int n = 0;
  for (int t = 0; t < kLpOffsets; ++t)
    if (kLpSetMask[s] >> t & 1) tap[static_cast<size_t>(n++)] = t;
  return n;
}

// §9.7.4 Context groups by the number of taps of the set used (6: no set).
constexpr int kLpGroups = 7;
constexpr int kLpActivities = 9;
inline int lp_group(int taps) {
  return taps >= 12 ? 0 : taps >= 9 ? 1 : taps >= 6 ? 2 : taps >= 3 ? 3 : taps == 2 ? 4 : 5;
}
constexpr int kLpNoSet = 255;
// §9.7.4 The offsets whose residuals give the activity context: (-1, 0), (0, -1), (1, -1), (-2, 0), (-1, -1), (2, -1).
constexpr int kLpActivityTap[6] = {2, 0, 1, 8, 4, 5};

// §9.7.4 Sign contexts (Flags bit 3, format 1.4): how the plane through three neighbours predicts against the
// prediction, five classes, and 5 where the three are not all there.
constexpr int kLpSignContexts = 6;
constexpr int kLpNoSignContext = 5;

struct LpModels {
  BitModel method;  // §9.7.4 per patch: 1 = linear prediction, 0 = difference patches of Overlap_Depth
  SignedIntModel weight;
  SignedIntModel residual[kLpGroups][kLpActivities];
  BitModel sign[kLpGroups][kLpSignContexts];  // §9.7.4 with Flags bit 3
  bool sign_context = false;                  // the stream's Flags bit 3 (format 1.4)
};

// §9.7.2 The predictor table of a stream: which sets are enabled and their weights; select(mask) is the first
// enabled set all of whose offsets are in `mask` (kLpNoSet if none), and group[s] the context group of set s.
struct LpTable {
  std::array<bool, kLpSets> enabled{};
  std::array<std::array<int32_t, kLpMaxTaps>, kLpSets> weight{};
  std::array<std::array<int, kLpMaxTaps>, kLpSets> tap{};  // lp_set_taps
  std::array<int, kLpSets> taps{};
  std::array<uint8_t, kLpSets> group{};  // lp_group(taps[s])

  LpTable() {
    for (int s = 0; s < kLpSets; ++s) {
      taps[s] = lp_set_taps(s, tap[s]);
      group[s] = static_cast<uint8_t>(lp_group(taps[s]));
    }
  }

  void set_defaults(int s) {
    for (int t = 0; t < kLpMaxTaps; ++t) weight[s][t] = t < 3 && s >= kLpFirstDefault ? kLpDefault[s - kLpFirstDefault][t] : 0;
  }
  // Starts the selection once `enabled` is final. The answers are worked out as masks are first asked (a patch
  // meets a few hundred of the 2^14 masks: filling the whole table cost 1.8% of a web-horse decode, callgrind).
  // Also makes the padded taps and weights from `tap` and `weight` (so it comes after the weights are final).
  void build_selection() {
    first_set_.assign(size_t{1} << kLpOffsets, kUnresolved);
    num_enabled_ = 0;
    for (int s = 0; s < kLpSets; ++s) {
      if (enabled[s]) enabled_set_[num_enabled_++] = static_cast<uint8_t>(s);
      for (int k = 0; k < kLpMaxTaps; ++k) {
        padded_tap[s][k] = k < taps[s] ? tap[s][k] : tap[s][0];
        padded_weight[s][k] = k < taps[s] ? weight[s][k] : 0;
      }
    }
  }
  // Set s as kLpMaxTaps taps: its own, then its first tap again with weight 0 (present whenever s is selected), so
  // that a prediction is one loop of fixed length (lp_predict; the same sum).
  std::array<std::array<int, kLpMaxTaps>, kLpSets> padded_tap{};
  std::array<std::array<int32_t, kLpMaxTaps>, kLpSets> padded_weight{};
  // The smallest index of an enabled set whose mask is a subset of `mask` (kLpNoSet, 255, if none).
  uint8_t select(uint32_t mask) const {
    const uint8_t s = first_set_[mask];
    return s != kUnresolved ? s : resolve(mask);
  }

 private:
  static constexpr uint8_t kUnresolved = 254;  // not a set index (< kLpSets) nor kLpNoSet
#if defined(__GNUC__) || defined(__clang__)
  __attribute__((noinline))
#endif
  uint8_t resolve(uint32_t mask) const {
    uint8_t s = kLpNoSet;
    for (int k = 0; k < num_enabled_; ++k)
      if ((kLpSetMask[enabled_set_[k]] & ~mask) == 0) {
        s = enabled_set_[k];
        break;
      }
    return first_set_[mask] = s;
  }
  std::array<uint8_t, kLpSets> enabled_set_{};  // the enabled sets, in increasing order
  int num_enabled_ = 0;
  mutable std::vector<uint8_t> first_set_;  // per mask: select's answer, or kUnresolved before it is asked
};

// The tap mask of a 14-bit occupancy key (LpRaster::mask_at): key bits 0-2 are the cells i - 3 .. i - 1 of row j,
// 3-7 the cells i - 2 .. i + 2 of row j - 1, 8-11 the cells i - 1 .. i + 2 of row j - 2, 12-13 the cells i + 1, i + 2
// of row j - 3; each is one of the 14 offsets of kLpOffset (bit t of the mask).
inline const std::array<uint16_t, 1u << kLpOffsets>& lp_mask_of_key() {
  static const std::array<uint16_t, 1u << kLpOffsets> table = [] {
    constexpr int kRowBase[4] = {0, 3, 8, 12}, kRowFirst[4] = {-3, -2, -1, 1};  // key bit and di of each row's first
    std::array<int, kLpOffsets> bit{};
    for (int t = 0; t < kLpOffsets; ++t) {
      const int row = -kLpOffset[t][1];
      bit[t] = kRowBase[row] + kLpOffset[t][0] - kRowFirst[row];
    }
    std::array<uint16_t, 1u << kLpOffsets> m{};
    for (uint32_t key = 0; key < m.size(); ++key)
      for (int t = 0; t < kLpOffsets; ++t) m[key] |= static_cast<uint16_t>((key >> bit[t] & 1u) << t);
    return m;
  }();
  return table;
}

// Whether the dense raster keeps occupancy bits for its tap masks (LpRaster::mask_at). Not in the WebAssembly build:
// there the table and the bits cost 318 B of the gzipped module (web/build.sh) for no measurable speed
// (web/bench/cpu_ab.mjs: horse 0.998x), and the masks come from the cells' heights (LpCellView::mask).
#if defined(__wasm__)
constexpr bool kLpOccupancyMasks = false;
#else
constexpr bool kLpOccupancyMasks = true;
#endif

// §9.7.4 A dense raster cell without a vertex (code_lp_heights' per-cell heights; no height is negative).
constexpr int64_t kLpEmptyCell = INT64_MIN;

// The index of the lowest set bit of bits (not 0).
inline int lowest_bit(uint32_t bits) {
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_ctz(bits);
#else
  int i = 0;
  while (!(bits >> i & 1u)) ++i;
  return i;
#endif
}

// §9.7.3 A patch's raster order and its lattice lookup. The order is by increasing (j, i, local id); the vertex at
// a lattice point is the one of lowest local id there. build() returns how many vertices share their lattice point
// with a lower local id (a self-overlapping patch has some). Small footprints use a dense grid with a margin for
// the offsets, sparse (long, thin) ones a sorted list searched by bisection; both give the same answers.
class LpRaster {
 public:
  static constexpr uint32_t kNone = UINT32_MAX;

  uint32_t build(const Level& level) {
    const uint32_t n = level.size();
    order_.clear();
    dense_ = false;
    if (n == 0) return 0;
    int64_t imin = level.coord[0][0], imax = imin, jmin = level.coord[0][1], jmax = jmin;
    for (const auto& c : level.coord) {
      imin = std::min(imin, c[0]);
      imax = std::max(imax, c[0]);
      jmin = std::min(jmin, c[1]);
      jmax = std::max(jmax, c[1]);
    }
    uint32_t shared = 0;
    // Margin: offsets reach 3 to the left, 2 to the right and 3 rows down.
    const int64_t width = imax - imin + 6, height = jmax - jmin + 4;
    if (width * height <= 8 * int64_t{n} + 4096) {
      dense_ = true;
      i0_ = imin - 3;
      j0_ = jmin - 3;
      width_ = width;
      grid_.assign(static_cast<size_t>(width * height), kNone);
      extra_.clear();
      for (uint32_t l = 0; l < n; ++l) {
        const int64_t b = index(level.coord[l][0], level.coord[l][1]);
        uint32_t& cell = grid_[static_cast<size_t>(b)];
        if (cell == kNone) {
          cell = l;
        } else {
          extra_.push_back({b, l});  // l > cell: ids are visited in increasing order
          ++shared;
        }
      }
      for (int t = 0; t < kLpOffsets; ++t) delta_[t] = kLpOffset[t][1] * width_ + kLpOffset[t][0];
      // One bit per cell, a row of width bits per lattice row, one byte of padding (mask_at reads two bytes).
      row_bytes_ = (width + 7) / 8 + 1;
      if (kLpOccupancyMasks) occupied_.assign(static_cast<size_t>(row_bytes_ * height), 0);
      for (uint32_t l = 0; kLpOccupancyMasks && l < n; ++l) {
        const int64_t x = level.coord[l][0] - i0_, y = level.coord[l][1] - j0_;
        occupied_[static_cast<size_t>(y * row_bytes_ + (x >> 3))] |= static_cast<uint8_t>(1u << (x & 7));
      }
      // The order: the occupied cells in increasing cell index, each cell's vertices by local id.
      order_.reserve(n);
      std::sort(extra_.begin(), extra_.end());
      size_t e = 0;
      auto visit = [&](size_t b) {
        order_.push_back(grid_[b]);
        while (e < extra_.size() && extra_[e].first == static_cast<int64_t>(b)) order_.push_back(extra_[e++].second);
      };
      if (kLpOccupancyMasks) {  // the set bits of the occupancy rows (a quarter or less of the cells hold a vertex)
        for (int64_t y = 0; y < height; ++y)
          for (int64_t k = 0; k + 1 < row_bytes_; ++k)
            for (uint32_t bits = occupied_[static_cast<size_t>(y * row_bytes_ + k)]; bits != 0; bits &= bits - 1)
              visit(static_cast<size_t>(y * width + 8 * k + lowest_bit(bits)));
      } else {
        for (size_t b = 0; b < grid_.size(); ++b)
          if (grid_[b] != kNone) visit(b);
      }
      return shared;
    }
    // Sparse: (j, i) as one key (j - jmin) * (imax - imin + 1) + (i - imin), which orders like (j, i); the pairs
    // (key, id) sort like (j, i, id), with the same sort as the dense grid's extra vertices.
    i0_ = imin;
    j0_ = jmin;
    width_ = imax - imin + 1;
    i1_ = imax;
    j1_ = jmax;
    sorted_.resize(n);
    for (uint32_t l = 0; l < n; ++l) sorted_[l] = {index(level.coord[l][0], level.coord[l][1]), l};
    std::sort(sorted_.begin(), sorted_.end());
    for (uint32_t r = 1; r < n; ++r) shared += sorted_[r].first == sorted_[r - 1].first;
    order_.reserve(n);
    for (const auto& k : sorted_) order_.push_back(k.second);
    return shared;
  }
  const std::vector<uint32_t>& order() const { return order_; }

  // The dense grid (dense() only): the cell of (i, j), its lowest local id (kNone if empty), the cell offsets of
  // the 14 tap offsets, and per-cell scratch for code_lp_heights (the height and |residual| of each cell's vertex).
  bool dense() const { return dense_; }
  int64_t cell(int64_t i, int64_t j) const { return index(i, j); }
  uint32_t owner(int64_t cell) const { return grid_[static_cast<size_t>(cell)]; }
  const int64_t* deltas() const { return delta_.data(); }
  // With kLpOccupancyMasks: the tap mask of (i, j) on the dense grid (as taps() gives it), from the occupancy bits:
  // the cells i - 3 .. i + 2 of rows j .. j - 3 are six bits of each row, of which the 14 offsets make a 14-bit key
  // (lp_mask_of_key).
  uint32_t mask_at(int64_t i, int64_t j) const {
    const int64_t x = i - i0_ - 3, y = j - j0_;  // x >= 0 and y >= 3: the margin
    auto window = [&](int64_t row) {
      const uint8_t* p = occupied_.data() + row * row_bytes_ + (x >> 3);
      return static_cast<uint32_t>(p[0] | p[1] << 8) >> (x & 7);
    };
    const uint32_t key = (window(y) & 7) | (window(y - 1) >> 1 & 31) << 3 | (window(y - 2) >> 2 & 15) << 8 |
                         (window(y - 3) >> 4 & 3) << 12;
    return lp_mask_of_key()[key];
  }
  size_t cells() const { return grid_.size(); }
  std::vector<int64_t> cell_height, cell_activity;

  // The local ids at the 14 offsets around (i, j) (kNone where there is no vertex) and their mask.
  PRM_WASM_INLINE uint32_t taps(int64_t i, int64_t j, std::array<uint32_t, kLpOffsets>& id) const {
    uint32_t mask = 0;
    if (dense_) {
      const int64_t b = index(i, j);
      for (int t = 0; t < kLpOffsets; ++t) {
        id[t] = grid_[static_cast<size_t>(b + delta_[t])];
        mask |= (id[t] != kNone ? 1u : 0u) << t;
      }
      return mask;
    }
    for (int t = 0; t < kLpOffsets; ++t) {
      id[t] = find(i + kLpOffset[t][0], j + kLpOffset[t][1]);
      mask |= (id[t] != kNone ? 1u : 0u) << t;
    }
    return mask;
  }

 private:
  int64_t index(int64_t i, int64_t j) const { return (j - j0_) * width_ + (i - i0_); }
  uint32_t find(int64_t i, int64_t j) const {
    if (i < i0_ || i > i1_ || j < j0_ || j > j1_) return kNone;
    const int64_t key = index(i, j);
    auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::pair<int64_t, uint32_t>{key, 0});
    // The first entry of (j, i) is its lowest local id.
    return it != sorted_.end() && it->first == key ? it->second : kNone;
  }

  bool dense_ = false;
  int64_t i0_ = 0, j0_ = 0, width_ = 0, i1_ = 0, j1_ = 0;  // sparse: the footprint [i0, i1] x [j0, j1]
  std::array<int64_t, kLpOffsets> delta_{};
  std::vector<uint32_t> grid_;
  std::vector<uint8_t> occupied_;  // dense: one bit per cell, rows of row_bytes_
  int64_t row_bytes_ = 0;
  std::vector<std::pair<int64_t, uint32_t>> extra_;  // (cell, id) of the vertices after a cell's first
  std::vector<std::pair<int64_t, uint32_t>> sorted_;  // sparse: (key, id), sorted
  std::vector<uint32_t> order_;
};

// §9.7.2 The predictor table's fields, coded by the encoder (`direct(bits, truth)` and `value(model, max_class,
// truth, out)` code the truth) or decoded by the decoder (they return what they read) through the same steps.
// `fitted[s]`: set s carries its weights. Ends with table.build_selection().
template <typename Direct, typename Value>
bool code_lp_table(LpTable& table, std::array<bool, kLpSets>& fitted, LpModels& m, Direct& direct, Value& value) {
  for (int s = 0; s < kLpSets; ++s) {
    table.enabled[s] = direct(1, table.enabled[s] ? 1u : 0u) != 0;
    fitted[s] = table.enabled[s] && (s < kLpFirstDefault || direct(1, fitted[s] ? 1u : 0u) != 0);
    if (!fitted[s]) {
      table.set_defaults(s);
      continue;
    }
    int64_t rest = 0;
    for (int k = 1; k < table.taps[s]; ++k) {
      int64_t w;
      if (!value(m.weight, kLpMaxWeightClass, table.weight[s][k], w)) return false;
      table.weight[s][k] = static_cast<int32_t>(w);
      rest += w;
    }
    for (int k = table.taps[s]; k < kLpMaxTaps; ++k) table.weight[s][k] = 0;
    table.weight[s][0] = static_cast<int32_t>(kLpOne - rest);
  }
  table.build_selection();
  return true;
}

// floor(a / 2^k) for any sign.
inline int64_t floor_shift(int64_t a, int k) { return a >= 0 ? a >> k : -((-a + (int64_t{1} << k) - 1) >> k); }

// §9.7.4 What a height sees at its 14 tap offsets, two ways with one interface: present(t), height(t) (a present
// tap's height) and activity(t) (|residual| of a tap coded in this patch, -1 if absent, placed by an earlier patch
// or not coded). LpIdView goes through the local ids of LpRaster::taps; LpCellView reads the dense grid's per-cell
// heights and activities directly (a cell holds its lowest local id's values, kLpEmptyCell if it has none: every
// tap cell precedes the current one in raster order, so its vertex is already known when it has one).
struct LpIdView {
  const std::array<uint32_t, kLpOffsets>& id;
  const std::vector<int64_t>& h;
  const std::vector<int64_t>* res;
  const std::vector<uint8_t>* coded;
  bool present(int t) const { return id[static_cast<size_t>(t)] != UINT32_MAX; }
  int64_t height(int t) const { return h[id[static_cast<size_t>(t)]]; }
  int64_t activity(int t) const {
    const uint32_t x = id[static_cast<size_t>(t)];
    if (x == UINT32_MAX || !(*coded)[x]) return -1;
    const int64_t r = (*res)[x];
    return r < 0 ? -r : r;
  }
};
struct LpCellView {
  const int64_t* cell_height;    // at the current cell
  const int64_t* cell_activity;  // at the current cell
  const int64_t* delta;
  bool present(int t) const { return cell_height[delta[t]] != kLpEmptyCell; }
  int64_t height(int t) const { return cell_height[delta[t]]; }
  int64_t activity(int t) const { return cell_activity[delta[t]]; }
  uint32_t mask() const {  // the tap mask, from the heights (without kLpOccupancyMasks)
    uint32_t m = 0;
    for (int t = 0; t < kLpOffsets; ++t) m |= (present(t) ? 1u : 0u) << t;
    return m;
  }
};

// §9.7.4 The prediction of one height from its taps (set s), before clamping.
template <typename View>
inline int64_t lp_predict(const LpTable& table, int s, const View& view) {
  int64_t sum = 0;
  for (int k = 0; k < kLpMaxTaps; ++k) sum += int64_t{table.padded_weight[s][k]} * view.height(table.padded_tap[s][k]);
  return floor_shift(sum + kLpOne / 2, kLpPrecisionBits);
}
inline int64_t lp_predict(const LpTable& table, int s, const std::array<uint32_t, kLpOffsets>& id,
                          const std::vector<int64_t>& h) {
  return lp_predict(table, s, LpIdView{id, h, nullptr, nullptr});
}

// §9.7.4 What the heights of a patch see of the rest of the mesh: for a vertex without a tap set, its mesh
// neighbours already decoded (placed by an earlier patch, or coded earlier in this patch).
struct LpNeighbours {
  // placed: per mesh vertex, placed by an earlier patch; q: 3 per mesh vertex, the placed vertices' positions;
  // local: per mesh vertex, its local id in the current patch or UINT32_MAX; global: per local id, the mesh vertex.
  // The vectors are the caller's and must outlive this.
  LpNeighbours(const ClosedMesh& m, const std::vector<uint8_t>& placed_vertices, const uint32_t* positions,
               const std::vector<uint32_t>& local_ids, const std::vector<uint32_t>& global_ids)
      : mesh(&m), placed(&placed_vertices), q(positions), local(&local_ids), global(&global_ids) {
    vertex_corners(m, vertex_corner);
  }
  const ClosedMesh* mesh;
  const std::vector<uint8_t>* placed;
  const uint32_t* q;
  const std::vector<uint32_t>* local;
  const std::vector<uint32_t>* global;
  std::vector<uint32_t> vertex_corner;  // §10.2 Vertex_Corner
  int height_axis = 0;                  // the current patch's pair k
};

// §9.7.4 The rounded mean of coordinate k over v's decoded mesh neighbours (fan walk of §10.2); false if none.
inline bool lp_neighbour_mean(const LpNeighbours& nb, uint32_t l, const std::vector<int64_t>& h,
                              const std::vector<uint8_t>& coded, int64_t& mean) {
  const ClosedMesh& mesh = *nb.mesh;
  const uint32_t v = (*nb.global)[l];
  const uint32_t c0 = nb.vertex_corner[v];
  if (c0 == UINT32_MAX) return false;
  int64_t sum = 0, count = 0;
  uint32_t c = c0;
  do {
    const uint32_t x = mesh.corner_vertex[corner_next(c)];
    const uint32_t lx = (*nb.local)[x];
    if ((*nb.placed)[x]) {
      sum += nb.q[3 * size_t{x} + static_cast<size_t>(nb.height_axis)];
      ++count;
    } else if (lx != UINT32_MAX && coded[lx]) {
      sum += h[lx];
      ++count;
    }
    c = fan_next(mesh.opp.data(), c);
  } while (c != c0);
  if (count == 0) return false;
  const int64_t num = 2 * sum + count, den = 2 * count;  // floor((2 sum + n) / 2n), as §10.3's RoundedMean
  mean = num >= 0 ? num / den : -((-num + den - 1) / den);
  return true;
}

// §9.7.4 The activity context of a height: from the residuals already coded at the activity offsets (8: none).
template <typename View>
inline int lp_activity(const View& view) {
  int64_t sum = 0;
  uint32_t count = 0;
  for (int t : kLpActivityTap) {
    const int64_t a = view.activity(t);
    if (a >= 0) {
      sum += a;
      ++count;
    }
  }
  if (count == 0) return 8;
  // The bit length of x = floor(3 * sum / count), at most 7: 7 once x >= 64, that is 3 * sum >= 64 * count; below
  // that 3 * sum < 384, and floor(3 * sum / count) = 3 * sum * ceil(2^16 / count) >> 16 (checked for every sum and
  // count 1..6), so no division per height.
  const uint64_t s3 = static_cast<uint64_t>(3 * sum);
  if (s3 >= 64 * uint64_t{count}) return 7;
  static constexpr uint32_t kInverse[7] = {0, 65536, 32768, 21846, 16384, 13108, 10923};
  const uint32_t x = static_cast<uint32_t>(s3) * kInverse[count] >> 16;
  return x == 0 ? 0 : int_class(x) + 1;
}
inline int lp_activity(const std::array<uint32_t, kLpOffsets>& id, const std::vector<int64_t>& res,
                       const std::vector<uint8_t>& coded) {
  static const std::vector<int64_t> none;
  return lp_activity(LpIdView{id, none, &res, &coded});
}

// §9.7.4 The sign context of a height predicted `pred` (Flags bit 3): with P = h(-1, 0) + h(1, -1) - h(0, -1), the
// plane through those three neighbours, and d = P - pred: 0 if d <= -2, 1 if d = -1, 2 if d = 0, 3 if d = 1, 4 if
// d >= 2; kLpNoSignContext if one of the three is missing.
template <typename View>
inline int lp_sign_context(const View& view, int64_t pred) {
  if (!view.present(0) || !view.present(1) || !view.present(2)) return kLpNoSignContext;
  const int64_t d = view.height(2) + view.height(1) - view.height(0) - pred;
  return d <= -2 ? 0 : d >= 2 ? 4 : static_cast<int>(d + 2);
}
inline int lp_sign_context(const std::array<uint32_t, kLpOffsets>& id, const std::vector<int64_t>& h, int64_t pred) {
  return lp_sign_context(LpIdView{id, h, nullptr, nullptr}, pred);
}

// The encoder's choice of the height it codes: the given one (lossless).
struct LpKeepHeight {
  int64_t operator()(uint32_t, int64_t, int64_t given, const SignedIntModel&, const BitModel&) const { return given; }
};

// §9.7.4 The heights of one patch in raster order. `placed[l]`: local vertex l was placed by an earlier patch, its
// height h[l] is known and not coded. h: in, the heights (encoder) or the placed ones (decoder); out, all heights.
// `value(model, max_class, truth, out, sign)` codes one signed integer, its sign with the model `sign`. Returns false
// when a decoded height leaves [lo, hi] (§9.7.4: bad_position). `res`, `coded`: scratch per local vertex. `nb`
// (optional): the mesh around the patch, for the vertices without a tap set. `choose(l, pred, h[l], model, sign)`
// (encoder only): the height the encoder codes for l once its prediction and residual models are known (lossless:
// h[l]).
template <typename Value, typename Choose = LpKeepHeight>
bool code_lp_heights(const Level& level, LpRaster& raster, const LpTable& table, LpModels& m, int bits,
                     int64_t lo, int64_t hi, const std::vector<uint8_t>& placed, std::vector<int64_t>& h,
                     std::vector<int64_t>& res, std::vector<uint8_t>& coded, Value& value,
                     const LpNeighbours* nb = nullptr, const Choose& choose = Choose{}) {
  const uint32_t n = level.size();
  res.assign(n, 0);
  coded.assign(n, 0);
  int64_t previous = lo + (hi - lo) / 2;
  int64_t activity_of_last = -1;  // |residual| of the height code_one did last, -1 if it was placed
  // One height in raster order, seen through `view` with tap mask `mask`.
  auto code_one = [&](uint32_t l, uint32_t mask, const LpCellView& view) {
    if (placed[l]) {
      previous = h[l];
      activity_of_last = -1;
      return true;
    }
    const int s = table.select(mask);
    int64_t pred = previous;
    if (s != kLpNoSet) {
      pred = lp_predict(table, s, view);
    } else if (nb) {
      int64_t mean;
      if (lp_neighbour_mean(*nb, l, h, coded, mean)) pred = mean;
    }
    pred = pred < lo ? lo : pred > hi ? hi : pred;
    const int activity = lp_activity(view);
    const int group = s == kLpNoSet ? kLpGroups - 1 : table.group[static_cast<size_t>(s)];
    int64_t r;
    SignedIntModel& model = m.residual[group][activity];
    BitModel& sign = m.sign_context ? m.sign[group][lp_sign_context(view, pred)] : model.sign;
    if (!value(model, bits, choose(l, pred, h[l], model, sign) - pred, r, &sign)) return false;
    const int64_t v = pred + r;
    if (v < lo || v > hi) return false;
    h[l] = v;
    res[l] = r;
    coded[l] = 1;
    previous = v;
    activity_of_last = r < 0 ? -r : r;
    return true;
  };
  // Dense: the heights and activities live in the grid's cells, written as each cell's first vertex is known.
  // Sparse (rare: long, thin patches): the 14 taps' heights and activities gathered through the local ids into a
  // cell view of their own (offset t at index t). One call of code_one serves both (one copy of it in the module).
  const bool dense = raster.dense();
  std::vector<int64_t>& ch = raster.cell_height;
  std::vector<int64_t>& ca = raster.cell_activity;
  if (dense) {
    ch.assign(raster.cells(), kLpEmptyCell);
    ca.assign(raster.cells(), -1);
  }
  std::array<uint32_t, kLpOffsets> id;
  std::array<int64_t, kLpOffsets> tap_height, tap_activity;
  static constexpr std::array<int64_t, kLpOffsets> kIdentity = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13};
  for (uint32_t l : raster.order()) {
    size_t b = 0;
    uint32_t mask;
    LpCellView view{tap_height.data(), tap_activity.data(), kIdentity.data()};
    if (dense) {
      b = static_cast<size_t>(raster.cell(level.coord[l][0], level.coord[l][1]));
      view = LpCellView{ch.data() + b, ca.data() + b, raster.deltas()};
      mask = kLpOccupancyMasks ? raster.mask_at(level.coord[l][0], level.coord[l][1]) : view.mask();
    } else {
      mask = raster.taps(level.coord[l][0], level.coord[l][1], id);
      const LpIdView ids{id, h, &res, &coded};
      for (int t = 0; t < kLpOffsets; ++t) {
        tap_height[static_cast<size_t>(t)] = ids.present(t) ? ids.height(t) : kLpEmptyCell;
        tap_activity[static_cast<size_t>(t)] = ids.activity(t);
      }
    }
    if (!code_one(l, mask, view)) return false;
    if (dense && raster.owner(static_cast<int64_t>(b)) == l) {  // h[l] and its activity, as code_one left them
      ch[b] = previous;
      ca[b] = activity_of_last;
    }
  }
  return true;
}

}  // namespace prm::codec
