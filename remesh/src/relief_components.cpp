#include "relief_components.h"

#include <algorithm>

#include "prm/vec3.h"
#include "relief_axes.h"

namespace prm::remesh {

void label_components(const Mesh& mesh, const std::vector<std::array<int32_t, 3>>& adjacency,
                      const std::vector<int8_t>& axis, std::vector<int32_t>& face_relief,
                      std::vector<Relief>& reliefs) {
  const size_t nf = mesh.triangles.size();
  face_relief.assign(nf, -1);
  reliefs.clear();
  std::vector<uint32_t> stack;
  for (size_t s = 0; s < nf; ++s) {
    if (face_relief[s] >= 0) continue;
    const int32_t id = static_cast<int32_t>(reliefs.size());
    Relief r;
    r.axis = axis[s];
    face_relief[s] = id;
    stack.assign(1, static_cast<uint32_t>(s));
    while (!stack.empty()) {
      const uint32_t f = stack.back();
      stack.pop_back();
      const Tri& t = mesh.triangles[f];
      ++r.faces;
      r.area += triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
      for (int32_t g : adjacency[f])
        if (g >= 0 && face_relief[static_cast<size_t>(g)] < 0 && axis[static_cast<size_t>(g)] == axis[f]) {
          face_relief[static_cast<size_t>(g)] = id;
          stack.push_back(static_cast<uint32_t>(g));
        }
    }
    reliefs.push_back(r);
  }
}

size_t merge_small_reliefs(const Mesh& mesh, const std::vector<std::array<int32_t, 3>>& adjacency,
                           const std::vector<Vec3>& face_normals, double min_facing, double min_area, int passes,
                           std::vector<int8_t>& axis, std::vector<int32_t>& face_relief,
                           std::vector<Relief>& reliefs) {
  const size_t nf = mesh.triangles.size();
  size_t merged = 0;
  std::vector<std::vector<std::pair<int32_t, double>>> shared;
  std::vector<std::vector<uint32_t>> faces_of;
  for (int pass = 0; pass < passes; ++pass) {
    const size_t nr = reliefs.size();
    shared.assign(nr, {});
    faces_of.assign(nr, {});
    bool any_small = false;
    for (size_t f = 0; f < nf; ++f) {
      const int32_t r = face_relief[f];
      if (!(reliefs[static_cast<size_t>(r)].area < min_area)) continue;
      any_small = true;
      faces_of[static_cast<size_t>(r)].push_back(static_cast<uint32_t>(f));
      const Tri& t = mesh.triangles[f];
      for (size_t k = 0; k < 3; ++k) {
        const int32_t g = adjacency[f][k];
        if (g < 0 || face_relief[static_cast<size_t>(g)] == r) continue;
        const int32_t n = face_relief[static_cast<size_t>(g)];
        const double len = norm(mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]);
        auto& list = shared[static_cast<size_t>(r)];
        auto it = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first == n; });
        if (it == list.end()) list.push_back({n, len});
        else it->second += len;
      }
    }
    if (!any_small) break;
    bool changed = false;
    for (size_t r = 0; r < nr; ++r) {
      auto& list = shared[r];
      if (list.empty()) continue;
      // Reliefs that stay first (two small ones would swap axes), then the longest shared boundary, then the lower
      // id, so that the result does not depend on the order.
      auto small = [&](int32_t n) { return reliefs[static_cast<size_t>(n)].area < min_area; };
      std::sort(list.begin(), list.end(), [&](const auto& a, const auto& b) {
        if (small(a.first) != small(b.first)) return !small(a.first);
        return a.second != b.second ? a.second > b.second : a.first < b.first;
      });
      for (const auto& [n, len] : list) {
        const int target = reliefs[static_cast<size_t>(n)].axis;
        if (target == reliefs[r].axis) continue;
        const bool faces_it = std::all_of(faces_of[r].begin(), faces_of[r].end(), [&](uint32_t f) {
          return axis_component(face_normals[f], target) >= min_facing;
        });
        if (!faces_it) continue;
        for (uint32_t f : faces_of[r]) axis[f] = static_cast<int8_t>(target);
        ++merged;
        changed = true;
        break;
      }
    }
    if (!changed) break;
    label_components(mesh, adjacency, axis, face_relief, reliefs);
  }
  return merged;
}

double relief_boundary_length(const Mesh& mesh, const std::vector<std::array<int32_t, 3>>& adjacency,
                              const std::vector<int32_t>& face_relief) {
  double length = 0;
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (size_t k = 0; k < 3; ++k) {
      const int32_t g = adjacency[f][k];
      if (g > static_cast<int32_t>(f) && face_relief[static_cast<size_t>(g)] != face_relief[f]) {
        const Tri& t = mesh.triangles[f];
        length += norm(mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]);
      }
    }
  return length;
}

}  // namespace prm::remesh
