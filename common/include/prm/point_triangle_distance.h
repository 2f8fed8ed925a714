// Exact closest point on a triangle to a point in space (double precision).
// The classic Voronoi-region walk: the answer lies in one of seven regions of the triangle's plane (three vertex
// regions, three edge regions, the interior), chosen from the signs of a few dot products. Degenerate triangles
// (zero area: repeated or collinear corners) fall back to the closest of their three edges, so the answer is
// always a point of the (possibly degenerate) triangle and never NaN for finite input.
#pragma once

#include <algorithm>

#include "prm/mesh.h"
#include "prm/vec3.h"

namespace prm {

// Closest point to p on the segment [a, b] (a == b allowed).
inline Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = dot(ab, ab);
  if (!(len2 > 0)) return a;
  const double t = std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
  return a + ab * t;
}

// Closest point to p on triangle (a, b, c).
inline Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;  // vertex region a

  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;  // vertex region b

  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;  // vertex region c

  // va, vb, vc are the (unnormalised) barycentric coordinates of p's projection, times the doubled area squared.
  const double vc = d1 * d4 - d3 * d2;
  const double va = d3 * d6 - d5 * d4;
  const double vb = d5 * d2 - d1 * d6;
  const double denom = va + vb + vc;
  if (!(denom > 0)) {
    // Zero (or, after rounding, negative) area: the triangle is a segment or a point.
    const Vec3 q0 = closest_point_on_segment(p, a, b), q1 = closest_point_on_segment(p, b, c),
               q2 = closest_point_on_segment(p, c, a);
    const double e0 = norm2(p - q0), e1 = norm2(p - q1), e2 = norm2(p - q2);
    return e0 <= e1 ? (e0 <= e2 ? q0 : q2) : (e1 <= e2 ? q1 : q2);
  }
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));  // edge ab
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));  // edge ac
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)                      // edge bc
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double v = vb / denom, w = vc / denom;  // interior
  return a + ab * v + ac * w;
}

inline double point_triangle_distance2(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return norm2(p - closest_point_on_triangle(p, a, b, c));
}

}  // namespace prm
