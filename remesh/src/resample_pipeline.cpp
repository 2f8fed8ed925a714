// Paper §2.2-2.4 in sequence: genericity nudge, per-relief slicing and constrained collapses (in parallel), loop fill,
// seam optimization, labels.
#include <map>
#include <tbb/parallel_for.h>

#include <memory>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "deviation_refinement.h"
#include "height_fitting.h"
#include "loop_fill.h"
#include "prm/aabb_tree.h"
#include "prm/error.h"
#include "prm/progress.h"
#include "prm/remesh/resample.h"
#include "prm/vec3.h"
#include "quantized_separation.h"
#include "relief_mesh.h"
#include "relief_resampling.h"
#include "relief_slicing.h"
#include "seam_optimization.h"

namespace prm::remesh {

bool is_grid_triangle(int axis, const std::array<int64_t, 2>& a, const std::array<int64_t, 2>& b,
                      const std::array<int64_t, 2>& c) {
  auto neighbours = [](const std::array<int64_t, 2>& p, const std::array<int64_t, 2>& q) {
    return lattice_neighbours(q[0] - p[0], q[1] - p[1]);
  };
  if (!neighbours(a, b) || !neighbours(b, c) || !neighbours(c, a)) return false;
  const int64_t o = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
  return axis_sign(axis) > 0 ? o == 1 : o == -1;
}

void label_face(PrmMesh& prm, size_t f) {
  const Tri& t = prm.mesh.triangles[f];
  prm.face_relief[f] = -1;
  prm.face_regular[f] = 0;
  const int32_t r = prm.vertex_relief[t[0]];
  if (r < 0 || prm.vertex_relief[t[1]] != r || prm.vertex_relief[t[2]] != r) return;
  prm.face_relief[f] = r;
  auto ij = [&](uint32_t v) { return std::array<int64_t, 2>{prm.lattice_i[v], prm.lattice_j[v]}; };
  prm.face_regular[f] = is_grid_triangle(prm.relief_axis[static_cast<size_t>(r)], ij(t[0]), ij(t[1]), ij(t[2]));
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<Vec3> unit_face_normals(const Mesh& m) {
  std::vector<Vec3> n(m.triangles.size());
  for (size_t f = 0; f < n.size(); ++f) {
    const Tri& t = m.triangles[f];
    n[f] = normalized(triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  }
  return n;
}

// resample_and_merge's last steps on a merged PRM with fitted heights: the local refinement (max_deviation) and the
// separation of quantized vertices.
// centroid_faces: the fit's (HeightFitOptions::centroid_faces) at prm's positions, or null.
void finish(PrmMesh& prm, const Mesh& input, const AabbTree& tree, const ResampleOptions& options,
            const std::vector<uint32_t>* centroid_faces = nullptr) {
  ResampleStats& st = prm.stats;
  if (options.max_deviation > 0) {
    DeviationRefinementOptions dro;
    dro.max_deviation = options.max_deviation;
    dro.thin_sheets = options.refine_thin_sheets;
    dro.lattice_moves = dro.lattice_reach = dro.dense_probes = dro.normal_reach = dro.stray_check =
        dro.descent_placement = dro.all_input_faces = dro.reach_onto_input = options.refine_notches;
    dro.facing_guard = options.refine_notches && options.refine_facing_guard;
    // h22r: `prm remesh horse.ply --target-error 2e-4`'s 135-degree crease at (0.0258, 0.0157, -0.0200) was still
    // being split in round 12 (a lattice vertex 1.16x the bound from the input, its faces 1.2-1.3x) and the output
    // kept 1.715e-3 there (8.57x the target); with 16 rounds 1.573e-3, with 20 below 1.45e-3.
    if (options.refine_notches) dro.max_rounds = options.refine_rounds;
    std::vector<double> face_deviation2;
    const DeviationRefinementStats ds = refine_deviations(prm, input, tree, dro, &face_deviation2);
    st.deviation_inserts = ds.inserted;
    st.deviation_refused = ds.refused;
    st.deviation_moves = ds.moved;
    st.deviation_facing_skipped = ds.facing_skipped;
    // The rounding to the stream's step, chosen near the bound (--local-refinement only: --max-error keeps the first
    // thin-sheet refinement, bench/README.md "Worst-case error").
    if (options.refine_notches) {
      st.deviation_rounded = round_towards_input(prm, input, tree, options.max_deviation, &face_deviation2,
                                                 options.refine_facing_guard);
    }
    st.vertices = prm.mesh.positions.size();
    st.faces = prm.mesh.triangles.size();
    st.regular_faces = static_cast<size_t>(std::count(prm.face_regular.begin(), prm.face_regular.end(), 1));
  }
  // Last, since it places vertices exactly on quantization points: the stream must hold this mesh, not one with
  // collapsed triangles.
  const QuantizedSeparationStats qs = separate_quantized_vertices(
      prm, &input, &tree, options.max_deviation > 0 && options.refine_notches ? options.max_deviation : 0,
      options.max_deviation > 0 ? nullptr : centroid_faces);  // the refinement moves and adds vertices
  st.quantized_degenerate = qs.degenerate_faces;
  st.quantized_rounding_turned = qs.rounding_turned;
  st.quantized_coincident = qs.coincident_vertices;
  st.quantized_moves = qs.moved;
  st.quantized_unresolved = qs.unresolved;
  st.quantized_turned = qs.turned;
  st.quantized_collapses = qs.collapsed;
  if (qs.collapsed > 0) {  // fewer vertices and faces, and the faces that took a collapsed vertex's place relabelled
    st.vertices = prm.mesh.positions.size();
    st.faces = prm.mesh.triangles.size();
    st.regular_faces = static_cast<size_t>(std::count(prm.face_regular.begin(), prm.face_regular.end(), 1));
    st.lattice_vertices = static_cast<size_t>(
        std::count_if(prm.vertex_relief.begin(), prm.vertex_relief.end(), [](int32_t r) { return r >= 0; }));
  }
}

}  // namespace

PrmMesh resample_and_merge(const LayoutInput& layout, const ResampleOptions& options) {
  if (!layout.refined || !layout.face_relief || !layout.relief_axis)
    throw std::invalid_argument("resample_and_merge: incomplete layout");
  const auto t0 = std::chrono::steady_clock::now();
  PrmMesh prm;
  prm.frame = options.frame;
  prm.lattice = lattice_of_grid(options.grid, prm.frame.bits);
  prm.relief_axis = *layout.relief_axis;
  ResampleStats& st = prm.stats;
  st.reliefs = layout.relief_axis->size();
  // A grid size per relief (spec §8.4.2): the distinct sizes, the first being options.grid.
  if (!options.relief_grid.empty() && options.relief_grid.size() != st.reliefs)
    throw std::invalid_argument("relief_grid needs one grid size per relief");
  prm.relief_grid = options.relief_grid.empty() ? std::vector<int64_t>(st.reliefs, options.grid) : options.relief_grid;
  std::vector<HexLattice> lattices = {prm.lattice};
  std::vector<int> relief_lattice(st.reliefs, 0);
  for (size_t r = 0; r < st.reliefs; ++r) {
    size_t g = 0;
    while (g < lattices.size() && lattices[g].A != prm.relief_grid[r]) ++g;
    if (g == lattices.size()) lattices.push_back(lattice_of_grid(prm.relief_grid[r], prm.frame.bits));
    relief_lattice[r] = static_cast<int>(g);
  }
  if (lattices.size() > kMaxReliefGrids)
    throw std::invalid_argument("relief_grid: more than " + std::to_string(kMaxReliefGrids) + " grid sizes");
  int64_t finest = prm.lattice.A;
  for (const HexLattice& l : lattices) finest = std::min(finest, l.A);

  // A copy to nudge (make_generic): positions and triangles only, not the layout's properties.
  Mesh refined;
  refined.positions = layout.refined->positions;
  refined.triangles = layout.refined->triangles;
  const auto& face_relief = *layout.face_relief;
  if (face_relief.size() != refined.triangles.size()) throw std::invalid_argument("face_relief has the wrong size");
  for (int32_t r : face_relief)
    if (r < 0 || static_cast<size_t>(r) >= st.reliefs) throw std::invalid_argument("face_relief out of range");

  // An open edge (no face across) is part of the mesh boundary: a seam with no neighbour, which the slicing keeps
  // (its vertices are relief-boundary vertices), the merge leaves open and the seam passes never move.
  ReliefMeshView view;
  view.opposite = face_adjacency(refined);  // the nudge moves no vertex to another face: computed once for both
  st.generic_moves =
      make_generic(refined, face_relief, prm.relief_axis, view.opposite, prm.frame, lattices, relief_lattice);

  view.mesh = &refined;
  view.face_relief = &face_relief;
  view.relief_axis = &prm.relief_axis;
  view.source_face = layout.source_face;
  view.frame = prm.frame;
  view.lattices = lattices;
  view.relief_grid = relief_lattice;
  prepare_view(view);

  // Reliefs are independent: slice and collapse them in parallel, largest first.
  std::vector<std::vector<int32_t>> relief_faces(st.reliefs);
  for (size_t f = 0; f < face_relief.size(); ++f) relief_faces[static_cast<size_t>(face_relief[f])].push_back(static_cast<int32_t>(f));
  std::vector<size_t> order(st.reliefs);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return relief_faces[a].size() > relief_faces[b].size(); });
  std::vector<ResampledRelief> resampled(st.reliefs);
  {
    Progress progress("remesh: resampling reliefs", face_relief.size());
    auto work = [&](size_t k) {
      const size_t r = order[k];
      if (relief_faces[r].empty()) return;
      const SlicedRelief sliced = slice_relief(view, relief_faces[r], prm.relief_axis[r]);
      resampled[r] = resample_relief(sliced, prm.relief_axis[r]);
      progress.advance(relief_faces[r].size());
    };
    if (options.parallel)
      tbb::parallel_for(size_t{0}, order.size(), [&](size_t k) { work(k); }, tbb::simple_partitioner());
    else
      for (size_t k = 0; k < order.size(); ++k) work(k);
    progress.finish();
  }
  for (const ResampledRelief& r : resampled) {
    st.sliced_vertices += r.sliced_vertices;
    st.sliced_faces += r.sliced_faces;
    st.collapses += r.collapses;
    st.cell_flips += r.flips;
    st.stuck += r.stuck;
  }
  st.seconds_slice = seconds_since(t0);

