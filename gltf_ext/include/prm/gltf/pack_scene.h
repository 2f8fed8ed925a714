// `prm pack IN.glb -o OUT.glb`: every triangle primitive the PRM stream can carry remeshed and compressed in its own
// frame (pipeline::pack), everything else of the scene kept as it was (spec/PRM_mesh_compression/README.md).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "prm/gltf/decompress.h"
#include "prm/gltf/document.h"
#include "prm/mesh.h"
#include "prm/pipeline/pack.h"

namespace prm::gltf {

struct ScenePackOptions {
  pipeline::PackOptions pack;
  bool fallback = false;  // also store the decoded geometry uncompressed (the extension is then not required)
};

struct PrimitiveReport {
  size_t mesh = 0, primitive = 0;
  std::string mesh_name;
  bool compressed = false;
  std::string reason;        // why it was kept as it was (empty when compressed)
  std::string input_codec;   // "" (plain accessors), KHR_draco_mesh_compression, EXT_meshopt_compression, ...
  size_t vertices_in = 0, triangles_in = 0;    // of the input primitive (before welding)
  size_t vertices_out = 0, triangles_out = 0;  // decoded
  size_t bytes_in = 0;       // its geometry in the input: accessor data, or the compressed data it came in
  size_t bytes_out = 0;      // the PRM stream, plus the fallback data with --fallback
  size_t stream_bytes = 0;
  double rms = 0, max = 0;   // symmetric Metro distances between input and decoded primitive, fraction of the
  double diagonal = 0;       // input primitive's bounding-box diagonal (model units)
  int bits = 0;
  bool repaired = false;     // holes or defects were fixed before remeshing
  // Boundary loops (issue 22, as `prm pack` reports them): of the input primitive (after pinch splits), of the
  // stream, and how many were filled (PackOptions::fill_holes); boundary_fallback: filled because the remesher could
  // not keep them (PackResult::boundary_fallback).
  size_t boundary_loops_in = 0, boundary_loops_out = 0, holes_filled = 0;
  bool boundary_fallback = false;
  std::string mode;          // the stream pipeline::pack kept: "prm" or "general" (PackOptions::mode)
  std::string mode_reason;   // why (PackResult::mode_reason)
};

struct ScenePackReport {
  std::vector<PrimitiveReport> primitives;
  DecompressReport input;
};

// Packs `doc` in place. Primitives already holding PRM_mesh_compression, Draco or meshopt data are decoded first and
// then treated as ordinary ones. Throws InputError for malformed input (naming it).
ScenePackReport pack_scene(Document& doc, const ScenePackOptions& options);

// A one-mesh, one-primitive asset (one node) holding `mesh`, for `prm pack mesh.ply -o out.glb`.
Document document_from_mesh(const Mesh& mesh, const std::string& name);

// The primitive's triangles in its own frame (TRIANGLES mode, plain accessors), coincident positions welded.
Mesh primitive_mesh(const Document& doc, size_t mesh, size_t primitive);

}  // namespace prm::gltf
