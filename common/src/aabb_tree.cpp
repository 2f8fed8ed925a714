#include "prm/aabb_tree.h"

#if defined(__SSE2__)
#include <emmintrin.h>  // part of every x86-64
#endif
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "prm/error.h"
#include "prm/point_triangle_distance.h"
#include "prm/vec3.h"

namespace prm {
namespace {

constexpr int kBins = 16;
constexpr uint32_t kMaxLeafSize = 8;     // SAH may stop here when a split does not pay
constexpr uint32_t kMinSplitSize = 3;    // ranges of at most 2 triangles are always leaves
constexpr uint32_t kParallelSize = 4096; // ranges larger than this build their children in parallel
constexpr int kSahMaxDepth = 40;         // below this depth, split at the median: bounds the depth (and the query
                                         // stack) even for pathological inputs such as many identical triangles
constexpr int kStackSize = 128;          // > kSahMaxDepth + log2(2^32)
constexpr uint32_t kWithinNeighbours = 2;  // within(): triangles tried on each side of the hint's in leaf order
constexpr double kTraversalCost = 1.0;   // SAH costs: a point-triangle test costs about two box tests
constexpr double kTriangleCost = 2.0;

struct Box {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL};
  Vec3 hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void add(const Vec3& p) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  void add(const Box& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], b.lo[k]);
      hi[k] = std::max(hi[k], b.hi[k]);
    }
  }
  bool valid() const { return lo[0] <= hi[0]; }
  double half_area() const {
    if (!valid()) return 0;
    const double x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
    return x * y + y * z + z * x;
  }
};

float round_down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -HUGE_VALF);
  return f;
}
float round_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, HUGE_VALF);
  return f;
}

struct BuildTriangle {
  Box box;
  Vec3 centroid;
};

// Builds the subtree of one node; children pairs are claimed from a shared atomic counter, so the node array is
// laid out in allocation order, which differs between runs only in the parallel part (the tree itself does not).
class AabbTreeBuilder {
 public:
  AabbTreeBuilder(std::vector<uint32_t>& ids, const std::vector<BuildTriangle>& tris, std::vector<float>& boxes,
                  std::vector<uint32_t>& links)
      : ids_(ids), tris_(tris), boxes_(boxes), links_(links) {}

  std::atomic<uint32_t> next{2};  // node 0 is the root, node 1 unused: children pairs start at even indices

  // box: bounds of the range's triangles; cbox: bounds of their centroids (both computed by the caller, which has
  // them from its own binning, so that each level makes only two passes over its range: binning and partition).
  void build(uint32_t node, uint32_t begin, uint32_t end, int depth, const Box& box, const Box& cbox) {
    for (int k = 0; k < 3; ++k) {
      boxes_[6 * node + k] = round_down(box.lo[k]);
      boxes_[6 * node + 3 + k] = round_up(box.hi[k]);
    }
    const uint32_t count = end - begin;
    if (count < kMinSplitSize) return make_leaf(node, begin, count);

    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (cbox.hi[k] - cbox.lo[k] > cbox.hi[axis] - cbox.lo[axis]) axis = k;
    const double extent = cbox.hi[axis] - cbox.lo[axis];

    uint32_t mid = begin + count / 2;
    Box left_box, left_cbox, right_box, right_cbox;
    bool use_median = depth >= kSahMaxDepth || !(extent > 0);
    if (!use_median) {
      // Binned SAH along the widest centroid axis.
      const double scale = kBins / extent;
      auto bin_of = [&](uint32_t id) {
        const int b = static_cast<int>((tris_[id].centroid[axis] - cbox.lo[axis]) * scale);
        return std::min(std::max(b, 0), kBins - 1);
      };
      Box bins[kBins], cbins[kBins];
      uint32_t counts[kBins] = {};
      for (uint32_t i = begin; i < end; ++i) {
        const BuildTriangle& t = tris_[ids_[i]];
        const int b = bin_of(ids_[i]);
        bins[b].add(t.box);
        cbins[b].add(t.centroid);
        ++counts[b];
      }
      double right_area[kBins];
      uint32_t right_count[kBins];
      Box acc;
      uint32_t n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.add(bins[b]);
        n += counts[b];
        right_area[b] = acc.half_area();
        right_count[b] = n;
      }
      acc = Box();
      n = 0;
      double best_cost = HUGE_VAL;
      int best_split = -1;
      for (int b = 1; b < kBins; ++b) {  // split between bins b-1 and b
        acc.add(bins[b - 1]);
        n += counts[b - 1];
        if (n == 0 || right_count[b] == 0) continue;
        const double cost = acc.half_area() * n + right_area[b] * right_count[b];
        if (cost < best_cost) {
          best_cost = cost;
          best_split = b;
        }
      }
      const double area = box.half_area();
      const double leaf_cost = kTriangleCost * count;
      const double split_cost =
          area > 0 ? kTraversalCost + kTriangleCost * best_cost / area : kTraversalCost + leaf_cost;
      if (best_split < 0) {
        use_median = true;
      } else if (count <= kMaxLeafSize && leaf_cost <= split_cost) {
        return make_leaf(node, begin, count);
      } else {
        mid = static_cast<uint32_t>(std::partition(ids_.data() + begin, ids_.data() + end,
                                                   [&](uint32_t id) { return bin_of(id) < best_split; }) -
                                    ids_.data());
        for (int b = 0; b < kBins; ++b) {
          (b < best_split ? left_box : right_box).add(bins[b]);
          (b < best_split ? left_cbox : right_cbox).add(cbins[b]);
        }
      }
    }
    if (use_median) {
      if (count <= kMaxLeafSize && !(extent > 0)) return make_leaf(node, begin, count);
      mid = begin + count / 2;
      std::nth_element(ids_.data() + begin, ids_.data() + mid, ids_.data() + end, [&](uint32_t x, uint32_t y) {
        return tris_[x].centroid[axis] < tris_[y].centroid[axis];
      });
      bounds(begin, mid, left_box, left_cbox);
      bounds(mid, end, right_box, right_cbox);
    }

