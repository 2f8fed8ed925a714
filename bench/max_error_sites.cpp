// Where the worst-case error of `prm pack` comes from (issue 22 item 3, bench/README.md "Worst-case error"): packs a
// mesh at a target RMS error, finds the k places of largest deviation between the decoded stream and the input (both
// directions, prm::worst_deviations), and measures each stage's mesh at the same grid, bit depth and step:
//   remesh  the remesher's mesh before quantization (least-squares heights and error flips as pack uses them)
//   nofit   the same without least-squares heights (lattice vertices on the input surface)
//   noflip  the same without error flips
//   rounded the remesh's mesh with every coordinate rounded to the stream's step (what --round-heights encodes)
//   decoded the stream pack chose (rate-distortion heights)
// For every site: the largest deviation of each stage within one grid size of it, and the geometry there (the largest
// dihedral angle of the input within a grid size: a crease; the PRM's irregular vertices within a grid size: a seam).
//   refined the remesh's mesh with the local refinement at --refine R (fraction of the diagonal), rounded
//   refunr  the same before the rounding (what the refinement itself leaves; refunr < R < refined: the rounding)
// Usage: prm_bench_max_error_sites MESH TARGET_ERROR [K] [--max-error E] [--refine R] [--[no-]local-refinement]
//        [--effort N] [--bits B] [--step-scale S] [--fill-holes]
//        prm_bench_max_error_sites MESH TARGET_ERROR [K] --mesh OTHER [--grid G]
// (--mesh: only OTHER's worst sites against MESH, e.g. `prm remesh`'s output, none of the stages; sites --grid G
// apart, a fraction of the diagonal, 0.0065 unless given)
// (--max-error, --[no-]local-refinement, --effort, --bits, --step-scale, --fill-holes: the options of the pack whose stream is the "decoded" stage; without
// them, pack's defaults)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "prm/codec.h"
#include "prm/mesh_io.h"
#include "prm/mesh_repair.h"
#include "prm/mesh_validate.h"
#include "prm/metro_distance.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack.h"
#include "prm/surface_sampler.h"
#include "prm/vec3.h"

using namespace prm;  // Vec3 operators (std::array: no argument-dependent lookup)