  const auto t1 = std::chrono::steady_clock::now();
  MergedMesh merged = merge_reliefs(view, resampled);
  // The slicing's inputs are used up: the nudged copy, its adjacency and the per-relief face lists go before the
  // seam passes (and, without a lent tree, the input's AABB tree) allocate theirs.
  std::vector<ResampledRelief>().swap(resampled);
  view = ReliefMeshView();
  refined = Mesh();
  std::vector<std::vector<int32_t>>().swap(relief_faces);
  st.fill_triangles = merged.fill_triangles;
  const Mesh& input = layout.input ? *layout.input : *layout.refined;
  const std::vector<Vec3> normals = unit_face_normals(input);
  SeamOptions so;
  so.max_normal_angle_deg = options.max_normal_angle_deg;
  so.grid_length = static_cast<double>(finest) * prm.frame.step;
  so.error_flip_weight = options.error_flip_weight;
  so.error_unit_stride = options.error_unit_stride;
  so.error_samples = options.error_samples;
  // The input's tree: the caller's (pack's Metro reference holds one of the same mesh), or one built here.
  std::unique_ptr<AabbTree> own_tree;
  if (!options.input_tree) own_tree = std::make_unique<AabbTree>(input);
  const AabbTree& tree = options.input_tree ? *options.input_tree : *own_tree;
  const SeamStats ss = optimize_seams(merged, input, normals, tree, so);
  st.loops_broken = ss.loops_broken;
  st.seam_collapses = ss.boundary_collapses;
  st.area_flips = ss.area_flips;
  st.valence_flips = ss.valence_flips;
  st.error_flips = ss.error_flips;
  st.repairs = ss.repairs;
  st.unrepaired = ss.unrepaired;
  st.seconds_merge = seconds_since(t1);

