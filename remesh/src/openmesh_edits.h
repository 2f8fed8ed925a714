// Two edits of the remesher's mesh (openmesh_types.h) compiled inline: a triangle added and a half-edge collapsed,
// with the same changes to the mesh as TriConnectivity::add_face and PolyConnectivity::collapse (the same handles
// created and linked, the same elements marked deleted, the same outgoing half-edge kept per vertex, so that every
// later circulation visits the same elements in the same order), without the library's cost: Debian's
// libOpenMeshCore is built with assertions, and every property access inside the library builds and compares a
// type-name string (add_face and collapse were half of resample_relief's time on the venus at effort 0, issue 21).
// The accessors used here are the inline ones of OpenMesh's headers. openmesh_queries.h does the same for the
// collapse and flip tests.
#pragma once

#include <cassert>
#include <cstddef>
#include <utility>

#include "openmesh_types.h"

namespace prm::remesh {

namespace openmesh_edits_detail {

using HH = OMesh::HalfedgeHandle;
using VH = OMesh::VertexHandle;

// A boundary half-edge out of v, when there is one, becomes v's half-edge (the first met around v).
inline void keep_boundary_outgoing(OMesh& m, VH v) {
  for (auto h : m.voh_range(v))
    if (m.is_boundary(h)) {
      m.set_halfedge_handle(v, h);
      return;
    }
}

// Removes the edge of h: its source vertex merges into its target, each of the edge's faces loses a corner.
inline void remove_edge(OMesh& m, HH h) {
  const HH h_next = m.next_halfedge_handle(h), h_prev = m.prev_halfedge_handle(h);
  const HH o = m.opposite_halfedge_handle(h);
  const HH o_next = m.next_halfedge_handle(o), o_prev = m.prev_halfedge_handle(o);
  const auto f_h = m.face_handle(h), f_o = m.face_handle(o);
  const VH kept = m.to_vertex_handle(h), gone = m.to_vertex_handle(o);
  for (auto in : m.vih_range(gone)) m.set_vertex_handle(in, kept);
  m.set_next_halfedge_handle(h_prev, h_next);
  m.set_next_halfedge_handle(o_prev, o_next);
  if (f_h.is_valid()) m.set_halfedge_handle(f_h, h_next);
  if (f_o.is_valid()) m.set_halfedge_handle(f_o, o_next);
  if (m.halfedge_handle(kept) == o) m.set_halfedge_handle(kept, h_next);
  keep_boundary_outgoing(m, kept);
  m.set_isolated(gone);
  m.status(m.edge_handle(h)).set_deleted(true);
  m.status(gone).set_deleted(true);
  m.status(h).set_deleted(true);
  m.status(o).set_deleted(true);
}

// h and next(h) form a face of two edges (left by remove_edge): h's edge goes, next(h) takes the place of h's
// opposite in the face on the other side, and the two-edge face is deleted.
inline void remove_two_edge_face(OMesh& m, HH h) {
  const HH h1 = m.next_halfedge_handle(h);
  const HH o = m.opposite_halfedge_handle(h), o1 = m.opposite_halfedge_handle(h1);
  const VH v0 = m.to_vertex_handle(h), v1 = m.to_vertex_handle(h1);
  const auto f_h = m.face_handle(h), f_o = m.face_handle(o);
  assert(m.next_halfedge_handle(h1) == h && h1 != o);
  m.set_next_halfedge_handle(h1, m.next_halfedge_handle(o));
  m.set_next_halfedge_handle(m.prev_halfedge_handle(o), h1);
  m.set_face_handle(h1, f_o);
  m.set_halfedge_handle(v0, h1);
  keep_boundary_outgoing(m, v0);
  m.set_halfedge_handle(v1, o1);
  keep_boundary_outgoing(m, v1);
  if (f_o.is_valid() && m.halfedge_handle(f_o) == o) m.set_halfedge_handle(f_o, h1);
  if (f_h.is_valid()) {
    m.set_halfedge_handle(f_h, OMesh::HalfedgeHandle());
    m.status(f_h).set_deleted(true);
  }
  m.status(m.edge_handle(h)).set_deleted(true);
  m.status(h).set_deleted(true);
  m.status(o).set_deleted(true);
}

// PolyConnectivity::find_halfedge: the half-edge from a to b, or an invalid handle.
inline HH find_halfedge(const OMesh& m, VH a, VH b) {
  for (auto h : m.voh_range(a))
    if (m.to_vertex_handle(h) == b) return h;
  return HH();
}

}  // namespace openmesh_edits_detail

// TriConnectivity::add_face(a, b, c): the triangle (a, b, c), or an invalid handle when it would make a vertex or an
// edge non-manifold. The edges it lacks are created in the order ab, bc, ca; where two of its edges exist and are
// not consecutive around the boundary, the patch between them is relinked to the nearest free boundary gap.
inline OMesh::FaceHandle add_triangle(OMesh& m, OMesh::VertexHandle a, OMesh::VertexHandle b, OMesh::VertexHandle c) {
  using namespace openmesh_edits_detail;
  const VH v[3] = {a, b, c};
  HH side[3];              // side[i]: the half-edge v[i] -> v[i + 1] inside the face
  bool fresh[3];           // created here
  bool adjust[3] = {};     // v[i]'s outgoing half-edge may have to move to a boundary one
  std::pair<HH, HH> link[18];  // (h, next(h)) set at the end, in this order
  size_t links = 0;
  for (int i = 0; i < 3; ++i) {
    if (!m.is_boundary(v[i])) return OMesh::FaceHandle();  // inside a closed fan already
    side[i] = find_halfedge(m, v[i], v[(i + 1) % 3]);
    fresh[i] = !side[i].is_valid();
    if (!fresh[i] && !m.is_boundary(side[i])) return OMesh::FaceHandle();  // the edge has both faces already
  }
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (fresh[i] || fresh[j] || m.next_halfedge_handle(side[i]) == side[j]) continue;
    // The boundary between the two existing sides holds another patch: move it to the next free gap around v[j].
    HH gap_prev = m.opposite_halfedge_handle(side[j]);
    do gap_prev = m.opposite_halfedge_handle(m.next_halfedge_handle(gap_prev));
    while (!m.is_boundary(gap_prev));
    if (gap_prev == side[i]) return OMesh::FaceHandle();  // no free gap
    link[links++] = {gap_prev, m.next_halfedge_handle(side[i])};
    link[links++] = {m.prev_halfedge_handle(side[j]), m.next_halfedge_handle(gap_prev)};
    link[links++] = {side[i], side[j]};
  }
  for (int i = 0; i < 3; ++i)
    if (fresh[i]) side[i] = m.new_edge(v[i], v[(i + 1) % 3]);
  const OMesh::FaceHandle f = m.new_face();
  m.set_halfedge_handle(f, side[2]);
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const VH corner = v[j];
    const HH in = side[i], out = side[j];
    const HH outer_in = m.opposite_halfedge_handle(out), outer_out = m.opposite_halfedge_handle(in);
    if (fresh[i] && !fresh[j]) {
      link[links++] = {m.prev_halfedge_handle(out), outer_out};
      m.set_halfedge_handle(corner, outer_out);
    } else if (!fresh[i] && fresh[j]) {
      const HH after = m.next_halfedge_handle(in);
      link[links++] = {outer_in, after};
      m.set_halfedge_handle(corner, after);
    } else if (fresh[i] && fresh[j]) {
      if (!m.halfedge_handle(corner).is_valid()) {
        m.set_halfedge_handle(corner, outer_out);
        link[links++] = {outer_in, outer_out};
      } else {
        const HH after = m.halfedge_handle(corner);
        link[links++] = {m.prev_halfedge_handle(after), outer_out};
        link[links++] = {outer_in, after};
      }
    }
    if (fresh[i] || fresh[j]) link[links++] = {in, out};
    else adjust[j] = m.halfedge_handle(corner) == out;
    m.set_face_handle(in, f);
  }
  for (size_t k = 0; k < links; ++k) m.set_next_halfedge_handle(link[k].first, link[k].second);
  for (int i = 0; i < 3; ++i)
    if (adjust[i]) keep_boundary_outgoing(m, v[i]);
  return f;
}

// PolyConnectivity::collapse(h): h's source vertex moves onto its target; the faces on both sides of the edge go.
inline void collapse(OMesh& m, OMesh::HalfedgeHandle h) {
  using namespace openmesh_edits_detail;
  const HH h1 = m.next_halfedge_handle(h);
  const HH o1 = m.next_halfedge_handle(m.opposite_halfedge_handle(h));
  remove_edge(m, h);
  if (m.next_halfedge_handle(m.next_halfedge_handle(h1)) == h1) remove_two_edge_face(m, m.next_halfedge_handle(h1));
  if (m.next_halfedge_handle(m.next_halfedge_handle(o1)) == o1) remove_two_edge_face(m, o1);
}

}  // namespace prm::remesh
