// Issue 23: where a PRM stream's bytes go, relief by relief (`prm pack --relief-costs`, bench/relief_bound.py). The
// codec's encoder reports the bits of each patch of the patches section (codec::EncodeReport::patch_costs, §8-§9);
// here each patch's bits are shared among the reliefs of the vertices it carries, in proportion to their count, and
// put beside each relief's lattice vertices, area and squared distance to the input (remesh::measure_relief_error).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/codec.h"
#include "prm/remesh/relief_grids.h"
#include "prm/remesh/resample.h"

namespace prm::pipeline {

struct ReliefCost {
  int64_t grid = 0;                // the relief's grid size in quantization steps (§8.4.2)
  double bits = 0;                 // patch headers and heights charged to it
  uint32_t lattice_vertices = 0;   // its grid vertices in the remeshed mesh
  uint32_t carried_vertices = 0;   // of them, the ones whose positions the patches section carries
  double area = 0, msq = 0;        // measure_relief_error: its faces' area and mean squared distance (model units)
  std::array<double, remesh::ReliefErrorSample::kErrorQuarters> msq_quarters{};  // its faces' msq by quarter of area
};

struct ReliefCosts {
  std::vector<ReliefCost> reliefs;  // per relief id of prm
  double prologue_bits = 0;         // the patches section's fields and predictor table (EncodeReport)
  double unattributed_bits = 0;     // patch bits on vertices without a relief (none expected; named, not dropped)
};

// `report` must be the report of `prm`'s stream (encode_prm_mesh(prm, ...), vertex indices of prm.mesh); the tree is
// the input's. Throws std::invalid_argument when the report does not belong to prm (vertex counts differ).
ReliefCosts relief_costs(const remesh::PrmMesh& prm, const codec::EncodeReport& report, const AabbTree& input_tree);

}  // namespace prm::pipeline