    const uint32_t left = next.fetch_add(2);
    links_[2 * node] = left;
    links_[2 * node + 1] = 0;
    if (count > kParallelSize) {
      tbb::parallel_invoke([&] { build(left, begin, mid, depth + 1, left_box, left_cbox); },
                           [&] { build(left + 1, mid, end, depth + 1, right_box, right_cbox); });
    } else {
      build(left, begin, mid, depth + 1, left_box, left_cbox);
      build(left + 1, mid, end, depth + 1, right_box, right_cbox);
    }
  }

  void bounds(uint32_t begin, uint32_t end, Box& box, Box& cbox) const {
    for (uint32_t i = begin; i < end; ++i) {
      box.add(tris_[ids_[i]].box);
      cbox.add(tris_[ids_[i]].centroid);
    }
  }

 private:
  void make_leaf(uint32_t node, uint32_t begin, uint32_t count) {
    links_[2 * node] = begin;
    links_[2 * node + 1] = count;
  }

  std::vector<uint32_t>& ids_;
  const std::vector<BuildTriangle>& tris_;
  std::vector<float>& boxes_;
  std::vector<uint32_t>& links_;
};

}  // namespace

AabbTree::AabbTree(const Mesh& mesh) { build(mesh.positions, mesh.triangles); }

AabbTree::AabbTree(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles) {
  build(positions, triangles);
}

