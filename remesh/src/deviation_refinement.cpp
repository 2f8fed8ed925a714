#include "deviation_refinement.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "prm/point_triangle_distance.h"
#include "prm/remesh/lattice.h"
#include "prm/vec3.h"
#include "input_facing.h"

namespace prm::remesh {
namespace {

// How far from the split edge towards the wanted point a new vertex (or a moved one) may go, tried in this order;
// part of the way is progress too, and the next round measures what is left.
constexpr double kShares[] = {1.0, 0.75, 0.5, 0.25};
// Edge flips a facing repair may make around a new vertex (repair_facing).
constexpr int kRepairFlips = 4;
// How many steps (along some axis, rounded) a repaired vertex must keep from each of its neighbours (repaired_insertion).
constexpr uint32_t kRepairSteps = 3;
// After this many rounds, a missed input point's split of a face next to its closest one (insert_on_facing_face) is
// kept only when the new triangles come nearer the point than the mesh was (hnine: at the horse's tail tip, 1.3e-4,
// such splits put their vertex 1.9-3.8x as far from the point as the mesh was, round after round, while the point
// stayed 1.6x the bound away; checked from the first or the fifth round, the feline passed 8x at 2e-4, 8.20x).
constexpr size_t kFacingNearerAfter = 8;
// After this many rounds, a missed input point (in>pr) still farther than the bound / kTradeGain may get a new vertex
// whose triangles stray past the bound (pr>in), when they and the new vertex both stay within kTradeGain x the
// point's distance: the place's worst deviation shrinks, and the next rounds may split the new triangles where they
// stray (hcrease: the horse at 12 bits, an input vertex on a sharp tip, 4 faces around it with dihedrals of 77-120
// degrees and edges shorter than the mesh's triangles; the edge split with the new vertex at the tip strays 1.88x the
// bound, so every split of its closest face was refused and the point stayed 1.4-2.2x the bound away, while splits of
// faces next to it put their vertex 1.0-1.6e-3 from it). From the first round on, the horse's ear at 2e-4 went from
// 7.48x to 10.43x; from the fifth, no stream of the seven meshes at 2e-4 but the horse's changes.
constexpr size_t kTradeAfter = 4;
constexpr double kTradeGain = 0.8;
// After this many rounds, a missed input point that every other step refused may get a split across the crease
// beyond its closest edge (insert_across_crease), kept only where its triangles come nearer the point. hear: from the
// first round, `prm pack venus --target-error 2e-4` went from 7.38x to 8.80x; from the third, no stream of the seven
// meshes at 2e-4 changed (bench/README.md "Worst-case error", hear).
constexpr size_t kCrossAfter = 2;
// Rim moves of one vertex, over all rounds (a straying point and a missed vertex could push it back and forth).
constexpr uint8_t kMaxMoves = 2;
// After this many rounds, a rim move must also keep the input vertices closest to the vertex's faces within the bound
// of them, or as near as they were (NearInputs; hcrease: the feline's remesh at 2e-4, 9.64x, where a round-11 move for
// one input vertex left another input point 1.48x the bound away, which no later round mended. From the first round
// the horse went to 8.58x; from the fifth the feline's remesh came to 8.88x, from the ninth 8.38x, the eleventh 8.41x).
constexpr size_t kRimGuardAfter = 8;
// Input triangles with a vertex farther than this share of the bound from the mesh are probed between their vertices.
constexpr double kFaceProbeShare = 0.5;
// The finest barycentric grid (divisions per side) an input triangle near a missed vertex is probed on.
constexpr double kMaxFaceGrid = 8;
// A point of a triangle this close to an edge (smallest barycentric coordinate) splits the edge, not the triangle.
constexpr double kEdgeBarycentric = 0.02;
// round_towards_input: the vertices near places straying more than this share of the bound are rounded towards the
// input, when another rounding strays less than kRoundGain x the nearest one.
constexpr double kRoundShare = 0.75;
constexpr double kRoundGain = 0.98;
// The points of a mesh triangle the first refinement measured against the input (thin_sheets false): its centroid
// and its edges' midpoints.
constexpr double kProbes[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
// place_by_descent: rounds of the pattern search at each step size (the first step the deviation's length, halved
// kDescentHalvings times), and the share of its start's deviation the place found must stray less than.
constexpr int kDescentRounds = 4;
constexpr int kDescentHalvings = 3;
constexpr double kDescentGain = 0.98;
// descend_vertex: a straying mesh vertex may also go to a place beyond the bound that is within this share of its
// distance (hfold: a lattice vertex that rim moves for its faces' points took 1.22x (the feline's remesh at 2e-4) or
// 1.38x (the horse's ear) the bound from the input, both moves spent, while the descent found a place 1.13x (1.05x)
// away and kept none of them, as they were beyond the bound; the feline's remesh 8.27x -> 7.73x).
constexpr double kDescendGain = 0.95;
// Steps of the walk along a mesh triangle's normal into a notch it bridges (normal_reach).
constexpr int kReachSteps = 4;

// Divisions per side of the barycentric grid a triangle is probed on: about as fine as the bound (a thin tip or a
// notch strays most between the vertices, where Metro's samples find it), at least 2, at most kMaxFaceGrid.
int grid_divisions(const Vec3& a, const Vec3& b, const Vec3& c, double bound) {
  const double longest = std::sqrt(std::max({norm2(b - a), norm2(c - b), norm2(a - c)}));
  return static_cast<int>(std::clamp(std::ceil(longest / bound), 2.0, kMaxFaceGrid));
}

// A face whose probes come within this share of the bound is probed again on a grid twice as fine (at most
// kMaxFineFaceGrid divisions a side): the distance peaks sharply between the probes at a crease.
constexpr double kFineProbeShare = 0.9;
constexpr double kMaxFineFaceGrid = 16;
int fine_grid_divisions(const Vec3& a, const Vec3& b, const Vec3& c, double bound) {
  const double longest = std::sqrt(std::max({norm2(b - a), norm2(c - b), norm2(a - c)}));
  return static_cast<int>(std::clamp(std::ceil(2 * longest / bound), 4.0, kMaxFineFaceGrid));
}

// Calls visit(x) for the points of triangle (a, b, c) on its barycentric grid with n divisions a side, its vertices
// left out (they are measured on their own).
template <class Visit>
void for_each_grid_point(const Vec3& a, const Vec3& b, const Vec3& c, int n, Visit&& visit) {
  for (int p = 0; p <= n; ++p)
    for (int q = 0; p + q <= n; ++q) {
      const int r = n - p - q;
      if (p == n || q == n || r == n) continue;
      visit((1.0 / n) * (static_cast<double>(p) * a + static_cast<double>(q) * b + static_cast<double>(r) * c));
    }
}

// Where the line through `at` along the unit normal n meets the input, found by walking along it by the normal part
// of the offset to the input's closest point (kReachSteps steps): a mesh triangle bridging a notch (between two legs,
// the fold of a thin sheet) strays from the notch's bottom, and the input's closest point to it lies on a wall of the
// notch, to the side, where a new vertex would turn a triangle over; the point below it along the normal does not.
Vec3 normal_reach(const AabbTree& input_tree, const Vec3& at, const Vec3& n) {
  Vec3 x = at;
  AabbTree::Hit hint;
  for (int k = 0; k < kReachSteps; ++k) {
    input_tree.closest(x, hint);
    if (!hint.found()) break;
    x = x + dot(hint.point - x, n) * n;
  }
  return x;
}

Vec3 face_normal(const Mesh& m, const Tri& t) {
  return triangle_normal_area2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
}

// Barycentric coordinates of q (a point of triangle t) in t.
std::array<double, 3> barycentric(const Mesh& m, const Tri& t, const Vec3& q) {
  const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
  const Vec3 v0 = b - a, v1 = c - a, v2 = q - a;
  const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0), d21 = dot(v2, v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  return {1 - v - w, v, w};
}

// The face other than `not_f` that holds vertices a and b (-1 if none).
int64_t other_face(const Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, uint32_t a, uint32_t b,
                   uint32_t not_f) {
  for (uint32_t f : vertex_faces[a]) {
    if (f == not_f) continue;
    const Tri& t = m.triangles[f];
    if (t[0] == b || t[1] == b || t[2] == b) return f;
  }
  return -1;
}

// The face across edge a-b from face f, when there is one not changed in this round (touched), and its corner off
// the edge.
struct FaceAcross {
  uint32_t face = 0, corner = 0;
};
bool face_across(const Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces,
                 const std::vector<uint8_t>& touched, uint32_t a, uint32_t b, uint32_t f, FaceAcross& out) {
  const int64_t g = other_face(m, vertex_faces, a, b, f);
  if (g < 0 || touched[static_cast<size_t>(g)]) return false;
  out.face = static_cast<uint32_t>(g);
  out.corner = m.triangles[out.face][0];
  for (uint32_t x : m.triangles[out.face])
    if (x != a && x != b) out.corner = x;
  return true;
}

// The squared distance from p to the nearest of triangles `tris` of m (infinity when there is none).
template <class Tris>
double nearest2(const Mesh& m, const Tris& tris, const Vec3& p) {
  double d = std::numeric_limits<double>::infinity();
  for (const Tri& t : tris)
    d = std::min(d, point_triangle_distance2(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  return d;
}
// The same for the faces numbered `faces`.
double nearest2_of_faces(const Mesh& m, const std::vector<uint32_t>& faces, const Vec3& p) {
  double d = std::numeric_limits<double>::infinity();
  for (uint32_t f : faces) {
    const Tri& t = m.triangles[f];
    d = std::min(d, point_triangle_distance2(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  }
  return d;
}

// Does every new triangle face the way the triangle it replaces faced (and keep some area)?
bool faces_agree(const Mesh& m, const Vec3& old_normal, const std::vector<Tri>& tris) {
  const double scale = norm(old_normal);
  for (const Tri& t : tris) {
    const Vec3 n = face_normal(m, t);
    if (!(dot(n, old_normal) > 1e-3 * norm(n) * scale)) return false;
  }
  return true;
}

// A place where the mesh is too far from the input: the point `at` of mesh triangle `face`, and the point of the
// input it should reach (an input vertex the mesh misses, or the input's closest point to a mesh point that strays).
struct Deviation {
  uint32_t face;
  Vec3 at;
  Vec3 wanted;
  double distance2;
  uint32_t input_vertex;  // an input vertex; kMeshPoint, kInputPoint or kMeshVertex for the others
  uint32_t vertex = UINT32_MAX;  // kMeshVertex: the mesh vertex that strays
};
// A point of a mesh triangle (pr>in), a point of an input triangle (in>pr), a mesh vertex (pr>in: moved only).
constexpr uint32_t kMeshPoint = UINT32_MAX, kInputPoint = UINT32_MAX - 1, kMeshVertex = UINT32_MAX - 2;
bool strays_from_input(const Deviation& d) { return d.input_vertex == kMeshPoint || d.input_vertex == kMeshVertex; }

// Calls visit(x) for the probe points of triangle (a, b, c): dense, its grid_divisions grid at `bound`; else its
// centroid and its edges' midpoints (kProbes).
template <class Visit>
void for_each_probe(const Vec3& a, const Vec3& b, const Vec3& c, bool dense, double bound, Visit&& visit) {
  if (dense) {
    for_each_grid_point(a, b, c, grid_divisions(a, b, c, bound), visit);
  } else {
    for (const auto& w : kProbes) visit(w[0] * a + w[1] * b + w[2] * c);
  }
}

// The largest squared distance to the input of the probe points (for_each_probe) of some triangles; once it reaches
// `limit`, the rest are left (a figure at least the limit).
double probe_deviation2(const Mesh& m, const std::vector<Tri>& tris, const AabbTree& input_tree, double bound,
                        bool dense, double limit = HUGE_VAL) {
  double worst = 0;
  AabbTree::Hit hint;
  for (const Tri& t : tris) {
    if (worst >= limit) break;
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    for_each_probe(a, b, c, dense, bound, [&](const Vec3& x) {
      if (worst >= limit) return;
      input_tree.closest(x, hint);
      worst = std::max(worst, hint.distance2);
    });
  }
  return worst;
}
// A mesh face whose dense probes all lie within kQuietShare x the bound of the input is quiet: no figure below that
// is read (a deviation is over the bound, the fine probes start at kFineProbeShare x it, round_towards_input's
// vertices at kRoundShare x it), so its probes only ask whether the input is that near (AabbTree::within, which stops
// at the first input triangle so near) instead of for their closest points (hcpu: most of the refinement's CPU was
// these probes' closest-point queries, and most faces are quiet).
constexpr double kQuietShare = kRoundShare;
static_assert(kQuietShare <= kRoundShare && kQuietShare <= kFineProbeShare, "a quiet face's figures are never read");
// Are all of triangle (a, b, c)'s dense probes (its grid_divisions grid at `bound`) within squared distance quiet2 of
// `tree`'s surface? Yes: `hit` holds a figure between their worst squared distance and quiet2 (and a surface point
// that near).
bool quiet_probes(const AabbTree& tree, const Vec3& a, const Vec3& b, const Vec3& c, double bound, double quiet2,
                  AabbTree::Hit& hit) {
  AabbTree::Hit hint, worst;
  bool quiet = true;
  for_each_grid_point(a, b, c, grid_divisions(a, b, c, bound), [&](const Vec3& x) {
    if (!quiet) return;
    quiet = tree.within(x, quiet2, hint);
    if (quiet && !(worst.found() && worst.distance2 >= hint.distance2)) worst = hint;
  });
  if (quiet) hit = worst;
  return quiet;
}

// The triangles of some faces.
std::vector<Tri> triangles_of(const Mesh& m, const std::vector<uint32_t>& faces) {
  std::vector<Tri> tris;
  for (uint32_t f : faces) tris.push_back(m.triangles[f]);
  return tris;
}

// What a new vertex must not do (thin sheets): make its triangles stray from the input (at their probe points) more
// than the bound and more than the triangles they replace did; a vertex at the input's closest point to the side of
// a notch, or on a wall of a dent, would. No input tree: not checked (the first refinement).
struct StrayCheck {
  const AabbTree* input_tree = nullptr;
  double bound = 0;
  bool dense = true;  // DeviationRefinementOptions::dense_probes
  InputFacing facing;  // DeviationRefinementOptions::facing_guard (no input: not checked)
  // trade2 > 0 (kTradeAfter): new triangles within that squared distance also pass when the new vertex at `placed`
  // is that near the missed point `wanted`.
  bool passes(const Mesh& m, const std::vector<Tri>& old_tris, const std::vector<Tri>& new_tris, double trade2 = 0,
              const Vec3& wanted = {}, const Vec3& placed = {}) const {
    if (input_tree == nullptr) return true;
    const double allowed2 = std::max(bound * bound, probe_deviation2(m, old_tris, *input_tree, bound, dense));
    const double new2 = probe_deviation2(m, new_tris, *input_tree, bound, dense);
    return new2 <= allowed2 || (new2 <= trade2 && norm2(placed - wanted) <= trade2);
  }
};

// Vertex nv's place near `start` where cost() (the worst squared deviation of its triangles; infinite when one
// turns over) is least: a pattern search along `directions` (both ways), `step` first, then halved kDescentHalvings
// times. True (nv there) when that place's cost is within limit2 (the squared bound: a place that is only better
// than before was tried and made the horse worse, 9.6x) and below kDescentGain x the cost at start (for a new
// vertex the new triangles lie in the old ones' plane there, so that is the old deviation seen by the new probes).
template <class Cost>
bool place_by_descent(Mesh& m, uint32_t nv, const Vec3& start, double step, double limit2, Cost&& cost,
                      const std::vector<Vec3>& directions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}) {
  m.positions[nv] = start;
  const double at_start = cost();
  if (!std::isfinite(at_start) || !(step > 0)) return false;
  Vec3 x = start;
  double cx = at_start;
  for (int level = 0; level <= kDescentHalvings; ++level, step *= 0.5) {
    bool improved = true;
    for (int round = 0; improved && round < kDescentRounds; ++round) {
      improved = false;
      for (const Vec3& dir : directions)
        for (double sign : {-1.0, 1.0}) {
          const Vec3 y = x + (sign * step) * dir;
          m.positions[nv] = y;
          const double cy = cost();
          if (cy < cx) x = y, cx = cy, improved = true;
        }
    }
  }
  m.positions[nv] = x;
  return cx < kDescentGain * at_start && cx <= limit2;
}

// Face f replaced by tris[0] and tris[1..2] appended (a split in three); they are touched.
void commit_split_in_three(Mesh& m, std::vector<uint8_t>& touched, uint32_t f, const std::vector<Tri>& tris) {
  m.triangles[f] = tris[0];
  m.triangles.push_back(tris[1]);
  m.triangles.push_back(tris[2]);
  touched[f] = 1;
  touched.resize(m.triangles.size(), 1);
}

// Faces f and g (across the split edge) replaced by mine[0] and theirs[0], mine[1] and theirs[1] appended; touched.
void commit_edge_split(Mesh& m, std::vector<uint8_t>& touched, uint32_t f, uint32_t g, const std::vector<Tri>& mine,
                       const std::vector<Tri>& theirs) {
  m.triangles[f] = mine[0];
  m.triangles.push_back(mine[1]);
  m.triangles[g] = theirs[0];
  m.triangles.push_back(theirs[1]);
  touched[f] = 1;
  touched[g] = 1;
  touched.resize(m.triangles.size(), 1);
}

// Faces around a new vertex nv (its last corner) that a facing repair may change: tris[i] replaces faces[i] (the rest
// are appended), and the edge of tris[i] opposite nv was an edge of face origin[i].
struct FacingPatch {
  std::vector<Tri> tris;
  std::vector<uint32_t> origin;
  std::vector<uint32_t> faces;
};

// Facing repair (hrefine2): where some of the new vertex nv's triangles face away from the input, the edge opposite nv
// in such a triangle is flipped with the face across it (untouched, not in the patch, its third corner not yet a
// neighbour of nv), at most kRepairFlips times, until every triangle faces the input. A flip's two triangles must
// agree with the two faces it replaces. False when some triangle still faces away.
bool repair_facing(const Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces,
                   const std::vector<uint8_t>& touched, const InputFacing& facing, uint32_t nv, FacingPatch& p) {
  if (facing.input == nullptr) return false;
  for (int flips = 0; flips <= kRepairFlips; ++flips) {
    size_t i = 0;
    while (i < p.tris.size() && facing.faces(m, p.tris[i])) ++i;
    if (i == p.tris.size()) return flips > 0;
    if (flips == kRepairFlips) return false;
    const uint32_t x = p.tris[i][0], y = p.tris[i][1];
    const int64_t h = other_face(m, vertex_faces, x, y, p.origin[i]);
    if (h < 0 || touched[static_cast<size_t>(h)] ||
        std::find(p.faces.begin(), p.faces.end(), static_cast<uint32_t>(h)) != p.faces.end())
      return false;
    const Tri& u = m.triangles[static_cast<size_t>(h)];
    uint32_t z = u[0];
    for (uint32_t w : u)
      if (w != x && w != y) z = w;
    for (const Tri& t : p.tris)
      if (t[0] == z || t[1] == z) return false;
    const std::vector<Tri> two = {{x, z, nv}, {z, y, nv}};
    if (!faces_agree(m, normalized(face_normal(m, p.tris[i])) + normalized(face_normal(m, u)), two)) return false;
    p.tris[i] = two[0];
    p.tris.push_back(two[1]);
    p.origin[i] = static_cast<uint32_t>(h);
    p.origin.push_back(static_cast<uint32_t>(h));
    p.faces.push_back(static_cast<uint32_t>(h));
  }
  return false;
}

// A repaired patch into m: p.tris over p.faces, the rest appended; all touched.
void commit_patch(Mesh& m, std::vector<uint8_t>& touched, const FacingPatch& p) {
  for (size_t i = 0; i < p.tris.size(); ++i) {
    if (i < p.faces.size()) {
      m.triangles[p.faces[i]] = p.tris[i];
      touched[p.faces[i]] = 1;
    } else {
      m.triangles.push_back(p.tris[i]);
    }
  }
  touched.resize(m.triangles.size(), 1);
}

// The new triangles (and the faces they replace) with the new vertex nv at its place: repaired (repair_facing) when
// some face away from the input, then kept when they face it and pass the check. False: m unchanged.
bool repaired_insertion(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, std::vector<uint8_t>& touched,
                        const StrayCheck& check, uint32_t nv, FacingPatch p) {
  if (!repair_facing(m, vertex_faces, touched, check.facing, nv, p)) {
    ++check.facing.refusals;
    return false;
  }
  if (!check.facing.keeps_facing(m, p.tris)) return false;  // (repair_facing found them all facing the input)
  // Within kRepairSteps of a neighbour once rounded, the separation may move one of them and turn a triangle (venus:
  // a knife edge repaired five times over, one decoded face away).
  if (check.facing.frame != nullptr)
    for (const Tri& t : p.tris)
      if (check.facing.steps_apart(m.positions[nv], m.positions[t[0]]) < kRepairSteps ||
          check.facing.steps_apart(m.positions[nv], m.positions[t[1]]) < kRepairSteps)
        return false;
  std::vector<Tri> old;
  for (uint32_t f : p.faces) old.push_back(m.triangles[f]);
  if (!check.passes(m, old, p.tris)) return false;
  commit_patch(m, touched, p);
  return true;
}

// Splits face f in three at the new vertex nv, placed at `to` or, where that turns a triangle over, part of the way
// there from `from` (kShares). nearer2 > 0: only a place whose triangles come nearer `to` than sqrt(nearer2). trade2:
// StrayCheck::passes. False (f unchanged) when every place turns one over or fails the check.
bool split_in_three(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, std::vector<uint8_t>& touched,
                    const StrayCheck& check, uint32_t f, uint32_t nv, const Vec3& from, const Vec3& to,
                    double nearer2 = 0, double trade2 = 0) {
  const Tri t = m.triangles[f];
  const Vec3 old_normal = face_normal(m, t);
  const std::vector<Tri> tris = {{t[0], t[1], nv}, {t[1], t[2], nv}, {t[2], t[0], nv}};
  for (double share : kShares) {
    m.positions[nv] = from + share * (to - from);
    if (nearer2 > 0 && nearest2(m, tris, to) >= nearer2) continue;
    if (!faces_agree(m, old_normal, tris)) continue;
    if (check.facing.away(m, tris) > 0) {
      if (repaired_insertion(m, vertex_faces, touched, check, nv, {tris, {f, f, f}, {f}})) return true;
      continue;
    }
    if (!check.facing.keeps(m, tris) || !check.passes(m, {t}, tris, trade2, to, m.positions[nv])) continue;
    commit_split_in_three(m, touched, f, tris);
    return true;
  }
  return false;
}

// Splits the edge of face f opposite its corner k, and the triangle across it, at the new vertex nv: placed at d's
// wanted point or, where that turns a triangle over (beyond a corner or a sharp crease), part of the way there from
// the edge (kShares); with along_normal (a straying point), then at the input along the pair's normal below the point
// on the edge. nearer2 > 0: only a place whose four triangles come nearer d's wanted point than sqrt(nearer2). trade2:
// StrayCheck::passes. onto_input: each place moved to the input's closest point to it (reach_onto_input). False
// (m unchanged) when every place turns one over or fails the check.
bool split_edge(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, std::vector<uint8_t>& touched,
                const AabbTree& input_tree, const StrayCheck& check, bool along_normal, double trade2,
                const Deviation& d, uint32_t f, int k, uint32_t nv, double nearer2 = 0, bool onto_input = false) {
  const Tri t = m.triangles[f];
  const Vec3 old_normal = face_normal(m, t);
  const uint32_t a = t[static_cast<size_t>((k + 1) % 3)], b = t[static_cast<size_t>((k + 2) % 3)],
                 c = t[static_cast<size_t>(k)];
  FaceAcross across;
  if (!face_across(m, vertex_faces, touched, a, b, f, across)) return false;
  const uint32_t g = across.face, e = across.corner;
  const Tri u = m.triangles[g];
  const std::vector<Tri> mine = {{a, nv, c}, {nv, b, c}}, theirs = {{b, nv, e}, {nv, a, e}};
  const Vec3 pa = m.positions[a], pb = m.positions[b];
  const double s = std::clamp(dot(d.wanted - pa, pb - pa) / std::max(norm2(pb - pa), 1e-300), 0.1, 0.9);
  const Vec3 on_edge = pa + s * (pb - pa);
  const Vec3 normal_u = face_normal(m, u);
  // The wanted point, then (a straying point) the input along the pair's normal below the point on the edge.
  std::vector<Vec3> targets = {d.wanted};
  if (along_normal)
    targets.push_back(normal_reach(input_tree, on_edge, normalized(normalized(old_normal) + normalized(normal_u))));
  for (const Vec3& target : targets)
    for (double share : kShares) {
      m.positions[nv] = on_edge + share * (target - on_edge);
      if (onto_input) m.positions[nv] = input_tree.closest(m.positions[nv]).point;
      if (nearer2 > 0 && nearest2(m, std::array<Tri, 4>{mine[0], mine[1], theirs[0], theirs[1]}, d.wanted) >= nearer2)
        continue;
      if (!faces_agree(m, old_normal, mine) || !faces_agree(m, normal_u, theirs)) continue;
      if (check.facing.away(m, {mine[0], mine[1], theirs[0], theirs[1]}) > 0) {
        const uint32_t gf = static_cast<uint32_t>(g);
        if (repaired_insertion(m, vertex_faces, touched, check, nv,
                               {{{c, a, nv}, {b, c, nv}, {e, b, nv}, {a, e, nv}}, {f, f, gf, gf}, {f, gf}}))
          return true;
        continue;
      }
      if (!check.facing.keeps(m, {mine[0], mine[1], theirs[0], theirs[1]}) ||
          !check.passes(m, {t, u}, {mine[0], mine[1], theirs[0], theirs[1]}, trade2, d.wanted, m.positions[nv]))
        continue;
      commit_edge_split(m, touched, f, static_cast<uint32_t>(g), mine, theirs);
      return true;
    }
  return false;
}

// Inserts a vertex for d into m (splitting d.face, or one of its edges and the triangle across it). False when every
// way of doing so turns a triangle over or touches a triangle changed in this round.
// A straying mesh point (strays_from_input) with `reach`: where the input's closest point would turn a triangle over,
// the new vertex goes along the normal (normal_reach) instead. `trade`: a missed input point's new vertex at it (or
// part of the way) may make triangles that stray past the bound, within kTradeGain x its distance (kTradeAfter).
bool insert(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, std::vector<uint8_t>& touched,
            const AabbTree& input_tree, const StrayCheck& check, bool reach, bool descent, bool trade,
            const Deviation& d) {
  const uint32_t f = d.face;
  const Tri t = m.triangles[f];
  const Vec3 old_normal = face_normal(m, t);
  const std::array<double, 3> bc = barycentric(m, t, d.at);
  const uint32_t nv = static_cast<uint32_t>(m.positions.size());
  const bool along_normal = reach && strays_from_input(d);
  const double trade2 = trade && !strays_from_input(d) ? kTradeGain * kTradeGain * d.distance2 : 0;
  m.positions.push_back(d.wanted);
  std::array<int, 3> corners = {0, 1, 2};  // the closest edge first: opposite the smallest coordinate
  std::sort(corners.begin(), corners.end(),
            [&](int x, int y) { return bc[static_cast<size_t>(x)] < bc[static_cast<size_t>(y)]; });
  if (bc[static_cast<size_t>(corners[0])] > kEdgeBarycentric) {
    // Inside the triangle: split it in three.
    if (split_in_three(m, vertex_faces, touched, check, f, nv, d.at, d.wanted, 0, trade2)) return true;
    if (along_normal &&
        split_in_three(m, vertex_faces, touched, check, f, nv, d.at, normal_reach(input_tree, d.at, normalized(old_normal))))
      return true;
  }
  // Near an edge (or where the split in three turns a triangle over): split an edge and both its triangles. The new
  // vertex at the wanted point or, where that turns a triangle over (beyond a corner or a sharp crease), part of the
  // way there from the edge.
  const bool on_edge_point = bc[static_cast<size_t>(corners[0])] <= kEdgeBarycentric;
  for (int k : corners) {
    // A point on an edge: only that edge (splitting another one leaves the point where it was, and a sliver).
    if (on_edge_point && k != corners[0]) break;
    if (split_edge(m, vertex_faces, touched, input_tree, check, along_normal, trade2, d, f, k, nv)) return true;
  }
  // descent_placement: no fixed place served; the place near the split point whose new triangles stray least (and,
  // for a missed input point, lie nearest it), when that is clearly less than at the split point.
  if (descent && check.input_tree != nullptr) {
    const double step = std::sqrt(d.distance2);
    const auto cost = [&](const std::vector<Tri>& tris, const std::vector<std::pair<Vec3, const std::vector<Tri>*>>&
                                                            normals) {
      for (const auto& [normal, group] : normals)
        if (!faces_agree(m, normal, *group)) return std::numeric_limits<double>::infinity();
      if (check.facing.away(m, tris) > 0) return std::numeric_limits<double>::infinity();
      // The probes leave the vertices out: the new vertex's own distance counts too.
      double worst = std::max(probe_deviation2(m, tris, *check.input_tree, check.bound, check.dense),
                              check.input_tree->closest(m.positions[nv]).distance2);
      if (!strays_from_input(d)) worst = std::max(worst, nearest2(m, tris, d.wanted));
      return worst;
    };
    const size_t k = static_cast<size_t>(corners[0]);
    if (bc[k] > kEdgeBarycentric) {
      const std::vector<Tri> tris = {{t[0], t[1], nv}, {t[1], t[2], nv}, {t[2], t[0], nv}};
      if (place_by_descent(m, nv, d.at, step, check.bound * check.bound,
                           [&] { return cost(tris, {{old_normal, &tris}}); })) {
        commit_split_in_three(m, touched, f, tris);
        return true;
      }
    } else {
      const uint32_t a = t[(k + 1) % 3], b = t[(k + 2) % 3], c = t[k];
      const int64_t g = other_face(m, vertex_faces, a, b, f);
      if (g >= 0 && !touched[static_cast<size_t>(g)]) {
        const Tri u = m.triangles[static_cast<size_t>(g)];
        uint32_t e = u[0];
        for (uint32_t x : u)
          if (x != a && x != b) e = x;
        const std::vector<Tri> mine = {{a, nv, c}, {nv, b, c}}, theirs = {{b, nv, e}, {nv, a, e}};
        const std::vector<Tri> all = {mine[0], mine[1], theirs[0], theirs[1]};
        const Vec3 pa = m.positions[a], pb = m.positions[b], normal_u = face_normal(m, u);
        const double s = std::clamp(dot(d.at - pa, pb - pa) / std::max(norm2(pb - pa), 1e-300), 0.1, 0.9);
        if (place_by_descent(m, nv, pa + s * (pb - pa), step, check.bound * check.bound,
                             [&] { return cost(all, {{old_normal, &mine}, {normal_u, &theirs}}); })) {
          commit_edge_split(m, touched, f, static_cast<uint32_t>(g), mine, theirs);
          return true;
        }
      }
    }
  }
  m.positions.pop_back();
  return false;
}

// A missed input point beyond a crease, where every split of the closest edge turns a new face over against the face
// it splits (hear: the horse's leg tip in `prm remesh --target-error 2e-4`, 10.31x -> 9.40x with the 6% budget; it
// does not serve the 115-degree place of the horse at 1.3e-4, still 9.42x). The face across that edge has two more
// edges; a split of one of them (split_edge, the new vertex at the point or part of the way there) puts the vertex
// on the crease's far side, where its triangles may face the point; kept only where they come nearer the point than
// d's distance. Nearest the point first. False when none is made.
bool insert_across_crease(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces,
                          std::vector<uint8_t>& touched, const AabbTree& input_tree, const StrayCheck& check,
                          double trade2, const Deviation& d) {
  const Tri t = m.triangles[d.face];
  const std::array<double, 3> bc = barycentric(m, t, d.at);
  const int k = static_cast<int>(std::min_element(bc.begin(), bc.end()) - bc.begin());
  const uint32_t a = t[static_cast<size_t>((k + 1) % 3)], b = t[static_cast<size_t>((k + 2) % 3)];
  FaceAcross across;
  if (!face_across(m, vertex_faces, touched, a, b, d.face, across)) return false;
  const uint32_t gf = across.face;
  const Tri u = m.triangles[gf];
  // (squared distance of its midpoint to the point, corner of u opposite it)
  std::vector<std::pair<double, int>> edges;
  for (int j = 0; j < 3; ++j) {
    const uint32_t x = u[static_cast<size_t>((j + 1) % 3)], y = u[static_cast<size_t>((j + 2) % 3)];
    if ((x == a && y == b) || (x == b && y == a)) continue;
    edges.push_back({norm2(d.wanted - 0.5 * (m.positions[x] + m.positions[y])), j});
  }
  std::sort(edges.begin(), edges.end());
  const uint32_t nv = static_cast<uint32_t>(m.positions.size());
  m.positions.push_back(d.wanted);
  for (const auto& [dist2, j] : edges)
    if (split_edge(m, vertex_faces, touched, input_tree, check, false, trade2, d, gf, j, nv, d.distance2)) return true;
  m.positions.pop_back();
  return false;
}

// reach_onto_input: a missed input point's closest edge split with the new vertex on the input (split_edge's
// onto_input), kept only where its four triangles come nearer the point than d's distance (as insert_across_crease's;
// without it, on htail2's strand beside a lattice rim the input ended 1.454 from the mesh instead of 0.938). False
// when it is not made.
bool insert_onto_input(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, std::vector<uint8_t>& touched,
                       const AabbTree& input_tree, const StrayCheck& check, const Deviation& d) {
  const std::array<double, 3> bc = barycentric(m, m.triangles[d.face], d.at);
  const int k = static_cast<int>(std::min_element(bc.begin(), bc.end()) - bc.begin());
  const uint32_t nv = static_cast<uint32_t>(m.positions.size());
  m.positions.push_back(d.wanted);
  if (split_edge(m, vertex_faces, touched, input_tree, check, false, 0, d, d.face, k, nv, d.distance2, true)) return true;
  m.positions.pop_back();
  return false;
}

// A missed input point beyond a corner or an edge of the mesh (a thin sheet's tip, cut off by the resampling): a
// split of the closest face would turn a triangle over, but a face next to it may face the point (the strip that
// closes the sheet, whose normal points along the sheet). Among the faces around d.face's corners, those facing the
// point best first, the first whose split in three with the new vertex at the point (or part of the way there from
// its centroid) turns nothing over is split; with `nearer`, only where its triangles come nearer the point than d's
// distance (kFacingNearerAfter). False when none is.
bool insert_on_facing_face(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces,
                           std::vector<uint8_t>& touched, const StrayCheck& check, const Deviation& d, bool nearer) {
  std::vector<std::pair<double, uint32_t>> candidates;  // (-cosine, face)
  for (uint32_t v : m.triangles[d.face])
    for (uint32_t h : vertex_faces[v]) {
      if (touched[h]) continue;
      const Tri& t = m.triangles[h];
      const Vec3 centroid = (1.0 / 3) * (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]);
      const Vec3 n = face_normal(m, t), to = d.wanted - centroid;
      const double len = norm(n) * norm(to);
      if (len > 0 && dot(n, to) > 0) candidates.push_back({-dot(n, to) / len, h});
    }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  const uint32_t nv = static_cast<uint32_t>(m.positions.size());
  m.positions.push_back(d.wanted);
  for (const auto& [cosine, h] : candidates) {
    const Tri& t = m.triangles[h];
    const Vec3 centroid = (1.0 / 3) * (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]);
    if (split_in_three(m, vertex_faces, touched, check, h, nv, centroid, d.wanted, nearer ? d.distance2 : 0))
      return true;
  }
  m.positions.pop_back();
  return false;
}

// A triangle that strays from the input at a point near its edge a-b (pr>in: it bridges a notch or the fold of a
// thin sheet) may follow the input with that edge flipped, at no cost in vertices: the pair (c, a, b), (b, a, e)
// becomes (c, a, e), (c, e, b) when c-e is not an edge yet, neither new face turns over against the pair, and the
// new faces' probe points stray less than the old ones'. False when the flip is not made.
bool flip_straying_edge(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, const AabbTree& input_tree,
                        double bound, bool dense, const InputFacing& facing, std::vector<uint8_t>& touched,
                        const Deviation& d) {
  const uint32_t f = d.face;
  const Tri t = m.triangles[f];
  const std::array<double, 3> bc = barycentric(m, t, d.at);
  const size_t k = static_cast<size_t>(std::min_element(bc.begin(), bc.end()) - bc.begin());
  if (bc[k] > kEdgeBarycentric) return false;
  const uint32_t c = t[k], a = t[(k + 1) % 3], b = t[(k + 2) % 3];
  FaceAcross across;
  if (!face_across(m, vertex_faces, touched, a, b, f, across)) return false;
  const uint32_t g = across.face, e = across.corner;
  const Tri u = m.triangles[g];
  if (e == c) return false;
  for (uint32_t h : vertex_faces[c]) {
    const Tri& w = m.triangles[h];
    if (w[0] == e || w[1] == e || w[2] == e) return false;  // c-e is an edge already
  }
  const Vec3 pair_normal = face_normal(m, t) + face_normal(m, u);
  const Tri old_f = t, old_g = u;
  const double before =
      probe_deviation2(m, {m.triangles[f], m.triangles[static_cast<size_t>(g)]}, input_tree, bound, dense);
  m.triangles[f] = {c, a, e};
  m.triangles[static_cast<size_t>(g)] = {c, e, b};
  if (faces_agree(m, pair_normal, {m.triangles[f], m.triangles[static_cast<size_t>(g)]}) &&
      facing.keeps(m, {m.triangles[f], m.triangles[static_cast<size_t>(g)]}) &&
      probe_deviation2(m, {m.triangles[f], m.triangles[static_cast<size_t>(g)]}, input_tree, bound, dense) < before) {
    touched[f] = 1;
    touched[static_cast<size_t>(g)] = 1;
    return true;
  }
  m.triangles[f] = old_f;
  m.triangles[static_cast<size_t>(g)] = old_g;
  return false;
}

// The input vertices whose closest face (this round's measure) is each mesh face, for the rim moves' check
// (kRimGuardAfter).
struct NearInputs {
  const Mesh* input = nullptr;
  const std::vector<AabbTree::Hit>* hits = nullptr;
  std::vector<std::vector<uint32_t>> of_face;
};

// The tip moves made (move_rim_vertex's tip_move, at most one per vertex over all rounds) and where each went.
struct TipMoves {
  std::vector<uint8_t> made;
  std::vector<Vec3> to;
};

// A thin sheet's rim (issue 22): where the resampling cut a tip off, the mesh's closest point to the missed input
// vertex lies on the seam that closes the sheet, between irregular vertices. Moving one of them out to the input
// vertex (or part of the way) follows the tip at no cost in vertices. Tries the face's irregular vertices, nearest
// the wanted point first; a move is kept when no face around the vertex turns over and the faces' probe points stay
// within the bound (or within what they strayed before). For a straying point (pr>in) a lattice vertex may move too,
// along its relief's axis only (a lattice vertex off a smooth part of the input: CGAL's bunny00), when its faces and
// itself then stray less; and (lattice_reach) for a missed input point, along its axis towards it, when the point
// then lies at least 10% nearer its faces and they stay within the bound (a move instead of a new vertex, which
// costs more bytes). False when no move is kept.
// With tip_move (htail: for a missed input point that no move, split or facing-face split above served): an
// irregular vertex not moved so before (`tips`, once per vertex over all rounds, apart from kMaxMoves) moves
// out to the point even where its faces then stray beyond the bound, as long as they stray no farther than the point
// was missed and the point comes no farther from them: a thin sheet's tip beyond the rim (the horse's tail at
// 1.3e-4) is missed by 1.6x the bound while its rim vertex, moved there, makes a face across the notch beside the tip
// stray 1.25x; later rounds split that face.
// With `near` (kRimGuardAfter), a move must also keep the input vertices closest to the vertex's faces within the
// bound of those faces or as near as they were.
// A tip move is kept from any round on: a later move of that vertex for a straying point must keep the point it went
// to (`tips`) within the bound of its faces when it is (h115: the horse's 115-degree place at 1.3e-4, an input
// vertex on a sharp crease whose tip move the next round's move for a straying point undid; no later step reached it).
bool move_rim_vertex(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, const PrmMesh& prm,
                     const AabbTree& input_tree, const DeviationRefinementOptions& options, double bound2,
                     const InputFacing& facing, std::vector<uint8_t>& touched, std::vector<uint8_t>& moved,
                     const std::vector<uint8_t>& boundary, const NearInputs* near, const Deviation& d,
                     TipMoves& tips, bool tip_move = false) {
  const Tri t = m.triangles[d.face];
  std::array<uint32_t, 3> order = {t[0], t[1], t[2]};
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return norm2(m.positions[a] - d.wanted) < norm2(m.positions[b] - d.wanted);
  });
  if (d.input_vertex == kMeshVertex) order = {d.vertex, d.vertex, d.vertex};
  const bool mesh_point = strays_from_input(d);
  for (uint32_t v : order) {
    // A lattice vertex keeps its lattice place: it moves only along its relief's axis (its height, as the
    // least-squares heights move it), for a straying point or (lattice_reach) towards a missed input point.
    const bool lattice = v < prm.vertex_relief.size() && prm.vertex_relief[v] >= 0;
    if (lattice && (!options.lattice_moves || (!mesh_point && !options.lattice_reach))) continue;
    if (tip_move && (lattice || mesh_point || v >= tips.made.size() || tips.made[v])) continue;
    if (v >= moved.size() || (!tip_move && moved[v] >= kMaxMoves)) continue;  // inserted in this round, or moved enough
    if (v < boundary.size() && boundary[v]) continue;  // the input's boundary stays where it is
    const std::vector<uint32_t>& faces = vertex_faces[v];
    if (std::any_of(faces.begin(), faces.end(), [&](uint32_t f) { return touched[f] != 0; })) continue;
    std::vector<Vec3> normals;
    for (uint32_t f : faces) normals.push_back(face_normal(m, m.triangles[f]));
    const std::vector<Tri> tris = triangles_of(m, faces);
    const Vec3 from = m.positions[v];
    // A missed input vertex: the vertex goes to it. A straying mesh point: the vertex moves as the point should, and
    // its faces must stray less than before.
    Vec3 to = mesh_point ? from + (d.wanted - d.at) : d.wanted;
    if (lattice) {
      const Vec3 axis = axis_vector(prm.relief_axis[static_cast<size_t>(prm.vertex_relief[v])]);
      to = d.input_vertex == kMeshVertex ? normal_reach(input_tree, from, axis) : from + dot(to - from, axis) * axis;
    }
    // The faces' probe points and (lattice_moves) the vertex itself.
    const auto deviation2 = [&] {
      const double faces2 =
          probe_deviation2(m, triangles_of(m, faces), input_tree, options.max_deviation, options.dense_probes);
      return options.lattice_moves ? std::max(faces2, input_tree.closest(m.positions[v]).distance2) : faces2;
    };
    // A missed input point a lattice vertex moves for: its distance to the vertex's faces, which the move must cut
    // by at least 10% (the axis may pass it by).
    const auto missed2 = [&] {
      return nearest2_of_faces(m, faces, d.wanted);
    };
    const double missed_before2 = lattice && !mesh_point ? missed2() : 0;
    // The input vertices closest to v's faces, each with the squared distance it may come to: the bound or where it was.
    std::vector<std::pair<Vec3, double>> guarded;
    if (near != nullptr)
      for (uint32_t f : faces)
        if (f < near->of_face.size())
          for (uint32_t u : near->of_face[f])
            guarded.push_back({near->input->positions[u], std::max(bound2, (*near->hits)[u].distance2)});
    if (mesh_point && v < tips.made.size() && tips.made[v] && nearest2_of_faces(m, faces, tips.to[v]) <= bound2)
      guarded.push_back({tips.to[v], bound2});
    const auto guarded_near = [&] {
      for (const auto& [q, allowed2] : guarded) {
        // (allowed2: the distance before the move, measured again)
        if (nearest2_of_faces(m, faces, q) > allowed2 * 1.0000001) return false;
      }
      return true;
    };
    const double before2 = deviation2();
    const double allowed2 = tip_move           ? std::max({bound2, before2, d.distance2})
                            : mesh_point       ? before2 * 0.999
                                               : std::max(bound2, before2);
    for (double share : kShares) {
      m.positions[v] = from + share * (to - from);
      bool ok = true;
      for (size_t k = 0; k < faces.size() && ok; ++k) {
        const Vec3 n = face_normal(m, m.triangles[faces[k]]);
        ok = dot(n, normals[k]) > 1e-3 * norm(n) * norm(normals[k]);
      }
      if (ok && lattice && !mesh_point) ok = missed2() < 0.81 * missed_before2;
      if (ok) ok = guarded_near();
      if (ok && tip_move) ok = missed2() <= d.distance2;
      if (ok && facing.keeps(m, tris) && deviation2() <= allowed2) {
        for (uint32_t f : faces) touched[f] = 1;
        if (tip_move) {
          tips.made[v] = 1;
          tips.to[v] = d.wanted;
        } else {
          ++moved[v];
        }
        return true;
      }
    }
    m.positions[v] = from;
  }
  return false;
}

// descent_placement for a mesh vertex v that strays (pr>in) and that move_rim_vertex left: the place near it where
// the worst of its own distance to the input and its faces' probe points is least (a lattice vertex along its
// relief's axis only: it keeps its lattice place), when that is within the bound and below kDescentGain x where it
// is (h22max5: the horse's hoof, a lattice vertex on an 82-degree crease whose axis move towards the input's
// closest point turned a face over), or (kDescendGain) beyond the bound but clearly nearer than the vertex was.
bool descend_vertex(Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, PrmMesh& prm,
                    const AabbTree& input_tree, const DeviationRefinementOptions& options, const InputFacing& facing,
                    std::vector<uint8_t>& touched, const std::vector<uint8_t>& boundary, const Deviation& d) {
  const uint32_t v = d.vertex;
  if (v < boundary.size() && boundary[v]) return false;  // the input's boundary stays where it is
  const std::vector<uint32_t>& faces = vertex_faces[v];
  if (std::any_of(faces.begin(), faces.end(), [&](uint32_t f) { return touched[f] != 0; })) return false;
  const std::vector<Tri> tris = triangles_of(m, faces);
  std::vector<Vec3> normals;
  for (const Tri& t : tris) normals.push_back(face_normal(m, t));
  const auto cost = [&] {
    for (size_t k = 0; k < tris.size(); ++k)
      if (!faces_agree(m, normals[k], {tris[k]})) return std::numeric_limits<double>::infinity();
    if (facing.away(m, tris) > 0) return std::numeric_limits<double>::infinity();
    return std::max(probe_deviation2(m, tris, input_tree, options.max_deviation, options.dense_probes),
                    input_tree.closest(m.positions[v]).distance2);
  };
  const bool lattice = v < prm.vertex_relief.size() && prm.vertex_relief[v] >= 0;
  std::vector<Vec3> directions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  if (lattice) directions = {axis_vector(prm.relief_axis[static_cast<size_t>(prm.vertex_relief[v])])};
  const Vec3 from = m.positions[v];
  const double limit2 =
      std::max(options.max_deviation * options.max_deviation, kDescendGain * kDescendGain * d.distance2);
  if (place_by_descent(m, v, from, std::sqrt(d.distance2), limit2, cost, directions)) {
    for (uint32_t f : faces) touched[f] = 1;
    return true;
  }
  m.positions[v] = from;
  if (lattice && place_by_descent(m, v, from, std::sqrt(d.distance2), limit2, cost)) {
    prm.vertex_relief[v] = -1;
    for (uint32_t f : faces) touched[f] = 1;
    return true;
  }
  m.positions[v] = from;
  return false;
}

// One probe point x of a triangle whose worst probe is sought: its closest point on `tree`, from the previous probe's
// answer with the dense probes, or each query alone without them, as the first refinement did (a hint may pick
// another face where two are as close, e.g. at an edge, and that face is the one split). Kept in (worst, worst_point)
// if it is the farthest yet.
void probe_worst(const AabbTree& tree, const Vec3& x, bool hinted, AabbTree::Hit& hint, AabbTree::Hit& worst,
                 Vec3& worst_point) {
  if (hinted) {
    tree.closest(x, hint);
  } else {
    hint = tree.closest(x);
  }
  if (hint.found() && (!worst.found() || hint.distance2 > worst.distance2)) {
    worst = hint;
    worst_point = x;
  }
}


// A knife edge or groove the mesh folds along (the faces' normals more than 25 degrees apart, kGrooveCos) strays most
// between its faces' probes, at the edge's midpoint, which a grid with an odd number of divisions never probes
// (hgroove: the horse's ear in `prm remesh --target-error 2e-4`, an edge along the rim of the thin ear, its faces'
// normals 153 degrees apart: the midpoint 1.52x the bound from the input, its ends 0.10x and 0.23x, its faces' probes
// 1.20-1.24x; probing every edge's midpoint in the rounds changed the horse's figure erratically, 8.79-12.13x, hfold,
// and the sharp ones' in the rounds gave 12.13x: the leg tip's order of service changes).
constexpr double kGrooveCos = 0.906;  // cos 25 degrees
// Rounds of groove_moves after the refinement's rounds (h22r: with the fine probes of the faces moved, the horse's
// ear's fan comes down in 13 moves from 1.517x to 1.018x the bound; its remesh is 7.66x the target at 5M samples with
// 4 rounds, 7.95x with 5, 6 or 8, 8.09x with 3).
constexpr int kGrooveRounds = 8;
// The shares of twice the midpoint's offset to the input an end of the edge is moved by (move_groove_end).
constexpr double kGrooveShares[] = {2.0, 1.5, 1.0, 0.5};

// Calls visit(x) with the midpoint of each edge of face f whose faces' normals are more than 25 degrees apart.
template <class Visit>
void for_each_sharp_midpoint(const Mesh& m, const std::vector<std::vector<uint32_t>>& vertex_faces, uint32_t f,
                             Visit&& visit) {
  const Tri& t = m.triangles[f];
  const Vec3 n = face_normal(m, t);
  for (size_t k = 0; k < 3; ++k) {
    const uint32_t a = t[k], b = t[(k + 1) % 3];
    const int64_t g = other_face(m, vertex_faces, a, b, f);
    if (g < 0) continue;
    const Vec3 u = face_normal(m, m.triangles[static_cast<size_t>(g)]);
    const double len = norm(n) * norm(u);
    if (len > 0 && dot(n, u) < kGrooveCos * len) visit(0.5 * (m.positions[a] + m.positions[b]));
  }
}

// Triangle (a, b, c)'s probes on its grid_divisions grid, then on its fine_grid_divisions grid (the two the
// refinement measures a face on near the bound).
template <class Visit>
void for_each_fine_probe(const Vec3& a, const Vec3& b, const Vec3& c, double bound, const Visit& visit) {
  for_each_grid_point(a, b, c, grid_divisions(a, b, c, bound), visit);
  for_each_grid_point(a, b, c, fine_grid_divisions(a, b, c, bound), visit);
}

// The worst squared distance to the input of triangle (a, b, c)'s probes (for_each_fine_probe).
double fine_probe_deviation2(const Vec3& a, const Vec3& b, const Vec3& c, const AabbTree& input_tree, double bound) {
  double worst = 0;
  AabbTree::Hit hint;
  for_each_fine_probe(a, b, c, bound, [&](const Vec3& x) {
    input_tree.closest(x, hint);
    worst = std::max(worst, hint.distance2);
  });
  return worst;
}

// A sharp edge's midpoint `d.at` that strays past the bound (for_each_sharp_midpoint), where a split of the edge with
// its new vertex on the input turns a new face away from the input (the ear's rim above: the input's closest face to
// one new face's centroid is on the far side of the thin ear): an end of the edge (not on the boundary, none of its
// faces touched) is moved by a share of twice the midpoint's offset to the input (kGrooveShares), so that the edge
// follows the input, then by a pattern search from the best of those, to the place where its fan's worst is least (its
// faces' fine probes, fine_probe_deviation2: h22r, on their dense grids alone the ear's fan was 1.28x the bound where
// it peaked at 1.40x between them; its edges' midpoints; its own distance), when that is less than before, no face
// turns over against its old normal and all face the input, and no input point near the fan goes past the bound
// (below). The ends in d.face's order. A lattice vertex moved becomes
// irregular. False when neither is moved. `mesh_tree`: the mesh's tree, built again here only when a move kept since
// its last build made it stale (most sites move nothing: one build a round, not one a site).
struct MeshTree {
  AabbTree tree;
  bool stale = true;
};
bool move_groove_end(PrmMesh& prm, const std::vector<std::vector<uint32_t>>& vertex_faces, const Mesh& input,
                     const AabbTree& input_tree, const DeviationRefinementOptions& options, const InputFacing& facing,
                     const std::vector<uint8_t>& boundary, std::vector<uint8_t>& touched, MeshTree& mesh_tree,
                     const Deviation& d) {
  Mesh& m = prm.mesh;
  const double bound = options.max_deviation;
  const Tri t = m.triangles[d.face];
  const std::array<double, 3> bc = barycentric(m, t, d.at);
  const size_t k = static_cast<size_t>(std::min_element(bc.begin(), bc.end()) - bc.begin());
  const Vec3 mid = 0.5 * (m.positions[t[(k + 1) % 3]] + m.positions[t[(k + 2) % 3]]);
  for (uint32_t v : {t[(k + 1) % 3], t[(k + 2) % 3]}) {
    if (v < boundary.size() && boundary[v]) continue;  // new vertices are never on the boundary
    const bool lattice = v < prm.vertex_relief.size() && prm.vertex_relief[v] >= 0;
    bool free = true;
    for (uint32_t h : vertex_faces[v]) free = free && !touched[h];
    if (!free) continue;
    const std::vector<Tri> fan = triangles_of(m, vertex_faces[v]);
    std::vector<Vec3> normals;
    for (const Tri& w : fan) normals.push_back(face_normal(m, w));
    const auto cost = [&] {
      double worst = input_tree.closest(m.positions[v]).distance2;
      for (const Tri& w : fan)
        worst = std::max(worst, fine_probe_deviation2(m.positions[w[0]], m.positions[w[1]], m.positions[w[2]],
                                                      input_tree, bound));
      for (const Tri& w : fan)
        for (size_t j = 0; j < 3; ++j)
          worst = std::max(worst,
                           input_tree.closest(0.5 * (m.positions[w[j]] + m.positions[w[(j + 1) % 3]])).distance2);
      return worst;
    };
    const Vec3 old = m.positions[v];
    // in>pr: the input's points near the fan (the vertices, centroids and edges' midpoints of the input triangles
    // with a corner within the fan's reach) and their distances to the fan; a place that takes one of them farther
    // than the bound and than it was is refused (hgroove: the feline's remesh went 7.73x -> 8.02x without).
    double reach2 = 0;
    for (const Tri& w : fan)
      for (uint32_t x : w) reach2 = std::max(reach2, norm2(m.positions[x] - old));
    reach2 = (std::sqrt(reach2) + 4 * bound) * (std::sqrt(reach2) + 4 * bound);
    // Only those whose closest face of the mesh is one of the fan's: a nearer face elsewhere stays where it is.
    if (mesh_tree.stale) {
      mesh_tree.tree = AabbTree(m);
      mesh_tree.stale = false;
    }
    std::vector<Vec3> near;
    AabbTree::Hit hint;
    for (const Tri& w : input.triangles) {
      const Vec3 &a = input.positions[w[0]], &b = input.positions[w[1]], &c = input.positions[w[2]];
      if (norm2(a - old) > reach2 && norm2(b - old) > reach2 && norm2(c - old) > reach2) continue;
      for (const Vec3& x : {a, b, c, (1.0 / 3) * (a + b + c), 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)}) {
        mesh_tree.tree.closest(x, hint);
        if (hint.found() &&
            std::find(vertex_faces[v].begin(), vertex_faces[v].end(), hint.face) != vertex_faces[v].end())
          near.push_back(x);
      }
    }
    const auto fan_distances2 = [&] {
      std::vector<double> out;
      for (const Vec3& x : near) out.push_back(nearest2(m, fan, x));
      return out;
    };
    const std::vector<double> near_before = fan_distances2();
    const double before = cost();
    double best = before;
    Vec3 best_at = old;
    // The fan's worst with v at its place, or infinity where a face turns against its old normal, stops facing the
    // input, or takes an input point near it past the bound and farther than it was.
    const auto guarded_cost = [&] {
      bool agree = true;
      for (size_t i = 0; i < fan.size(); ++i) agree = agree && faces_agree(m, normals[i], {fan[i]});
      if (!agree || !facing.keeps(m, fan)) return std::numeric_limits<double>::infinity();
      const std::vector<double> near_after = fan_distances2();
      for (size_t i = 0; i < near.size(); ++i)
        if (near_after[i] > std::max(bound * bound, near_before[i])) return std::numeric_limits<double>::infinity();
      return cost();
    };
    for (double share : kGrooveShares) {
      m.positions[v] = old + share * (d.wanted - mid);
      const double c = guarded_cost();
      if (c < best) {
        best = c;
        best_at = m.positions[v];
      }
    }
    // From the best of those, a pattern search (place_by_descent, the offset's length its first step) under the same
    // guards (h22r: the ear's fan 1.348x -> 1.164x the bound; its peak moves off the line of the offset).
    if (place_by_descent(m, v, best_at, norm(d.wanted - mid), HUGE_VAL, guarded_cost)) {
      best_at = m.positions[v];
      best = cost();
    }
    m.positions[v] = best_at;
    if (best < before) {
      if (lattice) prm.vertex_relief[v] = -1;  // off its lattice place (as descend_vertex's free move)
      for (uint32_t h : vertex_faces[v]) touched[h] = 1;
      mesh_tree.stale = true;
      return true;
    }
  }
  return false;
}

// prune_inserted: how far from a fan's faces (x the bound) the input is measured again.
constexpr double kPruneReach = 2;

// DeviationRefinementOptions::prune (h22max8): each vertex inserted by the rounds (index first_inserted and up), oldest
// first, whose triangles form a fan of 3 (a split in three) or 4 (an edge split) around it, is removed and its ring
// triangulated again (a quad: the diagonal that strays least) when, with the vertex gone, the new triangles' probes
// (both grids) and the input near them (the input vertices closest to the fan's triangles, and the input triangles
// around those, on their grid_divisions grids) stay within the bound: later rounds' moves and insertions nearby may
// have made it unneeded, and it costs the stream an irregular vertex and its regular patch. The input's distance is
// an upper bound (the new triangles, or the closest face at the start when no removal changed it), so a removal
// never passes on a figure lower than the true one. `stale` and `probe_hit` (per face) follow the faces; the
// removed fans' new triangles are stale. Returns the number removed.
size_t prune_inserted(Mesh& m, const QuantFrame& frame, size_t first_inserted, const Mesh& input,
                      const AabbTree& input_tree, double bound, const InputFacing& facing, std::vector<uint8_t>& stale,
                      std::vector<AabbTree::Hit>& probe_hit) {
  if (m.positions.size() <= first_inserted) return 0;
  const double bound2 = bound * bound;
  std::vector<std::vector<uint32_t>> vertex_faces = faces_around_vertices(m);
  // in>pr: the input near the fans (the faces around the inserted vertices): its vertices and the input triangles
  // with a probe (their grid_divisions grids) within kPruneReach x the bound of a fan's face, by that closest fan
  // face at the start. A superset of those whose closest face is a fan's face, but for the input already farther
  // than kPruneReach x the bound from the mesh there (h22max8: measuring all the input against the whole mesh cost
  // the feline 0.6 s CPU).
  const AabbTree tree(m);
  std::vector<uint32_t> fan_face_ids;
  std::vector<Tri> fan_tris;
  for (uint32_t f = 0; f < m.triangles.size(); ++f) {
    const Tri& t = m.triangles[f];
    if (t[0] >= first_inserted || t[1] >= first_inserted || t[2] >= first_inserted)
      fan_face_ids.push_back(f), fan_tris.push_back(t);
  }
  const AabbTree fan_tree(m.positions, fan_tris);
  const double reach2 = kPruneReach * kPruneReach * bound2;
  std::vector<uint8_t> used(input.positions.size(), 0);
  std::vector<std::vector<uint32_t>> input_vertex_faces(input.positions.size());
  for (uint32_t f = 0; f < input.triangles.size(); ++f)
    for (uint32_t v : input.triangles[f]) used[v] = 1, input_vertex_faces[v].push_back(f);
  std::vector<AabbTree::Hit> hits(input.positions.size());
  tbb::parallel_for(size_t{0}, input.positions.size(), [&](size_t v) {
    if (used[v]) hits[v] = fan_tree.closest(input.positions[v], reach2);
  });
  std::vector<std::vector<uint32_t>> attached(m.triangles.size());
  for (uint32_t v = 0; v < hits.size(); ++v)
    if (hits[v].found()) attached[fan_face_ids[hits[v].face]].push_back(v);
  std::vector<std::vector<uint32_t>> probe_faces(input.triangles.size());
  tbb::parallel_for(size_t{0}, input.triangles.size(), [&](size_t f) {
    const Tri& t = input.triangles[f];
    const Vec3 &a = input.positions[t[0]], &b = input.positions[t[1]], &c = input.positions[t[2]];
    std::vector<uint32_t>& out = probe_faces[f];
    for_each_grid_point(a, b, c, grid_divisions(a, b, c, bound), [&](const Vec3& x) {
      const AabbTree::Hit h = fan_tree.closest(x, reach2);
      if (h.found() && std::find(out.begin(), out.end(), fan_face_ids[h.face]) == out.end())
        out.push_back(fan_face_ids[h.face]);
    });
  });
  std::vector<std::vector<uint32_t>> attached_faces(m.triangles.size());
  for (uint32_t f = 0; f < probe_faces.size(); ++f)
    for (uint32_t g : probe_faces[f]) attached_faces[g].push_back(f);
  probe_faces = {};
  std::vector<uint8_t> changed(m.triangles.size(), 0), dead(m.triangles.size(), 0), removed(m.positions.size(), 0);
  // The distance of input point p to the mesh with `tris` in place of the fan: at most this.
  const auto input_distance2 = [&](const Vec3& p, const std::vector<Tri>& tris) {
    double d = nearest2(m, tris, p);
    if (d > bound2) {
      const AabbTree::Hit h = tree.closest(p);
      if (h.found() && !changed[h.face]) d = std::min(d, h.distance2);
    }
    return d;
  };
  size_t count = 0;
  for (uint32_t v = static_cast<uint32_t>(first_inserted); v < m.positions.size(); ++v) {
    const std::vector<uint32_t> faces = vertex_faces[v];
    if (faces.size() != 3 && faces.size() != 4) continue;
    // The ring: each face (v, a, b) in its order gives the ring's edge a -> b.
    std::vector<std::array<uint32_t, 2>> edges;
    for (uint32_t f : faces) {
      const Tri& t = m.triangles[f];
      const size_t k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
      edges.push_back({t[(k + 1) % 3], t[(k + 2) % 3]});
    }
    std::vector<uint32_t> ring = {edges[0][0], edges[0][1]};
    bool closed = false;
    while (ring.size() <= faces.size()) {
      const auto next = std::find_if(edges.begin(), edges.end(), [&](const auto& e) { return e[0] == ring.back(); });
      if (next == edges.end()) break;
      if ((*next)[1] == ring[0]) {
        closed = ring.size() == faces.size();
        break;
      }
      ring.push_back((*next)[1]);
    }
    if (!closed) continue;
    // An edge between ring vertices a and b outside the fan (a new triangle there would repeat it).
    const auto has_edge = [&](uint32_t a, uint32_t b) {
      for (uint32_t f : vertex_faces[a]) {
        if (std::find(faces.begin(), faces.end(), f) != faces.end()) continue;
        const Tri& t = m.triangles[f];
        if (t[0] == b || t[1] == b || t[2] == b) return true;
      }
      return false;
    };
    std::vector<std::vector<Tri>> ways;
    if (faces.size() == 3) {
      bool elsewhere = false;  // the triangle itself outside the fan (a tetrahedron's)
      for (uint32_t f : vertex_faces[ring[0]]) {
        const Tri& t = m.triangles[f];
        const auto in = [&](uint32_t x) { return t[0] == x || t[1] == x || t[2] == x; };
        elsewhere = elsewhere || (std::find(faces.begin(), faces.end(), f) == faces.end() && in(ring[1]) && in(ring[2]));
      }
      if (!elsewhere) ways.push_back({{ring[0], ring[1], ring[2]}});
    } else {
      if (!has_edge(ring[0], ring[2])) ways.push_back({{ring[0], ring[1], ring[2]}, {ring[0], ring[2], ring[3]}});
      if (!has_edge(ring[1], ring[3])) ways.push_back({{ring[1], ring[2], ring[3]}, {ring[1], ring[3], ring[0]}});
    }
    Vec3 old_normal = {0, 0, 0};
    for (uint32_t f : faces) old_normal = old_normal + face_normal(m, m.triangles[f]);
    // The input near the fan: its attached vertices, and the input triangles around them.
    std::vector<uint32_t> near_vertices, near_faces;
    for (uint32_t f : faces) near_vertices.insert(near_vertices.end(), attached[f].begin(), attached[f].end());
    std::sort(near_vertices.begin(), near_vertices.end());
    near_vertices.erase(std::unique(near_vertices.begin(), near_vertices.end()), near_vertices.end());
    for (uint32_t u : near_vertices)
      near_faces.insert(near_faces.end(), input_vertex_faces[u].begin(), input_vertex_faces[u].end());
    for (uint32_t f : faces) near_faces.insert(near_faces.end(), attached_faces[f].begin(), attached_faces[f].end());
    std::sort(near_faces.begin(), near_faces.end());
    near_faces.erase(std::unique(near_faces.begin(), near_faces.end()), near_faces.end());
    // The fan's faces go: the start's closest face is no bound where it is one of them.
    std::vector<uint8_t> was_changed;
    for (uint32_t f : faces) was_changed.push_back(changed[f]), changed[f] = 1;
    // The worst squared distance with `tris` in place of the fan (stops once past `limit`).
    const auto worst_of = [&](const std::vector<Tri>& tris, double limit) {
      double worst = 0;
      for (const Tri& t : tris) {
        worst = std::max(worst, fine_probe_deviation2(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]],
                                                      input_tree, bound));
        if (worst > limit) return worst;
      }
      for (size_t i = 0; i < near_vertices.size() && worst <= limit; ++i)
        worst = std::max(worst, input_distance2(input.positions[near_vertices[i]], tris));
      for (size_t i = 0; i < near_faces.size() && worst <= limit; ++i) {
        const Tri& t = input.triangles[near_faces[i]];
        const Vec3 &a = input.positions[t[0]], &b = input.positions[t[1]], &c = input.positions[t[2]];
        for_each_grid_point(a, b, c, grid_divisions(a, b, c, bound),
                            [&](const Vec3& x) { worst = std::max(worst, input_distance2(x, tris)); });
      }
      return worst;
    };
    // The same with the fan's vertices at their nearest rounding (the stream's; round_towards_input only takes
    // another where it strays less).
    const auto rounded_worst_of = [&](const std::vector<Tri>& tris, double limit) {
      std::vector<uint32_t> fan = ring;
      fan.push_back(v);
      std::vector<Vec3> kept;
      for (uint32_t u : fan) {
        kept.push_back(m.positions[u]);
        for (int a = 0; a < 3; ++a) {
          const size_t k = static_cast<size_t>(a);
          m.positions[u][k] = frame.to_real(static_cast<double>(frame.quantize(m.positions[u][k], a)), a);
        }
      }
      const double worst = worst_of(tris, limit);
      for (size_t i = 0; i < fan.size(); ++i) m.positions[fan[i]] = kept[i];
      return worst;
    };
    const double rounded_limit =
        std::max(bound2, rounded_worst_of(triangles_of(m, faces), std::numeric_limits<double>::infinity()));
    const std::vector<Tri>* best = nullptr;
    double best_worst = bound2;
    for (const std::vector<Tri>& tris : ways) {
      if (!faces_agree(m, old_normal, tris) || !facing.keeps(m, tris)) continue;
      const double worst = worst_of(tris, best_worst);
      if (worst <= best_worst && rounded_worst_of(tris, rounded_limit) <= rounded_limit)
        best = &tris, best_worst = worst;
    }
    if (best == nullptr) {
      for (size_t i = 0; i < faces.size(); ++i) changed[faces[i]] = was_changed[i];
      continue;
    }
    // The fan's first faces hold the new triangles, the others go.
    std::vector<uint32_t> merged, merged_faces;
    for (uint32_t f : faces) {
      merged.insert(merged.end(), attached[f].begin(), attached[f].end());
      merged_faces.insert(merged_faces.end(), attached_faces[f].begin(), attached_faces[f].end());
      changed[f] = 1;
      for (uint32_t r : m.triangles[f]) {
        auto& list = vertex_faces[r];
        list.erase(std::remove(list.begin(), list.end(), f), list.end());
      }
    }
    for (size_t i = 0; i < faces.size(); ++i) {
      if (i < best->size()) {
        m.triangles[faces[i]] = (*best)[i];
        for (uint32_t r : (*best)[i]) vertex_faces[r].push_back(faces[i]);
        attached[faces[i]] = merged;
        attached_faces[faces[i]] = merged_faces;
      } else {
        dead[faces[i]] = 1;
        attached[faces[i]].clear();
        attached_faces[faces[i]].clear();
      }
    }
    removed[v] = 1;
    ++count;
  }
  if (count == 0) return 0;
  // Compaction: the dead faces go, the removed vertices (all inserted) go and the later ones move down.
  std::vector<uint32_t> vertex_index(m.positions.size());
  uint32_t next = 0;
  for (uint32_t v = 0; v < m.positions.size(); ++v) {
    vertex_index[v] = next;
    if (!removed[v]) m.positions[next++] = m.positions[v];
  }
  m.positions.resize(next);
  stale.resize(m.triangles.size(), 1);
  probe_hit.resize(m.triangles.size());
  size_t kept = 0;
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    if (dead[f]) continue;
    Tri t = m.triangles[f];
    for (uint32_t& x : t) x = vertex_index[x];
    m.triangles[kept] = t;
    stale[kept] = changed[f] ? 1 : stale[f];
    probe_hit[kept] = probe_hit[f];
    ++kept;
  }
  m.triangles.resize(kept);
  stale.resize(kept);
  probe_hit.resize(kept);
  return count;
}

}  // namespace

