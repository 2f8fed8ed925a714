// The general-path candidate of `prm pack` (PackOptions::mode, issue 22): the input coded as it comes, through
// codec::encode (format 1.0, spec §6 and §10), at the smallest bit depth whose decoded mesh meets the target error.
// Never worse than not remeshing: pack() keeps it when its stream is smaller than the piecewise regular one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prm/codec.h"
#include "prm/mesh.h"
#include "prm/metro_distance.h"

namespace prm::pipeline {

// The bit depths the general candidate may use (codec::EncodeOptions::position_bits).
constexpr int kMinGeneralBits = 8;
constexpr int kMaxGeneralBits = 20;

struct GeneralPack {
  std::vector<uint8_t> stream;
  codec::EncodeReport report;
  int bits = 0;
  double rms = 0, max = 0;  // symmetric Metro distances of the decoded mesh to the input, fractions of the diagonal
  bool measured = false;    // rms and max measured (always for the depth kept; see pack_general)
  // The largest distance between a decoded vertex and the input vertex it codes, a fraction of the diagonal, when the
  // decoded triangles are the input's one for one (-1 otherwise): an upper bound of both Metro distances.
  double bound = -1;
  size_t zero_area = 0;     // decoded triangles of zero area (count_zero_area_triangles)
  double boundary_rms = 0;  // RMS distance of the decoded boundary vertices to the input's boundary, of the diagonal
  struct Trial {
    int bits = 0;
    size_t bytes = 0;
    double rms = -1;  // -1: not measured (the bit depth was decided by zero-area triangles or the bound)
  };
  std::vector<Trial> tried;  // every bit depth encoded, in the order tried
};

// bits > 0: that bit depth (target_error, when > 0, must still be met). bits = 0: the smallest of
// kMinGeneralBits..kMaxGeneralBits whose decoded mesh has an RMS distance to `reference` (the input's Metro
// reference) of at most `target` (bisection: the quantization error falls as the bit depth grows); `target` <= 0
// with bits = 0: 12 bits. Like every stream of pack (issue 17), the decoded mesh must have no triangle of zero area:
// a bit depth whose quantization collapses one does not meet the target either (an input with zero-area triangles
// of its own is left to the remesher). An open input's boundary (issue 22) must lie within the target too: the RMS
// distance of the decoded boundary vertices to the input's boundary polyline at most `target`. Throws prm::InputError with the codec's message when the general path refuses
// the mesh (non-manifold, ...), remesh::TargetNotReached when no bit depth meets the target. max_minor: the newest
// format 1.N the stream may need (PackOptions::max_minor; below 3, no CLERS seam context, §6.5.2). max_target > 0:
// the decoded mesh's maximum (Hausdorff) distance must be at most that too (PackOptions::max_error), also alone.
// Metro measures only the bit depths that need it (issue 21: it was most of the candidate's time): a depth whose
// decoded mesh has a zero-area triangle misses, and one whose displacement bound (GeneralPack::bound) is within the
// target and the maximum meets, without measuring; the depth kept is always measured. The choice is the one Metro at
// every depth would make.
GeneralPack pack_general(const Mesh& input, const MetroReference& reference, double target, int bits,
                         int max_minor = codec::kFormatMinorPatchGrids, double max_target = 0);

// The general stream's size at its fewest bits (kMinGeneralBits): one encode, no decode and no Metro. The stream
// grows with the bit depth (every residual carries one more bit per coordinate), so whatever depth pack_general would
// choose, its stream is at least about this large: pack() leaves the general candidate untried when a piecewise
// regular stream is already no larger (EffortPlan::general_floor_check, issue 21). Throws prm::InputError, as
// pack_general does, when the general path refuses the mesh.
size_t general_floor_bytes(const Mesh& input, int max_minor = codec::kFormatMinorPatchGrids);

}  // namespace prm::pipeline
