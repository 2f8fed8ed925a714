#include "prm/pipeline/boundary_simplification.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <unordered_map>
#include <utility>
#include <vector>

#include "prm/boundary_deviation.h"
#include "prm/vec3.h"

namespace prm::pipeline {
namespace {

constexpr uint32_t kNone = UINT32_MAX;
constexpr double kMinNormalCosine = 0.5;  // a moved face turns by less than 60 degrees

uint64_t edge_key(uint32_t a, uint32_t b) { return (uint64_t{a} << 32) | b; }

}  // namespace

BoundarySimplification simplify_boundary(Mesh& m, double tolerance) {
  BoundarySimplification st;
  const size_t nv = m.positions.size(), nf = m.triangles.size();
  // Directed half-edges; a boundary half-edge a -> b has no b -> a. next/prev: the loops, in the faces' direction.
  std::unordered_map<uint64_t, uint32_t> half_edge;  // (a, b) -> face
  half_edge.reserve(3 * nf);
  for (uint32_t f = 0; f < nf; ++f)
    for (size_t k = 0; k < 3; ++k) half_edge[edge_key(m.triangles[f][k], m.triangles[f][(k + 1) % 3])] = f;
  std::vector<uint32_t> next(nv, kNone), prev(nv, kNone);
  for (uint32_t f = 0; f < nf; ++f)
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
      if (!half_edge.count(edge_key(b, a))) {
        next[a] = b;
        prev[b] = a;
      }
    }
  std::vector<std::vector<uint32_t>> faces_of = faces_around_vertices(m);
  std::vector<uint8_t> dead_face(nf, 0), dead_vertex(nv, 0);
  // stands_for[v]: the input's boundary vertices the loop edge (prev[v], v) stands for (removed ones), in order.
  std::vector<std::vector<uint32_t>> stands_for(nv);
  std::vector<uint32_t> loop_of(nv, kNone);
  std::vector<size_t> sizes;  // each loop's vertex count
  for (uint32_t v = 0; v < nv; ++v) {
    if (next[v] == kNone || loop_of[v] != kNone) continue;
    const uint32_t id = static_cast<uint32_t>(sizes.size());
    size_t n = 0;
    for (uint32_t u = v; loop_of[u] == kNone; u = next[u]) {
      loop_of[u] = id;
      ++n;
      if (next[u] == kNone) break;
    }
    sizes.push_back(n);
    st.boundary_vertices_before += n;
  }

