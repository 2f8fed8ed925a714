// OpenMesh 9.0's topological tests of a collapse and a flip, and a vertex's valence, as inline functions of the
// remesher's half-edge mesh (openmesh_types.h). The same answers as TriConnectivity::is_collapse_ok,
// TriConnectivity::is_flip_ok and PolyConnectivity::valence, without their cost: Debian's libOpenMeshCore is
// built with assertions, so each property access inside the library builds and compares a type-name string
// (is_collapse_ok was a third of resample_relief's time on the venus at effort 0, issue 21). Here the accesses
// are the inline ones of OpenMesh's headers. is_collapse_ok also leaves the status "tagged" bits alone (the
// library's version uses them as scratch; nothing in the remesher reads them).
#pragma once

#include <cassert>
#include <vector>

#include "openmesh_types.h"

namespace prm::remesh {

// TriConnectivity::is_collapse_ok(h): may the edge of h collapse from h's source v0 onto its target v1?
namespace openmesh_queries_detail {

inline bool collapse_ok(const OMesh& m, OMesh::HalfedgeHandle v0v1) {
  if (m.status(m.edge_handle(v0v1)).deleted()) return false;
  const OMesh::HalfedgeHandle v1v0 = m.opposite_halfedge_handle(v0v1);
  const OMesh::VertexHandle v0 = m.to_vertex_handle(v1v0), v1 = m.to_vertex_handle(v0v1);
  if (m.status(v0).deleted() || m.status(v1).deleted()) return false;
  OMesh::VertexHandle vl, vr;
  // The edges v1-vl and vl-v0 must not both be boundary edges; nor v0-vr and vr-v1.
  if (!m.is_boundary(v0v1)) {
    const OMesh::HalfedgeHandle h1 = m.next_halfedge_handle(v0v1), h2 = m.next_halfedge_handle(h1);
    vl = m.to_vertex_handle(h1);
    if (m.is_boundary(m.opposite_halfedge_handle(h1)) && m.is_boundary(m.opposite_halfedge_handle(h2)))
      return false;
  }
  if (!m.is_boundary(v1v0)) {
    const OMesh::HalfedgeHandle h1 = m.next_halfedge_handle(v1v0), h2 = m.next_halfedge_handle(h1);
    vr = m.to_vertex_handle(h1);
    if (m.is_boundary(m.opposite_halfedge_handle(h1)) && m.is_boundary(m.opposite_halfedge_handle(h2)))
      return false;
  }
  if (vl == vr) return false;  // equal, or both invalid
  // The one-rings of v0 and v1 share no vertex but vl and vr.
  constexpr size_t kLocal = 64;
  OMesh::VertexHandle local[kLocal];
  std::vector<OMesh::VertexHandle> more;
  size_t n = 0;
  for (auto w : m.vv_range(v1)) {
    if (n < kLocal)
      local[n] = w;
    else
      more.push_back(w);
    ++n;
  }
  for (auto w : m.vv_range(v0)) {
    if (w == vl || w == vr) continue;
    for (size_t i = 0; i < n; ++i)
      if ((i < kLocal ? local[i] : more[i - kLocal]) == w) return false;
  }
  // An edge between two boundary vertices must be a boundary edge.
  if (m.is_boundary(v0) && m.is_boundary(v1) && !m.is_boundary(v0v1) && !m.is_boundary(v1v0)) return false;
  return true;
}

// TriConnectivity::is_flip_ok(e): not a boundary edge, and the flipped edge is not in the mesh already.
inline bool flip_ok(const OMesh& m, OMesh::EdgeHandle e) {
  if (m.is_boundary(e)) return false;
  const OMesh::VertexHandle a = m.to_vertex_handle(m.next_halfedge_handle(m.halfedge_handle(e, 0)));
  const OMesh::VertexHandle b = m.to_vertex_handle(m.next_halfedge_handle(m.halfedge_handle(e, 1)));
  if (a == b) return false;
  for (auto w : m.vv_range(a))
    if (w == b) return false;
  return true;
}

// PolyConnectivity::valence(v): the number of v's neighbours.
inline int count_neighbours(const OMesh& m, OMesh::VertexHandle v) {
  int n = 0;
  for (auto w : m.vv_range(v)) {
    (void)w;
    ++n;
  }
  return n;
}

}  // namespace openmesh_queries_detail

// A debug build checks every answer against the library's.
inline bool is_collapse_ok(const OMesh& m, OMesh::HalfedgeHandle h) {
  const bool ok = openmesh_queries_detail::collapse_ok(m, h);
  assert(ok == const_cast<OMesh&>(m).is_collapse_ok(h));
  return ok;
}

inline bool is_flip_ok(const OMesh& m, OMesh::EdgeHandle e) {
  const bool ok = openmesh_queries_detail::flip_ok(m, e);
  assert(ok == m.is_flip_ok(e));
  return ok;
}

inline int valence(const OMesh& m, OMesh::VertexHandle v) {
  const int n = openmesh_queries_detail::count_neighbours(m, v);
  assert(n == static_cast<int>(m.valence(v)));
  return n;
}

}  // namespace prm::remesh
