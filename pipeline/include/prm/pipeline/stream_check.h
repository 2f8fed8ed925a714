// What a decoded stream is checked for (issue 17): no triangle of zero area, no two vertices at one position, and
// every triangle facing the side of the surface it stands for (bench/zero_area_sweep.sh, the pack tests).
#pragma once

#include <cstddef>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/codec.h"
#include "prm/mesh.h"

namespace prm::pipeline {

struct StreamCheck {
  size_t zero_area = 0;   // triangles whose quantized corners are collinear or coincide (count_zero_area_triangles)
  size_t coincident = 0;  // vertices whose quantized position another vertex has too
  size_t turned = 0;      // triangles whose normal is 90 degrees or more from the normal of the reference's triangle
                          // nearest their centroid (the remesher's orientation test); 0 without a reference
};

// reference: the surface the stream was made from (the repaired input for `pack`), or null.
StreamCheck check_decoded(const codec::DecodedMesh& decoded, const Mesh* reference);
// StreamCheck::turned of mesh m against reference (whose tree is reference_tree).
size_t count_turned(const Mesh& m, const Mesh& reference, const AabbTree& reference_tree);
// A mesh and its turned triangles (turned_triangles), kept to test another mesh of the same triangles against.
struct TurnedTriangles {
  Mesh mesh;
  std::vector<size_t> turned;
};
// The triangles of m that count_turned counts, in m's order. known: where m has known->mesh's triangles, a triangle
// whose three corners are where they were there is taken from known->turned instead of being tested again (`pack`'s
// heights: the lambda streams of one mesh move some heights only).
std::vector<size_t> turned_triangles(const Mesh& m, const Mesh& reference, const AabbTree& reference_tree,
                                     const TurnedTriangles* known = nullptr);

// The largest distance from a vertex of m's triangles to the surface of `tree` (squared distances compared, the
// root taken once). It is at most the max of Metro's samples of m measured against that surface
// (MetroReference::compare's candidate-to-reference direction): every vertex of a triangle is one of those samples
// when MetroOptions::sample_vertices, and its distance is found through the same tree. So a mesh whose vertices
// already pass a bound passes it in Metro's max too (`pack`'s heights refuse such a lambda without its Metro run).
double vertex_distance_max(const Mesh& m, const AabbTree& tree);

// What `pack` remeshes: the mesh itself when the remesher takes it as it is, otherwise its repair (prm::InputError
// when it cannot be repaired).
Mesh pack_reference(const Mesh& input);

}  // namespace prm::pipeline
