#include "relief_refinement.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "prm/vec3.h"
#include "relief_envelope.h"

namespace prm::remesh {

namespace {

constexpr uint32_t kInner = 0x80000000u;  // marks a block-local inner point id until the blocks are joined
constexpr size_t kBlockFaces = 2048;

// A point on a face's boundary, in the face's corner order, with the label of the boundary piece that follows it.
// sides: bit k set when the point lies on side k (from corner k to corner k + 1); corner k is on sides k and k - 1.
struct BoundaryPoint {
  uint32_t id;
  uint8_t sides;
  int8_t label;
  double u, v;  // barycentric coordinates of corners 1 and 2
};

struct Block {
  std::vector<Tri> tris;
  std::vector<int8_t> axis;
  std::vector<int32_t> source;
  std::vector<Vec3> inner;
  size_t split = 0;
};

// 4 sqrt(3) area / sum of squared sides, 1 for an equilateral triangle, 0 for a degenerate one.
double quality(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double s = norm2(b - a) + norm2(c - b) + norm2(a - c);
  return s > 0 ? 2 * std::sqrt(3.0) * norm(triangle_normal_area2(a, b, c)) / s : 0;
}

// A point inside a face where three or more regions meet.
struct Inner {
  uint32_t id;
  Vec3 position;
  double u, v;
};

constexpr size_t kX = static_cast<size_t>(-1);  // the inner point in a polygon's ring

// The envelope of every edge. Most edges lie inside one relief: their envelope is one of seven (no label, or the
// whole edge on one axis; the splitter reads nothing else of them), which they share; only the split edges store
// their own. 4 bytes an edge instead of sizeof(EdgeEnvelope) = 72 (at 3 edges a vertex, the refinement's peak).
class EnvelopeTable {
 public:
  EnvelopeTable(const std::vector<AxisValues>& fields, const std::vector<std::array<uint32_t, 2>>& edges, double snap,
                bool parallel)
      : index_(edges.size()) {
    stored_.resize(kShared);
    for (int a = 0; a < kReliefAxes; ++a) {  // [0]: count 0; [1 + a]: count 1 on axis a
      stored_[static_cast<size_t>(1 + a)].count = 1;
      stored_[static_cast<size_t>(1 + a)].start[1] = 1;
      stored_[static_cast<size_t>(1 + a)].axis[0] = static_cast<int8_t>(a);
    }
    auto envelope = [&](size_t e) { return upper_envelope(fields[edges[e][0]], fields[edges[e][1]], snap); };
    auto each = [&](const auto& body) {
      if (parallel)
        tbb::parallel_for(tbb::blocked_range<size_t>(0, edges.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
          for (size_t e = r.begin(); e != r.end(); ++e) body(e);
        });
      else
        for (size_t e = 0; e < edges.size(); ++e) body(e);
    };
    each([&](size_t e) {
      const EdgeEnvelope env = envelope(e);
      index_[e] = env.count == 0 ? 0 : env.count == 1 ? static_cast<uint32_t>(1 + env.axis[0]) : kSplit;
    });
    uint32_t next = kShared;
    for (uint32_t& i : index_)
      if (i == kSplit) i = next++;
    stored_.resize(next);
    each([&](size_t e) {  // the split edges' envelopes again (the same function of the same values)
      if (index_[e] >= kShared) stored_[index_[e]] = envelope(e);
    });
  }

  const EdgeEnvelope& operator[](size_t e) const { return stored_[index_[e]]; }
  size_t size() const { return index_.size(); }

 private:
  static constexpr uint32_t kShared = 1 + kReliefAxes;
  static constexpr uint32_t kSplit = std::numeric_limits<uint32_t>::max();
  std::vector<EdgeEnvelope> stored_;
  std::vector<uint32_t> index_;
};

class FaceSplitter {
 public:
  FaceSplitter(const Mesh& input, const std::vector<Vec3>& positions, const std::vector<AxisValues>& fields,
               const EnvelopeTable& envelopes, const std::vector<uint32_t>& split_base,
               const std::vector<std::array<int32_t, 3>>& edge_of, const std::vector<int8_t>& closest, double snap)
      : in_(input), pos_(positions), D_(fields), env_(envelopes), base_(split_base), edge_of_(edge_of),
        closest_(closest), snap_(snap), margin_(std::max(snap, 0.01)) {}

