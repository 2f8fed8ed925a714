// Every mesh a command can draw or measure: a mesh file (prm/mesh_io.h), a .prm stream (decoded, spec §2) or a glTF
// asset whose primitives are compressed (PRM_mesh_compression, Draco, meshopt: decoded first, gltf_ext/).
#pragma once

#include <string>

#include "prm/mesh.h"

namespace prm::cli {

// Throws prm::IoError for a file that cannot be opened, prm::InputError for one that does not decode.
Mesh read_any_mesh(const std::string& path);

}  // namespace prm::cli
