#include "prm/surface_sampler.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "prm/error.h"
#include "prm/vec3.h"

namespace prm {
namespace {

constexpr size_t kGrain = 2048;

// splitmix64's output function: a good 64-bit mixer, used as a counter-based generator (value = mix(key + i·γ)).
inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
constexpr uint64_t kGamma = 0x9e3779b97f4a7c15ULL;

class FaceRandom {
 public:
  FaceRandom(uint64_t seed, uint64_t face) : state_(mix64(mix64(seed) ^ (face * kGamma + 0x632be59bd9b4e019ULL))) {}
  double uniform() {  // [0, 1)
    state_ += kGamma;
    return static_cast<double>(mix64(state_) >> 11) * 0x1.0p-53;
  }

 private:
  uint64_t state_;
};

void check_indices(const Mesh& mesh) {
  const size_t nv = mesh.positions.size();
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (uint32_t v : mesh.triangles[t])
      if (v >= nv)
        throw InputError("triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) + ", but the mesh has " +
                         std::to_string(nv) + " vertices");
}

// Number of samples of element i when element i gets density·measure[i], rounded by error diffusion:
// floor(S_i) − floor(S_{i−1}) with S_i the running sum. Writes counts and returns their total.
size_t diffuse_counts(const std::vector<double>& measure, double density, std::vector<uint32_t>& counts) {
  counts.assign(measure.size(), 0);
  if (!(density > 0)) return 0;
  double running = 0;
  double taken = 0;
  size_t total = 0;
  for (size_t i = 0; i < measure.size(); ++i) {
    running += measure[i] * density;
    const double whole = std::floor(running);
    const double c = whole - taken;
    if (c > 0) {
      counts[i] = static_cast<uint32_t>(std::min(c, 4.0e9));
      total += counts[i];
      taken = whole;
    }
  }
  return total;
}

std::vector<size_t> offsets_of(const std::vector<uint32_t>& counts, size_t start) {
  std::vector<size_t> offsets(counts.size());
  size_t at = start;
  for (size_t i = 0; i < counts.size(); ++i) {
    offsets[i] = at;
    at += counts[i];
  }
  return offsets;
}

}  // namespace

double surface_area(const Mesh& mesh) {
  check_indices(mesh);
  double area = 0;
  for (const Tri& t : mesh.triangles)
    area += triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
  return area;
}

SurfaceSamples sample_surface(const Mesh& mesh, const SamplingOptions& options) {
  check_indices(mesh);
  const std::vector<Vec3>& pos = mesh.positions;
  const std::vector<Tri>& tris = mesh.triangles;
  const size_t nf = tris.size();
  SurfaceSamples out;

  // Referenced vertices, in index order.
  std::vector<uint32_t> vertices;
  if (options.vertices) {
    std::vector<char> used(pos.size(), 0);
    for (const Tri& t : tris) used[t[0]] = used[t[1]] = used[t[2]] = 1;
    for (size_t v = 0; v < pos.size(); ++v)
      if (used[v]) vertices.push_back(static_cast<uint32_t>(v));
  }

  // Face areas; the total is summed in order, so it does not depend on the thread count.
  std::vector<double> areas(nf);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nf, kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t f = r.begin(); f != r.end(); ++f)
      areas[f] = triangle_area(pos[tris[f][0]], pos[tris[f][1]], pos[tris[f][2]]);
  });
  for (double a : areas) out.area += a;

  // Unique edges (vertex pairs), in sorted order.
  std::vector<uint64_t> edges;
  if (options.edges) {
    edges.reserve(3 * nf);
    for (const Tri& t : tris)
      for (int k = 0; k < 3; ++k) {
        uint32_t a = t[k], b = t[(k + 1) % 3];
        if (a == b) continue;
        if (a > b) std::swap(a, b);
        edges.push_back(static_cast<uint64_t>(a) << 32 | b);
      }
    tbb::parallel_sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  }
  std::vector<double> lengths(edges.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, edges.size(), kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t e = r.begin(); e != r.end(); ++e)
      lengths[e] = norm(pos[edges[e] & 0xffffffffu] - pos[edges[e] >> 32]);
  });
  for (double l : lengths) out.edge_length += l;

  // Split the budget (see SampleBudget).
  const double n = static_cast<double>(options.samples);
  std::vector<uint32_t> edge_counts, face_counts;
  out.vertex_samples = vertices.size();
  if (options.budget == SampleBudget::PerKind) {
    if (out.edge_length > 0) out.edge_samples = diffuse_counts(lengths, n / out.edge_length, edge_counts);
    if (options.faces && out.area > 0) out.face_samples = diffuse_counts(areas, n / out.area, face_counts);
  } else {
    double left = n - static_cast<double>(out.vertex_samples);
    if (left > 0 && options.edges && out.edge_length > 0) {
      // Metro's rule, except that the edges never take more than what is left (Metro would exceed the budget when
      // it is below a few samples per face).
      const double per_length = std::min(options.faces && out.area > 0 ? std::sqrt(left / out.area) : HUGE_VAL,
                                         left / out.edge_length);
      out.edge_samples = diffuse_counts(lengths, per_length, edge_counts);
      left -= static_cast<double>(out.edge_samples);
    }
    if (left > 0 && options.faces && out.area > 0) out.face_samples = diffuse_counts(areas, left / out.area, face_counts);
  }
  if (edge_counts.empty()) edge_counts.assign(edges.size(), 0);
  if (face_counts.empty()) face_counts.assign(nf, 0);

  out.points.resize(out.vertex_samples + out.edge_samples + out.face_samples);
  for (size_t i = 0; i < vertices.size(); ++i) out.points[i] = pos[vertices[i]];

  // Edge samples: evenly spaced, endpoints excluded (they are vertex samples).
  const std::vector<size_t> edge_at = offsets_of(edge_counts, out.vertex_samples);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, edges.size(), kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t e = r.begin(); e != r.end(); ++e) {
      const uint32_t c = edge_counts[e];
      if (c == 0) continue;
      const Vec3& a = pos[edges[e] >> 32];
      const Vec3& b = pos[edges[e] & 0xffffffffu];
      const double step = 1.0 / (static_cast<double>(c) + 1.0);
      for (uint32_t i = 0; i < c; ++i) out.points[edge_at[e] + i] = lerp(a, b, step * (i + 1));
    }
  });

  // Face samples: uniform in the triangle (parallelogram folding of two uniform numbers).
  const std::vector<size_t> face_at = offsets_of(face_counts, out.vertex_samples + out.edge_samples);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nf, kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t f = r.begin(); f != r.end(); ++f) {
      const uint32_t c = face_counts[f];
      if (c == 0) continue;
      const Vec3& a = pos[tris[f][0]];
      const Vec3 ab = pos[tris[f][1]] - a, ac = pos[tris[f][2]] - a;
      FaceRandom rng(options.seed, f);
      for (uint32_t i = 0; i < c; ++i) {
        double u = rng.uniform(), v = rng.uniform();
        if (u + v > 1) {
          u = 1 - u;
          v = 1 - v;
        }
        out.points[face_at[f] + i] = a + ab * u + ac * v;
      }
    }
  });
  return out;
}

}  // namespace prm
