// Paper §2.2, the collapse rules of the resampling stage, as predicates on slice vertices:
// boundary vertices and grid vertices never move; a vertex moves only within its carrier (the smallest grid cell
// — grid edge or grid triangle — that contains it), so no collapsed edge crosses a grid edge unless it lies in one;
// and no triangle may turn more than 90 degrees away from the defining vector (checked by the caller).
#pragma once

#include "relief_slicing.h"

namespace prm::remesh {

inline bool is_movable(const SliceVertex& v) { return !v.boundary && v.kind != SliceKind::Lattice; }

// The two lattice endpoints of grid edge `segment` on line (family, value).
inline std::array<std::array<int64_t, 2>, 2> segment_ends(int family, int64_t value, int64_t segment) {
  switch (family) {
    case 0: return {{{value, segment}, {value, segment + 1}}};
    case 1: return {{{segment, value}, {segment + 1, value}}};
    default: return {{{value - segment, segment}, {value - segment - 1, segment + 1}}};
  }
}

// Is point y (a slice vertex) on grid edge (family, value, segment), endpoints included?
inline bool on_grid_edge(const SliceVertex& y, int family, int64_t value, int64_t segment) {
  if (y.kind == SliceKind::Crossing) return y.family == family && y.value == value && y.segment == segment;
  if (y.kind == SliceKind::Lattice) {
    const auto ends = segment_ends(family, value, segment);
    for (const auto& e : ends)
      if (e[0] == y.i && e[1] == y.j) return true;
  }
  return false;
}

// May x move onto y? (x movable; y anywhere in the closure of x's carrier.)
inline bool may_collapse_onto(const SliceVertex& x, const SliceVertex& y) {
  if (x.kind == SliceKind::Crossing) return on_grid_edge(y, x.family, x.value, x.segment);
  // x is a corner strictly inside grid triangle (x.i, x.j, x.upper).
  if (y.kind == SliceKind::Corner) return y.i == x.i && y.j == x.j && y.upper == x.upper;
  const int64_t i = x.i, j = x.j;
  if (!x.upper)
    return on_grid_edge(y, 1, j, i) || on_grid_edge(y, 0, i, j) || on_grid_edge(y, 2, i + j + 1, j);
  return on_grid_edge(y, 1, j + 1, i) || on_grid_edge(y, 0, i + 1, j) || on_grid_edge(y, 2, i + j + 1, j);
}

}  // namespace prm::remesh
