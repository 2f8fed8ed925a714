#include "prm_stream_info.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "codec_cli_util.h"
#include "prm/codec.h"
#include "prm/error.h"

namespace prm::cli {

bool is_prm_stream_path(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".prm";
}

void print_prm_stream_info(const std::string& path, bool json) {
  const std::vector<uint8_t> bytes = read_file_bytes(path);
  const auto info = codec::inspect(bytes.data(), bytes.size());
  if (!info.ok()) throw InputError("'" + path + "' is not a valid PRM stream: " + describe(info.status));
  const codec::StreamInfo& s = info.value;
  // Decoding tells the section contents apart (components, holes); a stream whose container is fine but whose
  // sections do not decode is still described, with the error.
  const auto dec = codec::decode(bytes.data(), bytes.size(), {});
  const double v = s.vertices ? s.vertices : 1;
  if (json) {
    nlohmann::json sections = nlohmann::json::array();
    for (const auto& sec : s.sections)
      sections.push_back({{"id", sec.id},
                          {"name", sec.name},
                          {"offset", sec.offset},
                          {"bytes", sec.size},
                          {"bits_per_vertex", 8.0 * sec.size / v}});
    nlohmann::json j = {
        {"file", path},
        {"format", "prm"},
        {"version", std::to_string(s.version_major) + "." + std::to_string(s.version_minor)},
        {"flags", s.flags},
        {"vertices", s.vertices},
        {"triangles", s.triangles},
        {"position_bits", s.frame.bits},
        {"origin", {s.frame.origin[0], s.frame.origin[1], s.frame.origin[2]}},
        {"step", s.frame.step},
        {"bbox_min", {s.bbox_min[0], s.bbox_min[1], s.bbox_min[2]}},
        {"bbox_max", {s.bbox_max[0], s.bbox_max[1], s.bbox_max[2]}},
        {"header_bytes", s.header_bytes},
        {"sections", sections},
        {"crc32", s.crc},
        {"total_bytes", s.total_bytes},
        {"bits_per_vertex", 8.0 * s.total_bytes / v},
        {"decodes", dec.ok()}};
    if (!dec.ok()) j["decode_error"] = describe(dec.status);
    std::printf("%s\n", j.dump().c_str());
    return;
  }
  std::printf("%s: PRM stream, format %u.%u, %llu bytes (%.3f bits/vertex)\n", path.c_str(), s.version_major,
              s.version_minor, static_cast<unsigned long long>(s.total_bytes), 8.0 * s.total_bytes / v);
  std::printf("  vertices %u, triangles %u, flags %u\n", s.vertices, s.triangles, s.flags);
  std::printf("  quantization: %d bits, origin (%.17g, %.17g, %.17g), step %.17g\n", s.frame.bits,
              s.frame.origin[0], s.frame.origin[1], s.frame.origin[2], s.frame.step);
  std::printf("  bounding box (quantized): [%u, %u] x [%u, %u] x [%u, %u]\n", s.bbox_min[0], s.bbox_max[0],
              s.bbox_min[1], s.bbox_max[1], s.bbox_min[2], s.bbox_max[2]);
  std::printf("  %-14s %10s %10s %10s\n", "part", "offset", "bytes", "bits/vert");
  std::printf("  %-14s %10d %10llu %10.3f\n", "header", 0, static_cast<unsigned long long>(s.header_bytes),
              8.0 * s.header_bytes / v);
  for (const auto& sec : s.sections)
    std::printf("  %-14s %10llu %10llu %10.3f\n", sec.name, static_cast<unsigned long long>(sec.offset),
                static_cast<unsigned long long>(sec.size), 8.0 * sec.size / v);
  std::printf("  %-14s %10llu %10d   CRC-32 %08X\n", "crc", static_cast<unsigned long long>(s.total_bytes - 4), 4,
              s.crc);
  if (dec.ok())
    std::printf("  decodes: yes\n");
  else
    std::printf("  decodes: no: %s\n", describe(dec.status).c_str());
}

}  // namespace prm::cli
