#include "prm/pipeline/stream_check.h"

#include <array>
#include <unordered_map>

#include "prm/aabb_tree.h"
#include "prm/mesh_repair.h"
#include "prm/mesh_validate.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/vec3.h"

namespace prm::pipeline {

namespace {

struct PointHash {
  size_t operator()(const std::array<uint32_t, 3>& p) const {
    return (size_t{p[0]} * 73856093u) ^ (size_t{p[1]} * 19349663u) ^ (size_t{p[2]} * 83492791u);
  }
};

}  // namespace

StreamCheck check_decoded(const codec::DecodedMesh& decoded, const Mesh* reference) {
  StreamCheck c;
  c.zero_area = count_zero_area_triangles(decoded);
  std::unordered_map<std::array<uint32_t, 3>, uint32_t, PointHash> at;
  const size_t nv = decoded.num_vertices();
  at.reserve(nv);
  for (size_t v = 0; v < nv; ++v)
    ++at[{decoded.quantized[3 * v], decoded.quantized[3 * v + 1], decoded.quantized[3 * v + 2]}];
  for (const auto& [p, n] : at) c.coincident += n > 1 ? n : 0;
  if (!reference) return c;
  const Mesh m = to_mesh(decoded);
  const AabbTree tree(*reference);
  for (const Tri& t : m.triangles) {
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &d = m.positions[t[2]];
    const auto hit = tree.closest((a + b + d) * (1.0 / 3.0));
    const Tri& s = reference->triangles[hit.face];
    const Vec3 sn = triangle_normal_area2(reference->positions[s[0]], reference->positions[s[1]],
                                          reference->positions[s[2]]);
    c.turned += dot(triangle_normal_area2(a, b, d), sn) <= 0;
  }
  return c;
}

Mesh pack_reference(const Mesh& input) {
  return validate_mesh(input).ready_for_remesh() ? input : repair_mesh(input);
}

}  // namespace prm::pipeline
