// §10 Positions, decoder side: the mirror of position_encode.cpp.
#include <memory>
#include <string>

#include "position.h"
#include "position_shared.h"
#include "entropy_trace.h"
#include "range_decoder.h"
#include "status.h"

namespace prm::codec {
namespace {

// §10.4.1 The mirror of encode_residual. Returns false when the residual leaves the box (the stream is invalid);
// the Rice state is only updated with a valid magnitude.
inline bool decode_residual(RangeDecoder& rc, ResidualModels& m, int axis, int ctx, int64_t up, int64_t down,
                            int64_t& r) {
  r = 0;
  if (up + down == 0) return true;
  PRM_ENTROPY_TRACE_CALL(value_begin());
  PRM_ENTROPY_RETURN_VALUE(residual, r);
  RiceState& rice = m.rice[axis][ctx];
  const int k = rice.k();
  BitModel* unary = m.unary[axis][ctx];
  // The unary part: models 0 .. kUnaryModels - 2 one per position, then the last one up to the escape. Natively
  // two loops (no per-bit clamp of the model index: -1.9% instructions on feline_5k); in wasm one, as the two cost
  // 1.6 kB of the module (344 B gzipped) for no measured gain in V8.
  uint32_t q = 0;
#if defined(__wasm__)
  while (q < kUnaryEscape && rc.decode_bit(unary[q < kUnaryModels ? q : kUnaryModels - 1])) ++q;
#else
  while (q < kUnaryModels - 1 && rc.decode_bit(unary[q])) ++q;
  if (q == kUnaryModels - 1)
    while (q < kUnaryEscape && rc.decode_bit(unary[kUnaryModels - 1])) ++q;
#endif
  if (q == kUnaryEscape) q += rc.decode_direct(kEscapeBits);
  uint64_t u = q;
  if (k > 0) {
    u = u << 1 | static_cast<uint64_t>(rc.decode_bit(m.low[axis][k][q < 2 ? q : 2]));
    if (k > 1) u = u << (k - 1) | rc.decode_direct(k - 1);
  }
  const uint64_t magnitude = (u + 1) >> 1;
  if (magnitude > static_cast<uint64_t>((u & 1) ? down : up)) return false;
  rice.update(static_cast<uint32_t>(magnitude));
  r = (u & 1) ? -static_cast<int64_t>(magnitude) : static_cast<int64_t>(magnitude);
  PRM_ENTROPY_TRACE_CALL(residual(static_cast<uint32_t>(axis * kResidualContexts + ctx), r, up, down));
  return true;
}

}  // namespace

Status read_positions(const uint8_t* data, size_t size, uint64_t offset, const ClosedMesh& mesh,
                      const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi,
                      std::vector<uint32_t>& q, const std::vector<uint8_t>* known,
                      const std::vector<uint32_t>* vertex_corner) {
  std::vector<uint32_t> own_vertex_corner;
  auto corners = [&]() -> const std::vector<uint32_t>& {  // §10.2 Vertex_Corner: the caller's, or built here
    if (vertex_corner) return *vertex_corner;
    vertex_corners(mesh, own_vertex_corner);
    return own_vertex_corner;
  };
  if (!known) q.assign(size_t{3} * mesh.num_vertices, 0);
  uint32_t real = 0;  // vertices to decode here
  for (uint32_t v = 0; v < mesh.num_vertices; ++v) real += !mesh.is_dummy[v] && !(known && (*known)[v]);
  if (real == 0) {
    if (size != 0) return make_status(Error::trailing_bytes, "10", offset, "position data for no vertices");
    if (known) {  // §6.8 still holds for the vertices the patches placed
      const std::vector<uint32_t>& vc = corners();
      for (uint32_t v = 0; v < mesh.num_vertices; ++v)
        if (vc[v] == UINT32_MAX) return make_status(Error::bad_connectivity, "6.4.8", offset, "a vertex has no triangle");
      DegreeOrder order(mesh, known);
      std::vector<uint32_t> mark(mesh.num_vertices, UINT32_MAX);
      if (!seed_known(mesh, vc, *known, order, mark.data()))
        return make_status(Error::non_manifold_result, "6.8", offset, "two edges join a vertex to the same vertex");
    }
    return ok_status();
  }
  // The vertex count is already bounded by the connectivity section (§4.3); the range decoder needs 4 bytes.
  if (size < 4) return make_status(Error::truncated, "5.6", offset + size, "position data shorter than 4 bytes");
  const std::vector<uint32_t>& vc = corners();
  for (uint32_t v = 0; v < mesh.num_vertices; ++v)  // every id has a corner by §6.4; checked, not assumed
    if (vc[v] == UINT32_MAX)
      return make_status(Error::bad_connectivity, "6.4.8", offset, "a vertex has no triangle");
  DegreeOrder order(mesh, known);
  RangeDecoder rc;
  rc.init(data, size);
  if (rc.bad_start()) return make_status(Error::bad_section, "5.6", offset, "range-coded data starting with FF FF FF FF");
  auto models = std::make_unique<ResidualModels>();
  Prediction pr;
  std::vector<uint32_t> mark(mesh.num_vertices, UINT32_MAX);
  if (known && !seed_known(mesh, vc, *known, order, mark.data()))
    return make_status(Error::non_manifold_result, "6.8", offset, "two edges join a vertex to the same vertex");
  uint32_t previous = UINT32_MAX;
  for (uint32_t v = order.next(); v != UINT32_MAX; v = order.next()) {
    if (!predict_position(mesh, vc, q.data(), v, previous, lo, hi, order, mark.data(), pr))
      return make_status(Error::non_manifold_result, "6.8", offset,
                         "two edges join vertex " + std::to_string(v) + " to the same vertex");
    for (int k = 0; k < 3; ++k) {
      int64_t r;
      if (!decode_residual(rc, *models, k, residual_context(pr, k), int64_t{hi[k]} - pr.p[k],
                           pr.p[k] - int64_t{lo[k]}, r))
        return make_status(rc.failed() ? Error::truncated : Error::bad_position, "10.4", offset + rc.consumed(),
                           "vertex " + std::to_string(v) + " decodes outside the bounding box");
      q[3 * size_t{v} + k] = static_cast<uint32_t>(pr.p[k] + r);
    }
    if (rc.failed()) return make_status(Error::truncated, "5.5", offset + size, "the position data ends early");
    previous = v;
  }
  if (!rc.finish())
    return rc.failed() ? make_status(Error::truncated, "5.5", offset + size, "the position data ends early")
                       : make_status(Error::trailing_bytes, "5.6", offset + rc.consumed(),
                                     "bytes after the last position");
  return ok_status();
}

}  // namespace prm::codec