size_t prune_inserted_vertices(PrmMesh& prm, size_t first_inserted, const Mesh& input, const AabbTree& input_tree,
                               double bound) {
  std::vector<uint8_t> stale(prm.mesh.triangles.size(), 0);
  std::vector<AabbTree::Hit> probe_hit(prm.mesh.triangles.size());
  return prune_inserted(prm.mesh, prm.frame, first_inserted, input, input_tree, bound,
                        InputFacing(&input, &input_tree, &prm.frame, prm.mesh),
                        stale, probe_hit);
}

DeviationRefinementStats refine_deviations(PrmMesh& prm, const Mesh& input, const AabbTree& input_tree,
                                           const DeviationRefinementOptions& options,
                                           std::vector<double>* face_deviation2) {
  DeviationRefinementStats st;
  if (!(options.max_deviation > 0) || input.positions.empty()) return st;
  Mesh& m = prm.mesh;
  const size_t first_inserted = m.positions.size();
  // The vertices on the mesh's boundary (an open input's loops) are not moved: h22max8, with the refinement made the
  // default, the rim moves took elephant-with-holes' boundary vertices 19.7 quantization steps off the input's
  // boundary (PackOpenBoundaryReal). New vertices are never on the boundary (an edge split needs the face across).
  std::vector<uint8_t> boundary(m.positions.size(), 0);
  {
    std::vector<std::array<uint32_t, 2>> edges;
    for (const Tri& t : m.triangles)
      for (int k = 0; k < 3; ++k) edges.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i < edges.size();) {
      size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      if (j - i == 1) boundary[edges[i][0]] = boundary[edges[i][1]] = 1;
      i = j;
    }
  }
  const size_t budget = static_cast<size_t>(options.max_insert_share * static_cast<double>(m.positions.size()));
  std::vector<uint8_t> used(input.positions.size(), 0);
  for (const Tri& t : input.triangles)
    for (uint32_t v : t) used[v] = 1;
  const double bound2 = options.max_deviation * options.max_deviation;
  // As round_towards_input's share2 (bit for bit: a quiet face's figure never passes it).
  const double quiet2 = kQuietShare * kQuietShare * options.max_deviation * options.max_deviation;
  std::vector<std::vector<uint32_t>> vertex_faces;
  StrayCheck check;
  if (options.thin_sheets && options.stray_check) {
    check.input_tree = &input_tree;
    check.bound = options.max_deviation;
    check.dense = options.dense_probes;
  }
  if (options.facing_guard) check.facing = InputFacing(&input, &input_tree, &prm.frame, m);
  std::vector<uint8_t> moved;  // rim moves per vertex, over all rounds (at most kMaxMoves: no back and forth)
  TipMoves tips;  // per vertex: its tip move (move_rim_vertex's tip_move: at most one) and the point it went to
  // The pr>in measures (against the input, which does not change) of the mesh's faces and vertices, kept from round
  // to round: only the faces a round changed (`stale`, every face at first) and their vertices are measured again,
  // which gives the same figures as measuring all (h22max5: the probes of every face in every round were most of
  // the refinement's CPU time).
  std::vector<AabbTree::Hit> probe_hit, vertex_hits, hits, input_face_hit;
  std::vector<Vec3> input_face_point;
  std::vector<Vec3> probe_point;
  std::vector<uint8_t> stale;
  // all_input_faces: an input triangle whose probes all lie within kFaceProbeShare x the bound of the first round's
  // mesh is `quiet` there: its probes only ask whether the mesh is that near (quiet_probes), and its worst probe's
  // closest face, which later rounds read (a changed one has it probed again), is found on the first round's mesh
  // (first_tree) only when a face a later round changed lies that near it (hcpu: the same figures, for most of the
  // input's probes' closest-point queries).
  std::unique_ptr<AabbTree> first_tree;
  Mesh first_mesh;
  Mesh measured_mesh;  // the mesh the last round measured (with all_input_faces): its changed faces as they were
  std::vector<uint8_t> quiet_face;
  const auto probe_input_face = [&](const AabbTree& on, uint32_t f) {
    const Tri& t = input.triangles[f];
    const Vec3 &a = input.positions[t[0]], &b = input.positions[t[1]], &c = input.positions[t[2]];
    AabbTree::Hit hint;
    input_face_hit[f] = AabbTree::Hit{};
    for_each_grid_point(a, b, c, grid_divisions(a, b, c, options.max_deviation), [&](const Vec3& x) {
      probe_worst(on, x, options.dense_probes, hint, input_face_hit[f], input_face_point[f]);
    });
  };
  while (st.rounds < options.max_rounds && st.inserted < budget) {
    ++st.rounds;
    stale.resize(m.triangles.size(), 1);
    std::vector<uint8_t> stale_vertex(m.positions.size(), 0);
    for (uint32_t f = 0; f < m.triangles.size(); ++f)
      if (stale[f])
        for (uint32_t v : m.triangles[f]) stale_vertex[v] = 1;
    // in>pr: the input vertices far from the mesh. From the second round only those farther than kFaceProbeShare x
    // the bound or closest to a face the last round changed are measured again: the others' distance can only have
    // shrunk (the faces that did not change are where they were), and is read only against that share and the
    // bound, so the figures are those of measuring all.
    auto round_tree = std::make_unique<AabbTree>(m);
    const AabbTree& tree = *round_tree;
    const double share2 = kFaceProbeShare * kFaceProbeShare * bound2;
    hits.resize(input.positions.size());
    tbb::parallel_for(size_t{0}, input.positions.size(), [&](size_t v) {
      if (!used[v]) return;
      const AabbTree::Hit& old = hits[v];
      if (st.rounds == 1 || !old.found() || old.distance2 > share2 || stale[old.face]) hits[v] = tree.closest(input.positions[v]);
    });
    std::vector<Deviation> far;
    for (uint32_t v = 0; v < hits.size(); ++v)
      if (hits[v].found() && hits[v].distance2 > bound2)
        far.push_back({hits[v].face, hits[v].point, input.positions[v], hits[v].distance2, v});
    // in>pr between the input's vertices (Metro samples the faces, and a thin tip's faces stray more than its
    // vertices): the input triangles, each on a barycentric grid about as fine as the bound (a long triangle strays
    // most between its vertices), its worst probe the deviation. The first round probes every triangle with
    // all_input_faces (h22max5: a long flat input triangle of bunny_zipper's, its vertices on the mesh, strayed
    // 1.9e-3 of the diagonal inside), else those with a vertex farther than kFaceProbeShare x the bound; later
    // rounds those again, and those whose worst probe was that far or whose vertices' or worst probe's closest face
    // the last round changed.
    if (options.thin_sheets) {
      input_face_hit.resize(input.triangles.size());
      input_face_point.resize(input.triangles.size());
      const bool first_quiet = options.all_input_faces && st.rounds == 1;
      if (first_quiet) quiet_face.assign(input.triangles.size(), 0);
      // A quiet triangle near a face the last round changed (that face as it was in the first round): its figures
      // as the first round would have found them.
      if (!quiet_face.empty() && st.rounds > 1) {
        std::vector<Tri> changed_first;
        for (uint32_t g = 0; g < first_mesh.triangles.size(); ++g)
          if (stale[g]) changed_first.push_back(first_mesh.triangles[g]);
        if (!changed_first.empty()) {
          const AabbTree changed_tree(first_mesh.positions, changed_first);
          tbb::parallel_for(size_t{0}, input.triangles.size(), [&](size_t f) {
            if (!quiet_face[f]) return;
            const Tri& t = input.triangles[f];
            const Vec3 &a = input.positions[t[0]], &b = input.positions[t[1]], &c = input.positions[t[2]];
            // First the ball around the centroid that holds every probe's reach (one query instead of one a probe;
            // 0.1% more for the rounding).
            const Vec3 centroid = (1.0 / 3) * (a + b + c);
            const double reach =
                1.001 * (std::sqrt(std::max({norm2(a - centroid), norm2(b - centroid), norm2(c - centroid)})) +
                         std::sqrt(share2));
            AabbTree::Hit hint;
            if (!changed_tree.within(centroid, reach * reach, hint)) return;
            bool near = false;
            for_each_grid_point(a, b, c, grid_divisions(a, b, c, options.max_deviation),
                                [&](const Vec3& x) { near = near || changed_tree.within(x, share2, hint); });
            if (!near) return;
            probe_input_face(*first_tree, static_cast<uint32_t>(f));
            quiet_face[f] = 0;
          });
        }
      }
      // A probed triangle that comes back only for a far figure (a vertex or its worst probe farther than the share)
      // keeps its figures when no face the last round changed lies within its probes' reach, as it was before the
      // change or as it is now (hcpu3: the venus at 1.3e-4 probed some 5,500 input triangles again in each of its
      // 11 later rounds, for 12-519 changed faces): each probe's closest distance is the same.
      std::unique_ptr<AabbTree> changed_tree;
      Mesh changed_faces;
      if (options.all_input_faces && st.rounds > 1) {
        changed_faces.positions = measured_mesh.positions;
        changed_faces.positions.insert(changed_faces.positions.end(), m.positions.begin(), m.positions.end());
        const auto offset = static_cast<uint32_t>(measured_mesh.positions.size());
        for (uint32_t g = 0; g < m.triangles.size(); ++g)
          if (stale[g]) {
            if (g < measured_mesh.triangles.size()) changed_faces.triangles.push_back(measured_mesh.triangles[g]);
            const Tri& t = m.triangles[g];
            changed_faces.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
          }
        if (!changed_faces.triangles.empty())
          changed_tree = std::make_unique<AabbTree>(changed_faces.positions, changed_faces.triangles);
      }
      const auto changed_near = [&](uint32_t f) {
        if (!changed_tree) return false;
        const Tri& t = input.triangles[f];
        const Vec3 &a = input.positions[t[0]], &b = input.positions[t[1]], &c = input.positions[t[2]];
        const Vec3 centroid = (1.0 / 3) * (a + b + c);
        const double reach =
            1.001 * (std::sqrt(std::max({norm2(a - centroid), norm2(b - centroid), norm2(c - centroid)})) +
                     std::sqrt(input_face_hit[f].distance2));
        AabbTree::Hit hint;
        return changed_tree->within(centroid, reach * reach, hint);
      };
      std::vector<uint32_t> near_far;
      for (uint32_t f = 0; f < input.triangles.size(); ++f) {
        const Tri& t = input.triangles[f];
        double worst = 0;
        bool changed = false;
        for (uint32_t v : t)
          if (hits[v].found()) {
            worst = std::max(worst, hits[v].distance2);
            changed = changed || (st.rounds > 1 && stale[hits[v].face]);
          }
        const AabbTree::Hit& old = input_face_hit[f];
        const bool probed = options.all_input_faces && old.found();
        // (A quiet triangle's worst probe's closest face is none the last round changed: see above.)
        if (worst > share2 || (options.all_input_faces && st.rounds == 1) ||
            (probed && (changed || old.distance2 > share2 || (!quiet_face[f] && stale[old.face])))) {
          if (probed && st.rounds > 1 && !changed && !stale[old.face] && !changed_near(f)) {
            if (!quiet_face.empty()) quiet_face[f] = 0;  // as near_far's
          } else {
            near_far.push_back(f);
          }
        }
        else if (!options.all_input_faces)
          input_face_hit[f] = AabbTree::Hit{};
      }
      tbb::parallel_for(size_t{0}, near_far.size(), [&](size_t i) {
        const uint32_t f = near_far[i];
        if (!quiet_face.empty()) quiet_face[f] = 0;
        if (first_quiet) {
          const Tri& t = input.triangles[f];
          if (quiet_probes(tree, input.positions[t[0]], input.positions[t[1]], input.positions[t[2]],
                           options.max_deviation, share2, input_face_hit[f])) {
            quiet_face[f] = 1;
            return;
          }
        }
        probe_input_face(tree, f);
      });
      if (first_quiet) {
        first_mesh = m;
        first_tree = std::move(round_tree);
      }
      for (uint32_t f = 0; f < input.triangles.size(); ++f)
        if (input_face_hit[f].found() && input_face_hit[f].distance2 > bound2)
          far.push_back({input_face_hit[f].face, input_face_hit[f].point, input_face_point[f],
                         input_face_hit[f].distance2, kInputPoint});
    }
    // pr>in at the mesh's vertices (an irregular vertex left out on a tip is moved back towards the input, a lattice
    // vertex off the input along its axis).
    if (options.thin_sheets) {
      std::vector<uint32_t> a_face(m.positions.size(), UINT32_MAX);
      for (uint32_t f = 0; f < m.triangles.size(); ++f)
        for (uint32_t v : m.triangles[f]) a_face[v] = f;
      vertex_hits.resize(m.positions.size());
      tbb::parallel_for(size_t{0}, m.positions.size(), [&](size_t v) {
        if (!stale_vertex[v]) return;
        vertex_hits[v] = AabbTree::Hit{};
        const bool lattice = v < prm.vertex_relief.size() && prm.vertex_relief[v] >= 0;
        if ((options.lattice_moves || !lattice) && a_face[v] != UINT32_MAX)
          vertex_hits[v] = input_tree.closest(m.positions[v]);
      });
      for (uint32_t v = 0; v < vertex_hits.size(); ++v)
        if (vertex_hits[v].found() && vertex_hits[v].distance2 > bound2)
          far.push_back({a_face[v], m.positions[v], vertex_hits[v].point, vertex_hits[v].distance2, kMeshVertex, v});
    }
    // pr>in: the mesh's triangles with a point far from the input (thin sheets: on the grid Metro-like dense probes
    // see, grid_divisions; else the centroid and the edges' midpoints).
    probe_hit.resize(m.triangles.size());
    probe_point.resize(m.triangles.size());
    tbb::parallel_for(size_t{0}, m.triangles.size(), [&](size_t f) {
      if (!stale[f]) return;
      probe_hit[f] = AabbTree::Hit{};
      const Tri& t = m.triangles[f];
      const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
      if (options.thin_sheets && options.dense_probes &&
          quiet_probes(input_tree, a, b, c, options.max_deviation, quiet2, probe_hit[f]))
        return;
      AabbTree::Hit hint;
      const auto visit = [&](const Vec3& x) {
        probe_worst(input_tree, x, options.dense_probes, hint, probe_hit[f], probe_point[f]);
      };
      for_each_probe(a, b, c, options.thin_sheets && options.dense_probes, options.max_deviation, visit);
      // Near the bound, twice as fine (h22max6: the horse's worst place, 1.61e-3 of the diagonal at a 122-degree
      // crease, lay between the probes of a face whose 6-division grid found 0.99x the bound; 40 divisions, 1.2x).
      if (options.thin_sheets && options.dense_probes && options.fine_probes && probe_hit[f].found() &&
          probe_hit[f].distance2 > kFineProbeShare * kFineProbeShare * bound2 && probe_hit[f].distance2 <= bound2)
        for_each_grid_point(a, b, c, fine_grid_divisions(a, b, c, options.max_deviation), visit);
    });
    for (uint32_t f = 0; f < m.triangles.size(); ++f)
      if (probe_hit[f].found() && probe_hit[f].distance2 > bound2)
        far.push_back({f, probe_point[f], probe_hit[f].point, probe_hit[f].distance2, kMeshPoint});
    stale.assign(m.triangles.size(), 0);  // measured (the in>pr test above read them)
    if (far.empty()) break;
    if (options.all_input_faces) measured_mesh = m;
    // Farthest first; one insertion per triangle neighbourhood in a round (the rest is measured again next round).
    std::sort(far.begin(), far.end(), [](const Deviation& a, const Deviation& b) {
      if (a.distance2 != b.distance2) return a.distance2 > b.distance2;
      if (a.face != b.face) return a.face < b.face;
      if (a.input_vertex != b.input_vertex) return a.input_vertex < b.input_vertex;
      return a.vertex < b.vertex;
    });
    vertex_faces = faces_around_vertices(m);
    std::vector<uint8_t> touched(m.triangles.size(), 0);
    moved.resize(m.positions.size(), 0);
    tips.made.resize(m.positions.size(), 0);
    tips.to.resize(m.positions.size());
    check.facing.index_cells(m);
    NearInputs near;
    if (st.rounds > kRimGuardAfter) {
      near.input = &input;
      near.hits = &hits;
      near.of_face.assign(m.triangles.size(), {});
      for (uint32_t u = 0; u < hits.size(); ++u)
        if (hits[u].found()) near.of_face[hits[u].face].push_back(u);
    }
    size_t inserted_this_round = 0;
    for (const Deviation& d : far) {
      if (st.inserted >= budget) break;
      if (touched[d.face]) continue;
      const size_t facing_refusals = check.facing.refusals;
      if (options.thin_sheets &&
          move_rim_vertex(m, vertex_faces, prm, input_tree, options, bound2, check.facing, touched, moved, boundary,
                          st.rounds > kRimGuardAfter ? &near : nullptr, d, tips)) {
        ++st.moved;
        ++inserted_this_round;
        continue;
      }
      if (d.input_vertex == kMeshVertex && options.thin_sheets && options.descent_placement &&
          descend_vertex(m, vertex_faces, prm, input_tree, options, check.facing, touched, boundary, d)) {
        ++st.moved;
        ++inserted_this_round;
        continue;
      }
      if (d.input_vertex == kMeshVertex) {  // moved or left
        st.facing_skipped += check.facing.refusals > facing_refusals;
        continue;
      }
      if (options.thin_sheets && d.input_vertex == kMeshPoint &&
          flip_straying_edge(m, vertex_faces, input_tree, options.max_deviation, options.dense_probes, check.facing,
                             touched, d)) {
        ++st.flipped;
        ++inserted_this_round;
        continue;
      }
      if (insert(m, vertex_faces, touched, input_tree, check, options.thin_sheets && options.normal_reach,
                 options.thin_sheets && options.descent_placement, options.thin_sheets && st.rounds > kTradeAfter, d) ||
          (options.thin_sheets && !strays_from_input(d) && insert_on_facing_face(m, vertex_faces, touched, check, d,
                                                                               st.rounds > kFacingNearerAfter))) {
        ++st.inserted;
        ++inserted_this_round;
      } else if (options.thin_sheets && !strays_from_input(d) &&
                 move_rim_vertex(m, vertex_faces, prm, input_tree, options, bound2, check.facing, touched, moved,
                                 boundary, st.rounds > kRimGuardAfter ? &near : nullptr, d, tips, true)) {
        ++st.moved;
        ++inserted_this_round;
      } else if (options.thin_sheets && !strays_from_input(d) && st.rounds > kCrossAfter &&
                 insert_across_crease(m, vertex_faces, touched, input_tree, check,
                                      st.rounds > kTradeAfter ? kTradeGain * kTradeGain * d.distance2 : 0, d)) {
        ++st.inserted;
        ++inserted_this_round;
      } else if (options.thin_sheets && options.reach_onto_input && !strays_from_input(d) &&
                 insert_onto_input(m, vertex_faces, touched, input_tree, check, d)) {
        ++st.inserted;
        ++inserted_this_round;
      } else {
        ++st.refused;
        st.facing_skipped += check.facing.refusals > facing_refusals;
      }
    }
    if (inserted_this_round == 0) break;
    stale = std::move(touched);
    stale.resize(m.triangles.size(), 1);
  }
  // The sharp edges' midpoints past the bound, each served by a move of an end of its edge (move_groove_end), for
  // kGrooveRounds rounds after the rounds (where they would change what the rounds do: see kGrooveCos).
  // (With the lattice moves and the descent: without them, --max-error's refinement and the tests that ask for no
  // moves, none.)
  std::vector<uint8_t> groove_moved;  // the faces the last groove round's moves changed
  for (int round = 0; options.thin_sheets && options.dense_probes && options.lattice_moves &&
                      options.descent_placement && options.groove_moves && round < kGrooveRounds;
       ++round) {
    vertex_faces = faces_around_vertices(m);
    std::vector<Deviation> far;
    for (uint32_t f = 0; f < m.triangles.size(); ++f) {
      AabbTree::Hit hint, worst;
      Vec3 at{};
      bool sharp = false;
      for_each_sharp_midpoint(m, vertex_faces, f, [&](const Vec3& x) {
        sharp = true;
        probe_worst(input_tree, x, true, hint, worst, at);
      });
      // A sharp face the last round's moves changed: also its grids (fine_probe_deviation2's), where a moved end's
      // fan peaks off the midpoints (h22r: the ear's fan 1.165x the bound after two rounds, its midpoints within it).
      if (sharp && f < groove_moved.size() && groove_moved[f]) {
        const Tri& t = m.triangles[f];
        const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
        for_each_fine_probe(a, b, c, options.max_deviation,
                            [&](const Vec3& x) { probe_worst(input_tree, x, true, hint, worst, at); });
      }
      if (worst.found() && worst.distance2 > bound2) far.push_back({f, at, worst.point, worst.distance2, kMeshPoint});
    }
    std::sort(far.begin(), far.end(), [](const Deviation& a, const Deviation& b) {
      return a.distance2 != b.distance2 ? a.distance2 > b.distance2 : a.face < b.face;
    });
    check.facing.index_cells(m);
    std::vector<uint8_t> touched(m.triangles.size(), 0);
    size_t moved_this_round = 0;
    MeshTree mesh_tree;
    for (const Deviation& d : far)
      if (!touched[d.face] &&
          move_groove_end(prm, vertex_faces, input, input_tree, options, check.facing, boundary, touched, mesh_tree, d))
        ++moved_this_round;
    if (moved_this_round == 0) break;
    groove_moved = touched;
    st.moved += moved_this_round;
    stale.resize(m.triangles.size(), 1);
    for (size_t f = 0; f < touched.size(); ++f) stale[f] = stale[f] || touched[f];
  }
  if (options.prune && options.thin_sheets && options.dense_probes) {
    st.pruned = prune_inserted(m, prm.frame, first_inserted, input, input_tree, options.max_deviation, check.facing,
                               stale, probe_hit);
    st.inserted -= std::min(st.inserted, st.pruned);
  }
  // The faces' worst probes for round_towards_input (the faces the last round changed measured again).
  if (face_deviation2 != nullptr && options.thin_sheets && options.dense_probes && !probe_hit.empty()) {
    stale.resize(m.triangles.size(), 1);
    probe_hit.resize(m.triangles.size());
    face_deviation2->assign(m.triangles.size(), 0.0);
    tbb::parallel_for(size_t{0}, m.triangles.size(), [&](size_t f) {
      if (!stale[f]) {
        (*face_deviation2)[f] = probe_hit[f].found() ? probe_hit[f].distance2 : 0.0;
        return;
      }
      const Tri& t = m.triangles[f];
      AabbTree::Hit quiet;
      (*face_deviation2)[f] =
          quiet_probes(input_tree, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]], options.max_deviation,
                       quiet2, quiet)
              ? quiet.distance2
              : probe_deviation2(m, {t}, input_tree, options.max_deviation, true);
    });
  }
  st.facing_refused = check.facing.refusals;
  // Labels: the new vertices are irregular, and every triangle is labelled again (the split ones lost regularity).
  prm.vertex_relief.resize(m.positions.size(), -1);
  prm.lattice_i.resize(m.positions.size(), 0);
  prm.lattice_j.resize(m.positions.size(), 0);
  prm.face_relief.resize(m.triangles.size(), -1);
  prm.face_regular.resize(m.triangles.size(), 0);
  for (size_t f = 0; f < m.triangles.size(); ++f) label_face(prm, f);
  return st;
}

