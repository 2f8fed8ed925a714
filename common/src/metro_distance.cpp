#include "prm/metro_distance.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "prm/error.h"
#include "prm/progress.h"
#include "prm/vec3.h"

namespace prm {
namespace {

// Samples are processed in fixed chunks: consecutive samples lie on one face or edge, or on neighbouring ones, so
// the previous answer is a good starting bound for the next query (AabbTree's hint). Chunk sums are added in chunk
// order, which makes the result independent of the scheduling.
constexpr size_t kChunk = 1024;

struct ChunkSum {
  double sum = 0;
  double sum2 = 0;
  double max = 0;
};

// The chunk sums added in chunk order (so that the result does not depend on the scheduling): mean, RMS, maximum.
void summarize(const std::vector<ChunkSum>& sums, size_t n, OneSidedDistance& out) {
  ChunkSum total;
  for (const ChunkSum& s : sums) {
    total.sum += s.sum;
    total.sum2 += s.sum2;
    total.max = std::max(total.max, s.max);
  }
  out.mean = total.sum / static_cast<double>(n);
  out.rms = std::sqrt(total.sum2 / static_cast<double>(n));
  out.max = total.max;
}

OneSidedDistance one_sided(const std::vector<Vec3>& points, const AabbTree& surface, std::vector<double>* per_sample,
                           Progress* progress) {
  OneSidedDistance out;
  const size_t n = points.size();
  out.samples = n;
  if (n == 0 || surface.empty()) return out;
  if (per_sample) per_sample->resize(n);

  const size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<ChunkSum> sums(chunks);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t c = r.begin(); c != r.end(); ++c) {
      ChunkSum s;
      AabbTree::Hit hint;
      const size_t end = std::min(n, (c + 1) * kChunk);
      for (size_t i = c * kChunk; i < end; ++i) {
        surface.closest(points[i], hint);
        const double d = std::sqrt(hint.distance2);
        s.sum += d;
        s.sum2 += d * d;
        s.max = std::max(s.max, d);
        if (per_sample) (*per_sample)[i] = d;
      }
      sums[c] = s;
      if (progress) progress->advance(end - c * kChunk);
    }
  });
  summarize(sums, n, out);
  return out;
}

// The same over samples computed chunk by chunk (SamplePlan's chunks are kChunk samples): equal to the above on the
// stored samples, bit for bit, without storing them.
static_assert(SamplePlan::kSampleChunk == kChunk, "the sums are per chunk of kChunk samples");
OneSidedDistance one_sided(const SamplePlan& plan, const AabbTree& surface, Progress* progress) {
  OneSidedDistance out;
  const size_t n = plan.size();
  out.samples = n;
  out.vertex_samples = plan.vertex_samples;
  out.edge_samples = plan.edge_samples;
  out.face_samples = plan.face_samples;
  out.area = plan.area;
  if (n == 0 || surface.empty()) return out;
  std::vector<ChunkSum> sums(plan.chunks());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, sums.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<Vec3> points;
    for (size_t c = r.begin(); c != r.end(); ++c) {
      plan.chunk(c, points);
      ChunkSum s;
      AabbTree::Hit hint;
      for (const Vec3& p : points) {
        surface.closest(p, hint);
        const double d = std::sqrt(hint.distance2);
        s.sum += d;
        s.sum2 += d * d;
        s.max = std::max(s.max, d);
      }
      sums[c] = s;
      if (progress) progress->advance(points.size());
    }
  });
  summarize(sums, n, out);
  return out;
}

OneSidedDistance one_sided(const SurfaceSamples& samples, const AabbTree& surface, std::vector<double>* per_sample,
                           Progress* progress) {
  OneSidedDistance out = one_sided(samples.points, surface, per_sample, progress);
  out.vertex_samples = samples.vertex_samples;
  out.edge_samples = samples.edge_samples;
  out.face_samples = samples.face_samples;
  out.area = samples.area;
  return out;
}

