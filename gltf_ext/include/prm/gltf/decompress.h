// Turns what users' assets hold into ordinary accessors: primitives compressed with KHR_draco_mesh_compression
// (Draco's decoder), bufferViews compressed with EXT_meshopt_compression (meshoptimizer's decoders) and primitives
// with PRM_mesh_compression (our decoder). Quantized attributes (KHR_mesh_quantization) need no decoding: they are
// ordinary normalized or integer accessors, which read_accessor() reads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "prm/gltf/document.h"

namespace prm::gltf {

struct DecompressReport {
  size_t meshopt_views = 0;      // bufferViews decoded
  size_t draco_primitives = 0;   // primitives decoded
  size_t prm_primitives = 0;     // primitives decoded
  // Bytes each compressed primitive held in the input (the Draco or PRM bufferView), by (mesh, primitive).
  std::map<std::pair<size_t, size_t>, size_t> compressed_bytes;
  std::map<std::pair<size_t, size_t>, std::string> codec;  // "KHR_draco_mesh_compression", ...
};

// Decodes all of them in place and removes the extensions from the primitives / bufferViews and from
// extensionsUsed / extensionsRequired. InputError naming the primitive or bufferView and the field when an
// extension object is malformed or its data does not decode.
DecompressReport decompress(Document& doc);

// The two decoders one by one (decompress() calls them in this order).
size_t decode_meshopt_views(Document& doc);
size_t decode_draco_primitives(Document& doc, DecompressReport* report);
size_t decode_prm_primitives(Document& doc, DecompressReport* report);

}  // namespace prm::gltf
