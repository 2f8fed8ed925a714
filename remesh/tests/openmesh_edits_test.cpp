// The inline mesh edits (openmesh_edits.h) against OpenMesh's own add_face and collapse: the same connectivity,
// handle for handle, after the same sequence of edits.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include <OpenMesh/Core/System/omstream.hh>

#include "../src/openmesh_edits.h"
#include "../src/openmesh_queries.h"

namespace prm::remesh {
namespace {

using VH = OMesh::VertexHandle;
using HH = OMesh::HalfedgeHandle;

// Every handle the two meshes store, and the deleted flags.
void expect_same(const OMesh& a, const OMesh& b) {
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  ASSERT_EQ(a.n_edges(), b.n_edges());
  ASSERT_EQ(a.n_faces(), b.n_faces());
  for (size_t i = 0; i < a.n_halfedges(); ++i) {
    const HH h(static_cast<int>(i));
    ASSERT_EQ(a.next_halfedge_handle(h), b.next_halfedge_handle(h)) << "half-edge " << i;
    ASSERT_EQ(a.prev_halfedge_handle(h), b.prev_halfedge_handle(h)) << "half-edge " << i;
    ASSERT_EQ(a.to_vertex_handle(h), b.to_vertex_handle(h)) << "half-edge " << i;
    ASSERT_EQ(a.face_handle(h), b.face_handle(h)) << "half-edge " << i;
    ASSERT_EQ(a.status(h).deleted(), b.status(h).deleted()) << "half-edge " << i;
  }
  for (size_t i = 0; i < a.n_edges(); ++i)
    ASSERT_EQ(a.status(OMesh::EdgeHandle(static_cast<int>(i))).deleted(),
              b.status(OMesh::EdgeHandle(static_cast<int>(i))).deleted());
  for (size_t i = 0; i < a.n_vertices(); ++i) {
    const VH v(static_cast<int>(i));
    ASSERT_EQ(a.halfedge_handle(v), b.halfedge_handle(v)) << "vertex " << i;
    ASSERT_EQ(a.status(v).deleted(), b.status(v).deleted()) << "vertex " << i;
  }
  for (size_t i = 0; i < a.n_faces(); ++i) {
    const OMesh::FaceHandle f(static_cast<int>(i));
    ASSERT_EQ(a.halfedge_handle(f), b.halfedge_handle(f)) << "face " << i;
    ASSERT_EQ(a.status(f).deleted(), b.status(f).deleted()) << "face " << i;
  }
}

// An n x n grid of vertices, two triangles a cell, in a shuffled order (so that faces join existing patches from
// every side and patches are relinked), with some faces repeated and some reversed (refused by both).
std::vector<std::array<int, 3>> shuffled_grid(int n, unsigned seed) {
  std::vector<std::array<int, 3>> faces;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + 1, c = a + n, d = c + 1;
      faces.push_back({a, b, d});
      faces.push_back({a, d, c});
    }
  std::mt19937 rng(seed);
  std::shuffle(faces.begin(), faces.end(), rng);
  for (size_t k = 0; k < faces.size(); k += 17) {
    faces.push_back(faces[k]);
    faces.push_back({faces[k][0], faces[k][2], faces[k][1]});
  }
  return faces;
}

TEST(OpenMeshEdits, AddTriangleAndCollapseMatchTheLibrary) {
  omerr().disable();  // the library's add_face reports each refusal
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    OMesh lib, own;
    const int n = 24;
    for (int k = 0; k < n * n; ++k) {
      lib.add_vertex(OMesh::Point(k % n, k / n, 0));
      own.add_vertex(OMesh::Point(k % n, k / n, 0));
    }
    int refused = 0;
    for (const auto& t : shuffled_grid(n, seed)) {
      const auto f_lib = lib.add_face(VH(t[0]), VH(t[1]), VH(t[2]));
      const auto f_own = add_triangle(own, VH(t[0]), VH(t[1]), VH(t[2]));
      ASSERT_EQ(f_lib, f_own);
      refused += !f_own.is_valid();
    }
    EXPECT_GT(refused, 0);
    expect_same(lib, own);
    // Collapses in a random order of half-edges, each where the collapse test allows it, until a third of the
    // vertices are gone.
    std::mt19937 rng(seed + 100);
    std::uniform_int_distribution<int> pick(0, static_cast<int>(own.n_halfedges()) - 1);
    int collapsed = 0;
    for (int tries = 0; tries < 20000 && collapsed < n * n / 3; ++tries) {
      const HH h(pick(rng));
      if (own.status(h).deleted() || !is_collapse_ok(own, h)) continue;
      lib.collapse(h);
      collapse(own, h);
      ++collapsed;
    }
    EXPECT_EQ(collapsed, n * n / 3);
    expect_same(lib, own);
  }
}

}  // namespace
}  // namespace prm::remesh
