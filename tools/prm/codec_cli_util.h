// Helpers shared by the codec sub-commands (encode, decode, info on .prm): file bytes, codec errors as
// prm::InputError with the spec section, and mesh conversion.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prm/codec.h"

namespace prm::cli {

std::vector<uint8_t> read_file_bytes(const std::string& path);             // throws prm::IoError
void write_file_bytes(const std::string& path, const std::vector<uint8_t>& bytes);  // throws prm::IoError
// "count_exceeds_stream at byte 53 (spec §4.3): ..."
std::string describe(const codec::Status& status);

}  // namespace prm::cli