void AabbTree::build(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles) {
  const size_t n = triangles.size();
  if (n == 0) return;
  if (n >= kNoFace / 2) throw InputError("mesh has too many triangles for the distance tree");
  const size_t nv = positions.size();
  std::vector<BuildTriangle> tris(n);
  std::atomic<size_t> bad_index{n}, bad_value{n};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t t = r.begin(); t != r.end(); ++t) {
      const Tri& f = triangles[t];
      if (f[0] >= nv || f[1] >= nv || f[2] >= nv) {
        size_t cur = bad_index.load();
        while (t < cur && !bad_index.compare_exchange_weak(cur, t)) {
        }
        continue;
      }
      BuildTriangle& b = tris[t];
      for (int k = 0; k < 3; ++k) b.box.add(positions[f[k]]);
      b.centroid = (positions[f[0]] + positions[f[1]] + positions[f[2]]) * (1.0 / 3.0);
      // (min/max skip NaN, so the box alone would not show it; the centroid's sum does.)
      if (!std::isfinite(b.centroid[0] + b.centroid[1] + b.centroid[2])) {
        size_t cur = bad_value.load();
        while (t < cur && !bad_value.compare_exchange_weak(cur, t)) {
        }
      }
    }
  });
  if (bad_index.load() < n)
    throw InputError("triangle " + std::to_string(bad_index.load()) + " refers to a vertex that does not exist (" +
                     std::to_string(nv) + " vertices)");
  if (bad_value.load() < n)
    throw InputError("triangle " + std::to_string(bad_value.load()) + " has a vertex with a non-finite coordinate");

  ids_.resize(n);
  for (size_t t = 0; t < n; ++t) ids_[t] = static_cast<uint32_t>(t);
  const size_t max_nodes = 2 * n + 1;
  std::vector<float> boxes(6 * max_nodes, 0.0f);
  std::vector<uint32_t> links(2 * max_nodes, 0);
  size_t used = 0;
  {
    AabbTreeBuilder builder(ids_, tris, boxes, links);
    Box box, cbox;
    builder.bounds(0, static_cast<uint32_t>(n), box, cbox);
    builder.build(0, 0, static_cast<uint32_t>(n), 0, box, cbox);
    used = builder.next.load();
  }
  // Each piece of scratch is freed as soon as it is used up, so that a build's peak is its binning (the triangles'
  // boxes and centroids, 72 bytes a triangle, and the node slots, 64), not that plus the finished tree.
  std::vector<BuildTriangle>().swap(tris);

  pairs_.assign((used + 1) / 2, NodePair{});
  for (size_t i = 0; i < used; ++i) {
    NodePair& pair = pairs_[i / 2];
    const size_t side = i % 2;
    for (int k = 0; k < 3; ++k) {
      pair.lo[k][side] = boxes[6 * i + k];
      pair.hi[k][side] = boxes[6 * i + 3 + k];
    }
    pair.first[side] = links[2 * i];
    pair.count[side] = links[2 * i + 1];
  }
  for (int k = 0; k < 3; ++k) {  // the unused slot 1 gets an empty box so that nothing ever enters it
    pairs_[0].lo[k][1] = HUGE_VALF;
    pairs_[0].hi[k][1] = -HUGE_VALF;
  }
  pairs_[0].first[1] = pairs_[0].count[1] = 0;
  std::vector<float>().swap(boxes);
  std::vector<uint32_t>().swap(links);
  order_depth_first();

  // The used vertices, renumbered in the order the leaves first use them (neighbouring leaves share them, and read
  // them from nearby memory); the coordinates are copied exactly, so every distance is the same.
  std::vector<uint32_t> point_of(nv, kNoFace);
  triangles_.resize(n);
  slot_.resize(n);
  uint32_t used_points = 0;
  for (size_t k = 0; k < n; ++k) {
    const Tri& f = triangles[ids_[k]];
    uint32_t corner[3];
    for (int c = 0; c < 3; ++c) {
      uint32_t& q = point_of[f[static_cast<size_t>(c)]];
      if (q == kNoFace) q = used_points++;
      corner[c] = q;
    }
    triangles_[k] = Triangle{corner[0], corner[1], corner[2]};
    slot_[ids_[k]] = static_cast<uint32_t>(k);
  }
  points_.resize(used_points);
  for (size_t v = 0; v < nv; ++v)
    if (point_of[v] != kNoFace) points_[point_of[v]] = positions[v];
}

void AabbTree::refit(const Mesh& mesh) {
  if (mesh.triangles.size() != triangles_.size())
    throw InputError("refit: the mesh's triangles are not the tree's");
  for (size_t k = 0; k < triangles_.size(); ++k) {
    const Tri& f = mesh.triangles[ids_[k]];
    const Triangle& t = triangles_[k];
    for (size_t c = 0; c < 3; ++c)
      if (f[c] >= mesh.positions.size()) throw InputError("refit: the mesh's triangles are not the tree's");
    points_[t.a] = mesh.positions[f[0]];
    points_[t.b] = mesh.positions[f[1]];
    points_[t.c] = mesh.positions[f[2]];
    for (uint32_t q : {t.a, t.b, t.c})
      if (!(std::isfinite(points_[q][0]) && std::isfinite(points_[q][1]) && std::isfinite(points_[q][2])))
        throw InputError("refit: a corner is not finite");
  }
  // Children after their parents (order_depth_first): the pairs from the last, each side from its triangles (a leaf)
  // or from its children's pair.
  for (size_t i = pairs_.size(); i-- > 0;) {
    NodePair& pair = pairs_[i];
    for (size_t side = 0; side < 2; ++side) {
      if (i == 0 && side == 1) continue;  // the root's unused slot
      std::array<double, 3> lo, hi;
      lo.fill(HUGE_VAL);
      hi.fill(-HUGE_VAL);
      if (pair.count[side] > 0) {
        for (uint32_t k = pair.first[side], end = k + pair.count[side]; k < end; ++k)
          for (uint32_t q : {triangles_[k].a, triangles_[k].b, triangles_[k].c})
            for (size_t a = 0; a < 3; ++a) {
              lo[a] = std::min(lo[a], points_[q][a]);
              hi[a] = std::max(hi[a], points_[q][a]);
            }
        for (size_t a = 0; a < 3; ++a) {
          pair.lo[a][side] = round_down(lo[a]);
          pair.hi[a][side] = round_up(hi[a]);
        }
      } else {
        const NodePair& children = pairs_[pair.first[side] / 2];
        for (size_t a = 0; a < 3; ++a) {
          pair.lo[a][side] = std::min(children.lo[a][0], children.lo[a][1]);
          pair.hi[a][side] = std::max(children.hi[a][0], children.hi[a][1]);
        }
      }
    }
  }
}

