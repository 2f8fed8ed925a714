// §10 Positions: the vertex order, the prediction rule and the residual contexts, one copy for
// position_encode.cpp and position_decode.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "adaptive_model.h"
#include "always_inline.h"
#include "closed_mesh.h"
#include "corner_table.h"
#include "fan_walk.h"

namespace prm::codec {


// floor(a / b) for b > 0.
inline int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// §10.3 The rounded mean floor((2 * sum + n) / (2 * n)) of n >= 1 values; n = 1 and n = 2 without a division.
inline int64_t rounded_mean(int64_t sum, int64_t n) {
  if (n == 1) return sum;
  if (n == 2) return floor_div(sum + 1, 2);  // == floor((2 * sum + 2) / 4)
  return floor_div(2 * sum + n, 2 * n);
}

// §10.2 The prediction-degree order: the next vertex is the most recently pushed one with the most decoded
// neighbours (capped at kDegreeCap); when none is pending, the lowest-numbered real vertex not yet decoded. A vertex
// is pushed onto bucket min(degree, kDegreeCap) each time its degree grows, when a neighbour is decoded.
constexpr uint32_t kDegreeCap = 5;
class DegreeOrder {
 public:
  enum : uint8_t { kPending = 0, kDone = 1, kDummy = 2 };
  // known (optional, §10.2 for PRM streams): vertices whose positions the patches section already gave.
  explicit DegreeOrder(const ClosedMesh& mesh, const std::vector<uint8_t>* known = nullptr)
      : num_vertices_(mesh.num_vertices), degree_(mesh.num_vertices, 0) {
    state_.resize(mesh.num_vertices);
    for (uint32_t v = 0; v < num_vertices_; ++v)
      state_[v] = mesh.is_dummy[v] ? kDummy : (known && (*known)[v]) ? kDone : kPending;
    for (auto& b : buckets_) b.reserve(64);
  }
  // The next vertex, or UINT32_MAX at the end.
  uint32_t next() {
    for (int b = kDegreeCap; b >= 0; --b) {
      auto& bucket = buckets_[b];
      while (!bucket.empty()) {
        const uint32_t v = bucket.back();
        bucket.pop_back();
        if (state_[v] == kPending && capped(degree_[v]) == static_cast<uint32_t>(b)) return take(v);
      }
    }
    while (next_start_ < num_vertices_ && state_[next_start_] != kPending) ++next_start_;
    return next_start_ < num_vertices_ ? take(next_start_) : UINT32_MAX;
  }
  bool done(uint32_t v) const { return state_[v] == kDone; }
  // A neighbour of the vertex being decoded: one more decoded neighbour if it is pending.
  PRM_WASM_INLINE void push_neighbour(uint32_t w) {
    if (state_[w] != kPending) return;
    const uint32_t d = ++degree_[w];
    buckets_[capped(d)].push_back(w);
  }

