// hdecode8: the decoder with an oracle for §5 (codec/src/entropy_trace.h, PRM_ENTROPY_ORACLE): the range decoder
// hands out a captured decode's decisions and direct-bit values from memory, so the decode costs everything but the
// range coder's arithmetic and model updates. Compiled in namespace prm_oracle (bench/CMakeLists.txt).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rans_in_situ.h"
#include "trace_capture.h"

namespace entropy_study {

// Decodes `data` with the capture's decisions; false if it fails or leaves some unused. positions, triangles: the
// decoded mesh.
bool oracle_decode(const uint8_t* data, size_t size, const Capture& capture, std::vector<float>& positions,
                   std::vector<uint32_t>& triangles);
// The same with the captured values handed out whole (PRM_ENTROPY_VALUE_ORACLE, namespace prm_values).
bool value_oracle_decode(const uint8_t* data, size_t size, const Capture& capture, std::vector<float>& positions,
                         std::vector<uint32_t>& triangles);
// The same with those values decoded from a static rANS scheme's streams (PRM_ENTROPY_RANS, namespace prm_rans).
bool rans_in_situ_decode(const uint8_t* data, size_t size, const Capture& capture, const in_situ::Input& input,
                         std::vector<float>& positions, std::vector<uint32_t>& triangles);

}  // namespace entropy_study
