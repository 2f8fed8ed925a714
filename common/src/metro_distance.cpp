#include "prm/metro_distance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "prm/vec3.h"

namespace prm {
namespace {

double diagonal_of(const Mesh& m) {
  if (m.positions.empty()) return 0;
  Vec3 lo = m.positions[0], hi = lo;
  for (const Vec3& p : m.positions)
    for (size_t k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  return norm(hi - lo);
}

}  // namespace

std::vector<Vec3> sample_surface(const Mesh& m, const MetroOptions& o) {
  std::vector<Vec3> pts;
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  if (o.sample_vertices) {
    std::vector<uint8_t> used(m.positions.size(), 0);
    for (const Tri& t : m.triangles)
      for (uint32_t v : t) used[v] = 1;
    for (size_t v = 0; v < m.positions.size(); ++v)
      if (used[v]) pts.push_back(m.positions[v]);
  }
  if (o.sample_edges && o.samples > 0) {
    // Each edge once; samples evenly spaced along it, as many as its share of the total length (with carry).
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    edges.reserve(3 * m.triangles.size());
    for (const Tri& t : m.triangles)
      for (size_t k = 0; k < 3; ++k) {
        const uint32_t a = t[k], b = t[(k + 1) % 3];
        edges.push_back({std::min(a, b), std::max(a, b)});
      }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    double total = 0;
    for (const auto& e : edges) total += norm(m.positions[e.second] - m.positions[e.first]);
    if (total > 0) {
      const double step = total / static_cast<double>(o.samples);
      double carry = 0;
      for (const auto& e : edges) {
        const Vec3& a = m.positions[e.first];
        const Vec3& b = m.positions[e.second];
        const double want = norm(b - a) / step + carry;
        const size_t n = static_cast<size_t>(want);
        carry = want - static_cast<double>(n);
        for (size_t k = 0; k < n; ++k) pts.push_back(lerp(a, b, (static_cast<double>(k) + 0.5) / static_cast<double>(n)));
      }
    }
  }
  if (o.sample_faces && o.samples > 0 && !m.triangles.empty()) {
    std::vector<double> cdf(m.triangles.size());
    double acc = 0;
    for (size_t f = 0; f < m.triangles.size(); ++f) {
      const Tri& t = m.triangles[f];
      acc += triangle_area(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
      cdf[f] = acc;
    }
    if (acc > 0)
      for (size_t s = 0; s < o.samples; ++s) {
        const double r = uni(rng) * acc;
        const size_t f = std::min<size_t>(static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), r) - cdf.begin()),
                                          cdf.size() - 1);
        double u = uni(rng), v = uni(rng);
        if (u + v > 1) {
          u = 1 - u;
          v = 1 - v;
        }
        const Tri& t = m.triangles[f];
        const Vec3& a = m.positions[t[0]];
        pts.push_back(a + (m.positions[t[1]] - a) * u + (m.positions[t[2]] - a) * v);
      }
  }
  return pts;
}

OneSidedDistance distance_to_surface(const std::vector<Vec3>& points, const AabbTree& surface) {
  struct Acc {
    double sum = 0, sum2 = 0, max = 0;
  };
  OneSidedDistance out;
  out.samples = points.size();
  if (points.empty() || surface.empty()) return out;
  const Acc total = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, points.size(), 1024), Acc{},
      [&](const tbb::blocked_range<size_t>& r, Acc acc) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const double d = std::sqrt(surface.closest(points[i]).distance2);
          acc.sum += d;
          acc.sum2 += d * d;
          acc.max = std::max(acc.max, d);
        }
        return acc;
      },
      [](Acc a, const Acc& b) {
        a.sum += b.sum;
        a.sum2 += b.sum2;
        a.max = std::max(a.max, b.max);
        return a;
      });
  const double n = static_cast<double>(points.size());
  out.mean = total.sum / n;
  out.rms = std::sqrt(total.sum2 / n);
  out.max = total.max;
  return out;
}

namespace {
DistanceReport combine(const OneSidedDistance& ab, const OneSidedDistance& ba, double diagonal) {
  DistanceReport r;
  r.a_to_b = ab;
  r.b_to_a = ba;
  r.mean = std::max(ab.mean, ba.mean);
  r.rms = std::max(ab.rms, ba.rms);
  r.max = std::max(ab.max, ba.max);
  r.diagonal = diagonal;
  return r;
}
}  // namespace

DistanceReport metro_distance(const Mesh& a, const Mesh& b, const MetroOptions& o) {
  const AabbTree ta(a), tb(b);
  const OneSidedDistance ab = distance_to_surface(sample_surface(a, o), tb);
  MetroOptions ob = o;
  ob.seed = o.seed + 1;
  const OneSidedDistance ba = distance_to_surface(sample_surface(b, ob), ta);
  return combine(ab, ba, diagonal_of(a));
}

MetroReference::MetroReference(const Mesh& reference, const MetroOptions& options)
    : options_(options), tree_(reference), samples_(sample_surface(reference, options)), diagonal_(diagonal_of(reference)) {}

DistanceReport MetroReference::compare(const Mesh& candidate) const {
  const AabbTree tc(candidate);
  const OneSidedDistance ab = distance_to_surface(samples_, tc);
  MetroOptions ob = options_;
  ob.seed = options_.seed + 1;
  const OneSidedDistance ba = distance_to_surface(sample_surface(candidate, ob), tree_);
  return combine(ab, ba, diagonal_);
}

}  // namespace prm
