// §7-§9 The PRM sections' interface for the container code (codec_api_encode.cpp, codec_api_decode.cpp): the
// encoder's regularity check, and the patches section (§8 patch headers, §9 heights) on both sides. What the
// encoder (patch_encode.cpp) and the decoder (patch_decode.cpp) both run is in patch_shared.h.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "closed_mesh.h"
#include "prm/codec.h"

namespace prm::codec {

// §7.1 The encoder's regularity check, from the quantized positions cq (3 per closed-mesh vertex) and the grid
// sizes A (grids[0] = Grid_Size; more with format 1.5's grid table, §8.4.2): a triangle without dummy vertices is
// regular for axis a and grid g when its three vertices are lattice points of pair a / 2 (§8.1) of grid size
// grids[g] forming a unit grid triangle, counter-clockwise for a even, clockwise for a odd (the triangle faces the
// axis). The lowest grid index, then the lowest pair wins. Then, in one pass, every regular triangle with a regular
// neighbour of another axis or grid is made irregular (a patch has one axis and one grid, §8.2; demoting creates no
// new conflict). tri_axis: 0..5, or -1 for irregular and dummy triangles; tri_grid: the grid index of a regular one.
void classify_triangles(const ClosedMesh& mesh, const std::vector<uint32_t>& cq, const std::vector<int64_t>& grids,
                        std::vector<int8_t>& tri_axis, std::vector<uint8_t>& tri_grid);

struct PatchStats {
  uint32_t patches = 0;
  uint32_t patch_vertices = 0;
  uint32_t predicted_patches = 0;  // §9.7: patches coded by linear prediction
  // What each part cost, in bits of the range coder (RangeEncoder::bits(); EncodeReport::patch_costs): the section's
  // fields and predictor table before the first patch (§8.4, §9.7.2), then per patch (in section order) its header
  // (§8.4, §8.4.1, §8.4.2) and its heights (§9.7.4 Method included), and the vertices whose positions it carries.
  double prologue_bits = 0, coded_bits = 0;  // coded_bits: everything before the termination (§5.6)
  std::vector<double> header_bits, height_bits;
  std::vector<uint32_t> new_vertices;
  std::vector<uint32_t> vertex_patch;  // per closed-mesh vertex: the patch carrying its position, or UINT32_MAX
};

// §8-§9 How the encoder codes the patches section: its fields and the choices behind them.
struct PatchCoding {
  int bits = 0;                        // §3.3 quantization bits
  // §8.4 Grid_Size, then (Flags bit 4, format 1.5, when there is more than one) the extra grid sizes of §8.4.2's
  // table, in order; a regular triangle's lattice is grids[tri_grid[t]].
  std::vector<int64_t> grids;
  const std::vector<uint8_t>* tri_grid = nullptr;
  std::array<uint32_t, 3> box_lo{};    // §3.3 the header's quantized bounding box
  std::array<uint32_t, 3> box_hi{};
  int depth = 0;                       // §8.4 Height_Depth: 0..kMaxHeightDepth or kHeightDepthPredicted
  int overlap_depth = 0;               // §9.7.2 Overlap_Depth (linear prediction only)
  bool predict_every_patch = false;    // §9.7.4 Method 1 for every patch (else not for self-overlapping ones)
  bool contexts = false;               // Flags bit 3 (format 1.4)
};

// §8-§9 Encoder: the patches section for the regular triangles (tri_axis >= 0). `coding.depth` 0..kMaxHeightDepth:
// the heights by difference patches of that depth (§9.1-§9.3); kHeightDepthPredicted: by linear prediction (§9.7),
// the self-overlapping patches by difference patches of `overlap_depth`. Sets known[v] = 1 for every vertex of a
// patch (their positions are in this section). `coding.contexts`: Flags bit 3 (format 1.4): the bases from their
// references (§8.4.1) and the residuals' sign contexts (§9.7.4).
//
// `freedom` (optional, linear prediction only): the exact heights before rounding, how far from them a coded height
// may be and the Lagrange multiplier of the choice (PrmOptions::height_lambda); the encoder returns in `chosen`
// the positions it coded (cq with the heights it chose).
struct HeightFreedom {
  const std::vector<double>* exact = nullptr;  // 3 per closed-mesh vertex, in quantization steps
  double tolerance = 0;                        // in quantization steps; below 0.5 nothing changes
  double lambda = 0;                           // squared steps per bit; 0: nothing changes
  int sweeps = 0;                              // Appendix B.2 refinement sweeps (height_choice.h); 0: greedy only
};
Status write_patches(const ClosedMesh& mesh, const std::vector<uint32_t>& cq, const std::vector<int8_t>& tri_axis,
                     const PatchCoding& coding, std::vector<uint8_t>& payload, std::vector<uint8_t>& known,
                     PatchStats* stats, const HeightFreedom* freedom = nullptr,
                     std::vector<uint32_t>* chosen = nullptr);

// §8-§9 Decoder: positions of the patch vertices into q (3 per closed-mesh vertex), known[v] = 1 for them.
// cls: per triangle kRegular / kIrregular / kDummyTriangle (§7). vertex_corner: out, §10.2 Vertex_Corner of the
// mesh, which the patches need and read_positions reuses (built once per stream).
// contexts: Flags bit 3 (§8.4.1, §9.7.4); grids: Flags bit 4 (§8.4.2).
Status read_patches(const uint8_t* data, size_t size, uint64_t offset, const ClosedMesh& mesh, int bits,
                    const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi, bool contexts, bool grids,
                    const std::vector<uint8_t>& cls, std::vector<uint32_t>& q, std::vector<uint8_t>& known,
                    std::vector<uint32_t>& vertex_corner);

}  // namespace prm::codec
