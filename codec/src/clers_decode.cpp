// §6.3-6.4 The connectivity section, decoded by Spirale Reversi (spirale_reversi.cpp). The encoder side is
// clers_encode.cpp.
#include <algorithm>
#include <memory>
#include <string>

#include "clers.h"
#include "corner_table.h"
#include "limits.h"
#include "range_decoder.h"
#include "status.h"
#include "stream_reader.h"

namespace prm::codec {
namespace {

Status reader_error(const StreamReader& r, const char* section, const char* what) {
  return make_status(r.error(), section, r.error_offset(), std::string(what));
}

// §6.3 The section's fields before the symbols, as read and checked.
struct ConnectivityFields {
  std::vector<uint32_t> sizes;                  // Component_Size[]
  std::vector<uint32_t> comp_first, comp_end;   // per component: its first triangle and one past its last
  std::vector<HandleEvent> handles;
  std::vector<uint32_t> handles_in;             // handle events per component
  std::vector<uint32_t> dummies;
  uint32_t num_triangles = 0;                   // closed triangles, summed over the components
  uint32_t num_vertices = 0;                    // §6.4.8, dummies included
};

// §6.3 Component_Count and Component_Size[]: plausibility before allocation (§4.3): every varint takes a byte.
Status read_components(StreamReader& r, const DecodeLimits& limits, ConnectivityFields& f) {
  const uint32_t num_components = r.varint();
  if (r.failed()) return reader_error(r, "6.3", "Component_Count");
  if (num_components > r.remaining())
    return make_status(Error::count_exceeds_stream, "4.3", r.offset(),
                       "Component_Count " + std::to_string(num_components) + " exceeds the section's bytes");
  const uint64_t max_triangles = std::min<uint64_t>(limits.max_triangles, kHardMaxTriangles);
  f.sizes.resize(num_components);
  uint64_t total = 0;
  for (uint32_t k = 0; k < num_components; ++k) {
    const uint64_t at = r.offset();
    f.sizes[k] = r.varint();
    if (r.failed()) return reader_error(r, "6.3", "Component_Size");
    if (f.sizes[k] < 2 || f.sizes[k] % 2 != 0)
      return make_status(Error::bad_connectivity, "6.3", at,
                         "Component_Size " + std::to_string(f.sizes[k]) + " is not an even number >= 2");
    total += f.sizes[k];
    if (total > max_triangles)
      return make_status(Error::count_exceeds_limit, "4.1", at,
                         "the components have more than " + std::to_string(max_triangles) + " triangles");
  }
  f.num_triangles = static_cast<uint32_t>(total);
  // Component of each triangle is found by walking; first triangles are the running sums.
  f.comp_first.resize(num_components);
  f.comp_end.resize(num_components);
  uint32_t s = 0;
  for (uint32_t k = 0; k < num_components; ++k) {
    f.comp_first[k] = s;
    s += f.sizes[k];
    f.comp_end[k] = s;
  }
  return ok_status();
}

// §6.3 Handle_Count and the handle events.
Status read_handles(StreamReader& r, ConnectivityFields& f) {
  const uint32_t num_components = static_cast<uint32_t>(f.sizes.size());
  const uint32_t num_handles = r.varint();
  if (r.failed()) return reader_error(r, "6.3", "Handle_Count");
  if (num_handles > r.remaining() / 2)
    return make_status(Error::count_exceeds_stream, "4.3", r.offset(), "Handle_Count exceeds the section's bytes");
  f.handles.resize(num_handles);
  f.handles_in.assign(num_components, 0);
  uint64_t prev = 0;
  uint32_t k = 0;
  for (uint32_t h = 0; h < num_handles; ++h) {
    const uint64_t at = r.offset();
    const uint32_t delta = r.varint();
    const uint32_t packed = r.varint();
    if (r.failed()) return reader_error(r, "6.3", "handle event");
    const uint64_t t = prev + delta;
    const uint64_t partner = t + 1 + (packed >> 2);
    const uint32_t corner = packed & 3;
    if ((h > 0 && delta == 0) || partner >= f.num_triangles || corner > 2)
      return make_status(Error::bad_connectivity, "6.3", at, "handle event out of range");
    while (k < num_components && f.comp_end[k] <= t) ++k;
    if (t == f.comp_first[k] || partner >= f.comp_end[k])
      return make_status(Error::bad_connectivity, "6.3", at, "handle event on a first triangle or across components");
    ++f.handles_in[k];
    f.handles[h] = {static_cast<uint32_t>(t), static_cast<uint32_t>(partner), static_cast<uint8_t>(corner)};
    prev = t;
  }
  return ok_status();
}

// §6.4.8 Vertices per component: V = 2 - H + T / 2 (Euler, H = 2 * genus handle events).
Status count_vertices(const DecodeLimits& limits, uint64_t offset, ConnectivityFields& f) {
  uint64_t nv64 = 0;
  for (uint32_t k = 0; k < f.sizes.size(); ++k) {
    if (f.handles_in[k] % 2 != 0 || f.handles_in[k] + 1 > f.sizes[k] / 2)
      return make_status(Error::bad_connectivity, "6.3", offset,
                         "component " + std::to_string(k) + " has an impossible number of handle events");
    nv64 += 2 + f.sizes[k] / 2 - f.handles_in[k];
  }
  const uint64_t max_vertices = std::min<uint64_t>(limits.max_vertices, kHardMaxVertices);
  if (nv64 > max_vertices)
    return make_status(Error::count_exceeds_limit, "4.1", offset,
                       "the components have more than " + std::to_string(max_vertices) + " vertices");
  f.num_vertices = static_cast<uint32_t>(nv64);
  return ok_status();
}

// §6.3 Dummy_Count and dummy vertex ids.
Status read_dummies(StreamReader& r, uint32_t header_vertices, ConnectivityFields& f) {
  const uint32_t nv = f.num_vertices;
  const uint32_t num_dummies = r.varint();
  if (r.failed()) return reader_error(r, "6.3", "Dummy_Count");
  if (num_dummies > nv || num_dummies > r.remaining())
    return make_status(Error::count_exceeds_stream, "4.3", r.offset(), "Dummy_Count out of range");
  if (uint64_t{header_vertices} + num_dummies != nv)
    return make_status(Error::bad_connectivity, "6.3", r.offset(),
                       "Vertex_Count " + std::to_string(header_vertices) + " + Dummy_Count " +
                           std::to_string(num_dummies) + " differs from the components' " + std::to_string(nv) +
                           " vertices");
  f.dummies.resize(num_dummies);  // at most one per remaining byte: checked above
  uint64_t prev = 0;
  for (uint32_t d = 0; d < num_dummies; ++d) {
    const uint64_t at = r.offset();
    const uint32_t delta = r.varint();
    if (r.failed()) return reader_error(r, "6.3", "dummy vertex");
    const uint64_t v = prev + delta;
    if ((d > 0 && delta == 0) || v >= nv)
      return make_status(Error::bad_connectivity, "6.3", at, "dummy vertex id out of range or not increasing");
    f.dummies[d] = static_cast<uint32_t>(v);
    prev = v;
  }
  return ok_status();
}

// §6.4-6.5 The range-coded CLERS symbols (`clers`, `clers_size` bytes at stream offset `clers_offset`), decoded by
// Spirale Reversi in backward order into the closed mesh's triangles and opposite corners.
Status decode_symbols(const uint8_t* clers, size_t clers_size, uint64_t clers_offset, const ConnectivityFields& f,
                      bool seam_context, bool valences, ClosedMesh& mesh) {
  const uint32_t nt = f.num_triangles, nv = f.num_vertices;
  const uint32_t num_components = static_cast<uint32_t>(f.sizes.size());
  const uint32_t num_handles = static_cast<uint32_t>(f.handles.size());
  // §4.2 Every coded symbol takes at least one decision; forced symbols (§6.5.1) are the first decoded symbol of
  // each component and the handle S triangles.
  const uint64_t coded = uint64_t{nt} - 2 * uint64_t{num_components} - num_handles;
  if (clers_size < 4 || coded > kMaxDecisionsPerByte * (clers_size - 3))
    return make_status(Error::count_exceeds_stream, "4.2", clers_offset,
                       std::to_string(coded) + " symbols cannot be coded in " + std::to_string(clers_size) +
                           " bytes");

  // §4.5 Nothing below is sized by nt or nv before the triangles are decoded: Spirale Reversi grows as it goes.
  SpiraleReversi sr;
  sr.init(nt, nv, seam_context);
  RangeDecoder rc;
  rc.init(clers, clers_size);
  auto models = std::make_unique<ClersModels>();
  uint32_t comp = num_components;
  uint32_t h = num_handles;
  uint32_t prev1 = kE, prev2 = kE;
  auto fail = [&](const char* section) {
    if (rc.bad_start())
      return make_status(Error::bad_section, "5.6", clers_offset, "range-coded data starting with FF FF FF FF");
    if (rc.failed())
      return make_status(Error::truncated, "5.5", clers_offset + clers_size, "the CLERS symbols end early");
    return make_status(Error::bad_connectivity, section, clers_offset + rc.consumed(), sr.error());
  };
  // The next triangle (counting down) that is a component's first or a handle S: one comparison per triangle. The
  // two never coincide: read_handles rejects a handle event on a component's first triangle (§6.3).
  auto next_event = [&]() -> int64_t {
    const int64_t c = comp > 0 ? int64_t{f.comp_first[comp - 1]} : -1;
    const int64_t e = h > 0 ? int64_t{f.handles[h - 1].triangle} : -1;
    return c > e ? c : e;
  };
  int64_t event = next_event();
  for (uint32_t i = nt; i-- > 0;) {
    if (i == event) {
      if (comp > 0 && f.comp_first[comp - 1] == i) {
        if (!sr.close_component(i)) return fail("6.4.7");
        --comp;
        event = next_event();
        continue;
      }
      --h;  // a handle S
      if (!sr.apply_handle(i, f.handles[h], f.comp_end[comp - 1])) return fail("6.4.6");
      prev2 = prev1;
      prev1 = kS;
      event = next_event();
      continue;
    }
    // §6.5.1 Binarization.
    uint8_t s = kE;
    const uint32_t depth = sr.stack_depth();
    if (depth > 0) {
      uint32_t seam;
      const uint32_t count = sr.gate_start(seam_context, seam);
      BitModel* m = models->m[clers_context(prev1, prev2, count, seam)];
      PRM_ENTROPY_TRACE_CALL(value_begin());
      if (PRM_ENTROPY_VALUE(clers, s)) {
      } else if (!rc.decode_bit(m[0])) {
        s = kC;
      } else if (!rc.decode_bit(m[1])) {
        s = kR;
      } else if (depth >= 2 && !rc.decode_bit(m[2])) {
        s = kS;
      } else {
        s = rc.decode_bit(m[3]) ? kE : kL;
      }
      PRM_ENTROPY_TRACE_CALL(clers(clers_context(prev1, prev2, count, seam), s, depth >= 2));
      if (rc.failed()) return fail("5.5");
    }
    if (!sr.apply(i, s)) return fail("6.4");
    prev2 = prev1;
    prev1 = s;
  }
  if (!rc.finish())
    return rc.failed() ? fail("5.5")
                       : make_status(Error::trailing_bytes, "5.6", clers_offset + rc.consumed(),
                                     "bytes after the last CLERS symbol");
  if (!sr.finish(mesh.corner_vertex, valences ? &mesh.valence : nullptr))
    return make_status(sr.error_is_non_manifold() ? Error::non_manifold_result : Error::bad_connectivity, "6.8",
                       clers_offset, sr.error());
  mesh.num_vertices = nv;
  mesh.opp = std::move(sr.opposites());
  mesh.is_dummy.assign(nv, 0);  // nv vertices are decoded now (§6.4.8)
  for (uint32_t d : f.dummies) mesh.is_dummy[d] = 1;
  return ok_status();
}

// §6.7 Dummy vertices: no edge joins two of them, each real vertex meets at most one of them, and every real
// vertex keeps a real triangle. The output triangles (renumbered without the dummies) are built in the same pass.
// `at`: the stream offset the errors name.
Status remove_dummies(uint32_t header_triangles, uint64_t at, ClosedMesh& mesh) {
  const uint32_t nt = mesh.num_triangles(), nv = mesh.num_vertices;
  if (header_triangles > nt)
    return make_status(Error::bad_connectivity, "6.7", at, "Triangle_Count exceeds the closed mesh");
  std::vector<uint32_t>& old_to_new = mesh.old_to_new;
  old_to_new.assign(nv, UINT32_MAX);
  {
    uint32_t n = 0;
    for (uint32_t v = 0; v < nv; ++v)
      if (!mesh.is_dummy[v]) old_to_new[v] = n++;
  }
  std::vector<uint32_t> dummy_of(nv, UINT32_MAX);
  std::vector<uint8_t> has_real(nv, 0);
  std::vector<uint32_t>& out = mesh.output_triangles;
  out.clear();
  out.reserve(size_t{3} * header_triangles);
  for (uint32_t t = 0; t < nt; ++t) {
    const uint32_t* f = &mesh.corner_vertex[3 * t];
    const int dummies = mesh.is_dummy[f[0]] + mesh.is_dummy[f[1]] + mesh.is_dummy[f[2]];
    if (dummies > 1) return make_status(Error::non_manifold_result, "6.7", at, "an edge joins two dummy vertices");
    if (dummies == 0) {
      if (out.size() == size_t{3} * header_triangles)
        return make_status(Error::bad_connectivity, "6.7", at,
                           "more triangles than Triangle_Count " + std::to_string(header_triangles));
      for (int k = 0; k < 3; ++k) {
        has_real[f[k]] = 1;
        out.push_back(old_to_new[f[k]]);
      }
      continue;
    }
    const uint32_t d = mesh.is_dummy[f[0]] ? f[0] : mesh.is_dummy[f[1]] ? f[1] : f[2];
    for (int k = 0; k < 3; ++k) {
      if (f[k] == d) continue;
      if (dummy_of[f[k]] != UINT32_MAX && dummy_of[f[k]] != d)
        return make_status(Error::non_manifold_result, "6.7", at, "a vertex lies on two holes (pinched boundary)");
      dummy_of[f[k]] = d;
    }
  }
  for (uint32_t v = 0; v < nv; ++v)
    if (!mesh.is_dummy[v] && !has_real[v])
      return make_status(Error::non_manifold_result, "6.7", at, "a vertex has only dummy triangles");
  if (out.size() != size_t{3} * header_triangles)
    return make_status(Error::bad_connectivity, "6.7", at,
                       "Triangle_Count " + std::to_string(header_triangles) + " differs from the decoded " +
                           std::to_string(out.size() / 3));
  return ok_status();
}

}  // namespace

Status read_connectivity(const uint8_t* data, size_t size, uint64_t offset, const DecodeLimits& limits,
                         uint32_t header_vertices, uint32_t header_triangles, bool seam_context, ClosedMesh& mesh,
                         bool valences) {
  StreamReader r(data, size, offset);
  ConnectivityFields f;
  PRM_TRY(read_components(r, limits, f));
  PRM_TRY(read_handles(r, f));
  PRM_TRY(count_vertices(limits, offset, f));
  PRM_TRY(read_dummies(r, header_vertices, f));
  // §6.5 The range-coded symbols: the rest of the section.
  const uint64_t clers_offset = r.offset();
  const size_t clers_size = r.remaining();
  const uint8_t* clers = r.bytes(clers_size);
  if (f.num_triangles == 0) {
    if (clers_size != 0) return make_status(Error::trailing_bytes, "6.3", clers_offset, "symbols for no triangles");
    mesh.num_vertices = 0;
    mesh.is_dummy.clear();
    mesh.corner_vertex.clear();
    mesh.opp.clear();
    if (header_triangles != 0) return make_status(Error::bad_connectivity, "6.3", offset, "Triangle_Count mismatch");
    return ok_status();
  }
  PRM_TRY(decode_symbols(clers, clers_size, clers_offset, f, seam_context, valences, mesh));
  if (f.dummies.empty()) {
    if (f.num_triangles != header_triangles)
      return make_status(Error::bad_connectivity, "6.7", clers_offset,
                         "Triangle_Count " + std::to_string(header_triangles) + " differs from the decoded " +
                             std::to_string(f.num_triangles));
    return ok_status();
  }
  return remove_dummies(header_triangles, clers_offset, mesh);
}

}  // namespace prm::codec
