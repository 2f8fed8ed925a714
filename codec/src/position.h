// §10 The positions section: declarations for position_encode.cpp and position_decode.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "closed_mesh.h"
#include "prm/codec.h"

namespace prm::codec {

// q holds 3 quantized coordinates per closed-mesh vertex (dummies' entries are ignored), within [lo, hi].
// known (optional, PRM streams): vertices the patches section placed (§10.2); they are not coded here.
Status write_positions(const ClosedMesh& mesh, const std::vector<uint32_t>& q, const std::array<uint32_t, 3>& lo,
                       const std::array<uint32_t, 3>& hi, std::vector<uint8_t>& payload,
                       const std::vector<uint8_t>* known = nullptr);

// Fills q (3 per closed-mesh vertex; dummies get 0). With `known`, q already holds those vertices' positions and
// only the others are decoded. `vertex_corner`: §10.2 Vertex_Corner of the mesh if the caller has it (built here
// otherwise).
Status read_positions(const uint8_t* data, size_t size, uint64_t offset, const ClosedMesh& mesh,
                      const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi,
                      std::vector<uint32_t>& q, const std::vector<uint8_t>* known = nullptr,
                      const std::vector<uint32_t>* vertex_corner = nullptr);

}  // namespace prm::codec
