#include "json_report.h"

#include <cstdio>

namespace prm::cli {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

JsonReport::JsonReport(const char* command) {
  j_[json_key::kSchema] = kJsonSchemaVersion;
  j_[json_key::kCommand] = command;
}

JsonReport& JsonReport::input(const std::string& path) {
  j_[json_key::kInput] = path;
  return *this;
}

JsonReport& JsonReport::output(const std::string& path) {
  j_[json_key::kOutput] = path;
  return *this;
}

JsonReport& JsonReport::mesh_size(size_t vertices, size_t triangles) {
  j_[json_key::kVertices] = vertices;
  j_[json_key::kTriangles] = triangles;
  return *this;
}

JsonReport& JsonReport::bytes(size_t total, size_t vertices, const nlohmann::json& parts) {
  nlohmann::json b = parts, bpv = nlohmann::json::object();
  b[json_key::kTotal] = total;
  if (vertices)
    for (const auto& [name, value] : b.items())
      if (value.is_number()) bpv[name] = 8.0 * value.get<double>() / static_cast<double>(vertices);
  j_[json_key::kBytes] = b;
  if (vertices) j_[json_key::kBitsPerVertex] = bpv;
  return *this;
}

JsonReport& JsonReport::seconds(double s) {
  j_[json_key::kSeconds] = s;
  return *this;
}

JsonReport& JsonReport::distance(double rms_rel, double max_rel, double diagonal) {
  nlohmann::json d = {{"rms_rel", rms_rel}, {"max_rel", max_rel}};
  if (diagonal > 0) {
    d["rms"] = rms_rel * diagonal;
    d["max"] = max_rel * diagonal;
    d["diagonal"] = diagonal;
  }
  j_[json_key::kDistance] = d;
  return *this;
}

// Invalid UTF-8 (a path as the shell gave it) is replaced, not thrown: a report never fails on its own keys.
void JsonReport::print() const {
  std::printf("%s\n", j_.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
}

std::string error_json(int exit_code, const char* name, const std::string& message) {
  const nlohmann::json j = {{json_key::kSchema, kJsonSchemaVersion},
                            {json_key::kError, {{"code", exit_code}, {"name", name}, {"message", message}}}};
  // As print(): a path or a file's bytes quoted in the message may be invalid UTF-8.
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace prm::cli
