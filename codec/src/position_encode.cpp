// §10 Positions, encoder side: vertices in prediction-degree order (§10.2), parallelogram prediction (§10.3),
// residuals range coded (§10.4). The decoder side is position_decode.cpp.
#include <memory>

#include "position.h"
#include "position_shared.h"
#include "range_encoder.h"
#include "status.h"

namespace prm::codec {
namespace {

// §10.4.1 Residual r of one axis: nothing when the box leaves no room (up + down = 0); otherwise its zigzag value
// u = 2r (r >= 0) or -2r - 1 (r < 0), Rice coded with parameter k: q = u >> k in unary (modelled), then the highest
// of the k low bits (modelled) and the others (direct).
void encode_residual(RangeEncoder& rc, ResidualModels& m, int axis, int ctx, int64_t r, int64_t up, int64_t down) {
  if (up + down == 0) return;
  RiceState& rice = m.rice[axis][ctx];
  const int k = rice.k();
  const uint64_t magnitude = static_cast<uint64_t>(r < 0 ? -r : r);
  const uint64_t u = r >= 0 ? 2 * magnitude : 2 * magnitude - 1;
  const uint64_t q = u >> k;
  BitModel* unary = m.unary[axis][ctx];
  const uint64_t ones = q < kUnaryEscape ? q : kUnaryEscape;
  for (uint64_t i = 0; i < ones; ++i) rc.encode_bit(unary[i < kUnaryModels ? i : kUnaryModels - 1], 1);
  if (q < kUnaryEscape)
    rc.encode_bit(unary[q < kUnaryModels ? q : kUnaryModels - 1], 0);
  else
    rc.encode_direct(static_cast<uint32_t>(q - kUnaryEscape), kEscapeBits);
  if (k > 0) {
    rc.encode_bit(m.low[axis][k][q < 2 ? q : 2], static_cast<int>((u >> (k - 1)) & 1));
    if (k > 1) rc.encode_direct(static_cast<uint32_t>(u), k - 1);
  }
  rice.update(static_cast<uint32_t>(magnitude));
}

}  // namespace

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