  auto normal = [&](const Tri& t) { return triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]); };
  auto neighbours = [&](uint32_t v) {
    std::vector<uint32_t> out;
    for (uint32_t f : faces_of[v])
      for (uint32_t c : m.triangles[f])
        if (c != v) out.push_back(c);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  };
  // The distance of the farthest boundary vertex the new edge (prev[v], next[v]) would stand for.
  auto removal_cost = [&](uint32_t v) {
    const uint32_t a = prev[v], b = next[v];
    const Vec3 &pa = m.positions[a], &pb = m.positions[b];
    double worst = point_segment_distance(m.positions[v], pa, pb);
    for (const auto* list : {&stands_for[v], &stands_for[b]})
      for (uint32_t u : *list) worst = std::max(worst, point_segment_distance(m.positions[u], pa, pb));
    return worst;
  };
  // Collapsing v into w (a loop neighbour): allowed?
  auto can_collapse = [&](uint32_t v, uint32_t w) {
    // The boundary edge's face and its third corner.
    const bool w_next = next[v] == w;
    const auto it = half_edge.find(w_next ? edge_key(v, w) : edge_key(w, v));
    if (it == half_edge.end() || dead_face[it->second]) return false;
    const Tri& t = m.triangles[it->second];
    uint32_t o = kNone;
    for (uint32_t c : t)
      if (c != v && c != w) o = c;
    // The link condition on a boundary edge: v and w share exactly one neighbour, o.
    const auto nvs = neighbours(v), nws = neighbours(w);
    std::vector<uint32_t> common;
    std::set_intersection(nvs.begin(), nvs.end(), nws.begin(), nws.end(), std::back_inserter(common));
    if (common.size() != 1 || common[0] != o) return false;
    // v's faces other than (v, w, o) take w: each keeps an area and turns by less than 60 degrees.
    for (uint32_t f : faces_of[v]) {
      if (f == it->second) continue;
      Tri moved = m.triangles[f];
      const Vec3 before = normal(moved);
      for (uint32_t& c : moved)
        if (c == v) c = w;
      const Vec3 after = normal(moved);
      const double nb = norm(before), na = norm(after);
      if (!(na > 0) || !(nb > 0) || dot(before, after) < kMinNormalCosine * na * nb) return false;
    }
    return true;
  };
  auto collapse = [&](uint32_t v, uint32_t w) {
    const uint32_t a = prev[v], b = next[v];
    std::vector<uint32_t> merged = stands_for[v];
    merged.push_back(v);
    merged.insert(merged.end(), stands_for[b].begin(), stands_for[b].end());
    stands_for[b] = std::move(merged);
    next[a] = b;
    prev[b] = a;
    --sizes[loop_of[v]];
    for (uint32_t f : faces_of[v]) {
      Tri& t = m.triangles[f];
      if (std::find(t.begin(), t.end(), w) != t.end()) {  // the boundary edge's face goes
        dead_face[f] = 1;
        for (size_t k = 0; k < 3; ++k) half_edge.erase(edge_key(t[k], t[(k + 1) % 3]));
        for (uint32_t c : t)
          if (c != v) faces_of[c].erase(std::find(faces_of[c].begin(), faces_of[c].end(), f));
        continue;
      }
      for (size_t k = 0; k < 3; ++k) half_edge.erase(edge_key(t[k], t[(k + 1) % 3]));
      for (uint32_t& c : t)
        if (c == v) c = w;
      for (size_t k = 0; k < 3; ++k) half_edge[edge_key(t[k], t[(k + 1) % 3])] = f;
      faces_of[w].push_back(f);
    }
    faces_of[v].clear();
    dead_vertex[v] = 1;
    next[v] = prev[v] = kNone;
    ++st.removed;
  };

  for (bool progress = true; progress;) {
    progress = false;
    std::vector<std::pair<double, uint32_t>> order;
    for (uint32_t v = 0; v < nv; ++v)
      if (!dead_vertex[v] && next[v] != kNone && prev[v] != kNone && sizes[loop_of[v]] > 3) {
        const double c = removal_cost(v);
        if (c <= tolerance) order.push_back({c, v});
      }
    std::sort(order.begin(), order.end());
    for (const auto& [cost, v] : order) {
      if (dead_vertex[v] || sizes[loop_of[v]] <= 3) continue;
      const double c = removal_cost(v);  // its neighbours may have gone since
      if (c > tolerance) continue;
      const uint32_t a = prev[v], b = next[v];
      const bool a_nearer = norm(m.positions[a] - m.positions[v]) < norm(m.positions[b] - m.positions[v]);
      const uint32_t first = a_nearer ? a : b, second = a_nearer ? b : a;
      const uint32_t w = can_collapse(v, first) ? first : can_collapse(v, second) ? second : kNone;
      if (w == kNone) continue;
      st.max_distance = std::max(st.max_distance, c);
      collapse(v, w);
      progress = true;
    }
  }
  if (st.removed == 0) return st;

  // Compaction: the faces left, the vertices they use (with their properties).
  std::vector<Tri> faces;
  for (uint32_t f = 0; f < nf; ++f)
    if (!dead_face[f]) faces.push_back(m.triangles[f]);
  std::vector<uint32_t> index(nv, kNone);
  uint32_t n = 0;
  for (uint32_t v = 0; v < nv; ++v)
    if (!dead_vertex[v]) index[v] = n++;
  for (Tri& t : faces)
    for (uint32_t& c : t) c = index[c];
  auto keep = [&](auto& values) {
    size_t k = 0;
    for (uint32_t v = 0; v < nv; ++v)
      if (!dead_vertex[v]) values[k++] = values[v];
    values.resize(k);
  };
  keep(m.positions);
  for (Property& p : m.vertex_properties)
    if (p.values.size() == nv) keep(p.values);
  m.triangles = std::move(faces);
  m.face_properties.clear();  // the face set changed
  return st;
}

}  // namespace prm::pipeline
