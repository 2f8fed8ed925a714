#include "relief_slicing.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "prm/vec3.h"

namespace prm::remesh {

int64_t segment_of(int family, const std::array<double, 3>& F) {
  // alpha = c and alpha + beta = c lines are walked along beta; beta = c lines along alpha.
  return static_cast<int64_t>(std::floor(family == 1 ? F[0] : F[1]));
}

namespace {

struct UnionFind {
  std::vector<int32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int32_t find(int32_t x) {
    while (parent[static_cast<size_t>(x)] != x) {
      parent[static_cast<size_t>(x)] = parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
      x = parent[static_cast<size_t>(x)];
    }
    return x;
  }
  void unite(int32_t a, int32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
  }
};

// The lattice point on lines (f1 = c1) and (f2 = c2), f1 != f2.
std::array<int64_t, 2> lattice_of(int f1, int64_t c1, int f2, int64_t c2) {
  if (f1 > f2) {
    std::swap(f1, f2);
    std::swap(c1, c2);
  }
  if (f1 == 0 && f2 == 1) return {c1, c2};
  if (f1 == 0 && f2 == 2) return {c1, c2 - c1};
  return {c2 - c1, c1};  // f1 == 1, f2 == 2
}

struct LatticeSlot {
  int64_t i, j;
  int32_t vertex;
};

}  // namespace

SlicedRelief slice_relief(const ReliefMeshView& view, const std::vector<int32_t>& faces, int axis) {
  const int pair = axis_pair(axis);
  const int hu = pair_u(pair), hw = pair_w(pair), hh = pair_height(pair);
  const Mesh& mesh = *view.mesh;
  const int32_t relief = view.relief(faces.empty() ? 0 : faces[0]);
  const int slot = faces.empty() ? 0 : view.slot(relief);  // its lattice's grid lines (spec §8.4.2: its own grid)
  const size_t n = faces.size();

  std::unordered_map<int32_t, int32_t> local_of;
  local_of.reserve(n * 2);
  for (size_t li = 0; li < n; ++li) local_of.emplace(faces[li], static_cast<int32_t>(li));
  auto in_relief = [&](int32_t g) { return g >= 0 && view.relief(g) == relief; };
  auto tri = [&](size_t li) -> const Tri& { return mesh.triangles[static_cast<size_t>(faces[li])]; };

  // 1. Corner classes: corners of one vertex joined through relief-interior edges (splits pinched vertices).
  UnionFind uf(3 * n);
  std::vector<uint8_t> boundary_edge(3 * n, 0);
  for (size_t li = 0; li < n; ++li) {
    const int32_t f = faces[li];
    for (int k = 0; k < 3; ++k) {
      const int32_t g = view.opposite[static_cast<size_t>(f)][static_cast<size_t>(k)];
      if (!in_relief(g)) {
        boundary_edge[3 * li + static_cast<size_t>(k)] = 1;
        continue;
      }
      const size_t lg = static_cast<size_t>(local_of.at(g));
      const uint32_t a = tri(li)[static_cast<size_t>(k)], b = tri(li)[static_cast<size_t>((k + 1) % 3)];
      for (int m = 0; m < 3; ++m) {
        const uint32_t v = tri(lg)[static_cast<size_t>(m)];
        if (v == a) uf.unite(static_cast<int32_t>(3 * li) + k, static_cast<int32_t>(3 * lg) + m);
        if (v == b) uf.unite(static_cast<int32_t>(3 * li) + (k + 1) % 3, static_cast<int32_t>(3 * lg) + m);
      }
    }
  }
  SlicedRelief out;
  std::vector<int32_t> corner_vertex(3 * n, -1);
  for (size_t c = 0; c < 3 * n; ++c) {
    const int32_t root = uf.find(static_cast<int32_t>(c));
    if (corner_vertex[static_cast<size_t>(root)] < 0) {
      const size_t li = static_cast<size_t>(root) / 3;
      const uint32_t v = tri(li)[static_cast<size_t>(root) % 3];
      SliceVertex sv;
      sv.kind = SliceKind::Corner;
      sv.F = view.F(slot, static_cast<int32_t>(v));
      sv.i = static_cast<int64_t>(std::floor(sv.F[0]));
      sv.j = static_cast<int64_t>(std::floor(sv.F[1]));
      sv.upper = sv.F[2] > static_cast<double>(sv.i + sv.j + 1);
      sv.position = mesh.positions[v];
      sv.refined_vertex = static_cast<int32_t>(v);
      sv.source_face = view.source(faces[li]);
      corner_vertex[static_cast<size_t>(root)] = static_cast<int32_t>(out.vertices.size());
      out.vertices.push_back(sv);
    }
    corner_vertex[c] = corner_vertex[static_cast<size_t>(root)];
  }
  for (size_t li = 0; li < n; ++li)
    for (size_t k = 0; k < 3; ++k)
      if (boundary_edge[3 * li + k]) {
        out.vertices[static_cast<size_t>(corner_vertex[3 * li + k])].boundary = true;
        out.vertices[static_cast<size_t>(corner_vertex[3 * li + (k + 1) % 3])].boundary = true;
      }

  // 2. Crossings of every edge with the three families of grid lines, ordered from the lower refined vertex: edge
  // e's are crossings[crossing_begin[e] .. crossing_begin[e + 1]) (one array for all, not one allocation an edge).
  std::vector<int32_t> crossings;
  std::vector<size_t> crossing_begin{0};
  std::vector<int32_t> edge_list(3 * n, -1);
  for (size_t li = 0; li < n; ++li) {
    const int32_t f = faces[li];
    for (size_t k = 0; k < 3; ++k) {
      if (edge_list[3 * li + k] >= 0) continue;
      const uint32_t va = tri(li)[k], vb = tri(li)[(k + 1) % 3];
      const int32_t a = static_cast<int32_t>(std::min(va, vb)), b = static_cast<int32_t>(std::max(va, vb));
      const auto& Fa = view.F(slot, a);
      const auto& Fb = view.F(slot, b);
      const Vec3& Pa = view.position(a);
      const Vec3& Pb = view.position(b);
      for (int fam = 0; fam < 3; ++fam) {
        const double lo = std::min(Fa[static_cast<size_t>(fam)], Fb[static_cast<size_t>(fam)]);
        const double hi = std::max(Fa[static_cast<size_t>(fam)], Fb[static_cast<size_t>(fam)]);
        for (double c = std::ceil(lo); c < hi; c += 1.0) {
          const double t = (c - Fa[static_cast<size_t>(fam)]) / (Fb[static_cast<size_t>(fam)] - Fa[static_cast<size_t>(fam)]);
          SliceVertex sv;
          sv.kind = SliceKind::Crossing;
          sv.boundary = boundary_edge[3 * li + k] != 0;
          sv.family = static_cast<uint8_t>(fam);
          sv.value = static_cast<int64_t>(c);
          for (size_t g = 0; g < 3; ++g) sv.F[g] = Fa[g] + t * (Fb[g] - Fa[g]);
          sv.F[static_cast<size_t>(fam)] = c;
          sv.segment = segment_of(fam, sv.F);
          sv.position = lerp(Pa, Pb, t);
          sv.edge_a = a;
          sv.edge_b = b;
          sv.t = t;
          sv.source_face = view.source(f);
          crossings.push_back(static_cast<int32_t>(out.vertices.size()));
          out.vertices.push_back(sv);
        }
      }
      std::sort(crossings.begin() + static_cast<std::ptrdiff_t>(crossing_begin.back()), crossings.end(),
                [&](int32_t x, int32_t y) {
                  return out.vertices[static_cast<size_t>(x)].t < out.vertices[static_cast<size_t>(y)].t;
                });
      const int32_t id = static_cast<int32_t>(crossing_begin.size() - 1);
      crossing_begin.push_back(crossings.size());
      edge_list[3 * li + k] = id;
      const int32_t g = view.opposite[static_cast<size_t>(f)][k];
      if (in_relief(g)) {
        const size_t lg = static_cast<size_t>(local_of.at(g));
        for (size_t m = 0; m < 3; ++m) {
          const uint32_t x = tri(lg)[m], y = tri(lg)[(m + 1) % 3];
          if ((x == va && y == vb) || (x == vb && y == va)) edge_list[3 * lg + m] = id;
        }
      }
    }
  }

  // 3 and 4, per face: lattice points inside, then the pieces cut by the grid lines, fanned into triangles.
  std::vector<LatticeSlot> slots;
  std::vector<std::vector<int32_t>> polys, next;
  std::vector<int32_t> boundary;  // per face, reused
  std::vector<std::pair<int64_t, double>> alpha_hits;
  for (size_t li = 0; li < n; ++li) {
    const Tri& t = tri(li);
    std::array<int32_t, 3> cv;
    for (size_t k = 0; k < 3; ++k) cv[k] = corner_vertex[3 * li + k];
    // The boundary polygon in the face's orientation.
    boundary.clear();
    for (size_t k = 0; k < 3; ++k) {
      boundary.push_back(cv[k]);
      const size_t e = static_cast<size_t>(edge_list[3 * li + k]);
      const auto first = crossings.begin() + static_cast<std::ptrdiff_t>(crossing_begin[e]);
      const auto last = crossings.begin() + static_cast<std::ptrdiff_t>(crossing_begin[e + 1]);
      if (t[k] < t[(k + 1) % 3])
        boundary.insert(boundary.end(), first, last);
      else
        boundary.insert(boundary.end(), std::make_reverse_iterator(last), std::make_reverse_iterator(first));
    }
    // Lattice points: along each alpha = i line, between its two crossings with the face's edges.
    slots.clear();
    alpha_hits.clear();
    for (int32_t v : boundary) {
      const SliceVertex& sv = out.vertices[static_cast<size_t>(v)];
      if (sv.kind == SliceKind::Crossing && sv.family == 0) alpha_hits.push_back({sv.value, sv.F[1]});
    }
    std::sort(alpha_hits.begin(), alpha_hits.end());
    const auto F0 = out.vertices[static_cast<size_t>(cv[0])].F;  // copies: out.vertices grows below
    const auto F1 = out.vertices[static_cast<size_t>(cv[1])].F;
    const auto F2 = out.vertices[static_cast<size_t>(cv[2])].F;
    const double det = (F1[0] - F0[0]) * (F2[1] - F0[1]) - (F2[0] - F0[0]) * (F1[1] - F0[1]);
    for (size_t h = 0; h + 1 < alpha_hits.size(); h += 2) {
      if (alpha_hits[h].first != alpha_hits[h + 1].first)
        throw std::logic_error("slice_relief: a grid line crosses a triangle an odd number of times");
      const int64_t i = alpha_hits[h].first;
      const double b1 = std::min(alpha_hits[h].second, alpha_hits[h + 1].second);
      const double b2 = std::max(alpha_hits[h].second, alpha_hits[h + 1].second);
      for (double jd = std::ceil(b1); jd < b2; jd += 1.0) {
        const int64_t j = static_cast<int64_t>(jd);
        SliceVertex sv;
        sv.kind = SliceKind::Lattice;
        sv.i = i;
        sv.j = j;
        sv.F = {static_cast<double>(i), static_cast<double>(j), static_cast<double>(i + j)};
        // Barycentric coordinates in the lattice plane (an affine image of the base plane).
        const double x = static_cast<double>(i), y = static_cast<double>(j);
        const double l1 = ((x - F0[0]) * (F2[1] - F0[1]) - (F2[0] - F0[0]) * (y - F0[1])) / det;
        const double l2 = ((F1[0] - F0[0]) * (y - F0[1]) - (x - F0[0]) * (F1[1] - F0[1])) / det;
        const double l0 = 1.0 - l1 - l2;
        const auto base = view.lattice(relief).to_base(i, j);
        sv.position[static_cast<size_t>(hu)] = view.frame.to_real(static_cast<double>(base[0]), hu);
        sv.position[static_cast<size_t>(hw)] = view.frame.to_real(static_cast<double>(base[1]), hw);
        sv.position[static_cast<size_t>(hh)] = l0 * mesh.positions[t[0]][static_cast<size_t>(hh)] +
                                               l1 * mesh.positions[t[1]][static_cast<size_t>(hh)] +
                                               l2 * mesh.positions[t[2]][static_cast<size_t>(hh)];
        sv.source_face = view.source(faces[li]);
        slots.push_back({i, j, static_cast<int32_t>(out.vertices.size())});
        out.vertices.push_back(sv);
      }
    }
    auto find_slot = [&](int64_t i, int64_t j) {
      for (const LatticeSlot& s : slots)
        if (s.i == i && s.j == j) return s.vertex;
      throw std::logic_error("slice_relief: a grid-line intersection inside a triangle has no lattice vertex");
    };
    // Cut by every grid line crossing the face; all intersection points already exist as vertices.
    polys.assign(1, boundary);
    for (int fam = 0; fam < 3; ++fam) {
      const size_t fs = static_cast<size_t>(fam);
      const double lo = std::min({F0[fs], F1[fs], F2[fs]}), hi = std::max({F0[fs], F1[fs], F2[fs]});
      for (double c = std::ceil(lo); c < hi; c += 1.0) {
        next.clear();
        for (auto& poly : polys) {
          bool pos = false, neg = false;
          for (int32_t v : poly) {
            const double d = out.vertices[static_cast<size_t>(v)].F[fs] - c;
            pos |= d > 0;
            neg |= d < 0;
          }
          if (!pos || !neg) {
            next.push_back(std::move(poly));
            continue;
          }
          std::vector<int32_t> above, below;
          const size_t m = poly.size();
          for (size_t q = 0; q < m; ++q) {
            const SliceVertex& x = out.vertices[static_cast<size_t>(poly[q])];
            const SliceVertex& y = out.vertices[static_cast<size_t>(poly[(q + 1) % m])];
            const double dx = x.F[fs] - c, dy = y.F[fs] - c;
            if (dx >= 0) above.push_back(poly[q]);
            if (dx <= 0) below.push_back(poly[q]);
            if ((dx > 0 && dy < 0) || (dx < 0 && dy > 0)) {
              // The side runs along an earlier grid line (f2 = c2): the crossing point is a lattice vertex.
              int f2 = -1;
              for (int g = 0; g < fam; ++g)
                if (x.F[static_cast<size_t>(g)] == y.F[static_cast<size_t>(g)] &&
                    x.F[static_cast<size_t>(g)] == std::nearbyint(x.F[static_cast<size_t>(g)]))
                  f2 = g;
              if (f2 < 0) throw std::logic_error("slice_relief: inconsistent crossing order on a triangle edge");
              const auto ij = lattice_of(fam, static_cast<int64_t>(c), f2,
                                         static_cast<int64_t>(x.F[static_cast<size_t>(f2)]));
              const int32_t lv = find_slot(ij[0], ij[1]);
              above.push_back(lv);
              below.push_back(lv);
            }
          }
          next.push_back(std::move(above));
          next.push_back(std::move(below));
        }
        std::swap(polys, next);
      }
    }
    for (const auto& poly : polys) {
      if (poly.size() < 3) throw std::logic_error("slice_relief: a piece with fewer than three corners");
      for (size_t q = 1; q + 1 < poly.size(); ++q) out.faces.push_back({poly[0], poly[q], poly[q + 1]});
    }
  }
  // Grown by doubling: the spare capacity would stay through the relief's resampling.
  out.vertices.shrink_to_fit();
  out.faces.shrink_to_fit();
  return out;
}

}  // namespace prm::remesh
