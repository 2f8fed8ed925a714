// §6.1 The closed mesh: what the connectivity section (§6) decodes to and every later section (§7-§10) walks.
#pragma once

#include <cstdint>
#include <vector>

namespace prm::codec {

// §6.1 The closed mesh both sides agree on: triangles in forward order with canonical corners (§6.6), their
// opposite corners, and which vertices are dummies (§6.7).
struct ClosedMesh {
  uint32_t num_vertices = 0;             // dummies included
  std::vector<uint32_t> corner_vertex;   // 3 per triangle
  std::vector<int32_t> opp;              // 3 per triangle, all >= 0
  std::vector<uint8_t> is_dummy;         // per vertex
  // Decoder: per vertex, its triangle count capped at 255 (§7.3's valence context), as Spirale Reversi's records
  // counted them (§6.4.8); empty when not known (then lers_shared.h's vertex_valences counts the corners).
  std::vector<uint8_t> valence;
  // Decoder, when there are dummies (§6.7): the output triangles and the output id of each vertex (UINT32_MAX for
  // dummies). Without dummies the output is corner_vertex itself.
  std::vector<uint32_t> output_triangles;
  std::vector<uint32_t> old_to_new;
  uint32_t num_triangles() const { return static_cast<uint32_t>(corner_vertex.size() / 3); }
};

}  // namespace prm::codec