void AabbTree::order_depth_first() {
  std::vector<NodePair> ordered;
  ordered.reserve(pairs_.size());
  std::vector<uint32_t> index_of(pairs_.size(), 0);  // an old pair's new index
  std::vector<uint32_t> todo{0};                      // old pair indices; the root pair stays first
  while (!todo.empty()) {
    const uint32_t old = todo.back();
    todo.pop_back();
    index_of[old] = static_cast<uint32_t>(ordered.size());
    ordered.push_back(pairs_[old]);
    // Side 1 pushed first, so that side 0's subtree follows its parent directly (the root's side 1 is unused).
    for (int side = 1; side >= 0; --side)
      if (pairs_[old].count[side] == 0 && !(old == 0 && side == 1)) todo.push_back(pairs_[old].first[side] / 2);
  }
  for (NodePair& pair : ordered)
    for (int side = 0; side < 2; ++side)
      if (pair.count[side] == 0 && pair.first[side] != 0) pair.first[side] = 2 * index_of[pair.first[side] / 2];
  pairs_ = std::move(ordered);
}

namespace {

inline double box_distance2(const float* lo, const float* hi, const Vec3& p) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double below = static_cast<double>(lo[k]) - p[k];
    const double above = p[k] - static_cast<double>(hi[k]);
    const double e = std::max(std::max(below, above), 0.0);
    d2 += e * e;
  }
  return d2;
}

// box_distance2 of the two boxes of a pair (lo[axis][side], hi[axis][side]) at once, lane 0 side 0: the same
// operations in the same order on each lane (packed SSE2 is IEEE double as the scalar code is; max of -0 and +0 may
// pick the other zero, whose square is the same), so the distances, and with them the search's order and answer,
// are bit for bit box_distance2's.
inline void box_distance2_pair(const float (&lo2)[3][2], const float (&hi2)[3][2], const Vec3& p, double& d0,
                               double& d1) {
#if !defined(__SSE2__)
  const float lo0[3] = {lo2[0][0], lo2[1][0], lo2[2][0]}, hi0[3] = {hi2[0][0], hi2[1][0], hi2[2][0]};
  const float lo1[3] = {lo2[0][1], lo2[1][1], lo2[2][1]}, hi1[3] = {hi2[0][1], hi2[1][1], hi2[2][1]};
  d0 = box_distance2(lo0, hi0, p);
  d1 = box_distance2(lo1, hi1, p);
#else
  __m128d d2 = _mm_setzero_pd();
  const __m128d zero = _mm_setzero_pd();
  for (int k = 0; k < 3; ++k) {
    // Both sides' floats in one 8-byte load (_mm_loadl_epi64 may alias anything), widened exactly to doubles.
    const __m128d lo = _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(lo2[k]))));
    const __m128d hi = _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(hi2[k]))));
    const __m128d pk = _mm_set1_pd(p[k]);
    const __m128d e = _mm_max_pd(_mm_max_pd(_mm_sub_pd(lo, pk), _mm_sub_pd(pk, hi)), zero);
    d2 = _mm_add_pd(d2, _mm_mul_pd(e, e));
  }
  d0 = _mm_cvtsd_f64(d2);
  d1 = _mm_cvtsd_f64(_mm_unpackhi_pd(d2, d2));
#endif
}

