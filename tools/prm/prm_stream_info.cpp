#include "prm_stream_info.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "json_report.h"

#include "codec_cli_util.h"
#include "prm/codec.h"
#include "prm/error.h"
#include "prm/mesh_validate.h"
#include "prm/pipeline/codec_bridge.h"

namespace prm::cli {

bool is_prm_stream_path(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".prm";
}

namespace {

// The error of a stream that does not decode: spec §4.4's name, where it was found and the rule it breaks.
nlohmann::json error_json(const codec::Status& s) {
  return {{"name", codec::error_name(s.error)},
          {"byte_offset", s.byte_offset},
          {"spec_section", s.spec_section ? s.spec_section : ""},
          {"message", s.message}};
}

[[noreturn]] void invalid_stream(const std::string& path, const codec::Status& s) {
  throw InputError("'" + path + "' is not a valid PRM stream: " + describe(s));
}

}  // namespace

void print_prm_stream_info(const std::string& path, bool json) {
  const std::vector<uint8_t> bytes = read_file_bytes(path);
  const auto info = codec::inspect(bytes.data(), bytes.size());
  if (!info.ok()) {
    if (json) {
      JsonReport report("info");
      report.input(path).bytes(bytes.size(), 0);
      report["format"] = "prm";
      report["decodes"] = false;
      report["decode_error"] = describe(info.status);
      report["error"] = error_json(info.status);
      report.print();
    }
    invalid_stream(path, info.status);
  }
  const codec::StreamInfo& s = info.value;
  // The container is described whatever its sections hold; a stream is valid only if it decodes (the decoder's
  // memory follows what it decodes, spec §4.5, so a lying stream costs little here too). One that does not is
  // described with its error and is invalid input (exit 2).
  const auto dec = codec::decode(bytes.data(), bytes.size(), {});
  const double v = s.vertices ? s.vertices : 1;
  // The decoded mesh's boundary loops (the holes of spec §6.7: an open surface keeps them, issue 22).
  const size_t boundary_loops = dec.ok() ? validate_mesh(pipeline::to_mesh(dec.value)).boundary_loops : 0;
  if (json) {
    nlohmann::json sections = nlohmann::json::array();
    for (const auto& sec : s.sections)
      sections.push_back({{"id", sec.id},
                          {"name", sec.name},
                          {"offset", sec.offset},
                          {"bytes", sec.size},
                          {"bits_per_vertex", 8.0 * sec.size / v}});
    JsonReport report("info");
    report.input(path).mesh_size(s.vertices, s.triangles).bytes(s.total_bytes, s.vertices, stream_byte_split(bytes));
    nlohmann::json& j = report.json();
    j.update(nlohmann::json{
        {"format", "prm"},
        {"version", std::to_string(s.version_major) + "." + std::to_string(s.version_minor)},
        {"flags", s.flags},
        {"position_bits", s.frame.bits},
        {"origin", {s.frame.origin[0], s.frame.origin[1], s.frame.origin[2]}},
        {"step", s.frame.step},
        {"bbox_min", {s.bbox_min[0], s.bbox_min[1], s.bbox_min[2]}},
        {"bbox_max", {s.bbox_max[0], s.bbox_max[1], s.bbox_max[2]}},
        {"header_bytes", s.header_bytes},
        {"sections", sections},
        {"crc32", s.crc},
        {"decodes", dec.ok()}});
    if (dec.ok()) j["boundary_loops"] = boundary_loops;
    if (!dec.ok()) {
      j["decode_error"] = describe(dec.status);
      j["error"] = error_json(dec.status);
    }
    report.print();
    if (!dec.ok()) invalid_stream(path, dec.status);
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
  std::printf("  byte split: %s\n", describe_byte_split(stream_byte_split(bytes), s.vertices).c_str());
  if (dec.ok()) {
    std::printf("  decodes: yes, %zu boundary loop(s)\n", boundary_loops);
    return;
  }
  std::printf("  decodes: no: %s\n", describe(dec.status).c_str());
  std::fflush(stdout);
  invalid_stream(path, dec.status);
}

}  // namespace prm::cli
