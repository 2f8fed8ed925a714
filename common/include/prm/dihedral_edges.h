// The interior edges of a triangle mesh with the angle between their two faces: what the remesher's per-relief
// grids (remesh/src/relief_grids.cpp, the squared-curvature integral per relief) and pack's first-grid prediction
// (pipeline/src/first_grid.cpp, issue 21) measure of an input surface.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "prm/mesh.h"
#include "prm/vec3.h"

namespace prm {

// Per face: its area, unit normal (zero for a zero-area face) and centroid.
struct FaceFrames {
  std::vector<double> area;
  std::vector<Vec3> normal, centroid;
};

inline FaceFrames face_frames(const Mesh& m) {
  const size_t nf = m.triangles.size();
  FaceFrames out;
  out.area.resize(nf);
  out.normal.resize(nf);
  out.centroid.resize(nf);
  for (size_t f = 0; f < nf; ++f) {
    const Tri& t = m.triangles[f];
    const Vec3 n2 = triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
    out.area[f] = 0.5 * norm(n2);
    out.normal[f] = out.area[f] > 0 ? n2 * (0.5 / out.area[f]) : Vec3{0, 0, 0};
    out.centroid[f] = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) * (1.0 / 3.0);
  }
  return out;
}

// fn(f, g, angle, length, d) once per edge shared by two faces (g met first, f second; on an edge of more faces,
// each later face with the first), when both faces have positive area and distinct centroids: the angle between
// their normals (radians), the edge's length and the distance between the centroids.
template <class Fn>
void for_each_dihedral_edge(const Mesh& m, const FaceFrames& frames, Fn&& fn) {
  const uint32_t nf = static_cast<uint32_t>(m.triangles.size());
  std::unordered_map<uint64_t, uint32_t> first;  // undirected edge -> the first face seen
  first.reserve(3 * static_cast<size_t>(nf));
  for (uint32_t f = 0; f < nf; ++f)
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
      const uint64_t key = uint64_t{std::min(a, b)} << 32 | std::max(a, b);
      const auto [it, inserted] = first.emplace(key, f);
      if (inserted) continue;
      const uint32_t g = it->second;
      const double d = norm(frames.centroid[f] - frames.centroid[g]);
      if (!(d > 0) || !(frames.area[f] > 0) || !(frames.area[g] > 0)) continue;
      const double angle = std::acos(std::clamp(dot(frames.normal[f], frames.normal[g]), -1.0, 1.0));
      fn(f, g, angle, norm(m.positions[a] - m.positions[b]), d);
    }
}

}  // namespace prm