// closest_point_on_triangle(p, a, b, c) into q, and its squared distance to p, bit for bit, without its branches:
// every region's point is computed (the same operations on the same doubles; packed SSE2 is IEEE double lane by lane),
// and the region is chosen by the same tests in the same order, as masks. The search tests a few triangles a query,
// whose regions change from one to the next, and those branches were mispredicted. The degenerate (zero-area)
// triangles keep closest_point_on_triangle's code (rare, so predicted).
[[gnu::always_inline]] inline double closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& q) {
#if defined(__SSE2__)
  const Vec3 ab = b - a, ac = c - a, ap = p - a, bp = p - b, cp = p - c;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap), d3 = dot(ab, bp), d4 = dot(ac, bp), d5 = dot(ab, cp),
               d6 = dot(ac, cp);
  const double vc = d1 * d4 - d3 * d2;
  const double va = d3 * d6 - d5 * d4;
  const double vb = d5 * d2 - d1 * d6;
  const double denom = va + vb + vc;
  const double e43 = d4 - d3, e56 = d5 - d6;
  const __m128d zero = _mm_setzero_pd();
  const auto s = [](double x) { return _mm_set_sd(x); };
  // The region tests, in closest_point_on_triangle's order (a mask in lane 0).
  const __m128d in_a = _mm_and_pd(_mm_cmple_sd(s(d1), zero), _mm_cmple_sd(s(d2), zero));
  const __m128d in_b = _mm_and_pd(_mm_cmpge_sd(s(d3), zero), _mm_cmple_sd(s(d4), s(d3)));
  const __m128d in_c = _mm_and_pd(_mm_cmpge_sd(s(d6), zero), _mm_cmple_sd(s(d5), s(d6)));
  const __m128d flat = _mm_cmpngt_sd(s(denom), zero);
  if (_mm_movemask_pd(_mm_andnot_pd(_mm_or_pd(_mm_or_pd(in_a, in_b), in_c), flat)) & 1) {  // rare: predicted
    q = closest_point_on_triangle(p, a, b, c);
    return norm2(p - q);
  }
  const __m128d on_ab = _mm_and_pd(_mm_and_pd(_mm_cmple_sd(s(vc), zero), _mm_cmpge_sd(s(d1), zero)),
                                   _mm_cmple_sd(s(d3), zero));
  const __m128d on_ac = _mm_and_pd(_mm_and_pd(_mm_cmple_sd(s(vb), zero), _mm_cmpge_sd(s(d2), zero)),
                                   _mm_cmple_sd(s(d6), zero));
  const __m128d on_bc = _mm_and_pd(_mm_and_pd(_mm_cmple_sd(s(va), zero), _mm_cmpge_sd(s(e43), zero)),
                                   _mm_cmpge_sd(s(e56), zero));
  // The divisions two by two: {d1 / (d1 - d3), d2 / (d2 - d6)} (edges ab, ac), {e43 / (e43 + e56), vb / denom}
  // (edge bc, interior), vc / denom (interior).
  const __m128d t1 = _mm_div_pd(_mm_set_pd(d2, d1), _mm_set_pd(d2 - d6, d1 - d3));
  const __m128d t2 = _mm_div_pd(_mm_set_pd(vb, e43), _mm_set_pd(denom, e43 + e56));
  const __m128d t3 = _mm_div_sd(s(vc), s(denom));
  const auto bcast = [](__m128d x, int lane) { return lane ? _mm_unpackhi_pd(x, x) : _mm_unpacklo_pd(x, x); };
  // A point as {x, y} and {z, z}.
  struct P2 {
    __m128d xy, z;
  };
  const auto load = [](const Vec3& v) { return P2{_mm_loadu_pd(v.data()), _mm_set1_pd(v[2])}; };
  const auto add = [](const P2& u, const P2& v) { return P2{_mm_add_pd(u.xy, v.xy), _mm_add_pd(u.z, v.z)}; };
  const auto scale = [](const P2& u, __m128d t) { return P2{_mm_mul_pd(u.xy, t), _mm_mul_pd(u.z, t)}; };
  const auto pick = [&](__m128d mask, const P2& yes, const P2& no) {
    const __m128d m = bcast(mask, 0);
    return P2{_mm_or_pd(_mm_and_pd(m, yes.xy), _mm_andnot_pd(m, no.xy)),
              _mm_or_pd(_mm_and_pd(m, yes.z), _mm_andnot_pd(m, no.z))};
  };
  const P2 pa = load(a), pb = load(b), pc = load(c), vab = load(ab), vac = load(ac), vbc = load(c - b);
  P2 r = add(add(pa, scale(vab, bcast(t2, 1))), scale(vac, bcast(t3, 0)));  // interior
  r = pick(on_bc, add(pb, scale(vbc, bcast(t2, 0))), r);
  r = pick(on_ac, add(pa, scale(vac, bcast(t1, 1))), r);
  r = pick(on_ab, add(pa, scale(vab, bcast(t1, 0))), r);
  r = pick(in_c, pc, r);
  r = pick(in_b, pb, r);
  r = pick(in_a, pa, r);
  _mm_storeu_pd(q.data(), r.xy);
  _mm_store_sd(&q[2], r.z);
  return norm2(p - q);
