// Paper §2.1: relief construction. Distance fields (geodesic_distance.cpp), the upper envelope of the six fields
// along every edge, the split of the faces a relief boundary crosses, and the connected components.
#include "prm/remesh/reliefs.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "geodesic_distance.h"
#include "prm/error.h"
#include "prm/remesh/lattice.h"
#include "prm/vec3.h"
#include "relief_mesh.h"

namespace prm::remesh {

std::array<uint8_t, 3> relief_colour(int axis, int id) {
  // One hue per axis (opposite axes get related hues), lightness varied per component.
  static const double base[6][3] = {{0.90, 0.30, 0.25}, {0.95, 0.65, 0.20}, {0.30, 0.75, 0.30},
                                    {0.55, 0.85, 0.35}, {0.25, 0.45, 0.90}, {0.55, 0.40, 0.85}};
  const double shade = 0.75 + 0.25 * static_cast<double>((static_cast<unsigned>(id) * 2654435761u) % 1000) / 1000.0;
  std::array<uint8_t, 3> c{};
  for (size_t k = 0; k < 3; ++k)
    c[k] = static_cast<uint8_t>(std::clamp(255.0 * base[static_cast<size_t>(axis) % 6][k] * shade, 0.0, 255.0));
  return c;
}

namespace {

constexpr int kAxes = 6;
constexpr double kSnap = 0.02;  // a boundary crossing closer than this (fraction of the edge) moves to the end

// One piece of an edge's envelope: label `label` from parameter t on (to the next piece).
struct Piece {
  double t;
  int label;
};

using Values = std::array<double, kAxes>;

// The upper envelope of six linear functions along an edge, from a (t = 0) to b (t = 1); ties go to the larger
// slope, then to the lower axis. Pieces shorter than kSnap are removed (their neighbours meet in the middle).
std::vector<Piece> envelope(const Values& a, const Values& b) {
  std::vector<Piece> p;
  int cur = 0;
  for (int k = 1; k < kAxes; ++k) {
    const double dv = a[static_cast<size_t>(k)] - a[static_cast<size_t>(cur)];
    const double ds = (b[static_cast<size_t>(k)] - a[static_cast<size_t>(k)]) -
                      (b[static_cast<size_t>(cur)] - a[static_cast<size_t>(cur)]);
    if (dv > 0 || (dv == 0 && ds > 0)) cur = k;
  }
  double t = 0;
  p.push_back({0, cur});
  for (int guard = 0; guard < kAxes; ++guard) {
    const double sc = b[static_cast<size_t>(cur)] - a[static_cast<size_t>(cur)];
    double best_t = 2;
    int best = -1;
    for (int k = 0; k < kAxes; ++k) {
      if (k == cur) continue;
      const double sk = b[static_cast<size_t>(k)] - a[static_cast<size_t>(k)];
      if (sk <= sc) continue;
      const double tk = (a[static_cast<size_t>(cur)] - a[static_cast<size_t>(k)]) / (sk - sc);
      if (tk >= t && (tk < best_t || (tk == best_t && sk > b[static_cast<size_t>(best)] - a[static_cast<size_t>(best)]))) {
        best_t = tk;
        best = k;
      }
    }
    if (best < 0 || best_t >= 1) break;
    t = best_t;
    cur = best;
    if (p.back().t == t) p.back().label = cur;  // two crossings at one point
    else p.push_back({t, cur});
  }
  // Two crossings at one point can leave equal neighbours: merge them.
  for (size_t i = 1; i < p.size();)
    if (p[i].label == p[i - 1].label) p.erase(p.begin() + static_cast<std::ptrdiff_t>(i));
    else ++i;
  // Snap: drop pieces shorter than kSnap.
  for (bool changed = true; changed && p.size() > 1;) {
    changed = false;
    for (size_t i = 0; i < p.size(); ++i) {
      const double end = i + 1 < p.size() ? p[i + 1].t : 1.0;
      if (end - p[i].t >= kSnap) continue;
      if (i == 0) {
        p.erase(p.begin());
        p[0].t = 0;
      } else if (i + 1 == p.size()) {
        p.pop_back();
      } else {
        const double mid = 0.5 * (p[i].t + end);
        p.erase(p.begin() + static_cast<std::ptrdiff_t>(i));
        p[i].t = mid;
        if (p[i].label == p[i - 1].label) p.erase(p.begin() + static_cast<std::ptrdiff_t>(i));
      }
      changed = true;
      break;
    }
  }
  return p;
}

// Triangulates a convex polygon (2D coordinates; collinear points allowed on its sides) by clipping strictly
// convex corners whose removal leaves a polygon with area, so that no triangle has zero area and every point on a
// side stays a vertex (no T-junction with the neighbouring face).
void triangulate_convex(const std::vector<uint32_t>& ids, const std::vector<std::array<double, 2>>& uv,
                        std::vector<Tri>& out) {
  // Areas are in the face's barycentric plane (O(1)); below this, three points are collinear up to rounding.
  constexpr double kMinUvArea = 1e-9;
  std::vector<size_t> ring(ids.size());
  std::iota(ring.begin(), ring.end(), 0);
  auto cross2 = [&](size_t a, size_t b, size_t c) {
    return (uv[b][0] - uv[a][0]) * (uv[c][1] - uv[a][1]) - (uv[c][0] - uv[a][0]) * (uv[b][1] - uv[a][1]);
  };
  while (ring.size() > 3) {
    size_t best = SIZE_MAX;
    double best_area = kMinUvArea;
    const size_t n = ring.size();
    for (size_t i = 0; i < n; ++i) {
      const double area = cross2(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
      if (area <= best_area) continue;
      // The rest must keep some area: some consecutive triple of it turns.
      bool rest_has_area = false;
      for (size_t j = 0; j < n && !rest_has_area; ++j) {
        if (j == i) continue;
        const size_t pj = (j + n - 1) % n == i ? (j + n - 2) % n : (j + n - 1) % n;
        const size_t nj = (j + 1) % n == i ? (j + 2) % n : (j + 1) % n;
        rest_has_area = cross2(ring[pj], ring[j], ring[nj]) > kMinUvArea;
      }
      if (!rest_has_area) continue;
      best_area = area;
      best = i;
    }
    if (best == SIZE_MAX) break;  // all collinear: nothing with area left
    const size_t a = ring[(best + ring.size() - 1) % ring.size()], b = ring[best], c = ring[(best + 1) % ring.size()];
    out.push_back({ids[a], ids[b], ids[c]});
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(best));
  }
  if (ring.size() == 3 && cross2(ring[0], ring[1], ring[2]) > kMinUvArea)
    out.push_back({ids[ring[0]], ids[ring[1]], ids[ring[2]]});
}

}  // namespace

ReliefLayout build_reliefs(const Mesh& mesh, const ReliefOptions& options) {
  if (!(options.tau > 0) || !(options.tau < 1.0 / std::sqrt(3.0)))
    throw InputError("tau must be in (0, 1/sqrt(3)) = (0, 0.5773...), got " + std::to_string(options.tau));
  const size_t nv = mesh.positions.size(), nf = mesh.triangles.size();
  if (nf == 0) throw InputError("the mesh has no faces");
  const auto adjacency = face_adjacency(mesh);  // throws on non-manifold edges

  std::vector<Vec3> normal(nf);
  std::vector<int> closest_axis(nf);
  for (size_t f = 0; f < nf; ++f) {
    const Tri& t = mesh.triangles[f];
    normal[f] = normalized(triangle_normal_area2(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]));
    int best = 0;
    for (int a = 1; a < kAxes; ++a)
      if (dot(normal[f], axis_vector(a)) > dot(normal[f], axis_vector(best))) best = a;
    closest_axis[f] = best;
  }

