// §10 Positions, encoder side: vertices in prediction-degree order (§10.2), parallelogram prediction (§10.3),
// residuals range coded (§10.4). The decoder side is position_decode.cpp.
#include <memory>

#include "position.h"
#include "position_residual_encode.h"
#include "position_shared.h"
#include "range_encoder.h"
#include "status.h"

namespace prm::codec {

Status write_positions(const ClosedMesh& mesh, const std::vector<uint32_t>& q, const std::array<uint32_t, 3>& lo,
                       const std::array<uint32_t, 3>& hi, std::vector<uint8_t>& payload,
                       const std::vector<uint8_t>* known) {
  std::vector<uint32_t> vc;
  vertex_corners(mesh, vc);
  DegreeOrder order(mesh, known);
  RangeEncoder rc;
  auto models = std::make_unique<ResidualModels>();
  Prediction pr;
  std::vector<uint32_t> mark(mesh.num_vertices, UINT32_MAX);
  if (known && !seed_known(mesh, vc, *known, order, mark.data()))
    return make_status(Error::internal, "6.8", 0, "two edges join the same pair of vertices");
  uint32_t previous = UINT32_MAX;
  for (uint32_t v = order.next(); v != UINT32_MAX; v = order.next()) {
    if (!predict_position(mesh, vc, q.data(), v, previous, lo, hi, order, mark.data(), pr))
      return make_status(Error::internal, "6.8", 0, "two edges join the same pair of vertices");
    for (int k = 0; k < 3; ++k)
      encode_residual(rc, *models, k, residual_context(pr, k), int64_t{q[3 * size_t{v} + k]} - pr.p[k],
                      int64_t{hi[k]} - pr.p[k], pr.p[k] - int64_t{lo[k]});
    previous = v;
  }
  payload.clear();
  if (previous != UINT32_MAX) payload = rc.finish();
  return ok_status();
}

}  // namespace prm::codec