void require_surface(const Mesh& m, const char* which) {
  if (m.triangles.empty())
    throw InputError(std::string("mesh ") + which + " has no triangles: there is no surface to measure");
}

SamplingOptions sampling_options(const MetroOptions& o, size_t count) {
  SamplingOptions s;
  s.samples = count;
  s.budget = o.budget;
  s.vertices = o.sample_vertices;
  s.edges = o.sample_edges;
  s.faces = o.sample_faces;
  s.seed = o.seed;
  return s;
}

size_t sample_count(const MetroOptions& o, const Mesh& a, const Mesh& b) {
  if (o.samples) return o.samples;
  const size_t n =
      static_cast<size_t>(o.samples_per_face * static_cast<double>(std::max(a.triangles.size(), b.triangles.size())));
  return o.max_samples > 0 ? std::min(n, o.max_samples) : n;
}

}  // namespace

SamplingOptions metro_sampling(const MetroOptions& o, const Mesh& a, const Mesh& b) {
  return sampling_options(o, sample_count(o, a, b));
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

double bbox_diagonal(const Mesh& mesh) {
  if (mesh.positions.empty()) return 0;
  Vec3 lo = mesh.positions[0], hi = lo;
  for (const Vec3& p : mesh.positions)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  return norm(hi - lo);
}

OneSidedDistance distance_to_surface(const SurfaceSamples& samples, const AabbTree& surface,
                                     std::vector<double>* per_sample) {
  return one_sided(samples, surface, per_sample, nullptr);
}

OneSidedDistance distance_to_surface(const std::vector<Vec3>& points, const AabbTree& surface,
                                     std::vector<double>* per_sample) {
  return one_sided(points, surface, per_sample, nullptr);
}

DistanceReport metro_distance(const Mesh& a, const Mesh& b, const MetroOptions& options) {
  require_surface(a, "A");
  require_surface(b, "B");
  const SamplingOptions so = metro_sampling(options, a, b);
  // Each preparation is parallel inside; running them one after the other keeps all cores busy without nesting.
  const AabbTree tree_a(a), tree_b(b);
  const SamplePlan samples_a(a, so), samples_b(b, so);
  std::unique_ptr<Progress> progress;
  if (options.progress) progress = std::make_unique<Progress>("compare", samples_a.size() + samples_b.size());
  const OneSidedDistance ab = one_sided(samples_a, tree_b, progress.get());
  const OneSidedDistance ba = one_sided(samples_b, tree_a, progress.get());
  if (progress) progress->finish();
  return combine(ab, ba, bbox_diagonal(a));
}

std::vector<DeviationSite> worst_deviations(const Mesh& a, const Mesh& b, size_t k, double separation,
                                           const MetroOptions& options) {
  require_surface(a, "A");
  require_surface(b, "B");
  const SamplingOptions so = metro_sampling(options, a, b);
  const AabbTree tree_a(a), tree_b(b);
  const SurfaceSamples samples_a = sample_surface(a, so), samples_b = sample_surface(b, so);
  std::vector<double> da, db;
  one_sided(samples_a, tree_b, &da, nullptr);
  one_sided(samples_b, tree_a, &db, nullptr);
  // Candidates: (distance, direction, index), largest first; ties by direction and index, so the order is fixed.
  struct Candidate {
    double distance;
    bool a_to_b;
    size_t index;
  };
  std::vector<Candidate> all;
  all.reserve(da.size() + db.size());
  for (size_t i = 0; i < da.size(); ++i) all.push_back({da[i], true, i});
  for (size_t i = 0; i < db.size(); ++i) all.push_back({db[i], false, i});
  std::sort(all.begin(), all.end(), [](const Candidate& x, const Candidate& y) {
    if (x.distance != y.distance) return x.distance > y.distance;
    if (x.a_to_b != y.a_to_b) return x.a_to_b;
    return x.index < y.index;
  });
  std::vector<DeviationSite> out;
  const double sep2 = separation * separation;
  for (const Candidate& c : all) {
    if (out.size() >= k) break;
    const Vec3& p = c.a_to_b ? samples_a.points[c.index] : samples_b.points[c.index];
    bool near = false;
    for (const DeviationSite& s : out) near = near || norm2(s.sample - p) < sep2;
    if (near) continue;
    const AabbTree::Hit hit = (c.a_to_b ? tree_b : tree_a).closest(p);
    out.push_back({p, hit.point, hit.face, c.distance, c.a_to_b});
  }
  return out;
}

MetroReference::MetroReference(Mesh reference, const MetroOptions& options)
    : mesh_(std::make_shared<const Mesh>(std::move(reference))), options_(options) {
  require_surface(*mesh_, "A");
  tree_ = std::make_shared<const AabbTree>(*mesh_);
  diagonal_ = bbox_diagonal(*mesh_);
}

MetroReference::MetroReference(const Mesh* reference, const MetroOptions& options)
    : mesh_(std::shared_ptr<const Mesh>(std::shared_ptr<const Mesh>(), reference)), options_(options) {
  require_surface(*mesh_, "A");
  tree_ = std::make_shared<const AabbTree>(*mesh_);
  diagonal_ = bbox_diagonal(*mesh_);
}

MetroReference::MetroReference(const MetroReference& shared, const MetroOptions& options)
    : mesh_(shared.mesh_), options_(options), tree_(shared.tree_), diagonal_(shared.diagonal_), last_(shared.last_) {}

std::shared_ptr<const SamplePlan> MetroReference::samples_for(size_t count) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!samples_ || samples_count_ != count) {
    samples_.reset();  // before the new plan is made, not after
    samples_ = std::make_shared<const SamplePlan>(*mesh_, sampling_options(options_, count));
    samples_count_ = count;
  }
  return samples_;
}

