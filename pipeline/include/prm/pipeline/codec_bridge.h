// Conversions between the remesher's PrmMesh, prm::Mesh and the codec's flat arrays (prm/codec.h).
#pragma once

#include <cstdint>
#include <vector>

#include "prm/codec.h"
#include "prm/mesh.h"
#include "prm/remesh/resample.h"

namespace prm::pipeline {

// Encodes a piecewise regular mesh: positions quantized in the PRM's own frame (docs/ARCHITECTURE.md; the remesher's
// frame is the codec's, prm/lattice.h), so that grid vertices are lattice points in the integer coordinates the codec
// sees.
// `options`: the height coding (§9.4, §9.7); its grid is the PRM's.
codec::Result<std::vector<uint8_t>> encode_prm_mesh(const remesh::PrmMesh& prm, codec::EncodeReport* report,
                                                    const codec::PrmOptions& options = {});

// Encodes any mesh file's contents: a PRM (its PLY carries the prm-frame comment and lattice labels) through
// encode_prm_mesh, anything else through the general path at `bits` bits. `max_minor`: the newest format 1.N the
// stream may need (2: neither the seam context of 1.3 nor the patch contexts of 1.4; 3: no patch contexts; 4: one
// grid size, no grid table of 1.5).
codec::Result<std::vector<uint8_t>> encode_any_mesh(const Mesh& mesh, int bits, codec::EncodeReport* report,
                                                    bool* was_prm = nullptr,
                                                    int max_minor = codec::kFormatMinorPatchGrids);

// Encodes a mesh through the general path (spec §6, §10) at `bits` bits, whatever it carries (encode_any_mesh's
// branch for anything that is not a PRM; pack's general candidate). `max_minor` as above (below 3: no seam context).
codec::Result<std::vector<uint8_t>> encode_general_mesh(const Mesh& mesh, int bits, codec::EncodeReport* report,
                                                        int max_minor = codec::kFormatMinorPatchGrids);

// A decoded stream as a prm::Mesh (dequantized double positions).
Mesh to_mesh(const codec::DecodedMesh& decoded);

// Triangles of a decoded stream whose quantized corners are collinear or coincide (exactly zero area; the
// integer test, so no rounding decides it).
size_t count_zero_area_triangles(const codec::DecodedMesh& decoded);

// Vertices of a decoded stream whose quantized position another vertex has too (each such vertex counted).
size_t count_coincident_vertices(const codec::DecodedMesh& decoded);

}  // namespace prm::pipeline