 private:
  static uint32_t capped(uint32_t d) { return d < kDegreeCap ? d : kDegreeCap; }
  uint32_t take(uint32_t v) {
    state_[v] = kDone;
    return v;
  }
  uint32_t num_vertices_;
  std::vector<uint32_t> degree_;
  std::vector<uint8_t> state_;
  std::vector<uint32_t> buckets_[kDegreeCap + 1];
  uint32_t next_start_ = 0;
};

// §10.3 What the prediction of one vertex yields: the predicted position, the number of parallelograms used, and
// per axis their spread (max - min, when two or more) and the side length |x - z| + |y - z| (when exactly one).
struct Prediction {
  std::array<int64_t, 3> p{};
  int parallelograms = 0;
  std::array<int64_t, 3> spread{};
  std::array<int64_t, 3> scale{};
};

// §10.3 Prediction of vertex v from the decoded vertices (`done`), q[3 * id] the positions decoded so far:
//   1. the rounded mean of the parallelogram predictions x + y - z of every triangle (v, x, y) of v's fan whose
//      opposite triangle (y, x, z) has x, y, z decoded;
//   2. else the rounded mean of v's decoded neighbours;
//   3. else the position of the previously decoded vertex (bbox_min for the first);
// then clamped to the bounding box.
// The same walk pushes v's neighbours onto the order (§10.2); that changes no decoded state, so it may happen before
// v's residuals are coded.
// It also checks §6.8's last condition: no neighbour appears twice in v's fan (`mark` holds, per vertex, the last
// vertex whose fan listed it); returns false if one does.
inline bool predict_position(const ClosedMesh& mesh, const std::vector<uint32_t>& vertex_corner, const uint32_t* q,
                             uint32_t v, uint32_t previous, const std::array<uint32_t, 3>& lo,
                             const std::array<uint32_t, 3>& hi, DegreeOrder& order, uint32_t* mark,
                             Prediction& out) {
  // Neighbours are never v itself (no triangle repeats a vertex); only the far vertex z of a parallelogram can be
  // (two triangles on the same three vertices).
  const uint32_t* cv = mesh.corner_vertex.data();
  const int32_t* opp = mesh.opp.data();
  int64_t sum[3] = {0, 0, 0}, lo_p[3] = {INT64_MAX, INT64_MAX, INT64_MAX}, hi_p[3] = {INT64_MIN, INT64_MIN, INT64_MIN};
  int64_t n = 0;
  uint32_t first[3] = {0, 0, 0};  // x, y, z of the first parallelogram: its side lengths are used when n = 1
  const uint32_t c0 = vertex_corner[v];
  uint32_t c = c0;
  // Along the walk, corner c's y is the previous corner's x: carry it and whether it is decoded.
  uint32_t x = cv[corner_next(c)], y = cv[corner_prev(c)];
  bool dx = order.done(x), dy = order.done(y);
  do {
    if (mark[x] == v) return false;
    mark[x] = v;
    order.push_neighbour(x);
    if (dx && dy) {
      const uint32_t z = cv[static_cast<uint32_t>(opp[c])];
      if (z != v && order.done(z)) {
        const uint32_t *qx = q + 3 * size_t{x}, *qy = q + 3 * size_t{y}, *qz = q + 3 * size_t{z};
        for (int k = 0; k < 3; ++k) {
          const int64_t pk = int64_t{qx[k]} + qy[k] - qz[k];
          sum[k] += pk;
          if (pk < lo_p[k]) lo_p[k] = pk;
          if (pk > hi_p[k]) hi_p[k] = pk;
        }
        if (n == 0) {
          first[0] = x;
          first[1] = y;
          first[2] = z;
        }
        ++n;
      }
    }
    const uint32_t d = static_cast<uint32_t>(opp[corner_prev(c)]);  // across the edge v -> x
    c = corner_prev(d);
    y = x;
    dy = dx;
    x = cv[d];
    dx = order.done(x);
  } while (c != c0);
  out.parallelograms = static_cast<int>(n);
  if (n > 0) {
    const uint32_t *qx = q + 3 * size_t{first[0]}, *qy = q + 3 * size_t{first[1]}, *qz = q + 3 * size_t{first[2]};
    for (int k = 0; k < 3; ++k) {
      const int64_t p = rounded_mean(sum[k], n);
      out.p[k] = p < lo[k] ? lo[k] : p > hi[k] ? hi[k] : p;
      out.spread[k] = n > 1 ? hi_p[k] - lo_p[k] : 0;
      // The side length |x - z| + |y - z| of the only parallelogram.
      const int64_t a = qx[k], b = qy[k], d = qz[k];
      out.scale[k] = n == 1 ? (a > d ? a - d : d - a) + (b > d ? b - d : d - b) : 0;
    }
    return true;
  }
  // No parallelogram: the mean of the decoded neighbours (a second walk; rare in prediction-degree order).
  int64_t nsum[3] = {0, 0, 0}, nn = 0;
  c = c0;
  do {
    const uint32_t x = cv[corner_next(c)];
    if (order.done(x)) {
      for (int k = 0; k < 3; ++k) nsum[k] += q[3 * size_t{x} + k];
      ++nn;
    }
    c = fan_next(opp, c);
  } while (c != c0);
  for (int k = 0; k < 3; ++k) {
    const int64_t p = nn > 0 ? rounded_mean(nsum[k], nn) : previous == UINT32_MAX ? lo[k] : q[3 * size_t{previous} + k];
    out.p[k] = p < lo[k] ? lo[k] : p > hi[k] ? hi[k] : p;
    out.spread[k] = 0;
    out.scale[k] = 0;
  }
  return true;
}

// §10.2 Seeding for PRM streams: the vertices the patches section placed are decoded already; in increasing id,
// each one's fan is walked, pushing its pending neighbours (their degrees grow) and checking §6.8 (no neighbour
// twice). Returns false if a fan lists a neighbour twice.
inline bool seed_known(const ClosedMesh& mesh, const std::vector<uint32_t>& vertex_corner,
                       const std::vector<uint8_t>& known, DegreeOrder& order, uint32_t* mark) {
  const uint32_t* cv = mesh.corner_vertex.data();
  const int32_t* opp = mesh.opp.data();
  for (uint32_t v = 0; v < mesh.num_vertices; ++v) {
    if (!known[v]) continue;
    const uint32_t c0 = vertex_corner[v];
    // The fan walk (fan_next) moves c to prev(d), d = opp[prev(c)]: the next neighbour is the vertex of next(prev(d))
    // = d, the walk is back at c0 when d = next(c0), and the next step's prev(prev(d)) is next(d). k is prev(c).
    const uint32_t end = corner_next(c0);
    uint32_t x = cv[end], k = corner_prev(c0);
    for (;;) {
      if (mark[x] == v) return false;
      mark[x] = v;
      order.push_neighbour(x);
      const uint32_t d = static_cast<uint32_t>(opp[k]);
      if (d == end) break;
      x = cv[d];
      k = corner_next(d);
    }
  }
  return true;
}

// Class of a magnitude m >= 1: floor(log2 m) (-1 for 0).
inline int magnitude_class(uint64_t m) {
#if defined(__GNUC__) || defined(__clang__)
  return m ? 63 - __builtin_clzll(m) : -1;
#else
  int e = -1;
  while (m) {
    ++e;
    m >>= 1;
  }
  return e;
#endif
}

// Number of bits of x (0 for 0).
inline int bit_length(uint32_t x) {
#if defined(__GNUC__) || defined(__clang__)
  return x ? 32 - __builtin_clz(x) : 0;
#else
  int b = 0;
  while (x) {
    ++b;
    x >>= 1;
  }
  return b;
#endif
}

// §10.4 Residual coding state, per axis and context: an adaptive Rice parameter (JPEG-LS style: the sum of
// magnitudes A and the count N, halved at kRiceReset) and the models of the unary part; per axis, Rice parameter and
// unary length, the model of the first low bit.
constexpr int kResidualContexts = 24;
constexpr uint32_t kRiceReset = 256;
constexpr int kUnaryModels = 16;
constexpr uint32_t kUnaryEscape = 20;  // after 20 ones, q - 20 follows in kEscapeBits direct bits
static_assert(kUnaryModels - 1 < kUnaryEscape, "the unary part reaches its last model before the escape");
constexpr int kEscapeBits = 21;
constexpr int kMaxRice = 24;
struct RiceState {
  uint32_t a = 8, n = 1;
  // §10.4.1 k = min { k >= 0 : N * 2^k >= A }
  int k() const {
    // Start from the difference of bit lengths, then correct by one: the same value as counting up from 0.
    int k = bit_length(a) - bit_length(n);
    if (k < 0) k = 0;
    if ((uint64_t{n} << k) < a) ++k;
    if (k > 0 && (uint64_t{n} << (k - 1)) >= a) --k;
    return k;  // <= 21: A / N never exceeds the largest magnitude 2^20 - 1 by more than the start value 8
  }
  void update(uint32_t magnitude) {
    a += magnitude;
    if (++n == kRiceReset) {
      a >>= 1;
      n >>= 1;
    }
  }
};
struct ResidualModels {
  RiceState rice[3][kResidualContexts];
  BitModel unary[3][kResidualContexts][kUnaryModels];
  BitModel low[3][kMaxRice + 1][3];
};

// §10.4.2 Context of axis k: by the number of parallelograms n, from the class A(x) = 1 + floor(log2(x + 1)) of the
//   spread (n >= 2) or the side length (n < 2), capped at 7:  n >= 3: 16 + A;  n = 2: 8 + A;  else A (0 if n = 0).
inline int residual_context(const Prediction& pr, int axis) {
  const int n = pr.parallelograms;
  if (n == 0) return 0;
  const int64_t x = n >= 2 ? pr.spread[axis] : pr.scale[axis];
  int a = 1 + magnitude_class(static_cast<uint64_t>(x) + 1);
  if (a > 7) a = 7;
  return n >= 3 ? 16 + a : n == 2 ? 8 + a : a;
}

}  // namespace prm::codec
