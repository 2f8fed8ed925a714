#include "quantized_separation.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "prm/vec3.h"

namespace prm::remesh {
namespace {

using Q3 = std::array<int64_t, 3>;

struct Q3Hash {
  size_t operator()(const Q3& q) const {
    uint64_t h = 1469598103934665603ull;
    for (int64_t x : q) h = (h ^ static_cast<uint64_t>(x)) * 1099511628211ull;
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

Q3 minus(const Q3& a, const Q3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
// Coordinates are below 2^20, so the components stay below 2^42 and the dot products of two normals below 2^86.
Q3 cross(const Q3& a, const Q3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
bool is_zero(const Q3& n) { return n[0] == 0 && n[1] == 0 && n[2] == 0; }
__int128 dot(const Q3& a, const Q3& b) {
  return static_cast<__int128>(a[0]) * b[0] + static_cast<__int128>(a[1]) * b[1] + static_cast<__int128>(a[2]) * b[2];
}

}  // namespace

QuantizedSeparationStats separate_quantized_vertices(PrmMesh& prm, const Mesh* input, const AabbTree* tree) {
  QuantizedSeparationStats st;
  Mesh& m = prm.mesh;
  const QuantFrame& frame = prm.frame;
  const size_t nv = m.positions.size(), nf = m.triangles.size();
  const int64_t top = (int64_t{1} << frame.bits) - 1;
  std::vector<Q3> q(nv);
  for (size_t v = 0; v < nv; ++v)
    for (int a = 0; a < 3; ++a) q[v][static_cast<size_t>(a)] = frame.quantize(m.positions[v][static_cast<size_t>(a)], a);
  std::unordered_map<Q3, uint32_t, Q3Hash> at;  // vertices at each quantization point
  at.reserve(nv);
  for (size_t v = 0; v < nv; ++v) ++at[q[v]];

  auto normal = [&](size_t f) {
    const Tri& t = m.triangles[f];
    return cross(minus(q[t[1]], q[t[0]]), minus(q[t[2]], q[t[0]]));
  };
  std::vector<uint32_t> first(nv + 1, 0), faces_of(3 * nf);  // faces around each vertex
  for (const Tri& t : m.triangles)
    for (uint32_t v : t) ++first[v + 1];
  for (size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
  {
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (size_t f = 0; f < nf; ++f)
      for (uint32_t v : m.triangles[f]) faces_of[fill[v]++] = static_cast<uint32_t>(f);
  }
  for (size_t f = 0; f < nf; ++f) st.degenerate_faces += is_zero(normal(f));
  for (size_t v = 0; v < nv; ++v) st.coincident_vertices += at[q[v]] > 1;
  if (st.degenerate_faces == 0 && st.coincident_vertices == 0) return st;

  // The orientation a face must keep: its quantized normal, or where that is zero, its normal before quantization
  // (strict), or none (not strict: a sliver thinner than a step, say on the frame's boundary where the side it
  // faced has no quantization point, may come out either way; a thin triangle is better than none). Either way, with
  // the input at hand, a moved face never faces away from the input's surface next to it.
  bool strict = true, use_input = true;
  auto reference = [&](size_t f) {
    const Tri& t = m.triangles[f];
    return strict ? triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]) : Vec3{0, 0, 0};
  };
  auto height_axis_of = [&](size_t v) {
    const int32_t r = prm.vertex_relief[v];
    return r < 0 ? -1 : pair_height(axis_pair(prm.relief_axis[static_cast<size_t>(r)]));
  };
  // Where v is when moved to quantization point p: a lattice vertex only along its height axis.
  auto real_position = [&](size_t v, const Q3& p) {
    const int h = height_axis_of(v);
    Vec3 x = m.positions[v];
    for (int a = 0; a < 3; ++a)
      if (h < 0 || a == h) x[static_cast<size_t>(a)] = frame.to_real(static_cast<double>(p[static_cast<size_t>(a)]), a);
    return x;
  };
  // Moving v to p: -1 if not allowed (p is outside the frame or taken, or a face around v that has an area loses it
  // or turns over), otherwise how many faces around v that had none get one. Several vertices can share a point (a
  // triangle of three): then the first move makes no face whole and is progress all the same.
  auto faces_fixed = [&](size_t v, const Q3& p) {
    for (int a = 0; a < 3; ++a)
      if (p[static_cast<size_t>(a)] < 0 || p[static_cast<size_t>(a)] > top) return -1;
    if (at.count(p)) return -1;
    const Vec3 moved = real_position(v, p);
    int fixed = 0;
    for (uint32_t k = first[v]; k < first[v + 1]; ++k) {
      const size_t f = faces_of[k];
      const Tri& t = m.triangles[f];
      // The mesh the remesher returns (real coordinates) never turns a face over either.
      Vec3 r[3];
      for (int i = 0; i < 3; ++i) r[i] = t[static_cast<size_t>(i)] == v ? moved : m.positions[t[static_cast<size_t>(i)]];
      const Vec3 nr = triangle_normal_area2(r[0], r[1], r[2]);
      if (strict && prm::dot(nr, reference(f)) <= 0) return -1;
      if (use_input && input && tree) {
        const auto hit = tree->closest((r[0] + r[1] + r[2]) * (1.0 / 3.0));
        const Tri& s = input->triangles[hit.face];
        if (prm::dot(nr, triangle_normal_area2(input->positions[s[0]], input->positions[s[1]], input->positions[s[2]])) <= 0)
          return -1;
      }
      Q3 c[3];
      for (int i = 0; i < 3; ++i) c[i] = t[static_cast<size_t>(i)] == v ? p : q[t[static_cast<size_t>(i)]];
      const Q3 n = cross(minus(c[1], c[0]), minus(c[2], c[0]));
      const Q3 old = normal(f);
      if (!is_zero(old)) {
        if (is_zero(n) || dot(n, old) <= 0) return -1;
      } else if (!is_zero(n)) {
        const Vec3 r = reference(f);
        if (n[0] * r[0] + n[1] * r[1] + n[2] * r[2] < 0) return -1;
        ++fixed;
      }
    }
    return fixed;
  };
  // The point within `radius` steps that makes most faces around v whole, nearest first (from where v was before
  // rounding); found only if it is progress: a face made whole, or v no longer sharing its point.
  struct Move {
    bool found = false;
    int fixed = 0;
    double cost = 0;
    Q3 to{};
  };
  auto best_move_within = [&](size_t v, int64_t radius) {
    const int h = height_axis_of(v);
    Vec3 u;
    for (int a = 0; a < 3; ++a) u[static_cast<size_t>(a)] = frame.to_quant(m.positions[v][static_cast<size_t>(a)], a);
    std::vector<std::pair<double, Q3>> candidates;
    for (int64_t dx = -radius; dx <= radius; ++dx)
      for (int64_t dy = -radius; dy <= radius; ++dy)
        for (int64_t dz = -radius; dz <= radius; ++dz) {
          const Q3 d{dx, dy, dz};
          if (is_zero(d)) continue;
          // A lattice vertex keeps its place on the lattice: it moves along its relief's height axis only.
          if (h >= 0 && (d[static_cast<size_t>((h + 1) % 3)] != 0 || d[static_cast<size_t>((h + 2) % 3)] != 0)) continue;
          const Q3 p{q[v][0] + dx, q[v][1] + dy, q[v][2] + dz};
          double d2 = 0;
          for (size_t a = 0; a < 3; ++a) d2 += (static_cast<double>(p[a]) - u[a]) * (static_cast<double>(p[a]) - u[a]);
          candidates.push_back({d2, p});
        }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    const bool shared = at[q[v]] > 1;
    Move best;
    for (const auto& c : candidates) {
      const int fixed = faces_fixed(v, c.second);
      if (fixed < 0 || (fixed == 0 && !shared) || (best.found && fixed <= best.fixed)) continue;
      best = Move{true, fixed, c.first, c.second};
    }
    return best;
  };
  // Two steps, or where nothing within two helps, three (a crowded spot: several vertices in a few steps).
  auto best_move = [&](size_t v) {
    const Move near = best_move_within(v, 2);
    return near.found ? near : best_move_within(v, 3);
  };
  std::vector<uint32_t> loose;  // vertices the last pass moved
  auto apply = [&](size_t v, const Q3& to) {
    if (--at[q[v]] == 0) at.erase(q[v]);
    q[v] = to;
    ++at[q[v]];
    m.positions[v] = real_position(v, to);
    ++st.moved;
    if (!use_input) loose.push_back(static_cast<uint32_t>(v));
  };

  // Zero-area faces: move the corner that makes most faces whole, one off the lattices if any can (they are free in
  // all three axes, and a lattice vertex's height is a coded residual), the least; rounds until none moves, first
  // keeping orientations, then not; a moved face is first also held to the input's side (a two-sided sheet, which
  // repair makes of an open triangle, has no side: the last pass lets that go).
  for (int pass = 0; pass < 3; ++pass, strict = false, use_input = pass < 2)
    for (int round = 0; round < 8; ++round) {
      bool moved = false;
      for (size_t f = 0; f < nf; ++f) {
        if (!is_zero(normal(f))) continue;
        size_t chosen = nv;
        Move move;
        bool chosen_lattice = true;
        for (uint32_t v : m.triangles[f]) {
          const Move mv = best_move(v);
          const bool lattice = prm.vertex_relief[v] >= 0;
          if (!mv.found) continue;
          const bool better = chosen == nv || mv.fixed > move.fixed ||
                              (mv.fixed == move.fixed && ((chosen_lattice && !lattice) ||
                                                          (chosen_lattice == lattice && mv.cost < move.cost)));
          if (better) {
            chosen = v;
            move = mv;
            chosen_lattice = lattice;
          }
        }
        if (chosen < nv) {
          apply(chosen, move.to);
          moved = true;
        }
      }
      if (!moved) break;
    }
  // Vertices still sharing a position with another (not corners of one face): move all but one.
  for (size_t v = 0; v < nv; ++v)
    if (at[q[v]] > 1) {
      const Move mv = best_move(v);
      if (mv.found) apply(v, mv.to);
    }

  // The last pass's price, counted: faces around the vertices it moved that face away from the input.
  if (input && tree) {
    std::vector<uint32_t> around;
    for (uint32_t v : loose)
      for (uint32_t k = first[v]; k < first[v + 1]; ++k) around.push_back(faces_of[k]);
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    for (uint32_t f : around) {
      const Tri& t = m.triangles[f];
      const Vec3 nr = triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
      const auto hit = tree->closest((m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) * (1.0 / 3.0));
      const Tri& s = input->triangles[hit.face];
      st.turned += prm::dot(nr, triangle_normal_area2(input->positions[s[0]], input->positions[s[1]],
                                                      input->positions[s[2]])) <= 0;
    }
  }
  for (size_t f = 0; f < nf; ++f) st.unresolved += is_zero(normal(f));
  for (size_t v = 0; v < nv; ++v) st.unresolved += at[q[v]] > 1;
  return st;
}

}  // namespace prm::remesh
