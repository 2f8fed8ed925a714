// A PRM stream's bytes by part (connectivity, irregular triangles, geometry, header and framing): `prm info` of a
// .prm stream and of a glTF asset's PRM streams.
#include "prm_stream_info.h"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "codec_cli_util.h"
#include "prm/codec.h"
#include "prm/error.h"

namespace prm::cli {

namespace {

enum class Part { connectivity, irregular, geometry };

// Sections by name (codec::inspect): §6 connectivity; §7 irregular triangles; everything else is geometry.
Part part_of(const std::string& section) {
  if (section.find("connectivity") != std::string::npos) return Part::connectivity;
  if (section.find("irregular_triangles") != std::string::npos || section.find("lers") != std::string::npos)
    return Part::irregular;
  return Part::geometry;
}

}  // namespace

nlohmann::json stream_byte_split(const std::vector<uint8_t>& bytes) {
  const auto info = codec::inspect(bytes.data(), bytes.size());
  if (!info.ok()) throw InputError("not a valid PRM stream: " + describe(info.status));
  uint64_t parts[3] = {0, 0, 0}, payload = 0;
  for (const auto& sec : info.value.sections) {
    parts[static_cast<int>(part_of(sec.name))] += sec.size;
    payload += sec.size;
  }
  return {{"total", info.value.total_bytes},
          {"connectivity", parts[0]},
          {"irregular", parts[1]},
          {"geometry", parts[2]},
          {"header_and_framing", info.value.total_bytes - payload}};
}

std::string describe_byte_split(const nlohmann::json& split, size_t vertices) {
  const double v = vertices ? static_cast<double>(vertices) : 1.0;
  char buf[512];
  auto part = [&](const char* key) { return split[key].get<uint64_t>(); };
  std::snprintf(buf, sizeof buf,
                "connectivity %llu B (%.3f bpv), irregular triangles %llu B (%.3f bpv), geometry %llu B (%.3f bpv), "
                "header and framing %llu B; total %llu B (%.3f bpv)",
                static_cast<unsigned long long>(part("connectivity")), 8.0 * part("connectivity") / v,
                static_cast<unsigned long long>(part("irregular")), 8.0 * part("irregular") / v,
                static_cast<unsigned long long>(part("geometry")), 8.0 * part("geometry") / v,
                static_cast<unsigned long long>(part("header_and_framing")),
                static_cast<unsigned long long>(part("total")), 8.0 * part("total") / v);
  return buf;
}

}  // namespace prm::cli
