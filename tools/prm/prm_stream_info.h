// `prm info X.prm`: the container of a PRM stream (spec/prm-format.md §3): header fields and the bytes of every
// section. cmd_info.cpp dispatches here on the .prm extension.
#pragma once

#include <string>

namespace prm::cli {

bool is_prm_stream_path(const std::string& path);
// Prints the report (text, or one JSON object); throws prm::InputError for a malformed stream.
void print_prm_stream_info(const std::string& path, bool json);

}  // namespace prm::cli
