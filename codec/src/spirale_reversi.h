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
#include "corner_table.h"
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
  uint32_t gate_start_seam() { return stack_.empty() ? 0 : seam_of(3 * stack_.back(), find(rec_[3 * stack_.back()])); }
  // §6.5.2 Both inputs at once, with one lookup of the gate's start record (the stack is not empty): Count, and
  // Seam if `seam_context` (else 0). The same values as gate_start_count() and gate_start_seam().
  uint32_t gate_start(bool seam_context, uint32_t& seam) {
    const uint32_t c0 = 3 * stack_.back();
    const uint32_t r = find(rec_[c0]);
    seam = seam_context ? seam_of(c0, r) : 0;
    return records_[r].count;
  }

  // §6.4.3-6.4.7 One step each, for t = T - 1 down to 0 in turn; false (with error() set) when the operation is
  // impossible.
  bool apply(uint32_t t, uint8_t symbol);
  bool apply_handle(uint32_t t, const HandleEvent& event, uint32_t component_end);
  bool close_component(uint32_t t0);

  // §6.4.8 Final vertex ids per corner (3 per triangle, canonical corner order) and validation (§6.8). `valence`
  // (optional): per vertex id, its triangle count capped at 255 (§7.3's valence context), from the records' counts.
  bool finish(std::vector<uint32_t>& corner_vertex, std::vector<uint8_t>* valence = nullptr);

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
  // Corner c gets a new record (its count 1: set_corner of a new record).
  void set_corner_new(uint32_t c) {
    const uint32_t r = static_cast<uint32_t>(records_.size());
    records_.push_back({r, 1, -1, 0, 0});
    rec_[c] = r;
  }
  PRM_WASM_INLINE void set_corner(uint32_t c, uint32_t record) { set_corner_root(c, find(record)); }
  // set_corner of a record whose root is r. The corner is given r itself: the same vertex (and so the same ids,
  // counts and Seam), and the later finds from it start at a root or near one.
  PRM_WASM_INLINE void set_corner_root(uint32_t c, uint32_t r) {
    rec_[c] = r;
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
  // §6.5.2 Seam from corner c0 of the top piece's triangle, whose root record is r: 0 without the walk when no odd
  // record shares a triangle with r (Record::odd_near), else the walk (seam_walk).
  uint32_t seam_of(uint32_t c0, uint32_t r) {
    if (kSeamShortcut && seam_tracked_ && records_[r].odd_near == 0) return 0;
    return seam_walk(c0);
  }
  uint32_t seam_walk(uint32_t c0);
  // Closes the vertex of root record r, that of corner c.
  bool close_root(uint32_t r, uint32_t c);
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
  // root's count and id change only in set_corner and close_root, and records merge only while open). One struct,
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

// apply and close_root are defined here and forced inline (apply into the decoder's symbol loop, clers_decode.cpp,
// its one call there): natively 2.0% fewer instructions per decode than the calls (callgrind, web horse;
// bench/README.md "hdecode5"); in the wasm module 2-2.5% faster in V8 for 320 B gzipped (web/README.md "hweb2").

// §6.4.8 Closing a vertex gives it the next id, counting down from the number of vertices, so that ids end up in
// forward order of discovery (§6.6).
PRM_ALWAYS_INLINE bool SpiraleReversi::close_root(uint32_t r, uint32_t c) {
  Record& x = records_[r];
  if (x.id >= 0) return fail("a vertex is closed twice");
  if (closed_ >= num_vertices_) return fail("more vertices closed than the component sizes allow");
  x.id = static_cast<int32_t>(num_vertices_ - 1 - closed_);
  x.odd = x.count != 6;
  ++closed_;
  if (kSeamShortcut && x.odd && seam_tracked_) note_odd(c, r);
  return true;
}

// §6.4.3-6.4.5 One symbol applied to triangle t (corners 3t: a, 3t+1: b, 3t+2: v; gate a->b, right edge b->v,
// left edge v->a).
PRM_ALWAYS_INLINE bool SpiraleReversi::apply(uint32_t t, uint8_t symbol) {
  add_triangle(t);
  const uint32_t a = 3 * t, b = a + 1, v = a + 2;
  ++decoded_;
  if (symbol == kE) {  // §6.4.3 a new piece of one triangle
    set_corner_new(a);
    set_corner_new(b);
    set_corner_new(v);
    stack_.push_back(t);
    return true;
  }
  if (stack_.empty()) return fail("a C, L, R or S symbol with no piece to attach to");
  const uint32_t j = stack_.back();
  const uint32_t ja = 3 * j, jb = ja + 1, jg = ja + 2;  // j's gate is ja->jb, opposite jg
  switch (symbol) {
    case kC: {  // §6.4.4 attach by the right edge, then zip the left edge around the tip
      const uint32_t tip = find(rec_[ja]);
      if (records_[tip].id >= 0) return fail("C at a closed vertex");
      const int64_t e = open_edge_into(ja);
      if (e < 0 || static_cast<uint32_t>(e) == jg) return fail("C whose tip has no open edge to zip");
      glue(a, jg);
      set_corner_root(v, tip);  // tip stays the root: nothing below merges records
      set_corner(b, rec_[jb]);
      glue(b, static_cast<uint32_t>(e));
      set_corner(a, rec_[corner_next(static_cast<uint32_t>(e))]);
      stack_.back() = t;
      return close_root(tip, v);
    }
    case kL:  // §6.4.5 attach by the right edge; a is new
      glue(a, jg);
      set_corner(v, rec_[ja]);
      set_corner(b, rec_[jb]);
      set_corner_new(a);
      stack_.back() = t;
      return true;
    case kR:  // §6.4.5 attach by the left edge; b is new
      glue(b, jg);
      set_corner(a, rec_[ja]);
      set_corner(v, rec_[jb]);
      set_corner_new(b);
      stack_.back() = t;
      return true;
    case kS: {  // §6.4.5 join the top two pieces: right child on top, left child below
      if (stack_.size() < 2) return fail("S with fewer than two pieces");
      const uint32_t k = stack_[stack_.size() - 2];
      const uint32_t ka = 3 * k, kb = ka + 1, kg = ka + 2;
      const uint32_t r1 = find(rec_[ja]), r2 = find(rec_[kb]);
      if (r1 == r2) return fail("S joins a vertex to itself");
      if (records_[r1].id >= 0 || records_[r2].id >= 0) return fail("S at a closed vertex");
      glue(a, jg);
      glue(b, kg);
      set_corner(b, rec_[jb]);
      set_corner(a, rec_[ka]);
      merge(r1, r2);  // §6.4.5 the two records of the tip become one
      set_corner_root(v, r1);
      stack_.pop_back();
      stack_.back() = t;
      return true;
    }
    default:
      return fail("symbol out of range");
  }
}

}  // namespace prm::codec