namespace {

using prm::Mesh;
using prm::Vec3;

struct Stage {
  std::string name;
  Mesh mesh;
  std::vector<Vec3> points[2];  // samples of the input (to this mesh), of this mesh (to the input)
  std::vector<double> dist[2];
  prm::DistanceReport report;
};

void measure(Stage& s, const Mesh& input, const prm::AabbTree& input_tree, const prm::SamplingOptions& so) {
  s.report = prm::metro_distance(input, s.mesh);
  const prm::AabbTree tree(s.mesh);
  const prm::SurfaceSamples a = prm::sample_surface(input, so), b = prm::sample_surface(s.mesh, so);
  s.points[0] = a.points;
  s.points[1] = b.points;
  prm::distance_to_surface(a, tree, &s.dist[0]);
  prm::distance_to_surface(b, input_tree, &s.dist[1]);
}

double local_max(const Stage& s, const Vec3& p, double radius) {
  double m = 0;
  for (int d = 0; d < 2; ++d)
    for (size_t i = 0; i < s.points[d].size(); ++i)
      if (prm::norm2(s.points[d][i] - p) <= radius * radius) m = std::max(m, s.dist[d][i]);
  return m;
}

Vec3 face_normal(const Mesh& m, const prm::Tri& t) {
  return prm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
}

// The largest angle between the normals of two input faces that share an edge, both within `radius` of p (degrees).
double crease_near(const Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, const Vec3& p,
                   double radius) {
  double worst = 0;
  for (size_t v = 0; v < m.positions.size(); ++v) {
    if (prm::norm2(m.positions[v] - p) > radius * radius) continue;
    const auto& fs = vertex_faces[v];
    for (size_t i = 0; i < fs.size(); ++i)
      for (size_t j = i + 1; j < fs.size(); ++j) {
        const Vec3 a = face_normal(m, m.triangles[fs[i]]), b = face_normal(m, m.triangles[fs[j]]);
        const double na = prm::norm(a), nb = prm::norm(b);
        if (na <= 0 || nb <= 0) continue;
        const double c = std::clamp(prm::dot(a, b) / (na * nb), -1.0, 1.0);
        worst = std::max(worst, std::acos(c) * 180.0 / M_PI);
      }
  }
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s MESH TARGET_ERROR [K] [--max-error E] [--refine R] [--[no-]local-refinement]\n"
                 "  [--effort N] [--bits B] [--step-scale S] [--fill-holes]\n",
                 argv[0]);
    return 1;
  }
  prm::pipeline::PackOptions po;
  po.target_error = std::atof(argv[2]);
  size_t k = 8;
  double refine = 0, site_grid = 0.0065;
  const char* other = nullptr;
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--max-error" && i + 1 < argc) po.max_error = std::atof(argv[++i]);
    else if (a == "--refine" && i + 1 < argc) refine = std::atof(argv[++i]);
    else if (a == "--local-refinement") po.local_refinement = prm::pipeline::PackOptions::LocalRefinement::on;
    else if (a == "--no-local-refinement") po.local_refinement = prm::pipeline::PackOptions::LocalRefinement::off;
    else if (a == "--effort" && i + 1 < argc) po.effort = std::atoi(argv[++i]);
    else if (a == "--bits" && i + 1 < argc) po.bits = std::atoi(argv[++i]);
    else if (a == "--step-scale" && i + 1 < argc) po.step_scale = std::atof(argv[++i]);
    else if (a == "--fill-holes") po.fill_holes = true;
    else if (a == "--mesh" && i + 1 < argc) other = argv[++i];
    else if (a == "--grid" && i + 1 < argc) site_grid = std::atof(argv[++i]);
    else k = static_cast<size_t>(std::atoi(argv[i]));
  }
  Mesh input = prm::read_mesh(argv[1]);
  if (!prm::validate_mesh(input).ready_for_remesh()) input = prm::repair_mesh(input);
  const std::vector<std::vector<uint32_t>> vertex_faces = prm::faces_around_vertices(input);
  if (other != nullptr) {
    const Mesh mesh = prm::read_mesh(other);
    const double diagonal = prm::bbox_diagonal(input), grid = site_grid * diagonal;
    const prm::DistanceReport report = prm::metro_distance(input, mesh);
    std::printf("%s against %s: RMS %.3e, max %.3e (%.2fx the target)\n", other, argv[1], report.rel(report.rms),
                report.rel(report.max), report.rel(report.max) / po.target_error);
    for (const prm::DeviationSite& site : prm::worst_deviations(input, mesh, k, grid)) {
      const Vec3 p = site.a_to_b ? site.sample : site.closest;  // a point of the input
      std::printf("  %-5s %10.3e (%8.4f %8.4f %8.4f) crease %5.1f\n", site.a_to_b ? "in>pr" : "pr>in",
                  site.distance / diagonal, p[0], p[1], p[2], crease_near(input, vertex_faces, p, grid));
    }
    return 0;
  }
  const prm::pipeline::PackResult packed = prm::pipeline::pack(input, po);
  const auto decoded = prm::codec::decode(packed.stream.data(), packed.stream.size());
  if (!decoded.ok()) {
    std::fprintf(stderr, "the stream does not decode: %s\n", decoded.status.message.c_str());
    return 2;
  }
  const double grid = static_cast<double>(packed.remesh.prm.lattice.A) * packed.remesh.prm.frame.step;
  const double diagonal = prm::bbox_diagonal(input);
  std::printf("%s target %.3g: %zu bytes, bits %d, step scale %.4f, grid %.6g (%.4g of the diagonal), lambda %.3g\n",
              argv[1], po.target_error, packed.stream.size(), packed.bits, packed.step_scale, grid, grid / diagonal,
              packed.codec_options.height_lambda);

  std::vector<Stage> stages;
  auto remeshed = [&](const char* name, bool fit, double flip_weight, bool rounded, double refine = 0) {
    prm::remesh::RemeshOptions ro;
    ro.bits = packed.bits;
    ro.step_scale = packed.step_scale;
    ro.grid_size = grid;
    ro.fit_heights = fit;
    ro.error_flip_weight = flip_weight;
    // The refinement as pack runs it (set_refinement: the notch steps, the facing guard), at the bound R.
    if (refine > 0) prm::pipeline::set_refinement(ro, po.target_error, po.max_error, true, true);
    ro.refine_error = refine;
    Stage s;
    s.name = name;
    const prm::remesh::RemeshResult r = prm::remesh::remesh(input, ro);
    s.mesh = r.prm.mesh;
    if (refine > 0)
      if (rounded) std::printf("%s: %zu input vertices inserted, %zu refused; %zu vertices, %zu of %zu faces regular\n", name,
                  r.prm.stats.deviation_inserts, r.prm.stats.deviation_refused, r.prm.stats.vertices,
                  r.prm.stats.regular_faces, r.prm.stats.faces);
    if (rounded)
      for (Vec3& p : s.mesh.positions)
        for (int a = 0; a < 3; ++a)
          p[static_cast<size_t>(a)] = r.prm.frame.to_real(r.prm.frame.quantize(p[static_cast<size_t>(a)], a), a);
    stages.push_back(std::move(s));
    return r.prm;
  };
  const prm::remesh::PrmMesh prm = remeshed("remesh", true, po.error_flip_weight, false);
  remeshed("nofit", false, po.error_flip_weight, false);
  remeshed("noflip", true, -1, false);
  remeshed("rounded", true, po.error_flip_weight, true);
  if (refine > 0) remeshed("refunr", true, po.error_flip_weight, false, refine);
  if (refine > 0) remeshed("refined", true, po.error_flip_weight, true, refine);
  stages.push_back({"decoded", prm::pipeline::to_mesh(decoded.value), {}, {}, {}});

  const prm::AabbTree input_tree(input);
  prm::SamplingOptions so;
  so.samples = 10 * std::max(input.triangles.size(), prm.mesh.triangles.size());
  so.seed = 1;
  std::printf("%-8s %10s %10s %8s\n", "stage", "rms", "max", "max/rms");
  for (Stage& s : stages) {
    measure(s, input, input_tree, so);
    std::printf("%-8s %10.3e %10.3e %8.1f\n", s.name.c_str(), s.report.rel(s.report.rms), s.report.rel(s.report.max),
                s.report.max / s.report.rms);
  }

  const Stage& last = stages.back();
  const auto sites = prm::worst_deviations(input, last.mesh, k, grid);
  std::printf("sites (distances as fractions of the diagonal; local max within one grid size):\n");
  std::printf("%3s %-5s %10s %28s", "#", "dir", "distance", "position");
  for (const Stage& s : stages) std::printf(" %8s", s.name.c_str());
  std::printf(" %7s %9s\n", "crease", "irregular");
  for (size_t i = 0; i < sites.size(); ++i) {
    const prm::DeviationSite& site = sites[i];
    const Vec3 p = site.a_to_b ? site.sample : site.closest;  // a point of the input
    std::printf("%3zu %-5s %10.3e (%8.4f %8.4f %8.4f)", i, site.a_to_b ? "in>pr" : "pr>in", site.distance / diagonal,
                p[0], p[1], p[2]);
    for (const Stage& s : stages) std::printf(" %8.2e", local_max(s, p, grid) / diagonal);
    size_t irregular = 0;
    for (size_t v = 0; v < prm.mesh.positions.size(); ++v)
      if (prm.vertex_relief[v] < 0 && prm::norm2(prm.mesh.positions[v] - p) <= grid * grid) ++irregular;
    std::printf(" %7.1f %9zu\n", crease_near(input, vertex_faces, p, grid), irregular);
  }
  if (refine > 0) {
    const Stage& refined = stages[stages.size() - 2];
    std::printf("worst sites of the refined mesh:\n");
    for (const prm::DeviationSite& site : prm::worst_deviations(input, refined.mesh, k, grid))
      std::printf("  %-5s %10.3e (%8.4f %8.4f %8.4f)\n", site.a_to_b ? "in>pr" : "pr>in", site.distance / diagonal,
                  site.sample[0], site.sample[1], site.sample[2]);
  }
  return 0;
}