std::shared_ptr<const AabbTree> MetroReference::candidate_tree(const Mesh& candidate) const {
  LastCandidate& last = *last_;
  std::shared_ptr<AabbTree> tree;
  {
    std::lock_guard<std::mutex> lock(last.mutex);
    if (last.tree && last.triangles == candidate.triangles) {
      if (last.positions == candidate.positions) return last.tree;
      if (last.tree.use_count() == 1) tree = std::move(last.tree);  // no other compare() is reading it
    }
    last.tree.reset();
  }
  if (tree)
    tree->refit(candidate);
  else
    tree = std::make_shared<AabbTree>(candidate);
  std::lock_guard<std::mutex> lock(last.mutex);
  last.triangles = candidate.triangles;
  last.positions = candidate.positions;
  last.tree = tree;
  return tree;
}

void MetroReference::forget_candidate() const {
  std::lock_guard<std::mutex> lock(last_->mutex);
  last_->tree.reset();
  std::vector<Tri>().swap(last_->triangles);
  std::vector<Vec3>().swap(last_->positions);
}

DistanceReport MetroReference::compare(const Mesh& candidate) const {
  require_surface(candidate, "B");
  const size_t count = sample_count(options_, *mesh_, candidate);
  const std::shared_ptr<const SamplePlan> samples_a = samples_for(count);
  const std::shared_ptr<const AabbTree> tree_ptr = candidate_tree(candidate);
  const AabbTree& tree_b = *tree_ptr;
  const SamplePlan samples_b(candidate, sampling_options(options_, count));
  std::unique_ptr<Progress> progress;
  if (options_.progress) progress = std::make_unique<Progress>("compare", samples_a->size() + samples_b.size());
  const OneSidedDistance ab = one_sided(*samples_a, tree_b, progress.get());
  const OneSidedDistance ba = one_sided(samples_b, *tree_, progress.get());
  if (progress) progress->finish();
  return combine(ab, ba, diagonal_);
}

}  // namespace prm
