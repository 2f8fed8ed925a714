// The PRM_mesh_compression extension (spec/PRM_mesh_compression/README.md): a primitive's geometry as a PRM stream.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prm/codec.h"
#include "prm/gltf/document.h"

namespace prm::gltf {

constexpr const char* kExtensionName = "PRM_mesh_compression";
constexpr int kExtensionVersion = 1;  // = the PRM stream's Version_Major it carries (spec/prm-format.md §3.2)

// The extension object of one primitive, checked ("Loader behaviour" item 1): InputError naming the field.
struct PrmPrimitive {
  int64_t buffer_view = -1;
  int version = 0;
};
bool has_prm_extension(const nlohmann::json& primitive);
PrmPrimitive parse_prm_extension(const Document& doc, size_t mesh, size_t primitive);

// Decodes the primitive's stream ("Loader behaviour" items 2-3): InputError for an unknown version, a stream that
// fails to decode or whose Version_Major differs from `version`. Positions are float64 (origin + q step).
codec::DecodedMesh decode_prm_primitive(const Document& doc, size_t mesh, size_t primitive);

// The extension's normals ("Normals"): per vertex the normalized sum of (p_b - p_a) x (p_c - p_a) over its
// triangles, (0, 0, 1) where that sum is zero. positions: 3 per vertex; returns 3 per vertex.
std::vector<double> regenerate_normals(const std::vector<double>& positions, const std::vector<uint32_t>& triangles);

// Makes the primitive carry `stream` (whose decoding is `decoded`): new POSITION (and NORMAL when the primitive
// has one) and indices accessors with the decoded counts and min/max, without data, or holding the decoded mesh
// when `fallback`; the extension object; the declaration (required unless `fallback`). Returns the bytes the
// stream and any fallback data take.
size_t attach_prm_stream(Document& doc, size_t mesh, size_t primitive, std::vector<uint8_t> stream,
                         const codec::DecodedMesh& decoded, bool fallback);

// Replaces the primitive's extension by ordinary accessors holding its decoded mesh (what a loader fills).
void expand_prm_primitive(Document& doc, size_t mesh, size_t primitive, const codec::DecodedMesh& decoded);

}  // namespace prm::gltf
