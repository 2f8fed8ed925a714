#include "prm/mesh_repair.h"

#include <algorithm>
#include <map>

#include "prm/error.h"
#include "prm/mesh_validate.h"
#include "prm/vec3.h"

namespace prm {

Mesh repair_mesh(const Mesh& in, RepairReport* report) {
  RepairReport local;
  RepairReport& r = report ? *report : local;
  r = RepairReport{};
  Mesh m;
  m.positions = in.positions;
  m.comments = in.comments;
  // Faces: drop those using a vertex twice and repeats of an earlier face (in either orientation).
  std::vector<std::array<uint32_t, 3>> seen;
  seen.reserve(in.triangles.size());
  std::vector<std::pair<std::array<uint32_t, 3>, uint32_t>> keyed;
  keyed.reserve(in.triangles.size());
  for (uint32_t f = 0; f < in.triangles.size(); ++f) {
    const Tri& t = in.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++r.repeated_index_removed;
      continue;
    }
    std::array<uint32_t, 3> s = t;
    std::sort(s.begin(), s.end());
    keyed.push_back({s, f});
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint8_t> keep(in.triangles.size(), 0);
  for (size_t i = 0; i < keyed.size(); ++i) {
    if (i > 0 && keyed[i].first == keyed[i - 1].first) {
      ++r.duplicate_removed;
      continue;
    }
    keep[keyed[i].second] = 1;
  }
  for (uint32_t f = 0; f < in.triangles.size(); ++f)
    if (keep[f]) m.triangles.push_back(in.triangles[f]);

  const MeshReport check = validate_mesh(m);
  if (!check.manifold() || !check.oriented()) {
    std::string why = check.examples.empty() ? std::string() : ": " + check.examples.front();
    for (const std::string& e : check.examples)
      if (e.find("faces") != std::string::npos || e.find("pinched") != std::string::npos || e.find("same way") != std::string::npos) {
        why = ": " + e;
        break;
      }
    throw InputError("cannot repair safely: the mesh is " +
                     std::string(!check.manifold() ? "not a manifold" : "not consistently oriented") + why);
  }

  // Boundary loops, followed in face direction; the fan uses the reversed boundary edges.
  std::map<uint32_t, uint32_t> next;  // boundary edge a -> b (face direction), one per vertex on a manifold
  {
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (const Tri& t : m.triangles)
      for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    for (const auto& [e, c] : directed)
      if (!directed.count({e.second, e.first})) next[e.first] = e.second;
  }
  while (!next.empty()) {
    std::vector<uint32_t> loop;
    uint32_t v = next.begin()->first;
    while (next.count(v)) {
      loop.push_back(v);
      const uint32_t w = next[v];
      next.erase(v);
      v = w;
    }
    if (loop.size() < 3) {
      r.notes.push_back("a boundary loop of " + std::to_string(loop.size()) + " edges was left open");
      continue;
    }
    Vec3 c{0, 0, 0};
    for (uint32_t u : loop) c += m.positions[u];
    m.positions.push_back(c * (1.0 / static_cast<double>(loop.size())));
    const uint32_t centre = static_cast<uint32_t>(m.positions.size() - 1);
    for (size_t i = 0; i < loop.size(); ++i) m.triangles.push_back({centre, loop[(i + 1) % loop.size()], loop[i]});
    ++r.holes_filled;
    r.fill_triangles += loop.size();
  }
  // Unreferenced vertices.
  std::vector<uint32_t> id(m.positions.size(), UINT32_MAX);
  std::vector<Vec3> pos;
  for (const Tri& t : m.triangles)
    for (uint32_t v : t)
      if (id[v] == UINT32_MAX) {
        id[v] = 0;
      }
  for (uint32_t v = 0; v < m.positions.size(); ++v)
    if (id[v] != UINT32_MAX) {
      id[v] = static_cast<uint32_t>(pos.size());
      pos.push_back(m.positions[v]);
    } else {
      ++r.unreferenced_removed;
    }
  for (Tri& t : m.triangles)
    for (uint32_t& v : t) v = id[v];
  m.positions = std::move(pos);
  return m;
}

}  // namespace prm
