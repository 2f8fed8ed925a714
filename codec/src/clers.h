// §6 Connectivity: the interface between the container and the CLERS encoder (clers_encode.cpp, Edgebreaker) and
// decoder (clers_decode.cpp, Spirale Reversi).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "closed_mesh.h"
#include "prm/codec.h"
#include "spirale_reversi.h"

namespace prm::codec {

// Everything the encoder decided: the closed mesh plus the section's fields.
struct ConnectivityPlan {
  ClosedMesh mesh;
  std::vector<uint32_t> component_sizes;  // closed triangles per component, in forward order
  std::vector<HandleEvent> handles;       // sorted by triangle
  std::vector<uint32_t> dummies;          // vertex ids, increasing
  std::vector<uint8_t> symbols;           // per forward triangle; 0xFF for each component's first triangle
  std::vector<uint32_t> vertex_input;     // vertex id -> input vertex (UINT32_MAX for dummies)
  std::vector<uint32_t> triangle_input;   // forward triangle -> input triangle (UINT32_MAX for dummy triangles)
  std::vector<uint8_t> triangle_rotation; // input corner that is canonical corner 0
  uint32_t unreferenced = 0;
};

// Validates the input (indices, degenerate triangles, manifoldness), closes holes, runs Edgebreaker (§6.2).
Status plan_connectivity(const uint32_t* triangles, size_t num_triangles, size_t num_vertices,
                         ConnectivityPlan& plan);

// §6.3 Writes the connectivity section payload. Runs Spirale Reversi over the plan's symbols for the contexts, and
// checks that it rebuilds plan.mesh exactly (Error::internal otherwise). seam_context: §6.5.2's Seam input (the
// stream's Flags bit 2).
Status write_connectivity(const ConnectivityPlan& plan, bool seam_context, std::vector<uint8_t>& payload);

// §6.3-6.4 Reads the section at stream offset `offset`. `header_vertices` / `header_triangles` are the header's
// counts of the output mesh (dummies removed), checked against what the section decodes to. With dummies, also
// fills mesh.output_triangles and mesh.old_to_new (§6.7). `valences`: also fill mesh.valence (for §7.3's valence
// context, Flags bit 0).
Status read_connectivity(const uint8_t* data, size_t size, uint64_t offset, const DecodeLimits& limits,
                         uint32_t header_vertices, uint32_t header_triangles, bool seam_context, ClosedMesh& mesh,
                         bool valences = false);

}  // namespace prm::codec
