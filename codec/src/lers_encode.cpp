// §7 Irregular triangles, encoder side: LERS traversals (paper §3.2) started, in increasing triangle index, at every
// irregular triangle no earlier traversal discovered. The decoder side is lers_decode.cpp.
#include <memory>

#include "lers.h"
#include "lers_shared.h"
#include "range_encoder.h"
#include "status.h"

namespace prm::codec {

void write_irregular_triangles(const ClosedMesh& mesh, const std::vector<uint8_t>& irregular, bool valence_context,
                               std::vector<uint8_t>& payload) {
  const uint32_t nt = mesh.num_triangles();
  const std::vector<uint8_t> cls = dummy_triangles(mesh);
  // The traversal starts, found by running the walks without coding.
  std::vector<uint8_t> discovered(nt, 0);
  const std::vector<uint8_t> valence = valence_context ? vertex_valences(mesh) : std::vector<uint8_t>{};
  std::vector<uint32_t> stack, starts;
  auto models = std::make_unique<LersModels>();
  int history[2] = {0, 0};
  for (uint32_t t = 0; t < nt; ++t) {
    if (!irregular[t] || discovered[t] || cls[t] == kDummyTriangle) continue;
    starts.push_back(t);
    discovered[t] = 1;
    lers_traversal(mesh, cls, irregular, discovered, stack, *models, t, history, valence,
                   [](BitModel&, bool truth) { return truth; });
  }
  // §7.2 Then for real: the count, and per traversal the gap to the previous start and its decisions.
  RangeEncoder rc;
  models = std::make_unique<LersModels>();
  discovered.assign(nt, 0);
  history[0] = history[1] = 0;
  encode_signed(rc, models->count, static_cast<int64_t>(starts.size()));
  int64_t next = 0;
  for (uint32_t s : starts) {
    encode_signed(rc, models->gap, static_cast<int64_t>(s) - next);
    next = int64_t{s} + 1;
    discovered[s] = 1;
    lers_traversal(mesh, cls, irregular, discovered, stack, *models, s, history, valence, [&](BitModel& m, bool truth) {
      rc.encode_bit(m, truth ? 1 : 0);
      return truth;
    });
  }
  payload = rc.finish();
}

}  // namespace prm::codec
