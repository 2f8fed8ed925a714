// Paper §2.2-2.4: hexagonal resampling of the reliefs and their merging into one piecewise regular mesh.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prm/mesh.h"
#include "prm/remesh/lattice.h"

namespace prm {
class AabbTree;
}

namespace prm::remesh {

// A relief layout: a refined mesh whose faces are labelled by relief (see reliefs.h for how it is built).
struct LayoutInput {
  const Mesh* refined = nullptr;                      // 2-manifold, closed or with boundary (kept)
  const std::vector<int32_t>* face_relief = nullptr;  // relief id per refined face
  const std::vector<int>* relief_axis = nullptr;      // axis (0..5) per relief id
  const std::vector<int32_t>* source_face = nullptr;  // input face per refined face (null: the refined faces)
  const Mesh* input = nullptr;                        // the input mesh (reference normals); null: refined
};

// The seam error flips' weight on the valences they spoil (SeamOptions::error_flip_weight). Measured with `prm pack
// MODEL --target-error E --bits 10 --step-scale S --error-flip-weight W` (bytes at W = 1 / 2 / 4 / 8): feline (2.6e-4,
// S 1.09) 8,961 / 8,908 / 8,926 / 9,088; bunny (2e-4, S 1) 7,103 / 7,073 / 7,111 / 7,229 (flips of seam edges only;
// with the irregular edges inside reliefs too, at W = 2: 8,875 and 7,033).
constexpr double kDefaultErrorFlipWeight = 2.0;
// The points per triangle of the error flips' squared distance (error_flips.cpp), all of them;
// SeamOptions::error_samples takes the first ones (pack's effort 0 one, the centroid).
constexpr int kTriangleErrorSamples = 7;

struct PrmMesh;

struct ResampleOptions {
  QuantFrame frame;
  int64_t grid = 0;                    // grid size A in quantization steps (>= 2)
  // A grid size per relief id (spec §8.4.2, format 1.5), in quantization steps; empty: `grid` for every relief. At
  // most kMaxReliefGrids distinct sizes; reliefs of one axis pair and different grid sizes get different lattices
  // and are joined at their seam like reliefs of different pairs.
  std::vector<int64_t> relief_grid;
  double max_normal_angle_deg = 90.0;  // paper: no triangle may turn more than 90 degrees away
  bool parallel = true;                // resample reliefs concurrently
  bool fit_heights = true;             // move lattice vertices along their axes to the least-squares fit
  bool height_fit_reuse_faces = false;  // HeightFitOptions::reuse_faces
  int error_unit_stride = 1;           // SeamOptions::error_unit_stride
  int error_samples = kTriangleErrorSamples;  // SeamOptions::error_samples
  double error_flip_weight = kDefaultErrorFlipWeight;  // error flips (SeamOptions::error_flip_weight; < 0: none)
  // Local refinement (deviation_refinement.h): input vertices farther than this from the merged mesh (model units)
  // are inserted as irregular vertices. <= 0: none.
  double max_deviation = 0;
  bool refine_thin_sheets = true;  // the refinement's thin-sheet steps (DeviationRefinementOptions::thin_sheets)
  bool refine_notches = true;  // its notch steps (DeviationRefinementOptions::lattice_moves .. stray_check)
  // With the notch steps: no step nor rounding makes a triangle face away from the input
  // (DeviationRefinementOptions::facing_guard; round_towards_input's facing_guard).
  bool refine_facing_guard = true;
  // With the notch steps: the refinement's rounds (DeviationRefinementOptions::max_rounds). 20 for `prm remesh`
  // (h22r: the horse's 135-degree crease was still being split in round 12); pack asks for 12 (pipeline::kPackRefineRounds).
  size_t refine_rounds = 20;
  // The AABB tree of the layout's input mesh, if the caller has one (null: built for each call; at 2M input
  // vertices that is 4.3M triangles, 470 MB and seconds a grid round).
  const AabbTree* input_tree = nullptr;
  // When set, receives the merged PRM with its fitted heights, before the local refinement and the separation of
  // quantized vertices (finish_resampled takes it on from there).
  PrmMesh* fitted = nullptr;
};

struct ResampleStats {
  size_t reliefs = 0;
  size_t generic_moves = 0;        // vertices nudged off grid lines (by less than 1e-5 quantization steps)
  size_t sliced_vertices = 0, sliced_faces = 0;
  size_t collapses = 0, cell_flips = 0, stuck = 0;
  size_t fill_triangles = 0, loops_broken = 0;
  size_t seam_collapses = 0, area_flips = 0, repairs = 0, unrepaired = 0;
  size_t valence_flips = 0, error_flips = 0;
  size_t vertices = 0, faces = 0, regular_faces = 0, lattice_vertices = 0;
  size_t heights_moved = 0, height_moves_reverted = 0;  // least-squares heights (height_fitting.h)
  size_t deviation_inserts = 0, deviation_refused = 0;    // local refinement (deviation_refinement.h)
  size_t deviation_moves = 0;                             // its rim moves (irregular vertices moved, none inserted)
  size_t deviation_rounded = 0;  // then vertices put on another rounding than the nearest (round_towards_input)
  size_t deviation_facing_skipped = 0;  // deviations left since their places faced away from the input
  // Quantization (quantized_separation.h): faces that lost their area and vertices that shared a position when
  // rounded to the frame, the vertices moved so that none does, and what is left (faces and vertices).
  size_t quantized_degenerate = 0, quantized_rounding_turned = 0, quantized_coincident = 0, quantized_moves = 0,
         quantized_unresolved = 0,
         quantized_turned = 0,      // faces the last separation pass left facing away from the input
         quantized_collapses = 0;   // edges whose ends could only share a point, collapsed
  double seconds_slice = 0, seconds_merge = 0;
};

// The piecewise regular mesh and its labels.
// The most distinct grid sizes of one PRM (the codec's grid table, spec §8.4.2).
constexpr size_t kMaxReliefGrids = codec::kMaxGridSizes;

struct PrmMesh {
  Mesh mesh;  // positions, and the properties/comments of docs/ARCHITECTURE.md "The PRM file"
  QuantFrame frame;
  HexLattice lattice;                   // the grid size of ResampleOptions::grid (the stream's Grid_Size)
  std::vector<int> relief_axis;         // per relief id
  std::vector<int64_t> relief_grid;     // per relief id: its grid size in quantization steps (spec §8.4.2)
  int64_t grid_of(size_t relief) const { return relief < relief_grid.size() ? relief_grid[relief] : lattice.A; }
  std::vector<int32_t> vertex_relief;   // relief of a grid vertex, -1 otherwise
  std::vector<int32_t> lattice_i, lattice_j;
  std::vector<int32_t> face_relief;     // relief of the face's grid vertices when all agree, -1 otherwise
  std::vector<uint8_t> face_regular;    // projects onto a grid triangle of its relief
  ResampleStats stats;
};

PrmMesh resample_and_merge(const LayoutInput& layout, const ResampleOptions& options);

// resample_and_merge's last steps (the local refinement at options.max_deviation, the separation of quantized
// vertices) on `fitted`, the PRM that ResampleOptions::fitted received from resample_and_merge with the same layout
// and grid: the same PRM as resample_and_merge(layout, options) gives, without resampling again
// (RemeshOptions::refine_last).
PrmMesh finish_resampled(PrmMesh fitted, const LayoutInput& layout, const ResampleOptions& options);

// Regular patches: connected sets of regular triangles across shared edges (paper §3.3; the codec derives the
// same sets, spec §8.2).
size_t count_regular_patches(const PrmMesh& prm);

// Attaches the labels as PLY properties and comments (docs/ARCHITECTURE.md) / reads them back.
void store_prm_labels(PrmMesh& prm);
PrmMesh load_prm_labels(Mesh mesh);  // throws prm::InputError when the labels are missing or inconsistent

// Is triangle (a, b, c), given by lattice coordinates, a grid triangle facing `axis` in this vertex order?
bool is_grid_triangle(int axis, const std::array<int64_t, 2>& a, const std::array<int64_t, 2>& b,
                      const std::array<int64_t, 2>& c);
// Sets face_relief[f] and face_regular[f] from the labels of the face's corners.
void label_face(PrmMesh& prm, size_t f);

}  // namespace prm::remesh