// Spec-free encoder-side choice (h22max4): the stream holds every coordinate rounded to the frame's step (§10.1), which
// moves a vertex by up to half a step per axis, as much as 0.45x the bound at the RMS target's step. Near the bound
// that rounding alone pushes a place over it (venus at 2e-4: 1.38e-3 refined, 1.56e-3 rounded). So the vertices of
// triangles that stray more than kRoundShare x the bound, or that an input point farther than that is closest to,
// take, of the 2-8 ways to round them (each coordinate down or up; a lattice coordinate, already on its step,
// stays), the one whose triangles stray least (their probe points and the vertex itself, pr>in, and those input
// points, in>pr), and are put exactly there (the stream then holds that point). Worst first; a rounding that turns a
// triangle over is not taken; where the nearest rounding is as good, the vertex is left as it was.
size_t round_towards_input(PrmMesh& prm, const Mesh& input, const AabbTree& input_tree, double bound,
                           const std::vector<double>* face_deviation2, bool facing_guard) {
  Mesh& m = prm.mesh;
  const QuantFrame& frame = prm.frame;
  InputFacing facing = facing_guard ? InputFacing(&input, &input_tree, &frame, m) : InputFacing();
  facing.index_cells(m);
  const double share2 = kRoundShare * kRoundShare * bound * bound;
  std::vector<std::vector<uint32_t>> vertex_faces = faces_around_vertices(m);
  // in>pr: the input vertices farther than the share from the mesh, by their closest mesh face; and the points between
  // them, on the fine grid (fine_grid_divisions) of each input triangle with a vertex farther than kFaceProbeShare x
  // the bound (hfeline: the feline's worst place at 2e-4, an input crease edge's midpoint 1.02x the bound from the
  // refined mesh between two vertices within 0.65x, went to 1.22x by a rounding chosen for other points nearby).
  const AabbTree tree(m);
  std::vector<AabbTree::Hit> hits(input.positions.size());
  // (Only a distance over kFaceProbeShare x the bound is read: nearer, the first face found that near stands for the
  // closest.)
  const double face_share2 = kFaceProbeShare * kFaceProbeShare * bound * bound;
  tbb::parallel_for(size_t{0}, input.positions.size(), [&](size_t v) {
    if (!tree.within(input.positions[v], face_share2, hits[v])) hits[v] = tree.closest(input.positions[v]);
  });
  std::vector<Vec3> far_point;   // the input points farther than the share
  std::vector<double> far_distance2;
  std::vector<std::vector<uint32_t>> attached(m.triangles.size());  // per mesh face: its closest far points
  const auto attach = [&](const Vec3& p, const AabbTree::Hit& h) {
    attached[h.face].push_back(static_cast<uint32_t>(far_point.size()));
    far_point.push_back(p);
    far_distance2.push_back(h.distance2);
  };
  for (uint32_t v = 0; v < hits.size(); ++v)
    if (hits[v].found() && hits[v].distance2 > share2) attach(input.positions[v], hits[v]);
  std::vector<uint32_t> probed;
  for (uint32_t f = 0; f < input.triangles.size(); ++f) {
    const Tri& t = input.triangles[f];
    if (std::any_of(t.begin(), t.end(), [&](uint32_t v) { return hits[v].found() && hits[v].distance2 > face_share2; }))
      probed.push_back(f);
  }
  std::vector<std::vector<std::pair<Vec3, AabbTree::Hit>>> face_far(probed.size());
  tbb::parallel_for(size_t{0}, probed.size(), [&](size_t i) {
    const Tri& t = input.triangles[probed[i]];
    const Vec3 &a = input.positions[t[0]], &b = input.positions[t[1]], &c = input.positions[t[2]];
    AabbTree::Hit hint;
    for_each_grid_point(a, b, c, fine_grid_divisions(a, b, c, bound), [&](const Vec3& x) {
      if (hint.found() && tree.within(x, share2, hint)) return;
      tree.closest(x, hint);
      if (hint.found() && hint.distance2 > share2) face_far[i].push_back({x, hint});
    });
  });
  for (const auto& points : face_far)
    for (const auto& [p, h] : points) attach(p, h);
  // pr>in: each face's probe points.
  std::vector<double> face_dev2;
  if (face_deviation2 != nullptr && face_deviation2->size() == m.triangles.size()) {
    face_dev2 = *face_deviation2;
  } else {
    face_dev2.assign(m.triangles.size(), 0.0);
    tbb::parallel_for(size_t{0}, m.triangles.size(), [&](size_t f) {
      face_dev2[f] = probe_deviation2(m, {m.triangles[f]}, input_tree, bound, true);
    });
  }
  // pr>in at the vertices themselves (the probes leave them out; h22max6: the feline's worst place at 2e-4, 1.60e-3 of
  // the diagonal, was a lattice vertex at a 64-degree crease that a rounding other than the nearest took from 0.93x
  // to 1.18x the bound off the input, since its triangles' probes came nearer).
  std::vector<double> vertex_dev2(m.positions.size(), 0.0);
  tbb::parallel_for(size_t{0}, m.positions.size(), [&](size_t v) {
    AabbTree::Hit near;  // (as above: within the share, a figure no nearer than the vertex's and within it)
    if (!vertex_faces[v].empty())
      vertex_dev2[v] = input_tree.within(m.positions[v], share2, near) ? near.distance2
                                                                         : input_tree.closest(m.positions[v]).distance2;
  });
  std::vector<std::pair<double, uint32_t>> order;
  for (uint32_t v = 0; v < m.positions.size(); ++v) {
    double worst = vertex_dev2[v];
    for (uint32_t f : vertex_faces[v]) {
      worst = std::max(worst, face_dev2[f]);
      for (uint32_t u : attached[f]) worst = std::max(worst, far_distance2[u]);
    }
    if (worst > share2) order.push_back({worst, v});
  }
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  // Each vertex's ways are weighed with the neighbours weighed before it where the stream puts them: at the way
  // chosen for them, or at their nearest rounding (h22max6: weighed with them where they were, the horse's ear went
  // from 1.46e-3 of the diagonal to 1.63e-3 by the rounding after). Those left at their nearest rounding get their
  // own place back at the end. (With the neighbours not weighed at all at their rounding too, venus went from 7.1x to
  // 8.4x the target.)
  const std::vector<Vec3> unrounded = m.positions;
  std::vector<uint8_t> put(m.positions.size(), 0);
  size_t changed = 0;
  for (const auto& entry : order) {
    const uint32_t v = entry.second;  // not a structured binding: the lambdas below capture it (C++17)
    const std::vector<uint32_t>& faces = vertex_faces[v];
    const std::vector<Tri> tris = triangles_of(m, faces);
    std::vector<uint32_t> points;
    for (uint32_t f : faces) points.insert(points.end(), attached[f].begin(), attached[f].end());
    std::vector<Vec3> normals;  // the unrounded triangles' (a rounding must not turn them over)
    for (const Tri& t : tris)
      normals.push_back(triangle_normal_area2(unrounded[t[0]], unrounded[t[1]], unrounded[t[2]]));
    const Vec3 x = unrounded[v];
    // The worst of the triangles' probes and the attached input points with v at p; infinite when one turns over
    // (or faces away from the input, facing_guard). Once it reaches `limit` the rest is left (hcpu: a way is taken
    // only below it), a figure at least the limit.
    auto cost = [&](const Vec3& p, double limit) {
      m.positions[v] = p;
      for (size_t k = 0; k < tris.size(); ++k) {
        const Vec3 n = face_normal(m, tris[k]);
        if (!(dot(n, normals[k]) > 1e-3 * norm(n) * norm(normals[k]))) return std::numeric_limits<double>::infinity();
      }
      if (facing.away(m, tris) > 0) return std::numeric_limits<double>::infinity();
      double worst = input_tree.closest(p).distance2;
      if (worst < limit) worst = std::max(worst, probe_deviation2(m, tris, input_tree, bound, true, limit));
      for (uint32_t u : points) {
        if (worst >= limit) break;
        worst = std::max(worst, nearest2(m, tris, far_point[u]));
      }
      return worst;
    };
    std::array<std::array<double, 2>, 3> ways;
    Vec3 nearest;
    for (int a = 0; a < 3; ++a) {
      const size_t k = static_cast<size_t>(a);
      const double q = frame.to_quant(x[k], a), r = static_cast<double>(frame.quantize(x[k], a));
      nearest[k] = frame.to_real(r, a);
      const double top = std::ldexp(1.0, frame.bits) - 1;
      if (std::fabs(q - r) < 1e-6) {
        ways[k] = {r, r};  // on its step already (a lattice coordinate)
      } else {
        ways[k] = {std::clamp(std::floor(q), 0.0, top), std::clamp(std::ceil(q), 0.0, top)};
      }
    }
    const double keep = cost(nearest, HUGE_VAL);
    double best = keep;
    Vec3 chosen = nearest;
    for (int c = 0; c < 8; ++c) {
      Vec3 p;
      for (int a = 0; a < 3; ++a) p[static_cast<size_t>(a)] = frame.to_real(ways[static_cast<size_t>(a)][(c >> a) & 1], a);
      if (p == nearest) continue;
      const double e = cost(p, best * kRoundGain);
      if (e < best * kRoundGain) best = e, chosen = p;
    }
    if (chosen == nearest) {
      m.positions[v] = nearest;
    } else {
      m.positions[v] = chosen;
      put[v] = 1;
      ++changed;
    }
  }
  for (uint32_t v = 0; v < m.positions.size(); ++v)
    if (!put[v]) m.positions[v] = unrounded[v];
  // A way was weighed with the neighbours at their rounding, and those left at their nearest one are back where they
  // were: a vertex whose triangles now face away more than unrounded goes back too (the feline_5k at 1e-4: one
  // face), until none does.
  for (bool again = facing.input != nullptr; again;) {
    again = false;
    for (const auto& entry : order) {
      const uint32_t v = entry.second;
      if (!put[v] || facing.away(m, triangles_of(m, vertex_faces[v])) == 0) continue;
      m.positions[v] = unrounded[v];
      put[v] = 0;
      --changed;
      again = true;
    }
  }
  return changed;
}

}  // namespace prm::remesh