  void split(size_t f, Block& out) {
    const Tri& t = in_.triangles[f];
    collect_boundary(f, t);
    const size_t m = pts_.size();
    // Pieces of all-zero edges take the label of the piece before them; a face where every field vanishes takes
    // the axis closest to its normal (paper §2.1 leaves this case open; that axis faces the face best).
    for (int pass = 0; pass < 2; ++pass)
      for (size_t i = 0; i < m; ++i)
        if (pts_[i].label < 0) pts_[i].label = pts_[(i + m - 1) % m].label;
    if (pts_[0].label < 0)
      for (auto& p : pts_) p.label = closest_[f];
    find_changes();
    if (changes_.empty()) {
      if (m == 3) emit(out, t, pts_[0].label, f);
      else polygon(0, m - 1, pts_[0].label, f, out);  // split points of neighbours on its sides: fan them in
      return;
    }
    // A region much thinner than the face (a strip along a side, or a wedge squeezed against one) would only give
    // needles: it takes the label of its neighbour run, which moves the boundary by less than `snap` of the face's
    // width onto the face's side. A run on one side only (width 0) is the extreme case.
    const Vec3& a = in_.positions[t[0]];
    const Vec3& b = in_.positions[t[1]];
    const Vec3& c = in_.positions[t[2]];
    const double longest = std::sqrt(std::max({norm2(b - a), norm2(c - b), norm2(a - c)}));
    const double min_width = snap_ * norm(triangle_normal_area2(a, b, c)) / longest;  // snap * smallest height
    std::array<double, 2> x{};
    int band = -1;
    for (;;) {
      band = -1;
      if (changes_.size() == 2) {
        const double w0 = run_width(changes_[0], changes_[1], nullptr);
        const double w1 = run_width(changes_[1], changes_[0], nullptr);
        if (w0 <= min_width || w1 <= min_width) set_all(pts_[changes_[w0 <= w1 ? 1 : 0]].label);
        break;
      }
      if (changes_.size() < 3) break;
      band = find_band(t);
      if (band >= 0) {
        // The runs beside the band are cut off by chords: a thin one joins the band.
        const size_t b1 = static_cast<size_t>(band) + 1, b3 = (static_cast<size_t>(band) + 3) % 4;
        const double w1 = run_width(changes_[b1], changes_[(b1 + 1) % 4], nullptr);
        const double w3 = run_width(changes_[b3], changes_[(b3 + 1) % 4], nullptr);
        if (!(std::min(w1, w3) <= min_width)) break;
        const size_t r = w1 <= w3 ? b1 : b3;
        const size_t from = changes_[r], to = changes_[(r + 1) % 4];
        const int8_t label = pts_[changes_[static_cast<size_t>(band)]].label;
        for (size_t i = from; i != to; i = (i + 1) % m) pts_[i].label = label;
        find_changes();
        continue;
      }
      x = inner_point(t);
      const Vec3 xp = a * (1 - x[0] - x[1]) + b * x[0] + c * x[1];
      size_t thinnest = 0;
      double w = HUGE_VAL;
      for (size_t r = 0; r < changes_.size(); ++r) {
        const double wr = run_width(changes_[r], changes_[(r + 1) % changes_.size()], &xp);
        if (wr < w) {
          w = wr;
          thinnest = r;
        }
      }
      if (!(w <= min_width)) break;
      const size_t from = changes_[thinnest], to = changes_[(thinnest + 1) % changes_.size()];
      const int8_t label = pts_[(from + m - 1) % m].label;
      for (size_t i = from; i != to; i = (i + 1) % m) pts_[i].label = label;
      find_changes();
    }
    if (changes_.empty()) {
      polygon(0, m - 1, pts_[0].label, f, out);
      return;
    }
    ++out.split;
    if (changes_.size() == 2) {
      // Two labels meet along the segment between the change points, the zero set of d_a - d_b.
      polygon(changes_[0], changes_[1], pts_[changes_[0]].label, f, out);
      polygon(changes_[1], changes_[0], pts_[changes_[1]].label, f, out);
      return;
    }
    if (band >= 0) {
      // A band of one label crosses the face between two zero sets that do not meet inside it (the fields are
      // linear in the face, so each region is convex): two chords cut it from the runs beside it.
      const size_t r = static_cast<size_t>(band);
      auto run_label = [&](size_t k) { return pts_[changes_[k % 4]].label; };
      ring_.clear();
      append_run(changes_[r], changes_[r + 1]);
      append_run(changes_[r + 2], changes_[(r + 3) % 4]);
      triangulate_ring(run_label(r), f, out, nullptr);
      polygon(changes_[r + 1], changes_[r + 2], run_label(r + 1), f, out);
      polygon(changes_[(r + 3) % 4], changes_[r], run_label(r + 3), f, out);
      return;
    }
    // Three or more runs: the regions meet inside the face, at one inner point: where the three fields are equal
    // when there are three runs and that point is inside, else the middle of the change points. Each run's region
    // is the polygon of its boundary points and that point.
    Inner inner;
    inner.id = kInner | static_cast<uint32_t>(out.inner.size());
    inner.position = a * (1 - x[0] - x[1]) + b * x[0] + c * x[1];
    inner.u = x[0];
    inner.v = x[1];
    out.inner.push_back(inner.position);
    for (size_t r = 0; r < changes_.size(); ++r) {
      const size_t from = changes_[r], to = changes_[(r + 1) % changes_.size()];
      polygon(from, to, pts_[from].label, f, out, &inner);
    }
  }