  ReliefLayout out;
  std::vector<int> label;  // per refined face: axis
  if (options.naive) {
    out.mesh.positions = mesh.positions;
    out.mesh.triangles = mesh.triangles;
    label = closest_axis;
    out.source_face.resize(nf);
    std::iota(out.source_face.begin(), out.source_face.end(), 0);
  } else {
    // Distance fields d_v from A_v = {f : n_f . v < tau}; unreachable vertices get a huge finite value.
    const VertexStar star = vertex_star(mesh);
    std::vector<Values> D(nv);
    double diag = 0;
    {
      Vec3 lo = mesh.positions[0], hi = lo;
      for (const Vec3& p : mesh.positions)
        for (size_t k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], p[k]);
          hi[k] = std::max(hi[k], p[k]);
        }
      diag = norm(hi - lo);
    }
    const double far = 1e6 * (diag > 0 ? diag : 1.0);
    auto field = [&](size_t a) {
      std::vector<uint8_t> src(nf);
      for (size_t f = 0; f < nf; ++f) src[f] = dot(normal[f], axis_vector(static_cast<int>(a))) < options.tau;
      const std::vector<double> d = geodesic_distance(mesh, star, src, options.geodesic);
      for (size_t v = 0; v < nv; ++v) D[v][a] = std::min(d[v], far);
    };
    if (options.parallel) tbb::parallel_for(size_t{0}, size_t{kAxes}, field);
    else for (size_t a = 0; a < kAxes; ++a) field(a);

    // Envelope breakpoints, once per edge (from the lower vertex), as new vertices.
    out.mesh.positions = mesh.positions;
    struct EdgeSplit {
      std::vector<Piece> pieces;     // from the lower vertex
      std::vector<uint32_t> points;  // vertex ids of pieces[1..]
      bool zero = false;             // the envelope is 0 along the whole edge
    };
    std::vector<std::array<int32_t, 3>> edge_of(nf, {-1, -1, -1});
    std::vector<EdgeSplit> edges;
    edges.reserve(3 * nf / 2 + 1);
    for (size_t f = 0; f < nf; ++f)
      for (size_t k = 0; k < 3; ++k) {
        if (edge_of[f][k] >= 0) continue;
        const uint32_t a = std::min(mesh.triangles[f][k], mesh.triangles[f][(k + 1) % 3]);
        const uint32_t b = std::max(mesh.triangles[f][k], mesh.triangles[f][(k + 1) % 3]);
        EdgeSplit e;
        e.zero = *std::max_element(D[a].begin(), D[a].end()) == 0 && *std::max_element(D[b].begin(), D[b].end()) == 0;
        if (!e.zero) {
          e.pieces = envelope(D[a], D[b]);
          for (size_t i = 1; i < e.pieces.size(); ++i) {
            e.points.push_back(static_cast<uint32_t>(out.mesh.positions.size()));
            out.mesh.positions.push_back(lerp(mesh.positions[a], mesh.positions[b], e.pieces[i].t));
          }
        }
        const int32_t id = static_cast<int32_t>(edges.size());
        edges.push_back(std::move(e));
        edge_of[f][k] = id;
        const int32_t g = adjacency[f][k];
        if (g >= 0)
          for (size_t m = 0; m < 3; ++m)
            if (std::min(mesh.triangles[static_cast<size_t>(g)][m], mesh.triangles[static_cast<size_t>(g)][(m + 1) % 3]) == a &&
                std::max(mesh.triangles[static_cast<size_t>(g)][m], mesh.triangles[static_cast<size_t>(g)][(m + 1) % 3]) == b)
              edge_of[static_cast<size_t>(g)][m] = id;
      }

    // Per face: the cyclic boundary (corners and crossings, each with the label of the piece that follows) split
    // into one polygon per label run.
    std::vector<uint32_t> pts;
    std::vector<int> labs;
    std::vector<std::array<double, 2>> uv;
    for (size_t f = 0; f < nf; ++f) {
      const Tri& t = mesh.triangles[f];
      pts.clear();
      labs.clear();
      uv.clear();
      bool all_zero = true;
      static const double corner_uv[3][2] = {{0, 0}, {1, 0}, {0, 1}};
      for (size_t k = 0; k < 3; ++k) {
        const EdgeSplit& e = edges[static_cast<size_t>(edge_of[f][k])];
        const bool forward = t[k] < t[(k + 1) % 3];
        const auto& c0 = corner_uv[k];
        const auto& c1 = corner_uv[(k + 1) % 3];
        pts.push_back(t[k]);
        uv.push_back({c0[0], c0[1]});
        if (e.zero) {
          labs.push_back(-1);
          continue;
        }
        all_zero = false;
        const size_t n = e.pieces.size();
        if (forward) {
          labs.push_back(e.pieces[0].label);
          for (size_t i = 1; i < n; ++i) {
            pts.push_back(e.points[i - 1]);
            labs.push_back(e.pieces[i].label);
            const double s = e.pieces[i].t;
            uv.push_back({c0[0] + s * (c1[0] - c0[0]), c0[1] + s * (c1[1] - c0[1])});
          }
        } else {
          labs.push_back(e.pieces[n - 1].label);
          for (size_t i = n - 1; i >= 1; --i) {
            pts.push_back(e.points[i - 1]);
            labs.push_back(e.pieces[i - 1].label);
            const double s = 1.0 - e.pieces[i].t;
            uv.push_back({c0[0] + s * (c1[0] - c0[0]), c0[1] + s * (c1[1] - c0[1])});
          }
        }
      }
      if (all_zero) {
        out.mesh.triangles.push_back(t);
        label.push_back(closest_axis[f]);
        out.source_face.push_back(static_cast<int32_t>(f));
        continue;
      }
      // Pieces of zero edges take the label of the piece before them.
      const size_t m = pts.size();
      for (size_t pass = 0; pass < 2; ++pass)
        for (size_t i = 0; i < m; ++i)
          if (labs[i] < 0) labs[i] = labs[(i + m - 1) % m];
      // A run of one piece between a corner and its neighbour on the same edge has no area on this face: drop it.
      std::vector<size_t> change;
      for (size_t i = 0; i < m; ++i)
        if (labs[i] != labs[(i + m - 1) % m]) change.push_back(i);
      if (change.size() == 2 && (change[1] == change[0] + 1 || (change[0] == 0 && change[1] == m - 1))) {
        // The odd run is the single piece between two consecutive points: it lies on the edge, the face is one label.
        const size_t odd = change[1] == change[0] + 1 ? change[0] : m - 1;
        labs[odd] = labs[(odd + m - 1) % m];
        change.clear();
      }
      const size_t before = out.mesh.triangles.size();
      if (change.empty()) {
        // One label: the face stays whole (crossings on its sides, if any, are fanned in).
        std::vector<uint32_t> ids(pts.begin(), pts.end());
        triangulate_convex(ids, uv, out.mesh.triangles);
        label.resize(out.mesh.triangles.size(), labs[0]);
      } else if (change.size() == 2) {
        // Two labels: the chord between the two change points (the zero set of d_a - d_b is a line).
        for (int side = 0; side < 2; ++side) {
          const size_t from = change[static_cast<size_t>(side)], to = change[static_cast<size_t>(1 - side)];
          std::vector<uint32_t> ids;
          std::vector<std::array<double, 2>> puv;
          for (size_t i = from;; i = (i + 1) % m) {
            ids.push_back(pts[i]);
            puv.push_back(uv[i]);
            if (i == to) break;
          }
          const size_t b0 = out.mesh.triangles.size();
          triangulate_convex(ids, puv, out.mesh.triangles);
          label.resize(out.mesh.triangles.size(), labs[from]);
          (void)b0;
        }
      } else {
        // Three or more labels: regions meet inside the face; fan every run from one interior point X, the point
        // where the first three labels' fields are equal when it lies inside, else the mean of the change points.
        const int la = labs[change[0]], lb = labs[change[1]], lc = labs[change[2]];
        std::array<double, 3> bary{1.0 / 3, 1.0 / 3, 1.0 / 3};
        {
          // d(l) = D0 + u (D1 - D0) + v (D2 - D0); solve d(la) = d(lb) = d(lc).
          auto coef = [&](int l) {
            const double d0 = D[t[0]][static_cast<size_t>(l)], d1 = D[t[1]][static_cast<size_t>(l)],
                         d2 = D[t[2]][static_cast<size_t>(l)];
            return std::array<double, 3>{d0, d1 - d0, d2 - d0};
          };
          const auto A = coef(la), B = coef(lb), C = coef(lc);
          const double a11 = A[1] - B[1], a12 = A[2] - B[2], r1 = B[0] - A[0];
          const double a21 = A[1] - C[1], a22 = A[2] - C[2], r2 = C[0] - A[0];
          const double det = a11 * a22 - a12 * a21;
          bool inside = false;
          if (std::abs(det) > 1e-300) {
            const double u = (r1 * a22 - a12 * r2) / det, v = (a11 * r2 - r1 * a21) / det;
            if (u > 0.01 && v > 0.01 && u + v < 0.99) {
              bary = {1 - u - v, u, v};
              inside = true;
            }
          }
          if (!inside) {
            double u = 0, v = 0;
            for (size_t i : change) {
              u += uv[i][0];
              v += uv[i][1];
            }
            u /= static_cast<double>(change.size());
            v /= static_cast<double>(change.size());
            // Keep X off the sides.
            u = std::clamp(u, 0.02, 0.96);
            v = std::clamp(v, 0.02, 0.96);
            if (u + v > 0.98) {
              const double s = 0.98 / (u + v);
              u *= s;
              v *= s;
            }
            bary = {1 - u - v, u, v};
          }
        }
        const uint32_t x = static_cast<uint32_t>(out.mesh.positions.size());
        out.mesh.positions.push_back(mesh.positions[t[0]] * bary[0] + mesh.positions[t[1]] * bary[1] +
                                     mesh.positions[t[2]] * bary[2]);
        for (size_t c = 0; c < change.size(); ++c) {
          const size_t from = change[c], to = change[(c + 1) % change.size()];
          for (size_t i = from; i != to; i = (i + 1) % m) {
            out.mesh.triangles.push_back({x, pts[i], pts[(i + 1) % m]});
            label.push_back(labs[from]);
          }
        }
      }
      out.source_face.resize(out.mesh.triangles.size(), static_cast<int32_t>(f));
      if (out.mesh.triangles.size() - before > 1) ++out.split_faces;
    }
  }

  // Reliefs: connected components of equal labels across edges. Components smaller than a few input triangles
  // (slivers where the envelope turns for a moment, or an island left by snapping) hold no grid triangle at any
  // useful grid size: each joins the neighbour it shares the longest boundary with, if all its faces face that
  // neighbour's axis.
  const size_t rf = out.mesh.triangles.size();
  const auto radj = face_adjacency(out.mesh);
  double input_area = 0;
  for (const Tri& t : mesh.triangles) input_area += triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
  const double small_area = options.naive ? 0.0 : 16.0 * input_area / static_cast<double>(nf);
  std::vector<uint32_t> stack;
  for (int pass = 0; pass < 4; ++pass) {
    out.face_relief.assign(rf, -1);
    out.reliefs.clear();
    for (size_t s = 0; s < rf; ++s) {
      if (out.face_relief[s] >= 0) continue;
      const int32_t id = static_cast<int32_t>(out.reliefs.size());
      out.reliefs.push_back({label[s], 0, 0});
      out.face_relief[s] = id;
      stack.assign(1, static_cast<uint32_t>(s));
      while (!stack.empty()) {
        const uint32_t f = stack.back();
        stack.pop_back();
        const Tri& t = out.mesh.triangles[f];
        out.reliefs.back().faces++;
        out.reliefs.back().area += triangle_area(out.mesh.positions[t[0]], out.mesh.positions[t[1]], out.mesh.positions[t[2]]);
        for (int32_t g : radj[f])
          if (g >= 0 && out.face_relief[static_cast<size_t>(g)] < 0 && label[static_cast<size_t>(g)] == label[f]) {
            out.face_relief[static_cast<size_t>(g)] = id;
            stack.push_back(static_cast<uint32_t>(g));
          }
      }
    }
    if (pass == 3 || small_area <= 0) break;
    // Shared boundary lengths of the small reliefs with their neighbours.
    std::vector<std::vector<std::pair<int32_t, double>>> shared(out.reliefs.size());
    for (size_t f = 0; f < rf; ++f) {
      const int32_t r = out.face_relief[f];
      if (out.reliefs[static_cast<size_t>(r)].area >= small_area) continue;
      for (size_t k = 0; k < 3; ++k) {
        const int32_t g = radj[f][k];
        if (g < 0 || out.face_relief[static_cast<size_t>(g)] == r) continue;
        const Tri& t = out.mesh.triangles[f];
        const double len = norm(out.mesh.positions[t[(k + 1) % 3]] - out.mesh.positions[t[k]]);
        auto& list = shared[static_cast<size_t>(r)];
        auto it = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first == out.face_relief[static_cast<size_t>(g)]; });
        if (it == list.end()) list.push_back({out.face_relief[static_cast<size_t>(g)], len});
        else it->second += len;
      }
    }
    std::vector<std::vector<uint32_t>> faces_of(out.reliefs.size());
    for (size_t f = 0; f < rf; ++f)
      if (out.reliefs[static_cast<size_t>(out.face_relief[f])].area < small_area)
        faces_of[static_cast<size_t>(out.face_relief[f])].push_back(static_cast<uint32_t>(f));
    bool changed = false;
    for (size_t r = 0; r < out.reliefs.size(); ++r) {
      if (out.reliefs[r].area >= small_area || shared[r].empty()) continue;
      auto& list = shared[r];
      std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
      for (const auto& [n, len] : list) {
        const int axis = out.reliefs[static_cast<size_t>(n)].axis;
        const bool faces_it = std::all_of(faces_of[r].begin(), faces_of[r].end(), [&](uint32_t f) {
          return dot(normal[static_cast<size_t>(out.source_face[f])], axis_vector(axis)) > 0;
        });
        if (!faces_it) continue;
        for (uint32_t f : faces_of[r]) label[f] = axis;
        changed = true;
        break;
      }
    }
    if (!changed) break;
  }
  for (size_t f = 0; f < rf; ++f)
    for (size_t k = 0; k < 3; ++k) {
      const int32_t g = radj[f][k];
      if (g > static_cast<int32_t>(f) && out.face_relief[static_cast<size_t>(g)] != out.face_relief[f]) {
        const Tri& t = out.mesh.triangles[f];
        out.boundary_length += norm(out.mesh.positions[t[(k + 1) % 3]] - out.mesh.positions[t[k]]);
      }
    }
  // Face properties for the PLY file and the pictures.
  std::vector<double> rel(rf), red(rf), green(rf), blue(rf);
  for (size_t f = 0; f < rf; ++f) {
    const int32_t id = out.face_relief[f];
    rel[f] = id;
    const auto c = relief_colour(out.reliefs[static_cast<size_t>(id)].axis, id);
    red[f] = c[0];
    green[f] = c[1];
    blue[f] = c[2];
  }
  out.mesh.set_face_property("relief", ScalarType::Int32, std::move(rel));
  out.mesh.set_face_property("red", ScalarType::UInt8, std::move(red));
  out.mesh.set_face_property("green", ScalarType::UInt8, std::move(green));
  out.mesh.set_face_property("blue", ScalarType::UInt8, std::move(blue));
  for (size_t r = 0; r < out.reliefs.size(); ++r)
    out.mesh.comments.push_back("prm-relief " + std::to_string(r) + " axis " + std::to_string(out.reliefs[r].axis));
  return out;
}

}  // namespace prm::remesh
