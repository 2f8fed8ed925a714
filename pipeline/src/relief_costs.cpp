#include "prm/pipeline/relief_costs.h"

#include <stdexcept>

#include "prm/remesh/relief_grids.h"

namespace prm::pipeline {

ReliefCosts relief_costs(const remesh::PrmMesh& prm, const codec::EncodeReport& report, const AabbTree& input_tree) {
  const size_t nv = prm.mesh.positions.size();
  const size_t reliefs = prm.relief_axis.size();
  if (!report.vertex_patch.empty() && report.vertex_patch.size() != nv)
    throw std::invalid_argument("relief_costs: the encode report is not of this mesh's stream");
  ReliefCosts out;
  out.prologue_bits = report.patch_prologue_bits;
  out.reliefs.assign(reliefs, ReliefCost{});
  for (size_t r = 0; r < reliefs; ++r) out.reliefs[r].grid = prm.grid_of(r);
  auto relief_of = [&](size_t v) -> int32_t {
    const int32_t r = v < prm.vertex_relief.size() ? prm.vertex_relief[v] : -1;
    return r >= 0 && static_cast<size_t>(r) < reliefs ? r : -1;
  };
  for (size_t v = 0; v < nv; ++v)
    if (const int32_t r = relief_of(v); r >= 0) ++out.reliefs[static_cast<size_t>(r)].lattice_vertices;
  // Each patch's bits per carried vertex, charged to the relief of each vertex it carries.
  std::vector<double> per_vertex(report.patch_costs.size(), 0.0);
  for (size_t p = 0; p < report.patch_costs.size(); ++p) {
    const codec::EncodeReport::PatchCost& c = report.patch_costs[p];
    const double bits = c.header_bits + c.height_bits;
    if (c.vertices > 0)
      per_vertex[p] = bits / c.vertices;
    else
      out.unattributed_bits += bits;  // a patch carrying no new vertex (its vertices all coded by earlier ones)
  }
  for (size_t v = 0; v < report.vertex_patch.size(); ++v) {
    const uint32_t p = report.vertex_patch[v];
    if (p == UINT32_MAX) continue;
    if (p >= per_vertex.size()) throw std::invalid_argument("relief_costs: a vertex of a patch the report lacks");
    if (const int32_t r = relief_of(v); r >= 0) {
      out.reliefs[static_cast<size_t>(r)].bits += per_vertex[p];
      ++out.reliefs[static_cast<size_t>(r)].carried_vertices;
    } else {
      out.unattributed_bits += per_vertex[p];
    }
  }
  const double grid = static_cast<double>(prm.lattice.A) * prm.frame.step;
  const remesh::ReliefErrorSample e = remesh::measure_relief_error(prm, input_tree, reliefs, grid);
  for (size_t r = 0; r < reliefs; ++r) {
    out.reliefs[r].area = e.area[r];
    out.reliefs[r].msq = e.msq[r];
    out.reliefs[r].msq_quarters = e.msq_quarters[r];
  }
  return out;
}

}  // namespace prm::pipeline
