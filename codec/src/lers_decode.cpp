// §7 Irregular triangles, decoder side: the mirror of lers_encode.cpp.
#include <memory>
#include <string>

#include "lers.h"
#include "lers_shared.h"
#include "range_decoder.h"
#include "status.h"

namespace prm::codec {

Status read_irregular_triangles(const uint8_t* data, size_t size, uint64_t offset, const ClosedMesh& mesh,
                                bool valence_context, std::vector<uint8_t>& cls) {
  const uint32_t nt = mesh.num_triangles();
  cls = dummy_triangles(mesh);
  if (size < 4) return make_status(Error::truncated, "5.6", offset + size, "irregular-triangle data shorter than 4 bytes");
  RangeDecoder rc;
  rc.init(data, size);
  if (rc.bad_start()) return make_status(Error::bad_section, "5.6", offset, "range-coded data starting with FF FF FF FF");
  auto models = std::make_unique<LersModels>();
  int64_t count = 0;
  // §7.2 At most one traversal per triangle.
  if (!decode_signed(rc, models->count, 30, count) || count < 0 || count > int64_t{nt})
    return make_status(rc.failed() ? Error::truncated : Error::bad_section, "7.2", offset + rc.consumed(),
                       "traversal count out of range");
  std::vector<uint8_t> discovered(nt, 0);
  // §7.3 The valences the connectivity counted, else counted here.
  const bool counted = mesh.valence.size() == mesh.num_vertices;
  const std::vector<uint8_t> own = valence_context && !counted ? vertex_valences(mesh) : std::vector<uint8_t>{};
  const std::vector<uint8_t>& valence = !valence_context ? own : counted ? mesh.valence : own;
  std::vector<uint32_t> stack;
  const std::vector<uint8_t> none;
  int history[2] = {0, 0};
  int64_t next = 0;
  for (int64_t k = 0; k < count; ++k) {
    int64_t gap = 0;
    if (!decode_signed(rc, models->gap, 30, gap) || gap < 0 || next + gap >= int64_t{nt})
      return make_status(rc.failed() ? Error::truncated : Error::bad_section, "7.2", offset + rc.consumed(),
                         "traversal " + std::to_string(k) + " starts outside the mesh");
    const uint32_t s = static_cast<uint32_t>(next + gap);
    next = int64_t{s} + 1;
    if (discovered[s] || cls[s] == kDummyTriangle)
      return make_status(Error::bad_section, "7.2", offset + rc.consumed(),
                         "traversal " + std::to_string(k) + " starts at a discovered or dummy triangle " +
                             std::to_string(s));
    discovered[s] = 1;
    lers_traversal(mesh, cls, none, discovered, stack, *models, s, history, valence,
                   [&](BitModel& m, bool) { return rc.decode_bit(m) != 0; });
    if (rc.failed()) return make_status(Error::truncated, "5.5", offset + size, "the irregular-triangle data ends early");
  }
  if (!rc.finish())
    return rc.failed() ? make_status(Error::truncated, "5.5", offset + size, "the irregular-triangle data ends early")
                       : make_status(Error::trailing_bytes, "5.6", offset + rc.consumed(),
                                     "bytes after the last traversal");
  for (uint32_t t = 0; t < nt; ++t)
    if (cls[t] != kDummyTriangle) cls[t] = discovered[t] ? kIrregular : kRegular;
  return ok_status();
}

}  // namespace prm::codec
