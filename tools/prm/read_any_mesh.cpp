#include "read_any_mesh.h"

#include <filesystem>
#include <string>
#include <unistd.h>

#include "codec_cli_util.h"
#include "prm/error.h"
#include "prm/gltf/decompress.h"
#include "prm/gltf/document.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm_stream_info.h"

namespace prm::cli {
namespace {

Mesh decode_stream(const std::string& path) {
  const std::vector<uint8_t> bytes = read_file_bytes(path);
  codec::DecodeOptions dopt;
  dopt.positions = codec::PositionOutput::quantized_only;
  const auto dec = codec::decode(bytes.data(), bytes.size(), dopt);
  if (!dec.ok()) throw InputError("'" + path + "' is not a valid PRM stream: " + describe(dec.status));
  return pipeline::to_mesh(dec.value);
}

// The asset with every compressed primitive decoded, read as any glTF (its nodes place the primitives). The decoded
// asset goes through a temporary .glb: read_mesh() is the one reader that merges a scene.
Mesh read_compressed_gltf(const std::string& path) {
  gltf::Document doc = gltf::read_document(path);
  const gltf::DecompressReport report = gltf::decompress(doc);
  if (report.meshopt_views + report.draco_primitives + report.prm_primitives == 0) return read_mesh(path);
  const std::filesystem::path tmp = std::filesystem::temp_directory_path() /
                                    ("prm-render-" + std::to_string(::getpid()) + ".glb");
  try {
    gltf::write_document(doc, tmp.string());
    Mesh mesh = read_mesh(tmp.string());
    std::filesystem::remove(tmp);
    return mesh;
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

}  // namespace

Mesh read_any_mesh(const std::string& path) {
  if (is_prm_stream_path(path)) return decode_stream(path);
  if (gltf::is_gltf_path(path)) return read_compressed_gltf(path);
  return read_mesh(path);
}

}  // namespace prm::cli
