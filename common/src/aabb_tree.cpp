#include "prm/aabb_tree.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "prm/vec3.h"

namespace prm {

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  if (!std::isfinite(denom)) return a;  // a degenerate triangle: its vertices were checked above
  return a + ab * (vb * denom) + ac * (vc * denom);
}

namespace {
constexpr uint32_t kLeafSize = 4;

double box_distance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  double d = 0;
  for (size_t k = 0; k < 3; ++k) {
    const double e = p[k] < lo[k] ? lo[k] - p[k] : p[k] > hi[k] ? p[k] - hi[k] : 0.0;
    d += e * e;
  }
  return d;
}
}  // namespace

AabbTree::AabbTree(const Mesh& mesh) {
  const size_t n = mesh.triangles.size();
  if (n == 0) return;
  std::vector<Vec3> centroid(n);
  std::vector<uint32_t> order(n);
  for (uint32_t f = 0; f < n; ++f) {
    const Tri& t = mesh.triangles[f];
    centroid[f] = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) * (1.0 / 3.0);
    order[f] = f;
  }
  nodes_.reserve(2 * n / kLeafSize + 2);
  build(mesh, 0, static_cast<uint32_t>(n), order, centroid);
  // Triangles in leaf order, so that a leaf's triangles are contiguous.
  tris_.resize(n);
  face_ = std::move(order);
  for (size_t i = 0; i < n; ++i) {
    const Tri& t = mesh.triangles[face_[i]];
    tris_[i] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
  }
}

uint32_t AabbTree::build(const Mesh& mesh, uint32_t begin, uint32_t end, std::vector<uint32_t>& order,
                         const std::vector<Vec3>& centroid) {
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back({});
  Vec3 lo = mesh.positions[mesh.triangles[order[begin]][0]], hi = lo;
  Vec3 clo = centroid[order[begin]], chi = clo;
  for (uint32_t i = begin; i < end; ++i) {
    for (uint32_t v : mesh.triangles[order[i]])
      for (size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], mesh.positions[v][k]);
        hi[k] = std::max(hi[k], mesh.positions[v][k]);
      }
    for (size_t k = 0; k < 3; ++k) {
      clo[k] = std::min(clo[k], centroid[order[i]][k]);
      chi[k] = std::max(chi[k], centroid[order[i]][k]);
    }
  }
  nodes_[index].lo = lo;
  nodes_[index].hi = hi;
  if (end - begin <= kLeafSize) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  size_t axis = 0;
  for (size_t k = 1; k < 3; ++k)
    if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                   [&](uint32_t x, uint32_t y) { return centroid[x][axis] < centroid[y][axis]; });
  build(mesh, begin, mid, order, centroid);
  const uint32_t right = build(mesh, mid, end, order, centroid);
  nodes_[index].first = right;
  nodes_[index].count = 0;
  return index;
}

AabbTree::Hit AabbTree::closest(const Vec3& p) const { return closest(p, HUGE_VAL); }

AabbTree::Hit AabbTree::closest(const Vec3& p, double bound2) const {
  Hit best;
  best.distance2 = bound2;
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (box_distance2(p, n.lo, n.hi) >= best.distance2) continue;
    if (n.count) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        const Vec3 q = closest_point_on_triangle(p, tris_[i].a, tris_[i].b, tris_[i].c);
        const double d2 = norm2(q - p);
        if (d2 < best.distance2) {
          best.distance2 = d2;
          best.point = q;
          best.face = face_[i];
        }
      }
      continue;
    }
    // Visit the nearer child first (pushed last).
    const uint32_t left = static_cast<uint32_t>(&n - nodes_.data()) + 1, right = n.first;
    const double dl = box_distance2(p, nodes_[left].lo, nodes_[left].hi);
    const double dr = box_distance2(p, nodes_[right].lo, nodes_[right].hi);
    if (top + 2 > 128) continue;  // depth is O(log n): never reached
    if (dl < dr) {
      stack[top++] = right;
      stack[top++] = left;
    } else {
      stack[top++] = left;
      stack[top++] = right;
    }
  }
  if (best.face == UINT32_MAX && bound2 != HUGE_VAL) return closest(p, HUGE_VAL);  // the bound was too tight
  return best;
}

}  // namespace prm
