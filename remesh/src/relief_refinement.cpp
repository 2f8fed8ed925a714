#include "relief_refinement.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "prm/vec3.h"
#include "relief_envelope.h"

namespace prm::remesh {

namespace {

constexpr uint32_t kInner = 0x80000000u;  // marks a block-local inner point id until the blocks are joined
constexpr double kInnerMargin = 0.02;      // smallest barycentric coordinate of an inner point
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

class FaceSplitter {
 public:
  FaceSplitter(const Mesh& input, const std::vector<Vec3>& positions, const std::vector<AxisValues>& fields,
               const std::vector<EdgeEnvelope>& envelopes, const std::vector<uint32_t>& split_base,
               const std::vector<std::array<int32_t, 3>>& edge_of, const std::vector<int8_t>& closest)
      : in_(input), pos_(positions), D_(fields), env_(envelopes), base_(split_base), edge_of_(edge_of),
        closest_(closest) {}

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
    changes_.clear();
    for (size_t i = 0; i < m; ++i)
      if (pts_[i].label != pts_[(i + m - 1) % m].label) changes_.push_back(i);
    if (changes_.size() == 2) {
      // Two labels meet along the segment between the change points, the zero set of d_a - d_b. A run whose points
      // all lie on one side has no area in this face (snapping can leave one): the face takes the other label.
      if (flat_run(changes_[0], changes_[1])) set_all(pts_[changes_[1]].label);
      else if (flat_run(changes_[1], changes_[0])) set_all(pts_[changes_[0]].label);
    }
    if (changes_.empty()) {
      if (m == 3) emit(out, t, pts_[0].label, f);
      else polygon(0, m - 1, pts_[0].label, f, out);  // split points of neighbours on its sides: fan them in
      return;
    }
    ++out.split;
    if (changes_.size() == 2) {
      polygon(changes_[0], changes_[1], pts_[changes_[0]].label, f, out);
      polygon(changes_[1], changes_[0], pts_[changes_[1]].label, f, out);
      return;
    }
    // Three or more runs: the regions meet inside the face. Fan every run from one inner point: where the three
    // fields are equal when there are three runs and that point is inside, else the middle of the change points.
    const std::array<double, 2> x = inner_point(t);
    const uint32_t xid = kInner | static_cast<uint32_t>(out.inner.size());
    out.inner.push_back(in_.positions[t[0]] * (1 - x[0] - x[1]) + in_.positions[t[1]] * x[0] +
                        in_.positions[t[2]] * x[1]);
    for (size_t i = 0; i < m; ++i) emit(out, {xid, pts_[i].id, pts_[(i + 1) % m].id}, pts_[i].label, f);
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

  // The points from..to (cyclic, inclusive) all lie on one side of the face.
  bool flat_run(size_t from, size_t to) const {
    uint8_t common = 0x7;
    for (size_t i = from;; i = (i + 1) % pts_.size()) {
      common &= pts_[i].sides;
      if (i == to) break;
    }
    return common != 0;
  }

  void set_all(int8_t label) {
    for (auto& p : pts_) p.label = label;
    changes_.clear();
  }

  const Vec3& position(uint32_t id) const { return pos_[id]; }

  // Triangulates the convex polygon pts[from..to] (cyclic, inclusive; closed by the segment to -> from) by clipping
  // the best-shaped ear among the corners that turn; a corner between two points of its own side never does, so
  // every point stays a vertex (no T-junction) and no triangle is flat. Collinearity is decided from the sides the
  // points lie on, which is exact: three points of a face's boundary are collinear iff they share a side.
  void polygon(size_t from, size_t to, int8_t label, size_t f, Block& out) {
    ring_.clear();
    for (size_t i = from;; i = (i + 1) % pts_.size()) {
      ring_.push_back(i);
      if (i == to) break;
    }
    auto flat = [&](size_t a, size_t b, size_t c) { return (pts_[a].sides & pts_[b].sides & pts_[c].sides) != 0; };
    while (ring_.size() > 3) {
      const size_t n = ring_.size();
      size_t best = n;
      double best_q = -1;
      for (size_t i = 0; i < n; ++i) {
        const size_t p = ring_[(i + n - 1) % n], c = ring_[i], q = ring_[(i + 1) % n];
        if (flat(p, c, q)) continue;
        bool rest_has_area = false;  // what is left after clipping c must not be flat
        for (size_t j = 0; j < n && !rest_has_area; ++j) {
          if (j == i) continue;
          const size_t pj = (j + n - 1) % n == i ? (j + n - 2) % n : (j + n - 1) % n;
          const size_t nj = (j + 1) % n == i ? (j + 2) % n : (j + 1) % n;
          rest_has_area = !flat(ring_[pj], ring_[j], ring_[nj]);
        }
        if (!rest_has_area) continue;
        const double qual = quality(position(pts_[p].id), position(pts_[c].id), position(pts_[q].id));
        if (qual > best_q) {
          best_q = qual;
          best = i;
        }
      }
      if (best == n) throw std::logic_error("relief refinement: a face polygon has no ear");
      emit(out, {pts_[ring_[(best + n - 1) % n]].id, pts_[ring_[best]].id, pts_[ring_[(best + 1) % n]].id}, label, f);
      ring_.erase(ring_.begin() + static_cast<std::ptrdiff_t>(best));
    }
    if (ring_.size() == 3 && !flat(ring_[0], ring_[1], ring_[2]))
      emit(out, {pts_[ring_[0]].id, pts_[ring_[1]].id, pts_[ring_[2]].id}, label, f);
    else if (ring_.size() == 3)
      throw std::logic_error("relief refinement: a flat face polygon");
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
        if (u >= kInnerMargin && v >= kInnerMargin && 1 - u - v >= kInnerMargin) return {u, v};
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
      if (bi < kInnerMargin) s = std::min(s, (1.0 / 3 - kInnerMargin) / (1.0 / 3 - bi));
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
  const std::vector<EdgeEnvelope>& env_;
  const std::vector<uint32_t>& base_;
  const std::vector<std::array<int32_t, 3>>& edge_of_;
  const std::vector<int8_t>& closest_;
  std::vector<BoundaryPoint> pts_;
  std::vector<size_t> changes_, ring_;
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

  // The envelope of every edge, once; its breakpoints become vertices numbered after the input's.
  std::vector<EdgeEnvelope> env(edges.size());
  auto envelopes = [&](size_t lo, size_t hi) {
    for (size_t e = lo; e < hi; ++e) env[e] = upper_envelope(fields[edges[e][0]], fields[edges[e][1]], snap);
  };
  if (parallel) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, edges.size(), 4096),
                      [&](const tbb::blocked_range<size_t>& r) { envelopes(r.begin(), r.end()); });
  } else {
    envelopes(0, edges.size());
  }
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
    FaceSplitter splitter(mesh, out.mesh.positions, fields, env, split_base, edge_of, closest);
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
