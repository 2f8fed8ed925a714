// §7 The irregular-triangles section: its encoder (lers_encode.cpp) and decoder (lers_decode.cpp), for the container
// code. What both sides run is in lers_shared.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "closed_mesh.h"
#include "prm/codec.h"

namespace prm::codec {

// §7 Encoder: the payload for the irregular set (`irregular[t]` = 1 for irregular triangles; dummies excluded).
// valence_context: the §7.3 valence context (the stream's Flags bit 0).
void write_irregular_triangles(const ClosedMesh& mesh, const std::vector<uint8_t>& irregular, bool valence_context,
                               std::vector<uint8_t>& payload);

// §7 Decoder: fills cls (kRegular, kIrregular or kDummyTriangle per triangle).
Status read_irregular_triangles(const uint8_t* data, size_t size, uint64_t offset, const ClosedMesh& mesh,
                                bool valence_context, std::vector<uint8_t>& cls);

}  // namespace prm::codec
