// prm/codec.h: the PRM bitstream encoder and decoder. The only public header of prm_codec.
//
// C++17 and the standard library only. The normative description of the format is spec/prm-format.md; section
// numbers quoted here (§N.M) refer to it.
//
// Safety contract
// - decode() and inspect() are safe on untrusted input: any byte string returns either a valid mesh or a Status
//   naming the error, the byte offset and the spec section. They never throw, never read outside the given buffer,
//   and never allocate more than the limits allow (§4): a claimed count is checked against the caller's limits and
//   against what the stream's byte length can possibly encode before anything is allocated.
// - encode() never throws either; a mesh it cannot encode (non-manifold, degenerate, index out of range, non-finite
//   coordinates) returns a Status that says why and where.
// - Out of memory (std::bad_alloc) inside the codec is returned as Error::out_of_memory.
//
// What is encoded (§6): an indexed triangle mesh whose edges each have one or two triangles with opposite
// orientations and whose vertices each have one fan of triangles (an oriented 2-manifold, possibly with boundaries,
// handles and several components). Vertices no triangle uses are dropped. The decoded mesh has the same triangles
// up to the order of vertices, of triangles and the rotation of each triangle's corners; the order is the one the
// spec defines (§6.6), and encode() reports it (EncodeReport::vertex_order / triangle_order). Positions are quantized
// to `bits` bits per coordinate in a frame (origin, step) (§10.1) and decode exactly to the quantized input.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prm/export.h"
#include "prm/lattice.h"
#include "prm/version.h"

