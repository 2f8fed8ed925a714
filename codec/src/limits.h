// §4 Limits: constants of the format that bound what a decoder allocates.
#pragma once

#include <cstdint>

#include "prm/lattice.h"  // §3.3 kMinPositionBits, kMaxPositionBits

namespace prm::codec {

// §4.2 A range-coded block of L bytes (L >= 4) holds at most kMaxDecisionsPerByte * (L - 3) decisions
// (modelled or direct bits); this follows from the probability floor kProbMin = 127 (adaptive_model.h).
constexpr uint64_t kMaxDecisionsPerByte = 2880;

// §4.1 Hard caps, whatever the caller allows: corner indices (3 per triangle) must fit in int32.
constexpr uint64_t kHardMaxTriangles = uint64_t{1} << 29;
constexpr uint64_t kHardMaxVertices = uint64_t{1} << 28;

}  // namespace prm::codec