  // Output and labels.
  const size_t nv = merged.vertices.size(), nf = merged.faces.size();
  prm.mesh.positions.resize(nv);
  prm.vertex_relief.assign(nv, -1);
  prm.lattice_i.assign(nv, 0);
  prm.lattice_j.assign(nv, 0);
  for (size_t v = 0; v < nv; ++v) {
    const MergedVertex& mv = merged.vertices[v];
    prm.mesh.positions[v] = mv.position;
    if (mv.lattice) {
      prm.vertex_relief[v] = mv.relief;
      prm.lattice_i[v] = static_cast<int32_t>(mv.i);
      prm.lattice_j[v] = static_cast<int32_t>(mv.j);
      ++st.lattice_vertices;
    }
  }
  prm.mesh.triangles.resize(nf);
  prm.face_relief.assign(nf, -1);
  prm.face_regular.assign(nf, 0);
  for (size_t f = 0; f < nf; ++f) {
    const auto& t = merged.faces[f];
    // A face on a vertex the merge removed is a remesher bug (CGAL's elephant-with-holes at 1e-4 makes one): an
    // error that says so, not a read out of bounds.
    for (size_t k = 0; k < 3; ++k)
      if (t[k] < 0 || static_cast<size_t>(t[k]) >= nv)
        throw std::logic_error("resample_and_merge: the merge left face " + std::to_string(f) + " on vertex " +
                               std::to_string(t[k]) + " of " + std::to_string(nv) + " (a remesher bug)");
    prm.mesh.triangles[f] = {static_cast<uint32_t>(t[0]), static_cast<uint32_t>(t[1]), static_cast<uint32_t>(t[2])};
    label_face(prm, f);
    st.regular_faces += prm.face_regular[f];
  }
  st.vertices = nv;
  st.faces = nf;
  std::vector<uint32_t> centroid_faces;  // the fit's, for the separation's first pass
  if (options.fit_heights) {
    HeightFitOptions ho;
    ho.reuse_faces = options.height_fit_reuse_faces;
    ho.closest_faces = &merged.sample_face;
    ho.centroid_faces = &centroid_faces;
    const HeightFitStats hs = fit_heights(prm, input, tree, ho);
    st.heights_moved = hs.moved;
    st.height_moves_reverted = hs.reverted;
  }
  if (options.fitted != nullptr) *options.fitted = prm;
  finish(prm, input, tree, options, &centroid_faces);
  store_prm_labels(prm);
  return prm;
}

