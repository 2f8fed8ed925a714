#include "worst_site_rounding.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "prm/aabb_tree.h"
#include "prm/point_triangle_distance.h"
#include "prm/remesh/lattice.h"
#include "prm/surface_facing.h"
#include "prm/surface_sampler.h"
#include "prm/vec3.h"

namespace prm::pipeline {
namespace {

// The worst places looked at: the decoded mesh's samples past kSiteShare x the aim (h22t: at 0.97 the horse's tail
// at 1.3e-4, 0.997x the aim in Metro's samples and 1.13x in the dense probes below, was moved as well, and the
// stream's max went up instead of down).
constexpr size_t kSites = 8;
constexpr double kSiteShare = 1.0;
// in>pr: looked for when no decoded sample comes within this share of the stream's max; the input's samples near a
// place past this share of the aim are weighed with its faces.
constexpr double kMissedShare = 0.999;
// Passes of one-step moves over a site's vertices.
constexpr int kPasses = 2;
// The faces' probes: this many a side per aim of the longest edge, at most kMaxDivisions (Metro's samples find a
// peak between coarser ones: at 3 and 24 the horse's sites at 1.3e-4 came down in the probes and not in Metro's max).
constexpr double kProbesPerAim = 6;
constexpr double kMaxDivisions = 48;

// The worst squared distance of face t's probes to the input; once it reaches `limit`, the rest are left.
double face_worst2(const Mesh& m, const Tri& t, const AabbTree& tree, double aim, double limit = HUGE_VAL) {
  const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
  const double longest = std::sqrt(std::max({norm2(b - a), norm2(c - b), norm2(a - c)}));
  const int n = static_cast<int>(std::clamp(std::ceil(kProbesPerAim * longest / aim), 2.0, kMaxDivisions));
  double worst = 0;
  AabbTree::Hit hint;
  for (int p = 0; p <= n; ++p)
    for (int q = 0; p + q <= n; ++q) {
      const int r = n - p - q;
      if (worst >= limit) return worst;
      const Vec3 x = (1.0 / n) * (static_cast<double>(p) * a + static_cast<double>(q) * b + static_cast<double>(r) * c);
      tree.closest(x, hint);
      worst = std::max(worst, hint.distance2);
    }
  return worst;
}

// Each point's distance to `surface` where it lies farther than `near` (0 where within: AabbTree::within answers for
// most points, cheaper than their closest points), and the points farther than `past` (>= near), farthest first.
std::vector<size_t> farther(const std::vector<Vec3>& points, const AabbTree& surface, double near, double past,
                            std::vector<double>& distance) {
  distance.assign(points.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    AabbTree::Hit hint;
    for (size_t i = r.begin(); i != r.end(); ++i)
      if (!surface.within(points[i], near * near, hint)) {
        surface.closest(points[i], hint);
        distance[i] = std::sqrt(hint.distance2);
      }
  });
  std::vector<size_t> out;
  for (size_t i = 0; i < distance.size(); ++i)
    if (distance[i] > past) out.push_back(i);
  std::sort(out.begin(), out.end(),
            [&](size_t x, size_t y) { return distance[x] != distance[y] ? distance[x] > distance[y] : x < y; });
  return out;
}

Vec3 normal_of(const Mesh& m, const Tri& t) {
  return cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
}

}  // namespace

