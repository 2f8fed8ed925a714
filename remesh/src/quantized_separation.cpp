#include "quantized_separation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <optional>
#include <unordered_map>
#include <vector>

#include "prm/remesh/boundary_polyline.h"
#include "prm/surface_facing.h"
#include "prm/vec3.h"

namespace prm::remesh {
namespace {

// Issue 22: a mesh-boundary vertex is coded at the point within this many steps per coordinate of its rounding that is
// nearest the input's boundary polyline, and the polyline is searched this far around a point (in steps).
constexpr int64_t kBoundaryRoundingRadius = 2;
constexpr double kBoundaryReachSteps = 8;

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

// Drops the vertices and faces that collapses removed, with their labels and properties.
void remove_collapsed(PrmMesh& prm, const std::vector<uint8_t>& dead_vertex, const std::vector<uint8_t>& dead_face) {
  Mesh& m = prm.mesh;
  std::vector<uint32_t> index(dead_vertex.size(), 0);
  uint32_t next = 0;
  for (size_t v = 0; v < dead_vertex.size(); ++v) index[v] = dead_vertex[v] ? 0 : next++;
  auto keep = [](auto& values, const std::vector<uint8_t>& dead) {
    size_t n = 0;
    for (size_t k = 0; k < dead.size(); ++k)
      if (!dead[k]) values[n++] = values[k];
    values.resize(n);
  };
  keep(m.positions, dead_vertex);
  keep(prm.vertex_relief, dead_vertex);
  keep(prm.lattice_i, dead_vertex);
  keep(prm.lattice_j, dead_vertex);
  for (Property& p : m.vertex_properties) keep(p.values, dead_vertex);
  for (Tri& t : m.triangles)
    for (uint32_t& c : t) c = index[c];
  keep(m.triangles, dead_face);
  keep(prm.face_relief, dead_face);
  keep(prm.face_regular, dead_face);
  for (Property& p : m.face_properties) keep(p.values, dead_face);
}

}  // namespace

QuantizedSeparationStats separate_quantized_vertices(PrmMesh& prm, const Mesh* input, const AabbTree* tree,
                                                     double move_bound, const std::vector<uint32_t>* centroid_faces) {
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
  auto real_normal = [&](size_t f) {
    const Tri& t = m.triangles[f];
    return triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  };
  auto against = [](const Q3& n, const Vec3& r) { return n[0] * r[0] + n[1] * r[1] + n[2] * r[2] <= 0; };

  // Issue 22, an open input: the vertices on the mesh boundary (the input's boundary vertices and the grid's
  // crossings of its boundary edges, which the remesher never moves) are coded at the quantization point nearest the
  // input's boundary polyline, not the nearest one: rounding alone puts them up to half a step per coordinate off it.
  // The decoder is unaffected (it is the encoder's choice of quantized value). The passes below move them only when
  // no other corner of a broken face can move, and then to the free point nearest the polyline.
  std::optional<BoundaryPolyline> polyline;
  std::vector<uint8_t> on_boundary(nv, 0);
  if (input) {
    polyline.emplace(*input, kBoundaryReachSteps * frame.step);
    if (polyline->empty())
      polyline.reset();
    else
      on_boundary = boundary_vertex_flags(m);
  }
  auto real_point = [&](const Q3& p) {
    Vec3 x;
    for (int a = 0; a < 3; ++a) x[static_cast<size_t>(a)] = frame.to_real(static_cast<double>(p[static_cast<size_t>(a)]), a);
    return x;
  };
  auto polyline_steps = [&](const Q3& p) { return polyline->distance(real_point(p)) / frame.step; };
  if (polyline) {
    std::vector<std::vector<uint32_t>> faces_of(nv);
    for (size_t f = 0; f < nf; ++f)
      for (uint32_t v : m.triangles[f])
        if (on_boundary[v]) faces_of[v].push_back(static_cast<uint32_t>(f));
    for (size_t v = 0; v < nv; ++v) {
      if (!on_boundary[v] || prm.vertex_relief[v] >= 0) continue;
      Vec3 u;
      for (int a = 0; a < 3; ++a) u[static_cast<size_t>(a)] = frame.to_quant(m.positions[v][static_cast<size_t>(a)], a);
      // A candidate keeps every face around v with an area and on its side (its quantized normal within 90 degrees
      // of its normal before).
      auto keeps_faces = [&](const Q3& p) {
        for (uint32_t f : faces_of[v]) {
          const Tri& t = m.triangles[f];
          Q3 c[3];
          for (int i = 0; i < 3; ++i) c[i] = t[static_cast<size_t>(i)] == v ? p : q[t[static_cast<size_t>(i)]];
          const Q3 n = cross(minus(c[1], c[0]), minus(c[2], c[0]));
          if (is_zero(n) || against(n, real_normal(f))) return false;
        }
        return true;
      };
      Q3 best = q[v];
      double best_d = polyline_steps(q[v]), best_d2 = HUGE_VAL;
      const int64_t r = kBoundaryRoundingRadius;
      for (int64_t dx = -r; dx <= r; ++dx)
        for (int64_t dy = -r; dy <= r; ++dy)
          for (int64_t dz = -r; dz <= r; ++dz) {
            const Q3 p{q[v][0] + dx, q[v][1] + dy, q[v][2] + dz};
            if (is_zero({dx, dy, dz}) || std::min({p[0], p[1], p[2]}) < 0 || std::max({p[0], p[1], p[2]}) > top ||
                at.count(p))
              continue;
            const double d = polyline_steps(p);
            double d2 = 0;
            for (size_t a = 0; a < 3; ++a) d2 += (static_cast<double>(p[a]) - u[a]) * (static_cast<double>(p[a]) - u[a]);
            if (d > best_d || (d == best_d && d2 >= best_d2) || !keeps_faces(p)) continue;
            best = p;
            best_d = d;
            best_d2 = d2;
          }
      if (best == q[v]) continue;
      if (--at[q[v]] == 0) at.erase(q[v]);
      q[v] = best;
      ++at[q[v]];
      m.positions[v] = real_point(best);
      ++st.boundary_rounded;
    }
  }
  bool use_input = true;  // false in the last pass, which lets the input's side go
  // With the input: the normals of the input's faces nearest the centroid of face f as the remesher placed it and as
  // quantized (where the decoder puts it; the orientation test of the remesher's invariants, as bench's stream check
  // applies it to the decoded stream), computed when first needed and again after a corner moves.
  std::vector<std::array<Vec3, 2>> input_normal(input && tree ? nf : 0);
  std::vector<uint8_t> input_normal_known(input_normal.size(), 0);
  auto input_normal_of = [&](uint32_t face) {
    const Tri& s = input->triangles[face];
    return triangle_normal_area2(input->positions[s[0]], input->positions[s[1]], input->positions[s[2]]);
  };
  auto input_normal_near = [&](const Vec3& x) { return input_normal_of(tree->closest(x).face); };
  // The faces nearest the centroids as given, while no corner has moved (the first pass, unless the boundary's
  // rounding above moved one).
  const std::vector<uint32_t>* known_nearest =
      centroid_faces && centroid_faces->size() == nf && st.boundary_rounded == 0 ? centroid_faces : nullptr;
  auto dequantized_centroid = [&](const Q3 c[3]) {
    Vec3 x{0, 0, 0};
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 3; ++a)
        x[static_cast<size_t>(a)] += frame.to_real(static_cast<double>(c[i][static_cast<size_t>(a)]), a) / 3.0;
    return x;
  };
  auto input_normals_of = [&](size_t f) -> const std::array<Vec3, 2>& {
    if (!input_normal_known[f]) {
      const Tri& t = m.triangles[f];
      const Q3 c[3] = {q[t[0]], q[t[1]], q[t[2]]};
      const uint32_t known = known_nearest ? (*known_nearest)[f] : AabbTree::kNoFace;
      const Vec3 centroid = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) * (1.0 / 3.0);
      input_normal[f] = {known != AabbTree::kNoFace ? input_normal_of(known) : input_normal_near(centroid),
                         input_normal_near(dequantized_centroid(c))};
      input_normal_known[f] = 1;
    }
    return input_normal[f];
  };
  // A face that faced the input's side as remeshed and whose quantized normal is 90 degrees or more from the input's
  // where the decoder puts it: turned away from the input by the rounding (a rim sliver of a thin part, its normal
  // rounded square to the input's, or a sliver the rounding moved over a crease) while within 90 degrees of its own
  // normal. A face the remesher left facing away (the twin sheets of a two-sided part) is not the rounding's doing.
  auto turned_from_input = [&](size_t f, const Q3& n) {
    if (input_normal.empty() || is_zero(n)) return false;
    const std::array<Vec3, 2>& in = input_normals_of(f);
    return prm::dot(real_normal(f), in[0]) > 0 && against(n, in[1]);
  };
  // What the stream would not hold as remeshed: a face of zero area once quantized, or one that the rounding turns
  // over (a sliver whose quantized normal points against its normal before, or away from the input's side).
  auto turned_by_rounding = [&](size_t f) {
    const Q3 n = normal(f);
    return !is_zero(n) && (against(n, real_normal(f)) || (use_input && turned_from_input(f, n)));
  };
  auto broken = [&](size_t f) { return is_zero(normal(f)) || turned_by_rounding(f); };
  for (size_t f = 0; f < nf; ++f) {
    st.degenerate_faces += is_zero(normal(f));
    st.rounding_turned += turned_by_rounding(f);
  }
  known_nearest = nullptr;
  for (size_t v = 0; v < nv; ++v) st.coincident_vertices += at[q[v]] > 1;
  if (st.degenerate_faces == 0 && st.rounding_turned == 0 && st.coincident_vertices == 0) return st;
  std::vector<std::vector<uint32_t>> around(nv);  // faces around each vertex (collapses change them)
  for (size_t f = 0; f < nf; ++f)
    for (uint32_t v : m.triangles[f]) around[v].push_back(static_cast<uint32_t>(f));
  std::vector<uint8_t> dead_face(nf, 0), dead_vertex(nv, 0);  // removed by collapses
  auto shares_point = [&](size_t v) { return !dead_vertex[v] && at[q[v]] > 1; };

  // The orientation a face must keep: its quantized normal, or where that is zero, its normal before quantization
  // (strict), or none (not strict: a sliver thinner than a step, say on the frame's boundary where the side it
  // faced has no quantization point, may come out either way; a thin triangle is better than none). Either way, with
  // the input at hand, a moved face never faces away from the input's surface next to it.
  bool strict = true;
  bool boundary_moves = true;  // false: a vertex on the mesh boundary does not move
  auto reference = [&](size_t f) { return strict ? real_normal(f) : Vec3{0, 0, 0}; };
  // Does a face with corners r (real coordinates) and normal nr face the input's side: the orientation test of the
  // remesher's invariants, against the input's normal at the point nearest its centroid.
  auto faces_input_side = [&](const Vec3 r[3], const Vec3& nr) {
    return faces_surface(nr, (r[0] + r[1] + r[2]) * (1.0 / 3.0), *input, *tree);
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
  // or turns over), otherwise how many faces around v that had none get one, or that the rounding had turned over
  // are turned back. Several vertices can share a point (a
  // triangle of three): then the first move makes no face whole and is progress all the same.
  auto faces_fixed = [&](size_t v, const Q3& p) {
    for (int a = 0; a < 3; ++a)
      if (p[static_cast<size_t>(a)] < 0 || p[static_cast<size_t>(a)] > top) return -1;
    if (at.count(p)) return -1;
    const Vec3 moved = real_position(v, p);
    // move_bound (--local-refinement): not farther from the input than the bound, unless v already is (hknife: venus's
    // 178-degree knife edge, where three lattice vertices and a seam vertex round to one point and the seam vertex
    // went three steps off the fin, 2.10e-3 of the diagonal; an edge collapse or another corner's move mends it).
    if (move_bound > 0 && use_input && input && tree) {
      const double d2 = tree->closest(moved).distance2;
      if (d2 > move_bound * move_bound && d2 > tree->closest(m.positions[v]).distance2) return -1;
    }
    int fixed = 0;
    for (uint32_t f : around[v]) {
      const Tri& t = m.triangles[f];
      // The mesh the remesher returns (real coordinates) never turns a face over either.
      Vec3 r[3];
      for (int i = 0; i < 3; ++i) r[i] = t[static_cast<size_t>(i)] == v ? moved : m.positions[t[static_cast<size_t>(i)]];
      const Vec3 nr = triangle_normal_area2(r[0], r[1], r[2]);
      if (strict && prm::dot(nr, reference(f)) <= 0) return -1;
      if (use_input && input && tree && !faces_input_side(r, nr)) return -1;
      Q3 c[3];
      for (int i = 0; i < 3; ++i) c[i] = t[static_cast<size_t>(i)] == v ? p : q[t[static_cast<size_t>(i)]];
      const Q3 n = cross(minus(c[1], c[0]), minus(c[2], c[0]));
      const Q3 old = normal(f);
      // With the input, the moved face as quantized must face the input's side where it moves to.
      const bool away = use_input && !input_normal.empty() && !is_zero(n) &&
                        against(n, input_normal_near(dequantized_centroid(c)));
      if (turned_by_rounding(f)) {
        if (is_zero(n)) return -1;
        fixed += !against(n, real_normal(f)) && !away;
      } else if (!is_zero(old)) {
        if (is_zero(n) || dot(n, old) <= 0 || away) return -1;
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
          // A boundary vertex: nearest the input's boundary polyline first (then nearest where it was).
          if (polyline && on_boundary[v]) {
            const double d = polyline_steps(p);
            d2 = d * d + 1e-6 * d2;
          }
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
  auto apply = [&](size_t v, const Q3& to) {
    if (--at[q[v]] == 0) at.erase(q[v]);
    q[v] = to;
    ++at[q[v]];
    m.positions[v] = real_position(v, to);
    for (uint32_t f : around[v])
      if (!input_normal_known.empty()) input_normal_known[f] = 0;
    ++st.moved;
  };

  // Zero-area faces, and faces the rounding turned over: move the corner that makes most faces whole, one off the lattices if any can (they are free in
  // all three axes, and a lattice vertex's height is a coded residual), the least; rounds until none moves.
  auto move_zero_area_corners = [&] {
    for (int round = 0; round < 8; ++round) {
      bool moved = false;
      for (size_t f = 0; f < nf; ++f) {
        if (dead_face[f] || !broken(f)) continue;
        size_t chosen = nv;
        Move move;
        bool chosen_lattice = true, chosen_boundary = true;
        for (uint32_t v : m.triangles[f]) {
          if (on_boundary[v] && !boundary_moves) continue;
          const Move mv = best_move(v);
          const bool lattice = prm.vertex_relief[v] >= 0, boundary = on_boundary[v] != 0;
          if (!mv.found) continue;
          // A vertex off the mesh boundary first (issue 22: the boundary stays where the input's is).
          const bool better =
              chosen == nv || (chosen_boundary && !boundary) ||
              (chosen_boundary == boundary &&
               (mv.fixed > move.fixed || (mv.fixed == move.fixed && ((chosen_lattice && !lattice) ||
                                                                     (chosen_lattice == lattice && mv.cost < move.cost)))));
          if (better) {
            chosen = v;
            move = mv;
            chosen_lattice = lattice;
            chosen_boundary = boundary;
          }
        }
        if (chosen < nv) {
          apply(chosen, move.to);
          moved = true;
        }
      }
      if (!moved) break;
    }
  };
  // Vertices still sharing a position with another (not corners of one face): move all but one.
  // Those off the mesh boundary first.
  auto separate_coincident = [&] {
    for (bool boundary : {false, true})
      for (size_t v = 0; v < nv && (boundary_moves || !boundary); ++v)
        if (shares_point(v) && (on_boundary[v] != 0) == boundary) {
          const Move mv = best_move(v);
          if (mv.found) apply(v, mv.to);
        }
  };

  // Collapsing the edge (keep, gone) when its ends share a point and neither can move: gone's faces take keep (which
  // stays where it is, less than a step away), and the edge's two faces, of zero area, go. Allowed when it keeps a
  // closed manifold (the ends' only common neighbours are the edge's two opposite corners) and every face that takes
  // keep has a quantized area and keeps its side (its real and quantized normals against its real normal before,
  // and with the input, the input's side).
  auto can_collapse = [&](uint32_t keep, uint32_t gone) {
    if (on_boundary[gone]) return false;  // the mesh boundary stays (and an interior edge of two boundary vertices
                                          // would pinch)
    std::vector<uint32_t> opposite, ring_keep, ring_gone;
    for (uint32_t f : around[gone])
      for (uint32_t c : m.triangles[f]) {
        if (c != gone && c != keep) ring_gone.push_back(c);
        if (c == keep)
          for (uint32_t o : m.triangles[f])
            if (o != keep && o != gone) opposite.push_back(o);
      }
    if (opposite.size() != 2 || opposite[0] == opposite[1]) return false;
    for (uint32_t f : around[keep])
      for (uint32_t c : m.triangles[f])
        if (c != keep && c != gone) ring_keep.push_back(c);
    for (auto* ring : {&ring_keep, &ring_gone}) {
      std::sort(ring->begin(), ring->end());
      ring->erase(std::unique(ring->begin(), ring->end()), ring->end());
    }
    std::vector<uint32_t> common;
    std::set_intersection(ring_keep.begin(), ring_keep.end(), ring_gone.begin(), ring_gone.end(),
                          std::back_inserter(common));
    if (common.size() != 2) return false;  // the link condition (both opposite corners are common neighbours)
    for (uint32_t f : around[gone]) {
      Tri t = m.triangles[f];
      if (std::find(t.begin(), t.end(), keep) != t.end()) continue;
      for (uint32_t& c : t)
        if (c == gone) c = keep;
      const Vec3 r[3] = {m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]};
      const Vec3 nr = triangle_normal_area2(r[0], r[1], r[2]), before = real_normal(f);
      const Q3 n = cross(minus(q[t[1]], q[t[0]]), minus(q[t[2]], q[t[0]]));
      if (is_zero(n) || prm::dot(nr, before) <= 0 || against(n, before)) return false;
      if (input && tree && !faces_input_side(r, nr)) return false;
    }
    return true;
  };
  auto collapse = [&](uint32_t keep, uint32_t gone) {
    for (uint32_t f : around[gone]) {
      Tri& t = m.triangles[f];
      if (std::find(t.begin(), t.end(), keep) != t.end()) {
        dead_face[f] = 1;
        for (uint32_t c : t)
          if (c != gone) around[c].erase(std::find(around[c].begin(), around[c].end(), f));
        continue;
      }
      for (uint32_t& c : t)
        if (c == gone) c = keep;
      around[keep].push_back(f);
      label_face(prm, f);
      if (!input_normal_known.empty()) input_normal_known[f] = 0;
    }
    around[gone].clear();
    dead_vertex[gone] = 1;
    if (--at[q[gone]] == 0) at.erase(q[gone]);
    ++st.collapsed;
  };
  // Each pair of neighbours that still share a point, by collapsing their edge (the vertex off the lattices goes, if
  // one is: a lattice vertex's place makes triangles regular).
  auto collapse_inseparable = [&] {
    for (uint32_t v = 0; v < nv; ++v) {
      if (!shares_point(v)) continue;
      for (size_t k = 0; k < around[v].size() && shares_point(v); ++k)
        for (uint32_t u : m.triangles[around[v][k]]) {
          if (u == v || q[u] != q[v]) continue;
          const bool v_goes = on_boundary[v] != on_boundary[u] ? on_boundary[u] != 0 : prm.vertex_relief[v] < 0;
          const uint32_t gone_first = v_goes ? v : u, keep_first = v_goes ? u : v;
          if (can_collapse(keep_first, gone_first))
            collapse(keep_first, gone_first);
          else if (can_collapse(gone_first, keep_first))
            collapse(gone_first, keep_first);
          else
            continue;
          break;
        }
    }
  };

  // A face still of zero area or turned by the rounding that no move mends (a sliver on the frame's boundary, where
  // the side it should face has no quantization point: the 1 x 1 x 0.002 box at 10 and 11 bits, issue 17): one of
  // its edges collapsed, shortest first, the free end going, if that keeps every face on its side (can_collapse);
  // the sliver and its neighbour across the edge go.
  auto collapse_broken = [&] {
    for (size_t f = 0; f < nf; ++f) {
      if (dead_face[f] || !broken(f)) continue;
      const Tri t = m.triangles[f];
      std::array<std::pair<int64_t, std::array<uint32_t, 2>>, 3> edges;
      for (size_t i = 0; i < 3; ++i) {
        const Q3 d = minus(q[t[(i + 1) % 3]], q[t[i]]);
        edges[i] = {d[0] * d[0] + d[1] * d[1] + d[2] * d[2], {t[i], t[(i + 1) % 3]}};
      }
      std::sort(edges.begin(), edges.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (const auto& e : edges) {
        const uint32_t a = e.second[0], b = e.second[1];
        const bool a_goes = on_boundary[a] != on_boundary[b] ? on_boundary[b] != 0 : prm.vertex_relief[a] < 0;
        const uint32_t gone = a_goes ? a : b, keep = a_goes ? b : a;
        if (can_collapse(keep, gone)) {
          collapse(keep, gone);
          break;
        }
        if (can_collapse(gone, keep)) {
          collapse(gone, keep);
          break;
        }
      }
    }
  };

  // First keeping each face's side (strictly, then not), then collapsing neighbours that cannot be told apart, then
  // an edge of each face still broken; a last pass lets the input's side go, for a two-sided sheet (which repair
  // makes of an open triangle, and which has no side) and whatever is left.
  auto moves_then_collapses = [&] {
    strict = true;
    move_zero_area_corners();
    strict = false;
    move_zero_area_corners();
    for (bool s : {true, false}) {
      strict = s;
      separate_coincident();
    }
    collapse_inseparable();
    collapse_broken();
  };
  if (polyline) {
    // An open surface: first everything that leaves the mesh boundary where it is (moves of other vertices, then
    // collapses of an edge whose end off the boundary goes: a lattice vertex next to a straight boundary, which may
    // only move along its height, rounds onto the boundary's line), then the same passes again, which may move it.
    boundary_moves = false;
    moves_then_collapses();
    boundary_moves = true;
  }
  moves_then_collapses();
  use_input = false;
  move_zero_area_corners();
  separate_coincident();

  // The last pass's price, counted: faces that faced the input as remeshed and face away from it as quantized.
  for (size_t f = 0; f < nf; ++f) st.turned += !dead_face[f] && turned_from_input(f, normal(f));
  for (size_t f = 0; f < nf; ++f) st.unresolved += !dead_face[f] && broken(f);
  for (size_t v = 0; v < nv; ++v) st.unresolved += shares_point(v);
  if (st.collapsed > 0) remove_collapsed(prm, dead_vertex, dead_face);
  return st;
}

}  // namespace prm::remesh
