// §3.5 CRC-32 (ISO-HDLC / zlib: reflected polynomial 0xEDB88320, initial value and final xor 0xFFFFFFFF).
#pragma once

#include <cstddef>
#include <cstdint>

namespace prm::codec {

uint32_t crc32(const uint8_t* data, size_t size);

}  // namespace prm::codec