size_t round_worst_sites(remesh::PrmMesh& prm, const codec::DecodedMesh& decoded, const Mesh& decoded_mesh,
                         const std::vector<uint32_t>& vertex_order, const MetroReference& reference, double aim,
                         double max, std::vector<uint8_t>& held, int missed_reach) {
  const double grid = static_cast<double>(prm.lattice.A) * prm.frame.step;
  // The places: the decoded mesh's samples as the reference's Metro takes them (its pr>in samples, bit for bit)
  // farther than kSiteShare x the aim, farthest first, at most kSites, each a grid size from a farther one.
  const SamplingOptions so = metro_sampling(reference.options(), reference.mesh(), decoded_mesh);
  const SurfaceSamples samples = sample_surface(decoded_mesh, so);
  std::vector<double> distance;
  const std::vector<size_t> far = farther(samples.points, reference.tree(), kSiteShare * aim, kSiteShare * aim, distance);
  struct Place {
    Vec3 at;                  // on the decoded mesh
    std::vector<Vec3> missed;  // in>pr: the input's samples near it past kMissedShare x the aim
  };
  std::vector<Place> sites;
  for (size_t i : far) {
    if (sites.size() >= kSites) break;
    const Vec3& p = samples.points[i];
    if (std::none_of(sites.begin(), sites.end(), [&](const Place& x) { return norm2(x.at - p) < grid * grid; }))
      sites.push_back({p, {}});
  }
  // When the stream's max is the input's (in>pr: no decoded sample that far), its samples too.
  const double pr_max = distance.empty() ? 0.0 : *std::max_element(distance.begin(), distance.end());
  const AabbTree decoded_tree(decoded_mesh);
  if (pr_max < kMissedShare * max) {
    const SurfaceSamples input_samples = sample_surface(reference.mesh(), so);
    std::vector<double> missed;
    const std::vector<size_t> order =
        farther(input_samples.points, decoded_tree, kMissedShare * aim, kSiteShare * aim, missed);
    for (size_t i : order) {
      if (sites.size() >= kSites) break;
      const Vec3 at = decoded_tree.closest(input_samples.points[i]).point;
      if (std::any_of(sites.begin(), sites.end(), [&](const Place& x) { return norm2(x.at - at) < grid * grid; }))
        continue;
      Place place{at, {}};
      for (size_t j = 0; j < missed.size(); ++j)
        if (missed[j] > 0 && norm2(input_samples.points[j] - input_samples.points[i]) < grid * grid)
          place.missed.push_back(input_samples.points[j]);
      sites.push_back(std::move(place));
    }
  }
  if (sites.empty()) return 0;
  Mesh m = decoded_mesh;
  const size_t nv = m.positions.size();
  const std::vector<std::vector<uint32_t>> vertex_faces = faces_around_vertices(m);
  const AabbTree& tree = reference.tree();
  // The quantized points' range per axis (a move stays inside the decoded mesh's box).
  std::array<int64_t, 3> lo{INT64_MAX, INT64_MAX, INT64_MAX}, hi{INT64_MIN, INT64_MIN, INT64_MIN};
  for (size_t k = 0; k < decoded.quantized.size(); ++k) {
    lo[k % 3] = std::min<int64_t>(lo[k % 3], decoded.quantized[k]);
    hi[k % 3] = std::max<int64_t>(hi[k % 3], decoded.quantized[k]);
  }
  std::vector<std::array<int64_t, 3>> q(nv);
  for (uint32_t v = 0; v < nv; ++v)
    for (size_t a = 0; a < 3; ++a) q[v][a] = decoded.quantized[3 * v + a];
  const auto place = [&](uint32_t v) {
    for (int a = 0; a < 3; ++a)
      m.positions[v][static_cast<size_t>(a)] = prm.frame.to_real(static_cast<double>(q[v][static_cast<size_t>(a)]), a);
  };
  std::vector<double> worst2(m.triangles.size(), 0.0);
  std::vector<uint8_t> in_ring(m.triangles.size(), 0);
  std::vector<uint32_t> held_faces;
  size_t moved = 0;
  for (const Place& site : sites) {
    const Vec3& at = site.at;
    // The site's vertices (of the faces whose centroid lies within a grid size) and the faces around them (ring).
    std::vector<uint32_t> site_vertices, ring;
    std::vector<uint8_t> in_site(nv, 0);
    for (uint32_t f = 0; f < m.triangles.size(); ++f) {
      const Tri& t = m.triangles[f];
      const Vec3 c = (1.0 / 3) * (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]);
      if (norm2(c - at) > grid * grid) continue;
      for (uint32_t v : t)
        if (!std::exchange(in_site[v], uint8_t{1})) site_vertices.push_back(v);
    }
    std::fill(in_ring.begin(), in_ring.end(), uint8_t{0});
    for (uint32_t v : site_vertices)
      for (uint32_t f : vertex_faces[v])
        if (!std::exchange(in_ring[f], uint8_t{1})) ring.push_back(f);
    tbb::parallel_for(size_t{0}, ring.size(),
                      [&](size_t i) { worst2[ring[i]] = face_worst2(m, m.triangles[ring[i]], tree, aim); });
    // The missed points' distances to the faces outside the ring (which do not move), then to the ring's.
    std::vector<double> outside2(site.missed.size(), HUGE_VAL);
    for (size_t i = 0; i < site.missed.size(); ++i) {
      const AabbTree::Hit hit = decoded_tree.closest(site.missed[i]);
      if (hit.found() && !in_ring[hit.face]) outside2[i] = hit.distance2;
    }
    const auto ring_worst2 = [&] {
      double w = 0;
      for (uint32_t f : ring) w = std::max(w, worst2[f]);
      for (size_t i = 0; i < site.missed.size(); ++i) {
        double d2 = outside2[i];
        for (uint32_t f : ring) {
          const Tri& t = m.triangles[f];
          d2 = std::min(d2, point_triangle_distance2(site.missed[i], m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
        }
        w = std::max(w, d2);
      }
      return w;
    };
    if (ring_worst2() <= aim * aim) continue;
    size_t site_moved = 0;
    for (int pass = 0; pass < kPasses; ++pass) {
      bool any = false;
      for (uint32_t v : site_vertices) {
        if (v >= vertex_order.size()) continue;
        // At a pr>in place only a vertex of a face past the aim can bring its worst down.
        if (site.missed.empty() && std::none_of(vertex_faces[v].begin(), vertex_faces[v].end(),
                                                [&](uint32_t f) { return worst2[f] > aim * aim; }))
          continue;
        const uint32_t pv = vertex_order[v];
        const bool lattice = pv < prm.vertex_relief.size() && prm.vertex_relief[pv] >= 0;
        std::vector<std::array<int, 3>> steps;
        if (lattice) {
          const int axis = remesh::axis_pair(prm.relief_axis[static_cast<size_t>(prm.vertex_relief[pv])]);
          for (int s : {-1, 1}) {
            std::array<int, 3> d{0, 0, 0};
            d[static_cast<size_t>(axis)] = s;
            steps.push_back(d);
          }
        } else {
          const int r = site.missed.empty() ? 1 : std::max(1, missed_reach);
          for (int dx = -r; dx <= r; ++dx)
            for (int dy = -r; dy <= r; ++dy)
              for (int dz = -r; dz <= r; ++dz)
                if (dx != 0 || dy != 0 || dz != 0) steps.push_back({dx, dy, dz});
        }
        const std::vector<uint32_t>& faces = vertex_faces[v];
        std::vector<Vec3> normals;
        std::vector<uint8_t> facing;  // the faces that face the input (`pack`'s turned-triangle test) must keep to it
        for (uint32_t f : faces) {
          const Tri& t = m.triangles[f];
          normals.push_back(normal_of(m, t));
          facing.push_back(faces_surface(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]], reference.mesh(), tree));
        }
        const std::array<int64_t, 3> from = q[v];
        std::vector<double> from_worst2;
        for (uint32_t f : faces) from_worst2.push_back(worst2[f]);
        double best = ring_worst2();
        std::array<int64_t, 3> best_q = from;
        std::vector<double> best_worst2 = from_worst2;
        for (const auto& d : steps) {
          bool inside = true;
          for (size_t a = 0; a < 3; ++a) {
            q[v][a] = from[a] + d[a];
            inside = inside && q[v][a] >= lo[a] && q[v][a] <= hi[a];
          }
          if (!inside) continue;
          place(v);
          bool agree = true;
          for (size_t i = 0; i < faces.size() && agree; ++i) {
            const Tri& t = m.triangles[faces[i]];
            const Vec3 n = normal_of(m, t);
            agree = dot(n, normals[i]) > 1e-3 * norm(n) * norm(normals[i]) &&
                    (!facing[i] ||
                     faces_surface(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]], reference.mesh(), tree));
          }
          if (!agree) continue;
          // (A fan at least as far as the best so far is left at that: the other faces did not move.)
          double fan = 0;
          for (uint32_t f : faces) {
            worst2[f] = fan < best ? face_worst2(m, m.triangles[f], tree, aim, best) : best;
            fan = std::max(fan, worst2[f]);
          }
          const double w = fan < best ? ring_worst2() : best;
          if (w < best) {
            best = w;
            best_q = q[v];
            for (size_t i = 0; i < faces.size(); ++i) best_worst2[i] = worst2[faces[i]];
          }
          for (size_t i = 0; i < faces.size(); ++i) worst2[faces[i]] = from_worst2[i];
        }
        q[v] = best_q;
        place(v);
        for (size_t i = 0; i < faces.size(); ++i) worst2[faces[i]] = best_worst2[i];
        if (best_q != from) {
          ++site_moved;
          any = true;
        }
      }
      if (!any) break;
    }
    if (site_moved == 0) continue;
    moved += site_moved;
    held_faces.insert(held_faces.end(), ring.begin(), ring.end());
  }
  if (moved == 0) return 0;
  // The rings' vertices where the stream is to hold them.
  held.resize(prm.mesh.positions.size(), 0);
  for (uint32_t f : held_faces)
    for (uint32_t v : m.triangles[f]) {
      if (v >= vertex_order.size() || vertex_order[v] >= prm.mesh.positions.size()) continue;
      prm.mesh.positions[vertex_order[v]] = m.positions[v];
      held[vertex_order[v]] = 1;
    }
  return moved;
}

}  // namespace prm::pipeline
