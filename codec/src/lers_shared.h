// §7 The irregular-triangles section: LERS traversals of the irregular triangles (paper §3.2). The traversal walk
// and its contexts are here, once, for lers_encode.cpp and lers_decode.cpp (their entry points: lers.h).
#pragma once

#include <cstdint>
#include <vector>

#include "adaptive_model.h"
#include "closed_mesh.h"
#include "corner_table.h"
#include "regular_patches_shared.h"
#include "signed_int_model.h"

namespace prm::codec {

// §7.3 Models. A symbol is the pair of decisions (open across the edge opposite next(ce), open across the edge
// opposite prev(ce)) of a triangle entered across the edge opposite corner ce: S = both, R or L = one, E = none
// (paper Figure 7), numbered 2 * first + second. The context of the first decision is the two previous symbols and
// whether the second is forced; of the second, the two previous symbols, the first decision and whether it was forced.
// With the valence context (§7.3, Flags bit 0) both also see the valences around the neighbour they decide.
constexpr int kLersValenceContexts = 8;
struct LersModels {
  SignedIntModel count, gap;
  BitModel start[3];
  BitModel first[4][4][2][kLersValenceContexts];
  BitModel second[4][4][2][2][kLersValenceContexts];
};

// §7.2 One traversal from triangle s (already marked discovered), as both sides run it. `code(model, truth)`
// returns the decision: the encoder codes `truth` (open = irregular and not yet discovered) and returns it, the
// decoder ignores `truth` and returns the decoded bit. A neighbour is forced closed, and no decision coded, when it
// is discovered or a dummy triangle. `cls` holds kDummyTriangle for dummies; `truth_irregular` is the encoder's
// knowledge (the decoder passes an empty vector). Returns the number of triangles the traversal discovered.
template <typename Code>
uint32_t lers_traversal(const ClosedMesh& mesh, const std::vector<uint8_t>& cls,
                        const std::vector<uint8_t>& truth_irregular, std::vector<uint8_t>& discovered,
                        std::vector<uint32_t>& stack, LersModels& m, uint32_t s, int (&history)[2],
                        const std::vector<uint8_t>& valence, Code&& code) {
  const int32_t* opp = mesh.opp.data();
  auto closed = [&](uint32_t n) { return discovered[n] || cls[n] == kDummyTriangle; };
  auto truth = [&](uint32_t n) { return !truth_irregular.empty() && truth_irregular[n] && !discovered[n]; };
  // §7.3 Valence context (Flags bit 0, format 1.2): how many of the neighbour's vertices have a valence other than
  // 6, plus 4 if its far vertex (the one off the shared edge) does; 0 without the flag (empty `valence`).
  auto feat = [&](uint32_t oc) {
    if (valence.empty()) return 0;
    const uint32_t n = oc / 3;
    int k = 0;
    for (int c = 0; c < 3; ++c) k += valence[mesh.corner_vertex[3 * n + c]] != 6;
    return k + 4 * (valence[mesh.corner_vertex[oc]] != 6);
  };
  uint32_t found = 1;
  stack.clear();
  // §7.2 The start triangle: its three edges in corner order.
  for (uint32_t k = 0; k < 3; ++k) {
    const uint32_t oc = static_cast<uint32_t>(opp[3 * s + k]);
    const uint32_t n = oc / 3;
    if (closed(n)) continue;
    if (code(m.start[k], truth(n))) {
      discovered[n] = 1;
      ++found;
      stack.push_back(oc);
    }
  }
  // §7.2 Depth first: pop a triangle entered across the edge opposite corner ce; decide its two other edges.
  while (!stack.empty()) {
    const uint32_t ce = stack.back();
    stack.pop_back();
    const uint32_t c1 = corner_next(ce), c2 = corner_prev(ce);
    const uint32_t o1 = static_cast<uint32_t>(opp[c1]), o2 = static_cast<uint32_t>(opp[c2]);
    const uint32_t n1 = o1 / 3, n2 = o2 / 3;
    const bool f1 = closed(n1);
    int b1 = 0;
    if (!f1) b1 = code(m.first[history[0]][history[1]][closed(n2) ? 1 : 0][feat(o1)], truth(n1)) ? 1 : 0;
    if (b1) {
      discovered[n1] = 1;
      ++found;
    }
    int b2 = 0;
    if (!closed(n2)) b2 = code(m.second[history[0]][history[1]][b1][f1 ? 1 : 0][feat(o2)], truth(n2)) ? 1 : 0;
    if (b2) {
      discovered[n2] = 1;
      ++found;
      stack.push_back(o2);
    }
    if (b1) stack.push_back(o1);  // popped first: the walk goes on across the edge opposite next(ce)
    history[1] = history[0];
    history[0] = 2 * b1 + b2;
  }
  return found;
}

// Vertex valences (triangles per vertex), capped at 255.
inline std::vector<uint8_t> vertex_valences(const ClosedMesh& mesh) {
  std::vector<uint8_t> v(mesh.num_vertices, 0);
  uint8_t* at = v.data();
  for (uint32_t x : mesh.corner_vertex) at[x] = static_cast<uint8_t>(at[x] + (at[x] != 255));  // saturating
  return v;
}

}  // namespace prm::codec
