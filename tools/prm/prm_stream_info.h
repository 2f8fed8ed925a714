// `prm info X.prm`: the container of a PRM stream (spec/prm-format.md §3): header fields and the bytes of every
// section. cmd_info.cpp dispatches here on the .prm extension.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace prm::cli {

bool is_prm_stream_path(const std::string& path);
// Prints the report (text, or one JSON object); throws prm::InputError (exit 2) for a stream that does not decode,
// after printing what it could (with --json, an object whose "error" holds the error's name, byte offset and spec
// section).
void print_prm_stream_info(const std::string& path, bool json);

// The stream's bytes in the three parts the paper's Table 1 reports (issue 6): connectivity (CLERS, §6),
// irregular triangles (LERS, §7) and geometry (patch headers, heights, positions: §8-§10), plus header and framing.
// {"total", "connectivity", "irregular", "geometry", "header_and_framing"}; throws prm::InputError on a bad container.
nlohmann::json stream_byte_split(const std::vector<uint8_t>& bytes);
// "connectivity 1234 B (0.41 bpv), irregular triangles ..., geometry ..." for a report line.
std::string describe_byte_split(const nlohmann::json& split, size_t vertices);

}  // namespace prm::cli
