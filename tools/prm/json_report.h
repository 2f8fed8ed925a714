// The one JSON schema of every `prm` command's --json report (docs/cli-json.md): the shared key names are defined
// here once, and every command builds its report through JsonReport so that bytes, bits per vertex, times and
// surface errors read the same everywhere. Errors in --json mode are one object on stderr (error_json()).
#pragma once

#include <chrono>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace prm::cli {

// Raised when a key's name or meaning changes (docs/cli-json.md "Versions").
inline constexpr int kJsonSchemaVersion = 1;

// The --json flag's help, the same in every command.
inline constexpr const char* kJsonFlagHelp =
    "Print the report as one JSON object (schema: docs/cli-json.md); an error is then also one JSON object on stderr";

// The shared keys (docs/cli-json.md "Shared keys").
namespace json_key {
inline constexpr const char* kSchema = "schema";                  // integer, kJsonSchemaVersion
inline constexpr const char* kCommand = "command";                // "encode", "decode", ...
inline constexpr const char* kInput = "input";                    // path as given
inline constexpr const char* kOutput = "output";                  // path as given ("" when none is written)
inline constexpr const char* kVertices = "vertices";              // of the mesh the command wrote or inspected
inline constexpr const char* kTriangles = "triangles";            // idem
inline constexpr const char* kBytes = "bytes";                    // object: "total" and the command's parts, bytes
inline constexpr const char* kBitsPerVertex = "bits_per_vertex";  // object: "total" and parts, 8 * bytes / vertices
inline constexpr const char* kSeconds = "seconds";                // wall-clock seconds of the command's work
inline constexpr const char* kDistance = "distance";              // object: surface distance to the input
inline constexpr const char* kError = "error";                    // object: why the command failed
inline constexpr const char* kTotal = "total";
}  // namespace json_key

// Wall-clock seconds since t0 (the "seconds" key).
double seconds_since(std::chrono::steady_clock::time_point t0);

class JsonReport {
 public:
  // {"schema": 1, "command": command}
  explicit JsonReport(const char* command);

  JsonReport& input(const std::string& path);
  JsonReport& output(const std::string& path);
  JsonReport& mesh_size(size_t vertices, size_t triangles);
  // "bytes": {"total": total, ...parts}, "bits_per_vertex": {"total": ..., one per part} (parts: name -> bytes; the
  // bits per vertex are left out when vertices is 0).
  JsonReport& bytes(size_t total, size_t vertices, const nlohmann::json& parts = nlohmann::json::object());
  JsonReport& seconds(double s);
  // "distance": symmetric Metro distances as fractions of the reference's bounding-box diagonal ("rms_rel",
  // "max_rel"), with the absolute values ("rms", "max") when the diagonal is known (> 0).
  JsonReport& distance(double rms_rel, double max_rel, double diagonal = 0);

  // Any other key of the command's own.
  nlohmann::json& operator[](const char* key) { return j_[key]; }
  nlohmann::json& json() { return j_; }
  // One line on stdout.
  void print() const;

 private:
  nlohmann::json j_;
};

// {"schema": 1, "error": {"code": exit_code, "name": name, "message": message}} as one line, for stderr.
std::string error_json(int exit_code, const char* name, const std::string& message);

}  // namespace prm::cli