#else
  q = closest_point_on_triangle(p, a, b, c);
  return norm2(p - q);
#endif
}

// The two children of an inner node (nodes first and first + 1, one pair), the nearer to p first: their numbers and
// box distances (a tie keeps the order).
template <class Pair>
inline void order_children(const Pair& children, uint32_t first, const Vec3& p, uint32_t& nearer, uint32_t& farther,
                           double& d_nearer, double& d_farther) {
  box_distance2_pair(children.lo, children.hi, p, d_nearer, d_farther);
  nearer = first;
  farther = first + 1;
  if (d_farther < d_nearer) {
    std::swap(d_nearer, d_farther);
    std::swap(nearer, farther);
  }
}

}  // namespace

AabbTree::Hit AabbTree::closest(const Vec3& p) const {
  Hit hit;
  search(p, hit, HUGE_VAL);
  return hit;
}

AabbTree::Hit AabbTree::closest(const Vec3& p, double bound2) const {
  Hit hit;
  search(p, hit, bound2);
  return hit;
}

void AabbTree::closest(const Vec3& p, Hit& hint) const {
  if (!hint.found() || hint.face >= slot_.size()) return search(p, hint, HUGE_VAL);
  // The hint's triangle is usually the answer or close to it: its exact distance is the tightest start bound.
  const uint32_t slot = slot_[hint.face];
  const Triangle& t = triangles_[slot];
  const double d2 = closest_on_triangle(p, points_[t.a], points_[t.b], points_[t.c], hint.point);
  search(p, hint, d2, slot);
}

bool AabbTree::well_inside(const Vec3& p, uint32_t face) const {
  if (face >= slot_.size()) return false;
  const Triangle& t = triangles_[slot_[face]];
  const Vec3 &a = points_[t.a], &b = points_[t.b], &c = points_[t.c];
  const Vec3 ab = b - a, ac = c - a, ap = p - a, bp = p - b, cp = p - c;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap), d3 = dot(ab, bp), d4 = dot(ac, bp), d5 = dot(ab, cp),
               d6 = dot(ac, cp);
  // The barycentric coordinates of the projection times |n|^2, n = ab x ac.
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  const double m = kWellInside * (va + vb + vc);
  if (!(va > m && vb > m && vc > m)) return false;
  // p's height over the plane, h / |n|, at most the projection's distance to each edge (va / (|n| |bc|) for bc):
  // h^2 |bc|^2 <= va^2, and so on.
  const double h = dot(ap, cross(ab, ac)), h2 = h * h;
  return h2 * norm2(c - b) <= va * va && h2 * norm2(ac) <= vb * vb && h2 * norm2(ab) <= vc * vc;
}

AabbTree::Hit AabbTree::on_face(const Vec3& p, uint32_t face) const {
  Hit hit;
  if (face >= slot_.size()) return hit;
  const Triangle& t = triangles_[slot_[face]];
  hit.distance2 = closest_on_triangle(p, points_[t.a], points_[t.b], points_[t.c], hit.point);
  hit.face = face;
  return hit;
}

void AabbTree::closest_reusing(const Vec3& p, Hit& hint) const {
  if (hint.found() && well_inside(p, hint.face))
    hint = on_face(p, hint.face);
  else
    closest(p, hint);
}