PrmMesh finish_resampled(PrmMesh fitted, const LayoutInput& layout, const ResampleOptions& options) {
  const Mesh& input = layout.input ? *layout.input : *layout.refined;
  std::unique_ptr<AabbTree> own_tree;
  if (!options.input_tree) own_tree = std::make_unique<AabbTree>(input);
  finish(fitted, input, options.input_tree ? *options.input_tree : *own_tree, options);
  store_prm_labels(fitted);
  return fitted;
}

void store_prm_labels(PrmMesh& prm) {
  auto as_double = [](const auto& v) { return std::vector<double>(v.begin(), v.end()); };
  Mesh& m = prm.mesh;
  m.set_vertex_property("relief", ScalarType::Int32, as_double(prm.vertex_relief));
  m.set_vertex_property("lattice_i", ScalarType::Int32, as_double(prm.lattice_i));
  m.set_vertex_property("lattice_j", ScalarType::Int32, as_double(prm.lattice_j));
  m.set_face_property("relief", ScalarType::Int32, as_double(prm.face_relief));
  m.set_face_property("regular", ScalarType::UInt8, as_double(prm.face_regular));
  // Colours for viewing: regular triangles tinted by relief axis, irregular ones dark red.
  static const double palette[6][3] = {{230, 120, 120}, {120, 200, 120}, {120, 150, 230},
                                       {230, 200, 110}, {200, 130, 220}, {110, 210, 210}};
  std::vector<double> red(m.triangles.size()), green(m.triangles.size()), blue(m.triangles.size());
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    if (prm.face_regular[f]) {
      const int axis = prm.relief_axis[static_cast<size_t>(prm.face_relief[f])];
      red[f] = palette[axis][0];
      green[f] = palette[axis][1];
      blue[f] = palette[axis][2];
    } else {
      red[f] = 150;
      green[f] = 30;
      blue[f] = 30;
    }
  }
  m.set_face_property("red", ScalarType::UInt8, std::move(red));
  m.set_face_property("green", ScalarType::UInt8, std::move(green));
  m.set_face_property("blue", ScalarType::UInt8, std::move(blue));
  m.comments.erase(std::remove_if(m.comments.begin(), m.comments.end(),
                                  [](const std::string& c) { return c.rfind("prm-", 0) == 0; }),
                   m.comments.end());
  char buf[256];
  std::snprintf(buf, sizeof buf, "prm-frame bits %d origin %.17g %.17g %.17g step %.17g grid %lld", prm.frame.bits,
                prm.frame.origin[0], prm.frame.origin[1], prm.frame.origin[2], prm.frame.step,
                static_cast<long long>(prm.lattice.A));
  m.comments.push_back(buf);
  for (size_t r = 0; r < prm.relief_axis.size(); ++r) {
    std::string c = "prm-relief " + std::to_string(r) + " axis " + std::to_string(prm.relief_axis[r]);
    // Its own grid size (spec §8.4.2), when it is not the frame's.
    if (prm.grid_of(r) != prm.lattice.A) c += " grid " + std::to_string(prm.grid_of(r));
    m.comments.push_back(c);
  }
}