 private:
  void collect_boundary(size_t f, const Tri& t) {
    static const double corner_uv[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    pts_.clear();
    for (size_t k = 0; k < 3; ++k) {
      const size_t e = static_cast<size_t>(edge_of_[f][k]);
      const EdgeEnvelope& env = env_[e];
      const uint32_t a = t[k], b = t[(k + 1) % 3];
      const auto& c0 = corner_uv[k];
      const auto& c1 = corner_uv[(k + 1) % 3];
      const uint8_t side = static_cast<uint8_t>(1u << k);
      const uint8_t corner_sides = static_cast<uint8_t>(side | (1u << ((k + 2) % 3)));
      auto on_side = [&](uint32_t id, double s, int8_t label) {
        pts_.push_back({id, side, label, c0[0] + s * (c1[0] - c0[0]), c0[1] + s * (c1[1] - c0[1])});
      };
      const int n = env.count;
      if (n == 0) {
        pts_.push_back({a, corner_sides, -1, c0[0], c0[1]});
      } else if (a < b) {  // the envelope runs from the lower vertex id
        pts_.push_back({a, corner_sides, env.axis[0], c0[0], c0[1]});
        for (int i = 1; i < n; ++i)
          on_side(base_[e] + static_cast<uint32_t>(i - 1), env.start[static_cast<size_t>(i)], env.axis[static_cast<size_t>(i)]);
      } else {
        pts_.push_back({a, corner_sides, env.axis[static_cast<size_t>(n - 1)], c0[0], c0[1]});
        for (int i = n - 1; i >= 1; --i)
          on_side(base_[e] + static_cast<uint32_t>(i - 1), 1 - env.start[static_cast<size_t>(i)],
                  env.axis[static_cast<size_t>(i - 1)]);
      }
    }
  }

  // Four runs whose opposite runs share a label: the first of them (0 or 1), or -1. When both pairs share a label,
  // the band is the one whose label is larger at the middle of the change points.
  int find_band(const Tri& t) const {
    if (changes_.size() != 4) return -1;
    auto run_label = [&](size_t r) { return pts_[changes_[r]].label; };
    const bool even = run_label(0) == run_label(2), odd = run_label(1) == run_label(3);
    if (!even || !odd) return even ? 0 : odd ? 1 : -1;
    double u = 0, v = 0;
    for (size_t i : changes_) {
      u += pts_[i].u / 4;
      v += pts_[i].v / 4;
    }
    auto value = [&](int8_t l) {
      const size_t k = static_cast<size_t>(l);
      return D_[t[0]][k] * (1 - u - v) + D_[t[1]][k] * u + D_[t[2]][k] * v;
    };
    return value(run_label(1)) > value(run_label(0)) ? 1 : 0;
  }

  void find_changes() {
    changes_.clear();
    const size_t m = pts_.size();
    for (size_t i = 0; i < m; ++i)
      if (pts_[i].label != pts_[(i + m - 1) % m].label) changes_.push_back(i);
  }

  // Width (2 area / diameter) of the region of the run from..to (cyclic, inclusive): the polygon of those points,
  // or with an inner point x, the fan from x. 0 when, without x, all the points lie on one side of the face.
  double run_width(size_t from, size_t to, const Vec3* x) const {
    ring_.clear();
    uint8_t common = 0x7;
    for (size_t i = from;; i = (i + 1) % pts_.size()) {
      ring_.push_back(i);
      common &= pts_[i].sides;
      if (i == to) break;
    }
    if (!x && common != 0) return 0;
    const Vec3& o = x ? *x : position(pts_[ring_[0]].id);
    double area2 = 0, diameter2 = 0;
    for (size_t i = 0; i + 1 < ring_.size(); ++i)
      area2 += norm(triangle_normal_area2(o, position(pts_[ring_[i]].id), position(pts_[ring_[i + 1]].id)));
    for (size_t i = 0; i < ring_.size(); ++i) {
      const Vec3& p = position(pts_[ring_[i]].id);
      if (x) diameter2 = std::max(diameter2, norm2(p - o));
      for (size_t j = i + 1; j < ring_.size(); ++j) diameter2 = std::max(diameter2, norm2(position(pts_[ring_[j]].id) - p));
    }
    return diameter2 > 0 ? area2 / std::sqrt(diameter2) : 0;
  }

  void set_all(int8_t label) {
    for (auto& p : pts_) p.label = label;
    changes_.clear();
  }

  const Vec3& position(uint32_t id) const { return pos_[id]; }

  // Triangulates the polygon pts[from..to] (cyclic, inclusive), closed by the segment to -> from, or with an inner
  // point x by the segments to -> x -> from, so that its worst triangle is as well shaped as possible (dynamic
  // programming over the polygon's diagonals; polygons have a few dozen points at most). The polygon without x is
  // convex; with x it is star-shaped from x, and a triangulation of it is valid exactly when all its triangles turn
  // the face's way. A triangle of three points on one side of the face is flat and never used, so every point stays
  // a vertex (no T-junction) and no triangle has zero area; that collinearity is decided from the sides the points
  // lie on, which is exact: three points of a face's boundary are collinear iff they share a side.
  void polygon(size_t from, size_t to, int8_t label, size_t f, Block& out, const Inner* x = nullptr) {
    ring_.clear();
    append_run(from, to);
    if (x) ring_.push_back(kX);
    triangulate_ring(label, f, out, x);
  }

  void append_run(size_t from, size_t to) {
    for (size_t i = from;; i = (i + 1) % pts_.size()) {
      ring_.push_back(i);
      if (i == to) break;
    }
  }

  // Triangulates ring_ (boundary points in the face's order, then possibly the inner point x).
  void triangulate_ring(int8_t label, size_t f, Block& out, const Inner* x) {
    const size_t n = ring_.size();
    if (n < 3) throw std::logic_error("relief refinement: a face polygon with fewer than three points");
    auto pos = [&](size_t e) -> const Vec3& { return e == kX ? x->position : position(pts_[e].id); };
    auto quality_of = [&](size_t i, size_t k, size_t j) {
      const size_t p = ring_[i], q = ring_[k], r = ring_[j];
      if (p == kX || q == kX || r == kX) {
        // Orientation in the face's barycentric plane, where x is strictly inside.
        auto u = [&](size_t e) { return e == kX ? x->u : pts_[e].u; };
        auto v = [&](size_t e) { return e == kX ? x->v : pts_[e].v; };
        const double turn = (u(q) - u(p)) * (v(r) - v(p)) - (u(r) - u(p)) * (v(q) - v(p));
        if (!(turn > 1e-12)) return -1.0;
      } else if (pts_[p].sides & pts_[q].sides & pts_[r].sides) {
        return -1.0;  // flat
      }
      return quality(pos(p), pos(q), pos(r));
    };
    // best_[i][j]: the best worst quality of a triangulation of the sub-polygon i..j (i < j), split_[i][j] its apex.
    best_.assign(n * n, HUGE_VAL);
    split_.assign(n * n, 0);
    for (size_t len = 2; len < n; ++len)
      for (size_t i = 0; i + len < n; ++i) {
        const size_t j = i + len;
        double best = -HUGE_VAL;
        for (size_t k = i + 1; k < j; ++k) {
          const double q = std::min({best_[i * n + k], best_[k * n + j], quality_of(i, k, j)});
          if (q > best) {
            best = q;
            split_[i * n + j] = k;
          }
        }
        best_[i * n + j] = best;
      }
    if (!(best_[n - 1] > 0)) throw std::logic_error("relief refinement: a face polygon has no triangulation");
    auto id = [&](size_t e) { return e == kX ? x->id : pts_[e].id; };
    stack_.assign(1, {0, n - 1});
    while (!stack_.empty()) {
      const auto [i, j] = stack_.back();
      stack_.pop_back();
      if (j - i < 2) continue;
      const size_t k = split_[i * n + j];
      emit(out, {id(ring_[i]), id(ring_[k]), id(ring_[j])}, label, f);
      stack_.push_back({i, k});
      stack_.push_back({k, j});
    }
  }

  std::array<double, 2> inner_point(const Tri& t) const {
    if (changes_.size() == 3) {
      // d_l(u, v) = D0 + u (D1 - D0) + v (D2 - D0); solve d_a = d_b = d_c.
      auto coef = [&](int8_t l) {
        const size_t k = static_cast<size_t>(l);
        const double d0 = D_[t[0]][k];
        return std::array<double, 3>{d0, D_[t[1]][k] - d0, D_[t[2]][k] - d0};
      };
      const auto A = coef(pts_[changes_[0]].label), B = coef(pts_[changes_[1]].label), C = coef(pts_[changes_[2]].label);
      const double a11 = A[1] - B[1], a12 = A[2] - B[2], r1 = B[0] - A[0];
      const double a21 = A[1] - C[1], a22 = A[2] - C[2], r2 = C[0] - A[0];
      const double det = a11 * a22 - a12 * a21;
      if (det != 0) {
        const double u = (r1 * a22 - a12 * r2) / det, v = (a11 * r2 - r1 * a21) / det;
        if (u >= margin_ && v >= margin_ && 1 - u - v >= margin_) return {u, v};
      }
    }
    double u = 0, v = 0;
    for (size_t i : changes_) {
      u += pts_[i].u;
      v += pts_[i].v;
    }
    u /= static_cast<double>(changes_.size());
    v /= static_cast<double>(changes_.size());
    // Pull it towards the centroid until every barycentric coordinate is at least the margin.
    const double b[3] = {1 - u - v, u, v};
    double s = 1;
    for (double bi : b)
      if (bi < margin_) s = std::min(s, (1.0 / 3 - margin_) / (1.0 / 3 - bi));
    return {1.0 / 3 + s * (u - 1.0 / 3), 1.0 / 3 + s * (v - 1.0 / 3)};
  }

  static void emit(Block& out, const Tri& t, int8_t label, size_t f) {
    out.tris.push_back(t);
    out.axis.push_back(label);
    out.source.push_back(static_cast<int32_t>(f));
  }

  const Mesh& in_;
  const std::vector<Vec3>& pos_;
  const std::vector<AxisValues>& D_;
  const EnvelopeTable& env_;
  const std::vector<uint32_t>& base_;
  const std::vector<std::array<int32_t, 3>>& edge_of_;
  const std::vector<int8_t>& closest_;
  std::vector<BoundaryPoint> pts_;
  double snap_, margin_;
  std::vector<size_t> changes_;
  mutable std::vector<size_t> ring_;
  std::vector<double> best_;
  std::vector<size_t> split_;
  std::vector<std::pair<size_t, size_t>> stack_;
};

}  // namespace

Refinement refine_along_relief_boundaries(const Mesh& mesh, const std::vector<std::array<int32_t, 3>>& adjacency,
                                          const std::vector<AxisValues>& fields, const std::vector<int8_t>& closest,
                                          double snap, bool parallel) {
  const size_t nv = mesh.positions.size(), nf = mesh.triangles.size();
  // Edge ids: an edge is numbered by the first face that meets it.
  std::vector<std::array<int32_t, 3>> edge_of(nf, {-1, -1, -1});
  std::vector<std::array<uint32_t, 2>> edges;  // (lower, higher) vertex id
  edges.reserve(3 * nf / 2 + 3);
  for (size_t f = 0; f < nf; ++f) {
    const Tri& t = mesh.triangles[f];
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t a = t[k], b = t[(k + 1) % 3];
      const int32_t g = adjacency[f][k];
      if (g >= 0 && static_cast<size_t>(g) < f) {
        const Tri& s = mesh.triangles[static_cast<size_t>(g)];
        for (size_t m = 0; m < 3; ++m)
          if ((s[m] == a && s[(m + 1) % 3] == b) || (s[m] == b && s[(m + 1) % 3] == a))
            edge_of[f][k] = edge_of[static_cast<size_t>(g)][m];
      }
      if (edge_of[f][k] < 0) {
        edge_of[f][k] = static_cast<int32_t>(edges.size());
        edges.push_back({std::min(a, b), std::max(a, b)});
      }
    }
  }