bool AabbTree::within(const Vec3& p, double bound2, Hit& hint) const {
  const auto near = [&](uint32_t slot) {
    const Triangle& t = triangles_[slot];
    Vec3 q;
    const double d2 = closest_on_triangle(p, points_[t.a], points_[t.b], points_[t.c], q);
    if (!(d2 <= bound2)) return false;
    hint.distance2 = d2;
    hint.point = q;
    hint.face = ids_[slot];
    return true;
  };
  if (hint.found() && hint.face < slot_.size()) {
    // The hint's triangle, then its neighbours in leaf order (the same leaf or the next one: nearby in space).
    const uint32_t s = slot_[hint.face];
    if (near(s)) return true;
    for (uint32_t d = 1; d <= kWithinNeighbours; ++d)
      if ((s >= d && near(s - d)) || (s + d < triangles_.size() && near(s + d))) return true;
  }
  if (pairs_.empty()) return false;
  {
    const NodePair& root = pairs_[0];
    const float lo[3] = {root.lo[0][0], root.lo[1][0], root.lo[2][0]};
    const float hi[3] = {root.hi[0][0], root.hi[1][0], root.hi[2][0]};
    if (box_distance2(lo, hi, p) > bound2) return false;
  }
  uint32_t stack[kStackSize];
  int top = 0;
  uint32_t current = 0;
  for (;;) {
    const NodePair& pair = pairs_[current / 2];
    const uint32_t side = current % 2, first = pair.first[side], count = pair.count[side];
    if (count > 0) {
      for (uint32_t k = first, end = first + count; k < end; ++k)
        if (near(k)) return true;
    } else {
      uint32_t nearer, farther;
      double dl, dr;
      order_children(pairs_[first / 2], first, p, nearer, farther, dl, dr);
      if (dl <= bound2) {
        if (dr <= bound2) stack[top++] = farther;
        current = nearer;
        continue;
      }
    }
    if (top == 0) return false;
    current = stack[--top];
  }
}

void AabbTree::search(const Vec3& p, Hit& hit, double best, uint32_t skip) const {
  hit.distance2 = best;
  if (pairs_.empty()) return;

  struct Entry {
    uint32_t node;
    double distance2;
  };
  Entry stack[kStackSize];
  int top = 0;
  uint32_t current = 0;
  {
    const NodePair& root = pairs_[0];
    const float lo[3] = {root.lo[0][0], root.lo[1][0], root.lo[2][0]};
    const float hi[3] = {root.hi[0][0], root.hi[1][0], root.hi[2][0]};
    if (box_distance2(lo, hi, p) >= best) return;
  }
  for (;;) {
    const NodePair& pair = pairs_[current / 2];
    const uint32_t side = current % 2, first = pair.first[side], count = pair.count[side];
    bool descend = false;
    if (count > 0) {
      for (uint32_t k = first, end = first + count; k < end; ++k) {
        if (k == skip) continue;
        const Triangle& t = triangles_[k];
        Vec3 q;
        const double d2 = closest_on_triangle(p, points_[t.a], points_[t.b], points_[t.c], q);
        if (d2 < best) {
          best = d2;
          hit.point = q;
          hit.face = ids_[k];
        }
      }
      if (best == 0) break;
    } else {
      uint32_t near, far;
      double dl, dr;
      order_children(pairs_[first / 2], first, p, near, far, dl, dr);
      if (dl < best) {
        if (dr < best) stack[top++] = Entry{far, dr};
        current = near;
        descend = true;
      }
    }
    if (descend) continue;
    // Pop the next subtree that may still hold a closer point.
    bool found = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.distance2 < best) {
        current = e.node;
        found = true;
        break;
      }
    }
    if (!found) break;
  }
  hit.distance2 = best;
}

std::array<Vec3, 2> AabbTree::bounds() const {
  if (pairs_.empty()) return {Vec3{0, 0, 0}, Vec3{0, 0, 0}};
  Box box;
  for (const Vec3& q : points_) box.add(q);  // every point is a corner of a triangle
  return {box.lo, box.hi};
}

int AabbTree::depth() const {
  if (pairs_.empty()) return 0;
  int deepest = 0;
  std::vector<std::pair<uint32_t, int>> todo{{0u, 1}};
  while (!todo.empty()) {
    const auto [n, d] = todo.back();
    todo.pop_back();
    deepest = std::max(deepest, d);
    const NodePair& pair = pairs_[n / 2];
    if (pair.count[n % 2] == 0) {
      todo.push_back({pair.first[n % 2], d + 1});
      todo.push_back({pair.first[n % 2] + 1, d + 1});
    }
  }
  return deepest;
}

}  // namespace prm
