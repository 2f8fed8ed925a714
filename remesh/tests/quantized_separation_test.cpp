// The pass that keeps triangles from collapsing when the PRM is quantized to its frame (quantized_separation.h).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <set>

#include "../src/quantized_separation.h"
#include "prm/vec3.h"
#include "test_meshes.h"

namespace prm::remesh {
namespace {

using Q3 = std::array<int64_t, 3>;

Q3 quantized(const PrmMesh& prm, uint32_t v) {
  Q3 q;
  for (int a = 0; a < 3; ++a) q[static_cast<size_t>(a)] = prm.frame.quantize(prm.mesh.positions[v][static_cast<size_t>(a)], a);
  return q;
}

size_t zero_area_faces(const PrmMesh& prm) {
  size_t n = 0;
  for (const Tri& t : prm.mesh.triangles) {
    const Q3 a = quantized(prm, t[0]), b = quantized(prm, t[1]), c = quantized(prm, t[2]);
    const Q3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n += u[1] * w[2] == u[2] * w[1] && u[2] * w[0] == u[0] * w[2] && u[0] * w[1] == u[1] * w[0];
  }
  return n;
}

size_t shared_positions(const PrmMesh& prm) {
  std::map<Q3, int> at;
  for (uint32_t v = 0; v < prm.mesh.positions.size(); ++v) ++at[quantized(prm, v)];
  size_t n = 0;
  for (const auto& [q, k] : at) n += k > 1 ? static_cast<size_t>(k) : 0;
  return n;
}

// An icosphere of radius 40 quantization steps whose edge (a, b) is split by a vertex m a third of a step from a:
// the two triangles (a, m, *) lose their area when rounded, and m shares a's position.
PrmMesh split_sphere(uint32_t* a_out, uint32_t* m_out) {
  PrmMesh prm;
  prm.mesh = test::icosphere(2, 40.0);
  prm.frame.origin = {-50, -50, -50};
  prm.frame.step = 1;
  prm.frame.bits = 12;
  Mesh& m = prm.mesh;
  const Tri t0 = m.triangles[0];
  const uint32_t a = t0[0], b = t0[1];
  // Round a onto its quantization point, so that only m is ambiguous.
  for (size_t k = 0; k < 3; ++k) m.positions[a][k] = std::round(m.positions[a][k] + 50) - 50;
  const Vec3 dir = normalized(m.positions[b] - m.positions[a]);
  const uint32_t mid = static_cast<uint32_t>(m.positions.size());
  m.positions.push_back(m.positions[a] + dir * (1.0 / 3.0));
  std::vector<Tri> tris;
  for (const Tri& t : m.triangles) {
    int ka = -1;
    for (int k = 0; k < 3; ++k)
      if (t[static_cast<size_t>(k)] == a && t[static_cast<size_t>((k + 1) % 3)] == b) ka = k;
      else if (t[static_cast<size_t>(k)] == b && t[static_cast<size_t>((k + 1) % 3)] == a) ka = k;
    if (ka < 0) {
      tris.push_back(t);
      continue;
    }
    const uint32_t p = t[static_cast<size_t>(ka)], q = t[static_cast<size_t>((ka + 1) % 3)], r = t[static_cast<size_t>((ka + 2) % 3)];
    tris.push_back({p, mid, r});
    tris.push_back({mid, q, r});
  }
  m.triangles = tris;
  prm.vertex_relief.assign(m.positions.size(), -1);
  prm.relief_axis = {4};  // +z: height along z
  *a_out = a;
  *m_out = mid;
  return prm;
}

TEST(QuantizedSeparation, SplitVertexMovesOffItsNeighbour) {
  uint32_t a = 0, mid = 0;
  PrmMesh prm = split_sphere(&a, &mid);
  ASSERT_EQ(zero_area_faces(prm), 2u);
  ASSERT_EQ(shared_positions(prm), 2u);
  const Q3 a_before = quantized(prm, a);
  const QuantizedSeparationStats st = separate_quantized_vertices(prm);
  EXPECT_EQ(st.degenerate_faces, 2u);
  EXPECT_EQ(st.coincident_vertices, 2u);
  EXPECT_EQ(st.moved, 1u);
  EXPECT_EQ(st.unresolved, 0u);
  EXPECT_EQ(zero_area_faces(prm), 0u);
  EXPECT_EQ(shared_positions(prm), 0u);
  EXPECT_EQ(quantized(prm, a), a_before);  // the vertex off the lattice moved, within two steps
  const Q3 q = quantized(prm, mid);
  for (size_t k = 0; k < 3; ++k) EXPECT_LE(std::abs(q[k] - a_before[k]), 2);
  // Exactly on its quantization point: the search and the encoder round it the same way.
  for (size_t k = 0; k < 3; ++k) EXPECT_EQ(prm.mesh.positions[mid][k], prm.frame.to_real(static_cast<double>(q[k]), static_cast<int>(k)));
}

TEST(QuantizedSeparation, LatticeVerticesMoveAlongTheirHeightOnly) {
  uint32_t a = 0, mid = 0;
  PrmMesh prm = split_sphere(&a, &mid);
  prm.vertex_relief[a] = prm.vertex_relief[mid] = 0;
  const Q3 m_before = quantized(prm, mid), a_before = quantized(prm, a);
  const QuantizedSeparationStats st = separate_quantized_vertices(prm);
  EXPECT_EQ(st.unresolved, 0u);
  EXPECT_EQ(zero_area_faces(prm), 0u);
  EXPECT_EQ(shared_positions(prm), 0u);
  const Q3 mq = quantized(prm, mid), aq = quantized(prm, a);
  EXPECT_EQ(mq[0], m_before[0]);
  EXPECT_EQ(mq[1], m_before[1]);
  EXPECT_EQ(aq[0], a_before[0]);
  EXPECT_EQ(aq[1], a_before[1]);
  EXPECT_TRUE(mq[2] != m_before[2] || aq[2] != a_before[2]);
}

// Both ends of the split edge on a lattice (they move along z only) and every point they could move to within three
// steps taken (by vertices of no face): the edge collapses, its two zero-area faces go, and what is left is the
// closed sphere, every face still facing out.
TEST(QuantizedSeparation, InseparableNeighboursCollapse) {
  uint32_t a = 0, mid = 0;
  PrmMesh prm = split_sphere(&a, &mid);
  Mesh& m = prm.mesh;
  const size_t faces_before = m.triangles.size(), vertices_before = m.positions.size();
  for (int dz : {-3, -2, -1, 1, 2, 3}) m.positions.push_back(m.positions[a] + Vec3{0, 0, static_cast<double>(dz)});
  prm.vertex_relief.assign(m.positions.size(), -1);
  prm.vertex_relief[a] = prm.vertex_relief[mid] = 0;
  prm.lattice_i.assign(m.positions.size(), 0);
  prm.lattice_j.assign(m.positions.size(), 0);
  prm.face_relief.assign(m.triangles.size(), -1);
  prm.face_regular.assign(m.triangles.size(), 0);
  const QuantizedSeparationStats st = separate_quantized_vertices(prm);
  EXPECT_EQ(st.collapsed, 1u);
  EXPECT_EQ(st.unresolved, 0u);
  EXPECT_EQ(m.positions.size(), vertices_before + 6 - 1);
  EXPECT_EQ(m.triangles.size(), faces_before - 2);
  EXPECT_EQ(prm.vertex_relief.size(), m.positions.size());
  EXPECT_EQ(prm.face_relief.size(), m.triangles.size());
  EXPECT_EQ(zero_area_faces(prm), 0u);
  EXPECT_EQ(shared_positions(prm), 0u);
  std::map<std::pair<uint32_t, uint32_t>, int> edges;  // each directed edge once, and its reverse once
  for (const Tri& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[static_cast<size_t>(k)], t[static_cast<size_t>((k + 1) % 3)]}];
    const Vec3 centroid = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) * (1.0 / 3.0);
    EXPECT_GT(dot(triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]), centroid), 0);
  }
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u);
  }
}

TEST(QuantizedSeparation, NothingToDoChangesNothing) {
  PrmMesh prm;
  prm.mesh = test::icosphere(2, 40.0);
  prm.frame.origin = {-50, -50, -50};
  prm.frame.step = 1;
  prm.vertex_relief.assign(prm.mesh.positions.size(), -1);
  const std::vector<Vec3> before = prm.mesh.positions;
  const QuantizedSeparationStats st = separate_quantized_vertices(prm);
  EXPECT_EQ(st.degenerate_faces + st.coincident_vertices + st.moved + st.unresolved, 0u);
  EXPECT_EQ(prm.mesh.positions, before);
}

}  // namespace
}  // namespace prm::remesh