  // The envelope of every edge; its breakpoints become vertices numbered after the input's.
  const EnvelopeTable env(fields, edges, snap, parallel);
  std::vector<uint32_t> split_base(edges.size());
  uint32_t next = static_cast<uint32_t>(nv);
  for (size_t e = 0; e < edges.size(); ++e) {
    split_base[e] = next;
    next += static_cast<uint32_t>(std::max(env[e].count - 1, 0));
  }
  Refinement out;
  out.mesh.positions.resize(next);
  std::copy(mesh.positions.begin(), mesh.positions.end(), out.mesh.positions.begin());
  for (size_t e = 0; e < edges.size(); ++e)
    for (int i = 1; i < env[e].count; ++i)
      out.mesh.positions[split_base[e] + static_cast<uint32_t>(i - 1)] =
          lerp(mesh.positions[edges[e][0]], mesh.positions[edges[e][1]], env[e].start[static_cast<size_t>(i)]);

  // Faces in blocks (in parallel), joined in face order so that the result does not depend on the threads.
  const size_t nblocks = (nf + kBlockFaces - 1) / kBlockFaces;
  std::vector<Block> blocks(nblocks);
  auto run = [&](size_t b) {
    FaceSplitter splitter(mesh, out.mesh.positions, fields, env, split_base, edge_of, closest, snap);
    Block& blk = blocks[b];
    blk.tris.reserve(kBlockFaces + kBlockFaces / 4);
    for (size_t f = b * kBlockFaces; f < std::min(nf, (b + 1) * kBlockFaces); ++f) splitter.split(f, blk);
  };
  if (parallel) {
    tbb::parallel_for(size_t{0}, nblocks, run);
  } else {
    for (size_t b = 0; b < nblocks; ++b) run(b);
  }
  size_t ntris = 0;
  for (const Block& b : blocks) ntris += b.tris.size();
  out.mesh.triangles.reserve(ntris);
  out.axis.reserve(ntris);
  out.source_face.reserve(ntris);
  for (Block& b : blocks) {
    const uint32_t inner_base = static_cast<uint32_t>(out.mesh.positions.size());
    out.mesh.positions.insert(out.mesh.positions.end(), b.inner.begin(), b.inner.end());
    for (Tri t : b.tris) {
      for (uint32_t& v : t)
        if (v & kInner) v = inner_base + (v & ~kInner);
      out.mesh.triangles.push_back(t);
    }
    out.axis.insert(out.axis.end(), b.axis.begin(), b.axis.end());
    out.source_face.insert(out.source_face.end(), b.source.begin(), b.source.end());
    out.split_faces += b.split;
    out.inner_points += b.inner.size();
  }
  return out;
}

}  // namespace prm::remesh
