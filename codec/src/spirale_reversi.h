// §6.4 Spirale Reversi: rebuilds the closed mesh from the CLERS symbols taken in reverse order.
//
// One class, used by both sides: the decoder (clers_decode.cpp) feeds it the symbols it decodes; the encoder
// (clers_encode.cpp) runs it over its own symbol string to obtain exactly the contexts (§6.5.2) the decoder will
// see, and then checks that the mesh it rebuilds is the one being encoded.
//
// State (§6.4.1): for every corner its opposite corner (-1 while its edge is open) and its vertex record; vertex
// records are merged by union-find and carry a triangle count and, once closed, a vertex id; a stack of pieces, each
// named by the triangle whose gate is the piece's open gate.
//
// §4.5 Memory grows with what is decoded, not with the counts the stream claims: the per-corner tables hold only the
// triangles decoded so far (tail_table.h), and the vertex records are created as symbols create them.
#pragma once

#include <cassert>
#include <cstdint>
#include <string>
#include <vector>

#include "always_inline.h"
#include "clers_shared.h"
#include "tail_table.h"

namespace prm::codec {

// §6.5.2 The Seam shortcut (SpiraleReversi::Record::odd_near) is left out of the wasm module, whose size is an issue
// 20 target: it cost 200 B gzipped there (web/README.md "hdecode4").
#if defined(__wasm__)
constexpr bool kSeamShortcut = false;
#else
constexpr bool kSeamShortcut = true;
#endif

struct HandleEvent {     // §6.4.6
  uint32_t triangle;     // forward index of the S triangle whose left branch was consumed
  uint32_t partner;      // forward index of the triangle across its left edge (> triangle)
  uint8_t partner_corner;  // corner of `partner` (0..2) opposite the shared edge
};

class SpiraleReversi {
 public:
  // §6.4.1 Starts a closed mesh of `num_triangles` triangles and `num_vertices` vertices (dummies included); allocates
  // nothing in proportion to them (§4.5). `seam_context`: whether gate_start_seam() will be asked (§6.5.2); without
  // it the records' odd_near is not kept.
  void init(uint32_t num_triangles, uint32_t num_vertices, bool seam_context = false);
  // Room ahead for the next `triangles` triangles (at most all of them): the encoder's own count, or the decoder's
  // bound from the bytes of the symbols (§4.5, kReserveTrianglesPerByte), never the count the stream claims alone.
  void reserve(uint32_t triangles);

  // §6.5.2 Context inputs for the next symbol.
  uint32_t stack_depth() const { return static_cast<uint32_t>(stack_.size()); }
  uint32_t gate_start_count() {
    return stack_.empty() ? 0 : records_[find(rec_[3 * stack_.back()])].count;
  }
  // §6.5.2 Seam: 1 if a closed vertex of the decoded fan of the gate's start vertex has a valence other than 6.
  uint32_t gate_start_seam();

  // §6.4.3-6.4.7 One step each, for t = T - 1 down to 0 in turn; false (with error() set) when the operation is
  // impossible.
  bool apply(uint32_t t, uint8_t symbol);
  bool apply_handle(uint32_t t, const HandleEvent& event, uint32_t component_end);
  bool close_component(uint32_t t0);

  // §6.4.8 Final vertex ids per corner (3 per triangle, canonical corner order) and validation (§6.8).
  bool finish(std::vector<uint32_t>& corner_vertex);

  // All the opposite corners, once every triangle is applied.
  const std::vector<int32_t>& opposites() const { return opp_.all(); }
  std::vector<int32_t>& opposites() { return opp_.all(); }
  const std::string& error() const { return error_; }
  bool error_is_non_manifold() const { return non_manifold_; }

 private:
  uint32_t find(uint32_t r) {
    while (records_[r].parent != r) {
      records_[r].parent = records_[records_[r].parent].parent;
      r = records_[r].parent;
    }
    return r;
  }
  uint32_t new_record() {
    const uint32_t r = static_cast<uint32_t>(records_.size());
    records_.push_back({r, 0, -1, 0, 0});
    return r;
  }
  PRM_WASM_INLINE void set_corner(uint32_t c, uint32_t record) {
    rec_[c] = record;
    const uint32_t r = find(record);
    Record& x = records_[r];
    ++x.count;
    if (x.id >= 0) {
      x.odd = x.count != 6;
      if (kSeamShortcut) seam_tracked_ = false;  // a closed vertex gains a triangle (no valid stream does)
    }
  }
  void glue(uint32_t c1, uint32_t c2) {
    opp_[c1] = static_cast<int32_t>(c2);
    opp_[c2] = static_cast<int32_t>(c1);
  }
  // Closes the vertex of record `record`, that of corner c.
  bool close_vertex(uint32_t record, uint32_t c);
  // §6.5.2 The vertex of corner c (root record r) is closed with a triangle count other than 6: sets odd_near of
  // every record that shares a triangle with it.
  void note_odd(uint32_t c, uint32_t r);
  // §6.4.5 Record r2 joins record r1 (both roots, both open).
  void merge(uint32_t r1, uint32_t r2) {
    records_[r2].parent = r1;
    records_[r1].count += records_[r2].count;
    if (kSeamShortcut) records_[r1].odd_near |= records_[r2].odd_near;
  }
  bool fail(const char* message);
  // Triangle t joins the tables. The callers apply t = T - 1 down to 0, one each (a contract, asserted).
  void add_triangle(uint32_t t) {
    assert(t < num_triangles_ && decoded_ == num_triangles_ - 1 - t);
    if (size_t{3} * t < opp_.first()) {  // both tables hold the same corners
      opp_.extend_to(size_t{3} * t);
      rec_.extend_to(size_t{3} * t);
    }
  }
  // Corner whose opposite edge is the open edge ending at the vertex of corner c (rotating away from c's outgoing
  // edge), or -1.
  int64_t open_edge_into(uint32_t c);
  int64_t open_edge_out_of(uint32_t c);

  TailTable<int32_t> opp_;
  TailTable<uint32_t> rec_;
  // §6.4.1 A vertex record: its union-find parent, and for a root its triangle count, its vertex id once closed (-1
  // before), and whether it is closed with a triangle count other than 6 (§6.5.2 Seam; kept with count and id: a
  // root's count and id change only in set_corner and close_vertex, and records merge only while open). One struct,
  // so that a find and the fields it leads to share a cache line.
  //
  // odd_near (§6.5.2 Seam without the walk): for a root, 1 if an odd record may share a triangle with one of its
  // corners, 0 if none does; kept while seam_tracked_. Every glued edge joins corners of the same records at both
  // ends (§6.4.2), so the Seam walk from a corner of record X only meets triangles with a corner of X, and tests
  // records that share them: with odd_near 0 it finds no odd vertex and Seam is 0. A record becomes odd only when it
  // is closed (note_odd marks the records of all its triangles, its fan being complete) or when a closed record gains
  // a triangle (no valid stream does; tracking stops, and every Seam is walked from then on).
  struct Record {
    uint32_t parent, count;
    int32_t id;
    uint16_t odd, odd_near;
  };
  std::vector<Record> records_;
  std::vector<uint32_t> stack_;
  uint32_t num_triangles_ = 0, num_vertices_ = 0, closed_ = 0, decoded_ = 0;
  bool seam_tracked_ = true;  // odd_near is exact (see Record)
  std::string error_;
  bool non_manifold_ = false;
};

}  // namespace prm::codec
