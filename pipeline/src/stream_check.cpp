#include "prm/pipeline/stream_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/mesh_repair.h"
#include "prm/mesh_validate.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/surface_facing.h"
#include "prm/vec3.h"

namespace prm::pipeline {

StreamCheck check_decoded(const codec::DecodedMesh& decoded, const Mesh* reference) {
  StreamCheck c;
  c.zero_area = count_zero_area_triangles(decoded);
  c.coincident = count_coincident_vertices(decoded);
  if (!reference) return c;
  c.turned = count_turned(to_mesh(decoded), *reference, AabbTree(*reference));
  return c;
}

size_t count_turned(const Mesh& m, const Mesh& reference, const AabbTree& reference_tree) {
  return turned_triangles(m, reference, reference_tree).size();
}

std::vector<size_t> turned_triangles(const Mesh& m, const Mesh& reference, const AabbTree& reference_tree,
                                     const TurnedTriangles* known) {
  // `known` answers for a triangle whose corners are where they were in known->mesh (the test reads only them).
  const bool same_triangles = known && known->mesh.triangles == m.triangles &&
                              known->mesh.positions.size() == m.positions.size();
  std::vector<uint8_t> known_turned;
  if (same_triangles) {
    known_turned.assign(m.triangles.size(), 0);
    for (const size_t i : known->turned) known_turned[i] = 1;
  }
  const auto same_corners = [&](const Tri& t) {
    return m.positions[t[0]] == known->mesh.positions[t[0]] && m.positions[t[1]] == known->mesh.positions[t[1]] &&
           m.positions[t[2]] == known->mesh.positions[t[2]];
  };
  std::vector<size_t> turned;
  for (size_t i = 0; i < m.triangles.size(); ++i) {
    const Tri& t = m.triangles[i];
    const bool is_turned =
        same_triangles && same_corners(t)
            ? known_turned[i] != 0
            : !faces_surface(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]], reference, reference_tree);
    if (is_turned) turned.push_back(i);
  }
  return turned;
}

double vertex_distance_max(const Mesh& m, const AabbTree& tree) {
  std::vector<uint8_t> used(m.positions.size(), 0);
  for (const Tri& t : m.triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  double max2 = 0;
  AabbTree::Hit hint;
  for (size_t v = 0; v < used.size(); ++v)
    if (used[v]) {
      tree.closest(m.positions[v], hint);
      max2 = std::max(max2, hint.distance2);
    }
  return std::sqrt(max2);
}

Mesh pack_reference(const Mesh& input) {
  return validate_mesh(input).ready_for_remesh() ? input : repair_mesh(input);
}

}  // namespace prm::pipeline
