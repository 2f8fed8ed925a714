// Paper §2.2, second half: constrained edge collapses that remove every vertex of a sliced relief that is not a
// grid vertex, keeping the relief's boundary fixed (collapse_rules.h). Where no legal collapse exists for a vertex,
// edge flips inside its grid cell lower its degree until one does (our addition; counted in the statistics).
#pragma once

#include <cstddef>

#include "relief_slicing.h"

namespace prm::remesh {

struct ResampledRelief {
  std::vector<SliceVertex> vertices;          // the survivors: grid vertices, boundary vertices, stuck vertices
  std::vector<std::array<int32_t, 3>> faces;  // indices into vertices
  size_t sliced_vertices = 0, sliced_faces = 0;
  size_t collapses = 0, flips = 0, stuck = 0;
};

ResampledRelief resample_relief(const SlicedRelief& sliced, int axis);

}  // namespace prm::remesh
