// Packs a mesh file (OBJ, PLY, OFF, STL, glTF) into a .glb whose primitive holds a PRM_mesh_compression stream
// (prm::gltf, on top of prm::pipeline and prm::common), then reads the .glb back and decodes that primitive.
#include <cstdio>
#include <exception>
#include <string>

#include "prm/gltf/pack_scene.h"
#include "prm/gltf/prm_extension.h"
#include "prm/mesh_io.h"

int main(int argc, char** argv) {
  if (argc != 4) return std::fprintf(stderr, "usage: pack_glb MESH OUT.glb GRID_FRACTION\n"), 1;
  try {
    prm::gltf::Document doc = prm::gltf::document_from_mesh(prm::read_mesh(argv[1]), "mesh");
    prm::gltf::ScenePackOptions options;
    options.pack.grid_fraction = std::stod(argv[3]);  // grid size, fraction of the bounding-box diagonal
    const prm::gltf::PrimitiveReport p = prm::gltf::pack_scene(doc, options).primitives.at(0);
    prm::gltf::write_document(doc, argv[2]);
    const prm::codec::DecodedMesh back = prm::gltf::decode_prm_primitive(prm::gltf::read_document(argv[2]), 0, 0);
    std::printf("%zu triangles in, a %zu-byte PRM stream; the .glb decodes to %zu vertices, %zu triangles "
                "(RMS distance %.3g of the diagonal)\n",
                p.triangles_in, p.stream_bytes, back.num_vertices(), back.num_triangles(), p.rms);
    return p.compressed && back.num_triangles() == p.triangles_out ? 0 : 3;
  } catch (const std::exception& e) {
    return std::fprintf(stderr, "pack_glb: %s\n", e.what()), 2;
  }
}