namespace prm::codec {

// The library's version, PRM_VERSION_MAJOR * 10000 + PRM_VERSION_MINOR * 100 + PRM_VERSION_PATCH (prm/version.h):
// compare with PRM_VERSION_NUMBER to detect a header/library mismatch. Not the bitstream's format version (§3.2).
PRM_API uint32_t library_version();
PRM_API const char* library_version_string();

// Format version written by this encoder (§3.2). A decoder accepts major version kFormatMajor only.
constexpr uint8_t kFormatMajor = 1;
constexpr uint8_t kFormatMinor = 0;     // general-path streams (§3.2)
constexpr uint8_t kFormatMinorPrm = 1;        // PRM streams of format 1.1 (§3.2): read, no longer written
constexpr uint8_t kFormatMinorPredicted = 2;  // PRM streams without the seam context: format 1.2 (§3.2, §7.3, §9.7)
constexpr uint8_t kFormatMinorSeam = 3;       // streams with the CLERS seam context: format 1.3 (§3.2, §6.5.2)
constexpr uint8_t kFormatMinorPatchContexts = 4;  // PRM streams with the patch contexts: format 1.4 (§3.2, §8.4.1, §9.7.4)
constexpr uint8_t kFormatMinorPatchGrids = 5;  // PRM streams with a grid size per patch: format 1.5 (§3.2, §8.4.2)

enum class Error : uint8_t {
  ok = 0,
  // Encoder: the caller's mesh or options.
  invalid_argument,          // option out of range, index out of range, non-finite coordinate, frame not valid
  degenerate_triangle,       // a triangle uses one vertex twice
  non_manifold_edge,         // an edge with three or more triangles
  inconsistent_orientation,  // two triangles traverse an edge in the same direction
  non_manifold_vertex,       // a vertex whose triangles form more than one fan (a "pinched" vertex)
  // Decoder: the stream.
  truncated,                 // a read past the end of the stream or of a section
  bad_magic,                 // not a PRM stream (§3.1)
  unsupported_version,       // major version not 1 (§3.2)
  bad_header,                // a header field outside its range (§3.3)
  bad_section,               // missing, repeated, out-of-order or unknown section, bad length (§3.4)
  unsupported_feature,       // a section or flag reserved for a later version (§3.4)
  count_exceeds_limit,       // a count larger than the caller's DecodeLimits (§4.1)
  count_exceeds_stream,      // a count larger than the stream's bytes can encode (§4.2)
  bad_connectivity,          // the connectivity data does not describe a valid mesh (§6)
  non_manifold_result,       // decoding produced a non-manifold or degenerate mesh (§6.8)
  bad_position,              // a decoded position outside the bounding box (§10)
  trailing_bytes,            // a section or the stream has bytes after its last field (§3.4, §5.6)
  crc_mismatch,              // the CRC-32 does not match (§3.5)
  out_of_memory,             // an allocation failed
  internal,                  // a bug: encoder self-check failed
};

// A stable lower_snake name for an error ("count_exceeds_stream").
PRM_API const char* error_name(Error error);

struct Status {
  Error error = Error::ok;
  std::string message;            // human-readable, names the field or the mesh element
  uint64_t byte_offset = 0;       // decoder: offset in the stream where the problem was detected
  const char* spec_section = "";  // the spec section whose rule was broken, e.g. "6.4"
  bool ok() const { return error == Error::ok; }
};

template <typename T>
struct Result {
  Status status;
  T value{};
  bool ok() const { return status.ok(); }
};

// §10.1 The quantization frame (Frame, quantize, dequantize) and the lattices of §8.1 are in prm/lattice.h.

// The frame ARCHITECTURE.md prescribes for positions xyz[3 * n]: origin = min corner of the bounding box,
// step = largest extent / (2^bits - 1) (1.0 when all points coincide); frame_of_points() of prm/lattice.h.
PRM_API Frame make_frame(const double* xyz, size_t num_vertices, int bits);
PRM_API Frame make_frame(const float* xyz, size_t num_vertices, int bits);

struct EncodeOptions {
  int position_bits = 12;  // 8..20; ignored by encode_quantized (the frame gives the bits)
  // §6.5.2 The CLERS seam context (format 1.3): -1 the smaller connectivity section of with and without, 0 never
  // (a 1.0 stream), 1 always. encode_quantized takes -1.
  int seam_context = -1;
};

// What encode() did; sizes in bytes.
struct EncodeReport {
  size_t total_bytes = 0;
  size_t header_bytes = 0;        // magic, version, header (§3.3)
  size_t connectivity_bytes = 0;  // section 1 payload (§6.3)
  size_t position_bytes = 0;      // section 2 payload (§10): all vertices, or a PRM's vertices outside the patches
  size_t irregular_bytes = 0;     // section 3 payload (§7): the irregular triangles (LERS), PRM streams only
  size_t patch_bytes = 0;         // section 4 payload (§8-§9): patch headers and heights, PRM streams only
  size_t framing_bytes = 0;       // section ids, lengths, CRC
  uint32_t vertices = 0;          // encoded (= decoded) vertex count
  uint32_t triangles = 0;
  uint32_t components = 0;
  uint32_t holes = 0;             // boundary loops closed by a dummy vertex (§6.7)
  uint32_t handles = 0;           // sum of component genera (§6.4.6)
  uint32_t unreferenced_dropped = 0;
  // PRM streams (encode_prm): what the encoder's regularity check found (§7.1) and the chosen height depth (§9.4).
  uint32_t regular_triangles = 0;
  uint32_t regular_patches = 0;
  uint32_t patch_vertices = 0;   // vertices whose positions the patches section carries
  uint32_t predicted_patches = 0;  // patches whose heights are coded by linear prediction (§9.7)
  uint32_t grid_sizes = 0;       // §8.4.2 grid sizes the stream holds: 1, or 2..8 with the grid table (format 1.5)
  int height_depth = -1;         // §9.4 0..6 (difference patches), 7 (linear prediction, §9.7); -1: not a PRM stream
  int overlap_depth = -1;        // §9.7.2 with height_depth 7: the self-overlapping patches' difference depth
  // PRM streams: what the patches section's parts cost (an encoder statistic, not in the stream), in bits of the
  // range coder's information (32 - log2 Range plus 8 per byte shifted out): the fields and predictor table before
  // the first patch (§8.4, §9.7.2), then per patch in section order its header (§8.4-§8.4.2) and heights (§9.7.4
  // Method included) and the vertices whose positions it carries. patch_bytes * 8 exceeds the sum of all of them by
  // the range coder's termination, 24 to 32 bits (§5.6). vertex_patch: per input vertex, the index of the patch
  // carrying its position, or UINT32_MAX (irregular vertices, section 2).
  struct PatchCost {
    double header_bits = 0, height_bits = 0;
    uint32_t vertices = 0;
  };
  double patch_prologue_bits = 0;
  std::vector<PatchCost> patch_costs;
  std::vector<uint32_t> vertex_patch;
  // Decoded vertex k is input vertex vertex_order[k]; decoded triangle k is input triangle triangle_order[k], with
  // its corners rotated so that decoded corner 0 is input corner triangle_rotation[k] (0..2).
  std::vector<uint32_t> vertex_order;
  std::vector<uint32_t> triangle_order;
  std::vector<uint8_t> triangle_rotation;
};

// Encodes triangles[3 * num_triangles] (vertex indices) over positions xyz[3 * num_vertices], quantized to
// options.position_bits bits in make_frame()'s frame. `report` may be null.
PRM_API Result<std::vector<uint8_t>> encode(const float* xyz, size_t num_vertices, const uint32_t* triangles,
                                    size_t num_triangles, const EncodeOptions& options = {},
                                    EncodeReport* report = nullptr);
PRM_API Result<std::vector<uint8_t>> encode(const double* xyz, size_t num_vertices, const uint32_t* triangles,
                                    size_t num_triangles, const EncodeOptions& options = {},
                                    EncodeReport* report = nullptr);
// Pre-quantized positions q[3 * num_vertices], each in [0, 2^frame.bits - 1], in the caller's frame (the PRM
// remesher's frame, so that lattice points stay exact).
// seam_context: as EncodeOptions::seam_context.
PRM_API Result<std::vector<uint8_t>> encode_quantized(const uint32_t* q, size_t num_vertices, const uint32_t* triangles,
                                              size_t num_triangles, const Frame& frame,
                                              EncodeReport* report = nullptr, int seam_context = -1);

// §9.4 Height_Depth 7: the heights by linear prediction (§9.7).
constexpr int kLinearPredictionDepth = 7;

// A piecewise regular mesh (spec §7-§9): positions pre-quantized in the frame whose lattices the mesh was built on
// (docs/ARCHITECTURE.md: lattice point (i, j) of axis pair k at (U, W) = (A i + B j, C j), quantized units).
struct PrmOptions {
  int64_t grid = 0;       // the lattice's grid size A in quantized units, 2 .. 2^bits
  // §8.4.2 A grid size per patch (format 1.5: Flags bit 4): further grid sizes the mesh's lattices use, each
  // 2 .. 2^bits, distinct from `grid` and from each other, at most 7. A triangle is regular on the first of grid,
  // extra_grids... it fits (§7.1). The stream's grid table holds the extra grids its regular triangles use; none
  // used (or none given): no table, the stream of the single grid. Empty: one grid for the whole mesh.
  std::vector<int64_t> extra_grids;
  // false: extra_grids are not used (a stream of one grid, format 1.4 or older: the triangles on the other grids are
  // coded as irregular).
  bool patch_grids = true;
  // §9.4 The heights' coding: 0..6 levels of difference patches (the paper's), 7 linear prediction (§9.7), -1 the
  // encoder tries them all and keeps the smallest.
  int height_depth = -1;
  // §9.7.2 With height_depth 7: the difference depth of self-overlapping patches, 0..6 (-1: 3, the paper's).
  int overlap_depth = -1;
  // §9.7.4 Linear prediction for every patch, also the self-overlapping ones (the encoder otherwise codes a patch
  // with more than 1/64 of its vertices on shared lattice points by difference patches). For tests.
  bool predict_every_patch = false;
  // Rate-distortion choice of the heights (spec Appendix B; encoder only, the stream is an ordinary one). With `unrounded` (3 per
  // input vertex: the coordinates in quantization steps before rounding, q = round(unrounded)), a tolerance of at
  // least 0.5 steps and lambda > 0, the height of each patch vertex coded by linear prediction (§9.7), unless it is
  // on a face of the bounding box or in regular triangles of two axis pairs, may be any integer within
  // `height_tolerance` of its unrounded value: the encoder codes the one minimising (height - unrounded)^2 +
  // height_lambda * (estimated bits of its residual). The decoded mesh then differs from q in those heights only,
  // by at most the tolerance. Defaults: lossless (decode gives q).
  double height_tolerance = 0;
  double height_lambda = 0;
  const double* unrounded = nullptr;
  // With that freedom, 1 per input vertex (optional): a nonzero entry keeps that vertex's heights rounded (q). The
  // caller's mask of places where the chosen heights would do harm (pipeline: triangles turned from the input).
  const uint8_t* rounded_heights = nullptr;
  // With that freedom, the heights chosen one by one are then refined together by this many sweeps of coordinate
  // descent, in which a height also weighs the residuals of the later heights it predicts (spec Appendix B.2),
  // 0..16; 0: each height alone, in coding order.
  int height_sweeps = 4;
  // §6.5.2 The CLERS seam context (format 1.3): -1 the smaller, 0 never (a 1.2 stream), 1 always.
  int seam_context = -1;
  // §8.4.1, §9.7.4 The patch contexts (format 1.4: Flags bit 3): each patch's base coded from an already placed
  // vertex next to it, the heights' residual signs with a context. false: a 1.2 or 1.3 stream.
  bool patch_contexts = true;
};

// Encodes a PRM: the encoder checks which triangles are regular (§7.1: three lattice neighbours forming a grid
// triangle that faces its axis), sends the others by LERS traversals (§7), the regular patches' headers and
// heights (§8, §9) and the remaining vertices by prediction (§10). A mesh without regular triangles is encoded as
// encode_quantized does. decode() reads both.
PRM_API Result<std::vector<uint8_t>> encode_prm(const uint32_t* q, size_t num_vertices, const uint32_t* triangles,
                                        size_t num_triangles, const Frame& frame, const PrmOptions& options,
                                        EncodeReport* report = nullptr);

// §4.1 Limits the caller sets; a stream asking for more is rejected with count_exceeds_limit before allocation.
struct DecodeLimits {
  uint64_t max_vertices = uint64_t{1} << 26;   // decoded vertices, dummy vertices included
  uint64_t max_triangles = uint64_t{1} << 27;  // decoded triangles, dummy triangles included (hard cap 2^29)
};

enum class PositionOutput : uint8_t { quantized_only, float32, float64 };

struct DecodeOptions {
  DecodeLimits limits;
  PositionOutput positions = PositionOutput::float32;
};

struct DecodedMesh {
  Frame frame;
  std::vector<uint32_t> triangles;     // 3 per triangle, in the order of §6.6
  std::vector<uint32_t> quantized;     // 3 per vertex, exact
  std::vector<float> positions_f32;    // 3 per vertex when options.positions == float32
  std::vector<double> positions_f64;   // 3 per vertex when options.positions == float64
  size_t num_vertices() const { return quantized.size() / 3; }
  size_t num_triangles() const { return triangles.size() / 3; }
};

PRM_API Result<DecodedMesh> decode(const uint8_t* data, size_t size, const DecodeOptions& options = {});

// The container of a stream (§3), for `prm info`: header fields and every section's place and size. Checks the
// magic, version, header ranges, section framing and the CRC; does not decode the sections.
struct SectionInfo {
  uint8_t id = 0;
  const char* name = "";
  uint64_t offset = 0;  // of the payload
  uint64_t size = 0;    // payload bytes
};
struct StreamInfo {
  uint8_t version_major = 0, version_minor = 0;
  uint8_t flags = 0;
  uint32_t vertices = 0, triangles = 0;
  Frame frame;
  std::array<uint32_t, 3> bbox_min{}, bbox_max{};  // quantized
  uint64_t header_bytes = 0;
  std::vector<SectionInfo> sections;
  uint32_t crc = 0;
  uint64_t total_bytes = 0;
};
PRM_API Result<StreamInfo> inspect(const uint8_t* data, size_t size);

}  // namespace prm::codec
