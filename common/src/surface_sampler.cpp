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
  void skip(uint64_t draws) { state_ += draws * kGamma; }  // as `draws` calls of uniform()

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


}  // namespace

double surface_area(const Mesh& mesh) {
  check_indices(mesh);
  double area = 0;
  for (const Tri& t : mesh.triangles)
    area += triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
  return area;
}

SamplePlan::SamplePlan(const Mesh& mesh, const SamplingOptions& options) : mesh_(mesh), seed_(options.seed) {
  check_indices(mesh);
  const std::vector<Vec3>& pos = mesh.positions;
  const std::vector<Tri>& tris = mesh.triangles;
  const size_t nf = tris.size();

  // Referenced vertices, in index order.
  if (options.vertices) {
    std::vector<char> used(pos.size(), 0);
    for (const Tri& t : tris) used[t[0]] = used[t[1]] = used[t[2]] = 1;
    for (size_t v = 0; v < pos.size(); ++v)
      if (used[v]) vertices_.push_back(static_cast<uint32_t>(v));
  }

  // Face areas; the total is summed in order, so it does not depend on the thread count.
  std::vector<double> areas(nf);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nf, kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t f = r.begin(); f != r.end(); ++f)
      areas[f] = triangle_area(pos[tris[f][0]], pos[tris[f][1]], pos[tris[f][2]]);
  });
  for (double a : areas) area += a;

  // Unique edges (vertex pairs), in sorted order.
  if (options.edges) {
    edges_.reserve(3 * nf);
    for (const Tri& t : tris)
      for (int k = 0; k < 3; ++k) {
        uint32_t a = t[k], b = t[(k + 1) % 3];
        if (a == b) continue;
        if (a > b) std::swap(a, b);
        edges_.push_back(static_cast<uint64_t>(a) << 32 | b);
      }
    tbb::parallel_sort(edges_.begin(), edges_.end());
    edges_.erase(std::unique(edges_.begin(), edges_.end()), edges_.end());
    edges_.shrink_to_fit();
  }
  std::vector<double> lengths(edges_.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, edges_.size(), kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t e = r.begin(); e != r.end(); ++e)
      lengths[e] = norm(pos[edges_[e] & 0xffffffffu] - pos[edges_[e] >> 32]);
  });
  for (double l : lengths) edge_length += l;

  // Split the budget (see SampleBudget).
  const double n = static_cast<double>(options.samples);
  vertex_samples = vertices_.size();
  if (options.budget == SampleBudget::PerKind) {
    if (edge_length > 0) edge_samples = diffuse_counts(lengths, n / edge_length, edge_counts_);
    if (options.faces && area > 0) face_samples = diffuse_counts(areas, n / area, face_counts_);
  } else {
    double left = n - static_cast<double>(vertex_samples);
    if (left > 0 && options.edges && edge_length > 0) {
      // Metro's rule, except that the edges never take more than what is left (Metro would exceed the budget when
      // it is below a few samples per face).
      const double per_length =
          std::min(options.faces && area > 0 ? std::sqrt(left / area) : HUGE_VAL, left / edge_length);
      edge_samples = diffuse_counts(lengths, per_length, edge_counts_);
      left -= static_cast<double>(edge_samples);
    }
    if (left > 0 && options.faces && area > 0) face_samples = diffuse_counts(areas, left / area, face_counts_);
  }
  if (edge_counts_.empty()) edge_counts_.assign(edges_.size(), 0);
  if (face_counts_.empty()) face_counts_.assign(nf, 0);

  // Where each chunk starts: one pass over the elements in sample order.
  starts_.resize(chunks());
  size_t at = 0, element = 0;  // samples before `element`
  auto count_of = [&](size_t e) -> size_t {
    if (e < vertices_.size()) return 1;
    e -= vertices_.size();
    return e < edges_.size() ? edge_counts_[e] : face_counts_[e - edges_.size()];
  };
  for (size_t c = 0; c < starts_.size(); ++c) {
    const size_t first = c * kSampleChunk;
    while (at + count_of(element) <= first) at += count_of(element++);
    starts_[c] = {element, static_cast<uint32_t>(first - at)};
  }
}

void SamplePlan::chunk(size_t c, std::vector<Vec3>& out) const {
  const size_t first = c * kSampleChunk;
  out.resize(std::min(size(), first + kSampleChunk) - first);
  const std::vector<Vec3>& pos = mesh_.positions;
  const size_t nv = vertices_.size(), ne = edges_.size();
  size_t element = starts_[c].element;
  uint32_t skip = starts_[c].skip;
  for (size_t k = 0; k < out.size(); ++element, skip = 0) {
    if (element < nv) {
      out[k++] = pos[vertices_[element]];
    } else if (element < nv + ne) {
      // Edge samples: evenly spaced, endpoints excluded (they are vertex samples).
      const size_t e = element - nv;
      const uint32_t n = edge_counts_[e];
      const Vec3& a = pos[edges_[e] >> 32];
      const Vec3& b = pos[edges_[e] & 0xffffffffu];
      const double step = 1.0 / (static_cast<double>(n) + 1.0);
      for (uint32_t i = skip; i < n && k < out.size(); ++i) out[k++] = lerp(a, b, step * (i + 1));
    } else {
      // Face samples: uniform in the triangle (parallelogram folding of two uniform numbers).
      const size_t f = element - nv - ne;
      const uint32_t n = face_counts_[f];
      if (n == 0) continue;
      const Tri& t = mesh_.triangles[f];
      const Vec3& a = pos[t[0]];
      const Vec3 ab = pos[t[1]] - a, ac = pos[t[2]] - a;
      FaceRandom rng(seed_, f);
      rng.skip(2 * uint64_t{skip});
      for (uint32_t i = skip; i < n && k < out.size(); ++i) {
        double u = rng.uniform(), v = rng.uniform();
        if (u + v > 1) {
          u = 1 - u;
          v = 1 - v;
        }
        out[k++] = a + ab * u + ac * v;
      }
    }
  }
}

SurfaceSamples sample_surface(const Mesh& mesh, const SamplingOptions& options) {
  const SamplePlan plan(mesh, options);
  SurfaceSamples out;
  out.vertex_samples = plan.vertex_samples;
  out.edge_samples = plan.edge_samples;
  out.face_samples = plan.face_samples;
  out.area = plan.area;
  out.edge_length = plan.edge_length;
  out.points.resize(plan.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, plan.chunks(), 1), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<Vec3> chunk;
    for (size_t c = r.begin(); c != r.end(); ++c) {
      plan.chunk(c, chunk);
      std::copy(chunk.begin(), chunk.end(), out.points.begin() + static_cast<long>(c * SamplePlan::kSampleChunk));
    }
  });
  return out;
}

}  // namespace prm