PrmMesh load_prm_labels(Mesh mesh) {
  PrmMesh prm;
  bool have_frame = false;
  long long grid = 0;
  for (const std::string& c : mesh.comments) {
    std::istringstream in(c);
    std::string tag;
    in >> tag;
    if (tag == "prm-frame") {
      std::string k1, k2, k3, k4;
      in >> k1 >> prm.frame.bits >> k2 >> prm.frame.origin[0] >> prm.frame.origin[1] >> prm.frame.origin[2] >> k3 >>
          prm.frame.step >> k4 >> grid;
      if (!in || k1 != "bits" || k2 != "origin" || k3 != "step" || k4 != "grid" || prm.frame.bits < 8 ||
          prm.frame.bits > 20 || !(prm.frame.step > 0) || !valid_grid_size(grid, prm.frame.bits))
        throw InputError("malformed 'prm-frame' comment: " + c);
      have_frame = true;
    } else if (tag == "prm-relief") {
      long long id = -1, own_grid = 0;
      std::string k, kg;
      int axis = -1;
      in >> id >> k >> axis;
      const bool parsed = static_cast<bool>(in);
      if (in >> kg >> own_grid) {
        if (kg != "grid") throw InputError("malformed 'prm-relief' comment: " + c);
      } else {
        own_grid = 0;
      }
      if (!parsed || k != "axis" || id < 0 || id > 1000000 || axis < 0 || axis > 5)
        throw InputError("malformed 'prm-relief' comment: " + c);
      if (prm.relief_axis.size() <= static_cast<size_t>(id)) {
        prm.relief_axis.resize(static_cast<size_t>(id) + 1, -1);
        prm.relief_grid.resize(static_cast<size_t>(id) + 1, 0);
      }
      prm.relief_axis[static_cast<size_t>(id)] = axis;
      prm.relief_grid[static_cast<size_t>(id)] = own_grid;  // 0: the frame's, set below
    }
  }
  if (!have_frame) throw InputError("not a PRM file: the 'prm-frame' comment is missing (run prm remesh first)");
  prm.lattice = HexLattice::with_grid(grid);
  for (int64_t& g : prm.relief_grid) {
    if (g == 0) g = grid;
    if (!valid_grid_size(g, prm.frame.bits))
      throw InputError("a 'prm-relief' grid size " + std::to_string(g) + " outside 2..2^bits");
  }
  auto column = [&](const Property* p, const char* what) -> const std::vector<double>& {
    if (!p) throw InputError(std::string("not a PRM file: the property '") + what + "' is missing");
    return p->values;
  };
  const auto& vr = column(mesh.find_vertex_property("relief"), "vertex relief");
  const auto& li = column(mesh.find_vertex_property("lattice_i"), "lattice_i");
  const auto& lj = column(mesh.find_vertex_property("lattice_j"), "lattice_j");
  prm.vertex_relief.assign(vr.begin(), vr.end());
  prm.lattice_i.assign(li.begin(), li.end());
  prm.lattice_j.assign(lj.begin(), lj.end());
  for (int32_t r : prm.vertex_relief)
    if (r < -1 || (r >= 0 && (static_cast<size_t>(r) >= prm.relief_axis.size() || prm.relief_axis[static_cast<size_t>(r)] < 0)))
      throw InputError("vertex relief label " + std::to_string(r) + " has no 'prm-relief' comment");
  if (const Property* fr = mesh.find_face_property("relief")) prm.face_relief.assign(fr->values.begin(), fr->values.end());
  if (const Property* rg = mesh.find_face_property("regular")) prm.face_regular.assign(rg->values.begin(), rg->values.end());
  prm.mesh = std::move(mesh);
  return prm;
}

size_t count_regular_patches(const PrmMesh& prm) {
  const Mesh& m = prm.mesh;
  const size_t nf = m.triangles.size();
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> first_face;  // directed edge -> face
  for (uint32_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) first_face[{m.triangles[f][k], m.triangles[f][(k + 1) % 3]}] = f;
  std::vector<uint32_t> parent(nf);
  for (uint32_t f = 0; f < nf; ++f) parent[f] = f;
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (uint32_t f = 0; f < nf; ++f) {
    if (!prm.face_regular[f]) continue;
    for (int k = 0; k < 3; ++k) {
      auto it = first_face.find({m.triangles[f][(k + 1) % 3], m.triangles[f][k]});
      if (it != first_face.end() && prm.face_regular[it->second]) parent[find(f)] = find(it->second);
    }
  }
  size_t patches = 0;
  for (uint32_t f = 0; f < nf; ++f) patches += prm.face_regular[f] && find(f) == f;
  return patches;
}

}  // namespace prm::remesh
