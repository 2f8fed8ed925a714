// Seven points of a triangle (barycentric coordinates, equal weights): the centroid first, then three towards the
// corners and three towards the edges' midpoints. The seam error flips' triangle error (error_flips.cpp) and the
// least-squares heights (height_fitting.cpp) take the same points the same way, a * w[0] + b * w[1] + c * w[2], so
// that the closest input faces the first finds for a face's points are the answers the second looks for on a face
// the flips left as it was (MergedMesh::sample_face).
#pragma once

#include "prm/remesh/resample.h"

namespace prm::remesh {

inline constexpr double kTriangleSamples[kTriangleErrorSamples][3] = {
    {1.0 / 3, 1.0 / 3, 1.0 / 3},   {2.0 / 3, 1.0 / 6, 1.0 / 6},   {1.0 / 6, 2.0 / 3, 1.0 / 6},
    {1.0 / 6, 1.0 / 6, 2.0 / 3},   {1.0 / 6, 5.0 / 12, 5.0 / 12}, {5.0 / 12, 1.0 / 6, 5.0 / 12},
    {5.0 / 12, 5.0 / 12, 1.0 / 6}};

}  // namespace prm::remesh
