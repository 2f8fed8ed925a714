#include "geodesic_distance.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <queue>

#include "prm/vec3.h"

namespace prm::remesh {

namespace {

// The distance at x of a front known at a (da) and b (db) that crosses the triangle (a, b, x), or +infinity when
// the front's characteristic through x does not cross segment ab (then the edges give the value).
double triangle_update(const Vec3& a, const Vec3& b, const Vec3& x, double da, double db) {
  const Vec3 e = b - a;
  const double L2 = norm2(e);
  if (!(L2 > 0)) return HUGE_VAL;
  const double L = std::sqrt(L2);
  const Vec3 ax = x - a;
  const double x1 = dot(ax, e) / L;                          // x in the frame a = (0, 0), b = (L, 0), x2 > 0
  const double x2 = std::sqrt(std::max(0.0, norm2(ax) - x1 * x1));
  if (!(x2 > 0)) return HUGE_VAL;
  const double dd = db - da;
  if (std::abs(dd) >= L) return HUGE_VAL;  // one of a, b lies on the other's shortest path: no front through both
  // A planar front through a and b (the classic fast-marching update): unit direction n = (dd / L, sqrt(1 -
  // (dd / L)^2)) and d(p) = da + n . p; its characteristic through x must cross ab. (A virtual point source at
  // distances da and db from a and b is exact around convex corners of the source set, but measured worse: on a
  // straight front it bends the front (mean error 0.0031 against 0.0014 here), on the sphere's latitude field 7x
  // worse; relief_envelope_test has the figures.)
  const double n1 = dd / L, n2 = std::sqrt(1 - n1 * n1);
  const double t = x1 - n1 * (x2 / n2);
  if (t < 0 || t > L) return HUGE_VAL;
  return da + n1 * x1 + n2 * x2;
}

}  // namespace

void geodesic_distance(const Mesh& m, const VertexStar& star, const std::vector<uint8_t>& source,
                       GeodesicMethod method, std::vector<double>& d) {
  const size_t nv = m.positions.size();
  d.assign(nv, HUGE_VAL);
  std::vector<uint8_t> done(nv, 0);
  using Item = std::pair<double, uint32_t>;
  std::vector<Item> storage;
  storage.reserve(nv / 4);
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap(std::greater<Item>(), std::move(storage));
  auto relax = [&](uint32_t v, double value) {
    if (value < d[v]) {
      d[v] = value;
      heap.push({value, v});
    }
  };
  const bool fmm = method == GeodesicMethod::FastMarching;
  // Settling u: its neighbours get the edge paths through u and, with FastMarching, the triangle updates of the
  // faces (u, p, q) where p is settled and q is not.
  auto settle = [&](uint32_t u) {
    const double du = d[u];
    for (uint32_t i = star.nbr_offset[u]; i < star.nbr_offset[u + 1]; ++i) {
      const uint32_t w = star.neighbours[i];
      if (!done[w]) relax(w, du + star.length[i]);
    }
    if (!fmm) return;
    for (uint32_t i = star.offset[u]; i < star.offset[u + 1]; ++i) {
      const Tri& t = m.triangles[star.faces[i]];
      const int k = t[0] == u ? 0 : t[1] == u ? 1 : 2;
      const uint32_t p = t[static_cast<size_t>((k + 1) % 3)], q = t[static_cast<size_t>((k + 2) % 3)];
      if (done[p] && !done[q]) relax(q, triangle_update(m.positions[u], m.positions[p], m.positions[q], du, d[p]));
      if (done[q] && !done[p]) relax(p, triangle_update(m.positions[u], m.positions[q], m.positions[p], du, d[q]));
    }
  };
  // The sources are settled at 0 without the heap; the front starts from the ones on the rim of the source set.
  for (uint32_t f = 0; f < m.triangles.size(); ++f)
    if (source[f])
      for (uint32_t v : m.triangles[f]) {
        d[v] = 0;
        done[v] = 1;
      }
  for (uint32_t v = 0; v < nv; ++v) {
    if (!done[v]) continue;
    bool rim = false;
    for (uint32_t i = star.nbr_offset[v]; i < star.nbr_offset[v + 1] && !rim; ++i) rim = !done[star.neighbours[i]];
    if (rim) settle(v);
  }
  while (!heap.empty()) {
    const uint32_t u = heap.top().second;
    heap.pop();
    if (done[u]) continue;
    done[u] = 1;
    settle(u);
  }
}

std::vector<AxisValues> axis_distance_fields(const Mesh& mesh, const VertexStar& star,
                                             const std::vector<Vec3>& normals, double tau, GeodesicMethod method,
                                             bool parallel) {
  const size_t nv = mesh.positions.size(), nf = mesh.triangles.size();
  std::vector<AxisValues> D(nv);
  // Larger than any geodesic distance: the sum of all edge lengths (each counted twice).
  double beyond = 1;
  for (double l : star.length) beyond += l;
  auto field = [&](size_t a) {
    std::vector<uint8_t> src(nf);
    for (size_t f = 0; f < nf; ++f)
      src[f] = norm2(normals[f]) > 0 && axis_component(normals[f], static_cast<int>(a)) < tau;
    std::vector<double> d;
    geodesic_distance(mesh, star, src, method, d);
    for (size_t v = 0; v < nv; ++v) D[v][a] = std::min(d[v], beyond);
  };
  if (parallel) {
    tbb::parallel_for(size_t{0}, size_t{kReliefAxes}, field);
  } else {
    for (size_t a = 0; a < kReliefAxes; ++a) field(a);
  }
  return D;
}

}  // namespace prm::remesh
