// The glTF side of `prm pack`, `prm unpack` and `prm info` (spec/PRM_mesh_compression/README.md): cmd_pack.cpp,
// cmd_unpack.cpp and cmd_info.cpp dispatch here when a path ends in .glb or .gltf.
#pragma once

#include <string>

#include "prm/pipeline/pack.h"

namespace prm::cli {

bool is_gltf_file_path(const std::string& path);

// The size of a file in bytes, 0 when it cannot be read (for the reports).
size_t file_size(const std::string& path);

// prm pack IN -o OUT.glb|.gltf: IN a glTF asset (every primitive it can carry compressed, the rest kept) or any mesh
// file (one primitive). Prints the per-primitive report (text or JSON).
void run_gltf_pack(const std::string& input, const std::string& output, const pipeline::PackOptions& options,
                   bool fallback, bool json);

// `prm pack` writes a .prm stream or a glTF asset: refuses (CLI::ValidationError, exit 1) an output named like a mesh
// file (.ply .obj .off .stl), and --fallback without a glTF output.
void check_pack_output(const std::string& output, bool fallback);

// prm pack IN.prm -o OUT.glb|.gltf: the stream as it is, in a one-primitive asset (no remeshing).
void wrap_prm_stream(const std::string& input, const std::string& output, bool fallback, bool json);

// prm pack IN.glb|.gltf -o OUT.prm: says on stderr that the scene is merged into one mesh and what a .prm stream
// does not hold (nothing for other inputs).
void note_gltf_to_prm(const std::string& input);

// prm unpack IN.glb|.gltf -o OUT.glb|.gltf: every compressed primitive (PRM, Draco, meshopt) decoded into ordinary
// accessors.
void run_gltf_unpack(const std::string& input, const std::string& output, bool json);

// prm info IN.glb|.gltf when the asset uses PRM_mesh_compression: its primitives, their streams and byte split.
// Returns false (nothing printed) for an asset without the extension.
bool print_gltf_prm_info(const std::string& path, bool json);

}  // namespace prm::cli
