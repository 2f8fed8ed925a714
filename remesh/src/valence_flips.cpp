// Valence flips (ours, after the paper's passes): seam edges flipped towards valence 6.
#include "prm/vec3.h"
#include "seam_optimizer.h"

namespace prm::remesh {

namespace {

// Valence flips on the seams (ours): flip an edge between two reliefs when that brings the valences of its
// four vertices closer to 6 (the sum of (valence - 6)^2 falls by at least 2), both new triangles are valid
// and the quad's area grows by at most kValenceFlipArea. Regular vertices cost the connectivity coder almost
// nothing (spec §6.5.2) and the seams are where the irregular valences are; such an edge never borders a
// regular triangle (it joins two reliefs).
constexpr double kValenceFlipArea = 0.2;

}  // namespace

bool SeamOptimizer::try_valence_flip(EH e) {
  Quad q;
  if (!flippable(e, q)) return false;
  auto dev = [](int v) { return (v - 6) * (v - 6); };
  const int va = valence(mesh_, q.a), vb = valence(mesh_, q.b);
  const int vc = valence(mesh_, q.c), vd = valence(mesh_, q.d);
  const int before = dev(va) + dev(vb) + dev(vc) + dev(vd);
  const int after = dev(va - 1) + dev(vb - 1) + dev(vc + 1) + dev(vd + 1);
  if (after > before - 2 || va <= 3 || vb <= 3) return false;
  if (!(q.area_after <= q.area_before * (1.0 + kValenceFlipArea)) || !flip_is_valid(q)) return false;
  mesh_.flip(e);
  return true;
}

size_t SeamOptimizer::regularize_valences() {
  size_t flips = 0;
  for (int round = 0; round < 4; ++round) {
    size_t now = 0;
    for (auto e : mesh_.edges())
      if (!mesh_.status(e).deleted() && joins_reliefs(e) && try_valence_flip(e)) ++now;
    flips += now;
    if (now == 0) break;
  }
  return flips;
}

}  // namespace prm::remesh
