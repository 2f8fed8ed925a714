// Local refinement for a bounded worst-case error (issue 22): the hexagonal resampling (paper §2.2) cannot follow a
// feature narrower than the grid, so a thin tip (an ear, a hoof's edge, a tail) is cut off and the input's vertices
// there lie far from the piecewise regular mesh; they make its Hausdorff distance 25x its RMS error on the horse.
// This stage inserts irregular vertices where the mesh is farther than a bound from the input, in both directions:
// at the input vertices the mesh misses (in>pr), and at the input's closest point to a triangle's centroid or edge
// midpoint that strays from it (pr>in: a triangle bridging a notch, e.g. between an ear and the head). Each splits
// the closest triangle, or its closest edge, farthest deviation first, round after round until none is left or the
// budget is spent. The regular triangles away from the inserted vertices keep their connectivity.
// Thin sheets (DeviationRefinementOptions::thin_sheets) need more than a split of the closest face: a tip beyond a
// lattice corner, an input triangle longer than the bound whose vertices are near the mesh, a vertex left out on a
// tip, two triangles bridging a fold, a lattice vertex off a smooth part of the input (CGAL's bunny00); see there.
#pragma once

#include <cstddef>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/mesh.h"
#include "prm/remesh/resample.h"

namespace prm::remesh {

struct DeviationRefinementOptions {
  double max_deviation = 0;  // model units: input vertices farther than this from the mesh are inserted (<= 0: none)
  // At most this share of the mesh's vertices is inserted (hear: 3% ran out in round 8 on `prm remesh horse.ply
  // --target-error 2e-4`, the leg tip still 1.77x the bound away; pack at 2e-4 inserts 0.2-1.4%).
  double max_insert_share = 0.06;
  // Rounds of insertions (each measures the deviations of the refined mesh again; later rounds only the faces the
  // last one changed). The remesher's local refinement takes 20 (resample_pipeline.cpp's finish).
  size_t max_rounds = 12;
  // Thin sheets (issue 22, the cause of the worst case): before inserting a vertex, move an irregular vertex out to a
  // missed input point (a cut-off tip's rim) or back to the input (a mesh vertex that strays), move a lattice vertex
  // that strays along its relief's axis (its height: it keeps its lattice place), or flip an edge whose triangles
  // bridge a notch; measure the input's triangles near a missed vertex and every mesh triangle on a barycentric grid
  // about as fine as the bound (as Metro's samples find a place that strays between vertices); where the closest
  // point to a straying mesh point would turn a triangle over, put the new vertex along the normal (a notch's
  // bottom); keep a new vertex only when its triangles stray no further than the bound or the triangles they
  // replace; and where no split of the closest face reaches a missed point, split a face next to it that faces it.
  // false: only the closest face's splits (as the first local refinement did; bench/README.md "Worst-case error").
  bool thin_sheets = true;
  // The notch steps (h22thin2 and h22thin3; each needs thin_sheets). All of them false: the thin-sheet refinement of h22thin, query
  // for query (each closest-point query alone: a query started from a hint may answer with another of two faces as
  // close, and that face is the one split), which --max-error keeps (bench/README.md "Worst-case error", h22thin3).
  bool lattice_moves = true;  // a lattice vertex that strays moves along its relief's axis (its height)
  bool dense_probes = true;   // mesh triangles probed on the grid_divisions grid (false: centroid, edge midpoints)
  bool normal_reach = true;   // a straying point's new vertex may go along the normal, into the notch
  bool stray_check = true;    // a new vertex's triangles must not stray more than the bound or those they replace
  // A lattice vertex of a face that misses an input point moves along its axis towards it before a vertex is
  // inserted there (needs lattice_moves; h22thin3: fewer new vertices, bench/README.md "Worst-case error").
  bool lattice_reach = true;
  // Where every fixed place of a new vertex (the wanted point, along the normal, part of the way) turns a triangle
  // over or strays further, a pattern search near the split point for the place whose triangles stray least
  // (h22max5: the horse's ear, where the input's closest point lies on one face of a thin sheet and a vertex moved
  // towards it pushes the triangles off the other face). Needs stray_check.
  bool descent_placement = true;
  // A missed input point that every other step refused (the last one, after the split across the crease): the split
  // of its closest edge with the new vertex on the input, the input's closest point to each place between the edge
  // and the point (htail2's step, now last; h115: the horse's tail at 1.3e-4, a thin strand whose far side is nearer
  // a new face's centroid when the new vertex is off the input, so that face counts as facing away). Needs stray_check.
  bool reach_onto_input = true;
  // Every input triangle is probed for in>pr in the first round (not only those with a vertex near the bound), and
  // again when its worst probe comes near the bound or its closest faces change (h22max5: bunny_zipper).
  bool all_input_faces = true;
  // A mesh triangle whose dense probes come within 0.9x the bound is probed again on a grid twice as fine (needs
  // dense_probes; h22max6: the horse's worst place lay between the probes of a face at 0.99x the bound).
  bool fine_probes = true;
  // After the rounds, an end of a sharp edge whose midpoint strays past the bound is moved so that the edge follows
  // the input (hgroove: the horse's ear, a knife edge, where a split turns a face away from the input).
  bool groove_moves = true;
  // After the rounds, an inserted vertex whose fan of 3 or 4 triangles can be triangulated again without it, within
  // the bound, is removed (h22max8: needs thin_sheets and dense_probes).
  bool prune = true;
  // No change (a move, a split, a flip, a pruned fan) makes a triangle that faces away from the input
  // (input_facing.h: the normal against that of the input's face closest to the centroid, also with the corners at
  // their nearest rounding to prm.frame's step, or a corner on a point another vertex rounds to);
  // a place that would tries the next one (a part of the way, an edge split, the descent), else the site is left
  // (issue 22 item 3: the refinement folded triangles, issue 17's `turned`).
  bool facing_guard = true;
};

struct DeviationRefinementStats {
  size_t inserted = 0;  // vertices inserted
  size_t refused = 0;   // deviations left: every split would turn a triangle over
  size_t flipped = 0;   // edges flipped for a straying mesh point
  size_t moved = 0;     // vertex moves: irregular ones (a rim), lattice ones along their axis (their height)
  size_t rounds = 0;
  size_t pruned = 0;    // inserted vertices removed again (DeviationRefinementOptions::prune; `inserted` is net)
  size_t facing_refused = 0;  // places (moves, splits, flips, fans) refused as facing away from the input
  size_t facing_skipped = 0;  // deviations left or moved no further after such a refusal (part of `refused`, or a
                              // mesh vertex left where it was)
};

// prm: a merged PRM with its labels (the new vertices and triangles are labelled; all triangles are relabelled).
// input_tree: the input's closest-point tree.
// face_deviation2 (thin_sheets and dense_probes; may be null): set to the refined mesh's faces' squared worst probe
// distances (their grid_divisions grids), which round_towards_input needs.
DeviationRefinementStats refine_deviations(PrmMesh& prm, const Mesh& input, const AabbTree& input_tree,
                                           const DeviationRefinementOptions& options,
                                           std::vector<double>* face_deviation2 = nullptr);

// DeviationRefinementOptions::prune on its own (refine_deviations runs it after its rounds): prm's vertices from
// first_inserted on, each with a fan of 3 or 4 triangles, removed where the fan's ring triangulated again stays within
// `bound` (model units) of the input, with the fan's vertices unrounded and at their nearest rounding to prm.frame's
// step (there no worse than before, or within the bound). Returns how many were removed; prm's labels are not set.
size_t prune_inserted_vertices(PrmMesh& prm, size_t first_inserted, const Mesh& input, const AabbTree& input_tree,
                               double bound);
// After the refinement: the vertices near places straying more than 0.75x `bound` (model units) are put on the way of
// rounding them to prm.frame's step whose triangles and the vertex itself stray least from the input (the stream
// holds rounded coordinates; a lattice coordinate stays). Returns how many were put elsewhere than their nearest rounding.
// face_deviation2: refine_deviations' figures for prm's faces (null or another size: measured here).
// facing_guard: no rounding that leaves one of a vertex's triangles facing away from the input (input_facing.h).
size_t round_towards_input(PrmMesh& prm, const Mesh& input, const AabbTree& input_tree, double bound,
                           const std::vector<double>* face_deviation2 = nullptr, bool facing_guard = true);

}  // namespace prm::remesh
