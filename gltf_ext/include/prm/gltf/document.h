// A glTF 2.0 asset as its JSON and its buffers' bytes: read from .glb or .gltf (data: URIs and files beside it),
// written as .glb or .gltf with one buffer. Everything the JSON holds is kept as it is (unknown extensions, extras,
// cameras, animations...); the functions of prm/gltf/*.h edit it in place.
//
// The JSON layer is parsed here with nlohmann-json rather than through tinygltf: tinygltf 2.7 refuses the
// spec-valid layouts compressed assets use (an `indices` accessor without a bufferView, a .gltf buffer without a
// uri: ../shared/guide/ECOSYSTEM.md §2.2) and rewrites what it does not model.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace prm::gltf {

struct Document {
  nlohmann::json json;                        // the asset's JSON (the GLB JSON chunk)
  std::vector<std::vector<uint8_t>> buffers;  // buffers[i]: bytes of json["buffers"][i] (empty: no data, e.g. a
                                              // meshopt fallback buffer)
  std::string path;                           // where it was read from (for messages)
};

// Throws prm::IoError if the file (or a buffer file beside a .gltf) cannot be read, prm::InputError naming the
// problem for anything malformed: a bad GLB header or chunk, JSON that does not parse, a buffer whose bytes are
// missing or shorter than its byteLength, a bufferView outside its buffer. Buffers that are not data: URIs are read
// only from regular files in the asset's folder or below it.
Document read_document(const std::string& path);

// True for a path ending in .glb or .gltf (any case).
bool is_gltf_path(const std::string& path);

// Writes the asset: .glb (one BIN chunk) or .gltf (the buffer as a data: URI), chosen by the extension. Unused
// accessors and bufferViews are dropped first and every bufferView is moved into one buffer, 4-byte aligned
// (compact()); `repack` false writes the buffers as they are (tests that build their own layouts). Throws
// prm::IoError when the file cannot be written.
void write_document(Document& doc, const std::string& path, bool repack = true);

// Drops accessors no primitive, skin, animation or EXT_mesh_gpu_instancing node uses, then bufferViews no accessor,
// image or compression extension uses, renumbering the references; then copies every bufferView into one buffer.
void compact(Document& doc);

// Appends `bytes` as a new bufferView (in a buffer of its own until compact()); returns its index.
// target: 34962 (ARRAY_BUFFER), 34963 (ELEMENT_ARRAY_BUFFER) or 0 (none).
int add_buffer_view(Document& doc, std::vector<uint8_t> bytes, int target = 0, int byte_stride = 0);

// The bytes of bufferView `index`, checked against its buffer; InputError naming `where` otherwise.
struct ByteSpan {
  const uint8_t* data = nullptr;
  size_t size = 0;
};
ByteSpan buffer_view_bytes(const Document& doc, int64_t index, const std::string& where);

// "meshes[2].primitives[0]" for messages.
std::string primitive_name(size_t mesh, size_t primitive);

// Adds / removes a name in extensionsUsed (and extensionsRequired when `required`); empty arrays are removed.
void declare_extension(Document& doc, const std::string& name, bool required);
void remove_extension_declaration(Document& doc, const std::string& name);

}  // namespace prm::gltf
