// Which way a mesh triangle faces the input (issue 17's count, issue 22 item 3): it faces away when its normal and the
// normal of the input's face closest to its centroid make an angle of 90 degrees or more, the test
// pipeline::check_decoded applies to the decoded stream (`turned`) and quantized_separation to the quantized mesh.
// The local refinement (deviation_refinement.cpp) keeps a move, a split, a flip, a pruned fan or a rounding only when
// all its new triangles face the input: the separation mends only what the rounding turns, not what the remesher
// leaves facing away.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "prm/aabb_tree.h"
#include "prm/lattice.h"
#include "prm/mesh.h"
#include "prm/surface_facing.h"
#include "prm/vec3.h"

namespace prm::remesh {

struct InputFacing {
  InputFacing() = default;
  // stream_frame is used only when it holds every point of `mesh` (a PRM without its frame yet: none).
  InputFacing(const Mesh* input_mesh, const AabbTree* input_tree, const codec::Frame* stream_frame, const Mesh& mesh)
      : input(input_mesh), tree(input_tree), frame(holds(*stream_frame, mesh) ? stream_frame : nullptr) {}
  // (The remeshed surface may pass the input's bounding box, which the frame is made of, by a few steps.)
  static constexpr double kSlack = 4;
  static bool holds(const codec::Frame& f, const Mesh& mesh) {
    const double top = static_cast<double>((uint64_t{1} << f.bits) - 1);
    for (const Vec3& p : mesh.positions)
      for (int a = 0; a < 3; ++a) {
        const double q = f.to_quant(p[static_cast<size_t>(a)], a);
        if (!(q >= -kSlack && q <= top + kSlack)) return false;
      }
    return true;
  }

  const Mesh* input = nullptr;  // null: every triangle counts as facing the input (no check)
  const AabbTree* tree = nullptr;
  // Not null: the triangle must also face the input with its corners at their nearest rounding to the stream's step
  // (and keep some area there), as the decoder puts it unless the separation moves them: a vertex inserted within a
  // step of another makes a sliver the separation cannot always turn back (feline_5k at 1e-4).
  const codec::Frame* frame = nullptr;
  mutable size_t refusals = 0;  // changes refused by keeps()
  // With the frame: how many vertices round to each point (index_cells), and where each did then. A change whose
  // triangles have a corner on a point another vertex rounds to is refused: the separation moves one of the two, and
  // with the change around it that move may turn a face (feline_5k at 1e-4: a lattice vertex's move beside two
  // vertices rounding to one point).
  std::unordered_map<uint64_t, uint32_t> cells;
  std::vector<uint64_t> cell_at_index;

  uint64_t cell(const Vec3& p) const {
    uint64_t key = 0;
    for (int a = 0; a < 3; ++a) key = (key << 21) | frame->quantize(p[static_cast<size_t>(a)], a);
    return key;
  }
  void index_cells(const Mesh& m) {
    if (input == nullptr || frame == nullptr) return;
    cells.clear();
    cell_at_index.resize(m.positions.size());
    for (size_t v = 0; v < m.positions.size(); ++v) ++cells[cell_at_index[v] = cell(m.positions[v])];
  }
  // Does another vertex round to v's point (as indexed)?
  bool shares_cell(const Mesh& m, uint32_t v) const {
    if (cells.empty()) return false;
    const uint64_t c = cell(m.positions[v]);
    const auto it = cells.find(c);
    const uint32_t n = it == cells.end() ? 0 : it->second;
    return n > (v < cell_at_index.size() && cell_at_index[v] == c ? 1u : 0u);
  }

  bool faces(const Vec3& a, const Vec3& b, const Vec3& c) const { return faces_surface(a, b, c, *input, *tree); }
  Vec3 rounded(const Vec3& p) const {
    Vec3 r;
    for (int a = 0; a < 3; ++a)
      r[static_cast<size_t>(a)] = frame->to_real(static_cast<double>(frame->quantize(p[static_cast<size_t>(a)], a)), a);
    return r;
  }
  // How many steps apart p and q round to, along the axis where they are farthest (needs the frame).
  uint32_t steps_apart(const Vec3& p, const Vec3& q) const {
    uint32_t n = 0;
    for (int a = 0; a < 3; ++a) {
      const uint32_t qp = frame->quantize(p[static_cast<size_t>(a)], a), qq = frame->quantize(q[static_cast<size_t>(a)], a);
      n = std::max(n, qp > qq ? qp - qq : qq - qp);
    }
    return n;
  }
  bool faces(const Mesh& m, const Tri& t) const {
    if (input == nullptr) return true;
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    if (!faces(a, b, c)) return false;
    return frame == nullptr || faces(rounded(a), rounded(b), rounded(c));
  }
  // How many of tris face away from the input.
  size_t away(const Mesh& m, const std::vector<Tri>& tris) const {
    size_t n = 0;
    if (input != nullptr)
      for (const Tri& t : tris) n += !faces(m, t);
    return n;
  }
  // Do all of new_tris face the input (and none has a corner on a shared point)? Not only no more of them than of
  // the triangles they replace: where some faced away already (venus's fitted mesh: 17, with its corners rounded),
  // that let the separation leave 3 decoded faces away, 0 with this.
  bool keeps(const Mesh& m, const std::vector<Tri>& new_tris) const {
    if (input == nullptr) return true;
    if (away(m, new_tris) != 0) {
      ++refusals;
      return false;
    }
    return keeps_facing(m, new_tris);
  }
  // keeps() of triangles just found facing the input (repair_facing tested each): only the shared points (hcpu: the
  // facing test again was a second closest-point query per triangle).
  bool keeps_facing(const Mesh& m, const std::vector<Tri>& facing_tris) const {
    bool ok = true;
    for (size_t i = 0; ok && i < facing_tris.size(); ++i)
      for (uint32_t v : facing_tris[i]) ok = ok && !shares_cell(m, v);
    refusals += !ok;
    return ok;
  }
};

}  // namespace prm::remesh
