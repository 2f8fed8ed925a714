#include "spirale_reversi.h"

#include <algorithm>

#include "corner_table.h"

namespace prm::codec {

// §6.4.1 Initial state: every edge open, no records, empty stack. Nothing is sized by the claimed counts (§4.5).
void SpiraleReversi::init(uint32_t num_triangles, uint32_t num_vertices, bool seam_context) {
  num_triangles_ = num_triangles;
  num_vertices_ = num_vertices;
  opp_.reset(size_t{3} * num_triangles, -1);
  rec_.reset(size_t{3} * num_triangles, 0);
  records_.clear();
  stack_.clear();
  closed_ = 0;
  decoded_ = 0;
  seam_tracked_ = kSeamShortcut && seam_context;
  error_.clear();
  non_manifold_ = false;
}

void SpiraleReversi::reserve(uint32_t triangles) {
  const size_t t = std::min(triangles, num_triangles_);
  opp_.reserve_tail(3 * t);
  rec_.reserve_tail(3 * t);
  records_.reserve(t / 2 + 16);  // about one record per two triangles (V = T / 2 + 2 on a sphere)
}

bool SpiraleReversi::fail(const char* message) {
  if (error_.empty()) error_ = message;
  return false;
}

// §6.4.2 Rotation about the vertex of corner c across glued edges, away from c's outgoing edge, until an open edge
// ending at that vertex is met. Returns the corner opposite that open edge, or -1 if the fan closes (or the walk
// exceeds the number of corners, which only a corrupt state can cause).
// Each step moves c to next(d), d = opp[next(c)]: the rotation is back at c when d = prev(c), and the next step's
// corner next(next(d)) is prev(d).
// The walk is a function of k alone: past as many steps as there are corners it repeats itself for ever, so any bound
// above that gives the same result. Two steps per bound test.
int64_t SpiraleReversi::open_edge_into(uint32_t c) {
  const int32_t stop = static_cast<int32_t>(corner_prev(c));
  const int32_t* opp = opp_.all().data();
  const size_t first = opp_.first();
  uint32_t k = corner_next(c);
  for (uint64_t steps = 0; steps <= 3 * uint64_t{decoded_} + 3; steps += 2) {
    int32_t d = opp[k - first];
    if (d < 0) return k;
    if (d == stop) return -1;
    k = corner_prev(static_cast<uint32_t>(d));
    d = opp[k - first];
    if (d < 0) return k;
    if (d == stop) return -1;
    k = corner_prev(static_cast<uint32_t>(d));
  }
  return -1;
}

// The mirror: rotation across outgoing edges until an open edge leaving the vertex of c.
int64_t SpiraleReversi::open_edge_out_of(uint32_t c) {
  const int32_t stop = static_cast<int32_t>(corner_next(c));
  const uint64_t bound = 3 * uint64_t{decoded_} + 3;
  uint32_t k = corner_prev(c);
  for (uint64_t steps = 0; steps <= bound; ++steps) {
    const int32_t d = opp_[k];
    if (d < 0) return k;
    if (d == stop) return -1;
    k = corner_next(static_cast<uint32_t>(d));
  }
  return -1;
}

// §6.5.2 Seam. From corner A_j of the top piece's triangle j, the fan of the gate's start vertex over glued edges:
// first j itself and up to kSeamWalk triangles rotating across the edge opposite next(c), then up to kSeamWalk
// rotating across the edge opposite prev(c) from j; each walk stops at an open edge or back at j. Seam is 1 if the
// vertex of a visited triangle's corner next(c) or prev(c) is closed and has a triangle count other than 6.
uint32_t SpiraleReversi::seam_walk(uint32_t c0) {
  auto odd = [&](uint32_t c) { return records_[find(rec_[c])].odd != 0; };
  // One side: 1 odd vertex found, 0 the fan closed (every triangle seen), 2 an open edge or the bound. Crossing the
  // edge opposite turn(c) into the triangle of d, the next triangle's two other vertices are the far end of that
  // edge, tested already (a glued edge joins corners of the same records, §6.4.2), and the vertex of d itself: only
  // that one is tested.
  auto walk = [&](uint32_t (*turn)(uint32_t)) {
    uint32_t c = c0;
    for (uint32_t k = 0; k < kSeamWalk; ++k) {
      const int32_t d = opp_[turn(c)];
      if (d < 0) break;
      c = turn(static_cast<uint32_t>(d));
      if (c == c0) return 0u;
      if (odd(static_cast<uint32_t>(d))) return 1u;
    }
    return 2u;
  };
  if (odd(corner_next(c0)) || odd(corner_prev(c0))) return 1;
  const uint32_t forward = walk(corner_next);
  return forward == 2 ? walk(corner_prev) & 1u : forward;
}

// Rotates about the vertex of c across glued edges and sets odd_near of the two other corners' records of every
// triangle met. The rotation meets every corner of r only if it closes after exactly count(r) triangles
// (corners of one record are joined only through glued edges, §6.4.2); otherwise tracking stops.
// Only next(k)'s record is marked in each triangle: the step crosses the edge prev(k) -> k into the triangle of d,
// whose next(next(d)) = prev(d) has prev(k)'s record (a glued edge joins corners of the same records at both ends,
// §6.4.2), so over a closed rotation the records of the prev corners are those of the next corners; a rotation that
// does not close stops the tracking, and its marks are never read.
void SpiraleReversi::note_odd(uint32_t c, uint32_t r) {
  const uint32_t count = records_[r].count;
  uint32_t k = c, n = 0;
  do {
    const int32_t d = opp_[corner_next(k)];
    if (d < 0 || n == count) {
      seam_tracked_ = false;
      return;
    }
    records_[find(rec_[corner_next(k)])].odd_near = 1;
    ++n;
    k = corner_next(static_cast<uint32_t>(d));
  } while (k != c);
  if (n != count) seam_tracked_ = false;
}

// §6.4.6 An S whose left branch was consumed by its right branch: attach the right edge to the top piece, and glue
// the left edge to the named edge of a later triangle of the same piece.
bool SpiraleReversi::apply_handle(uint32_t t, const HandleEvent& event, uint32_t component_end) {
  add_triangle(t);
  ++decoded_;
  if (stack_.empty()) return fail("handle S with no piece to attach to");
  // partner > t: a triangle decoded already.
  if (event.partner <= t || event.partner >= component_end || event.partner >= num_triangles_ ||
      event.partner_corner > 2)
    return fail("handle partner outside the component");
  const uint32_t pc = 3 * event.partner + event.partner_corner;
  if (opp_[pc] >= 0) return fail("handle partner edge already glued");
  const uint32_t a = 3 * t, b = a + 1, v = a + 2;
  const uint32_t j = stack_.back();
  const uint32_t ja = 3 * j, jb = ja + 1, jg = ja + 2;
  // The partner edge runs p -> q (corners next(pc) -> prev(pc)); glued to t's left edge v -> a, so q is v and p is a.
  const uint32_t rq = find(rec_[corner_prev(pc)]);
  const uint32_t r1 = find(rec_[ja]);
  if (rq == r1) return fail("handle joins a vertex to itself");
  if (records_[rq].id >= 0 || records_[r1].id >= 0) return fail("handle at a closed vertex");
  glue(a, jg);
  glue(b, pc);
  set_corner(b, rec_[jb]);
  set_corner(a, rec_[corner_next(pc)]);
  merge(r1, rq);
  set_corner_root(v, r1);
  stack_.back() = t;
  return true;
}

// §6.4.7 The first triangle of a component closes its only piece, whose open boundary must be three edges.
bool SpiraleReversi::close_component(uint32_t t0) {
  add_triangle(t0);
  ++decoded_;
  if (stack_.size() != 1) return fail("a component does not end with exactly one piece");
  const uint32_t j = stack_.back();
  const uint32_t ja = 3 * j, jb = ja + 1, jg = ja + 2;
  const uint32_t p = 3 * t0, q = p + 1, r = p + 2;
  // t0's gate p->q is glued to j's gate ja->jb: p is jb, q is ja.
  const int64_t out_b = open_edge_out_of(jb);  // the open edge jb -> y
  const int64_t in_a = open_edge_into(ja);     // the open edge y' -> ja
  if (out_b < 0 || in_a < 0 || out_b == jg || in_a == jg || out_b == in_a)
    return fail("the last piece of a component is not closed by its first triangle");
  // The open edge facing corner k runs from next(k) to prev(k).
  const uint32_t y = rec_[corner_prev(static_cast<uint32_t>(out_b))];
  const uint32_t y2 = rec_[corner_next(static_cast<uint32_t>(in_a))];
  if (find(y) != find(y2)) return fail("the last piece of a component is not closed by its first triangle");
  glue(r, jg);
  set_corner(p, rec_[jb]);
  set_corner(q, rec_[ja]);
  set_corner(r, y);
  glue(p, static_cast<uint32_t>(in_a));   // t0's right edge q->r against y'->ja
  glue(q, static_cast<uint32_t>(out_b));  // t0's left edge r->p against jb->y
  stack_.pop_back();
  // §6.6 ids in forward order: r, q, p are the last three closed in reverse.
  const uint32_t rr = find(rec_[r]), rq = find(rec_[q]), rp = find(rec_[p]);
  if (rr == rq || rq == rp || rr == rp) return fail("the first triangle of a component is degenerate");
  return close_root(rr, r) && close_root(rq, q) && close_root(rp, p);
}

// §6.4.8 / §6.8 Final ids and validation: every edge glued, every record closed, and the result an oriented closed
// 2-manifold (each vertex one cycle of triangles, no triangle using a vertex twice, no two edges joining the same
// pair of vertices).
bool SpiraleReversi::finish(std::vector<uint32_t>& corner_vertex, std::vector<uint8_t>* valence) {
  if (!stack_.empty()) return fail("pieces left on the stack");
  if (closed_ != num_vertices_) return fail("vertex count differs from the component sizes and handles");
  // Vertex id of every record, then of every corner.
  const uint32_t num_records = static_cast<uint32_t>(records_.size());
  for (uint32_t r = 0; r < num_records; ++r) {
    const int32_t id = records_[find(r)].id;
    if (id < 0) return fail("a vertex is never closed");
    records_[r].id = id;
  }
  if (decoded_ != num_triangles_ || opp_.first() != 0) return fail("triangles missing");
  std::vector<int32_t>& opp = opp_.all();  // every triangle is held now
  std::vector<uint32_t>& rec = rec_.all();
  non_manifold_ = true;
  for (size_t c = 0; c < opp.size(); c += 3) {
    if ((opp[c] | opp[c + 1] | opp[c + 2]) < 0) {
      non_manifold_ = false;
      return fail("an edge is left open");
    }
    // Records become ids; one branch for the three tests.
    const uint32_t x = static_cast<uint32_t>(records_[rec[c]].id), y = static_cast<uint32_t>(records_[rec[c + 1]].id),
                   z = static_cast<uint32_t>(records_[rec[c + 2]].id);
    rec[c] = x;
    rec[c + 1] = y;
    rec[c + 2] = z;
    if ((x == y) | (y == z) | (x == z)) return fail("a decoded triangle uses a vertex twice");
  }
  // A root's count is the number of corners set to its records (set_corner, merge): its vertex's triangle count.
  if (valence) {
    valence->assign(num_vertices_, 0);
    for (uint32_t r = 0; r < num_records; ++r)
      if (records_[r].parent == r)
        (*valence)[static_cast<uint32_t>(records_[r].id)] = static_cast<uint8_t>(std::min<uint32_t>(records_[r].count, 255));
  }
  corner_vertex.swap(rec_.all());
  rec_.reset(0, 0);
  std::vector<Record>().swap(records_);  // the records are done with
  // Every glued edge joins corners of the same records at both ends and records only merge through a triangle
  // glued to both (§6.4.2), so each vertex is one closed fan. That no two edges join the same pair of vertices is
  // checked while the fans are walked for the positions (§6.8, §10.3).
  non_manifold_ = false;
  return true;
}

}  // namespace prm::codec
