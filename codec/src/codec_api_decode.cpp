// The decoding entry points of prm/codec.h: error names, the library version, decode, inspect. The decoder
// (prm_decoder) holds these and no encoder code. Nothing throws out of here.
#include <new>
#include <string>

#include "clers.h"
#include "container.h"
#include "lers.h"
#include "limits.h"
#include "patch.h"
#include "position.h"
#include "prm/codec.h"
#include "status.h"

namespace prm::codec {

// §4.4 Error names.
const char* error_name(Error error) {
  switch (error) {
    case Error::ok: return "ok";
    case Error::invalid_argument: return "invalid_argument";
    case Error::degenerate_triangle: return "degenerate_triangle";
    case Error::non_manifold_edge: return "non_manifold_edge";
    case Error::inconsistent_orientation: return "inconsistent_orientation";
    case Error::non_manifold_vertex: return "non_manifold_vertex";
    case Error::truncated: return "truncated";
    case Error::bad_magic: return "bad_magic";
    case Error::unsupported_version: return "unsupported_version";
    case Error::bad_header: return "bad_header";
    case Error::bad_section: return "bad_section";
    case Error::unsupported_feature: return "unsupported_feature";
    case Error::count_exceeds_limit: return "count_exceeds_limit";
    case Error::count_exceeds_stream: return "count_exceeds_stream";
    case Error::bad_connectivity: return "bad_connectivity";
    case Error::non_manifold_result: return "non_manifold_result";
    case Error::bad_position: return "bad_position";
    case Error::trailing_bytes: return "trailing_bytes";
    case Error::crc_mismatch: return "crc_mismatch";
    case Error::out_of_memory: return "out_of_memory";
    case Error::internal: return "internal";
  }
  return "unknown";
}

uint32_t library_version() { return PRM_VERSION_NUMBER; }
const char* library_version_string() { return PRM_VERSION_STRING; }

Result<DecodedMesh> decode(const uint8_t* data, size_t size, const DecodeOptions& options) {
  Result<DecodedMesh> res;
  try {
    Container c;
    res.status = read_container(data, size, c);
    if (!res.ok()) return res;
    const Header& h = c.header;
    // §4.1 The header's counts against the caller's limits, before anything is allocated.
    if (h.vertices > options.limits.max_vertices || h.triangles > options.limits.max_triangles) {
      res.status = make_status(Error::count_exceeds_limit, "4.1", 8,
                               "the stream has " + std::to_string(h.vertices) + " vertices and " +
                                   std::to_string(h.triangles) + " triangles, beyond the caller's limits");
      return res;
    }
    const Section* cs = c.find(kSectionConnectivity);
    const Section* ps = c.find(kSectionPositions);
    ClosedMesh mesh;
    res.status = read_connectivity(data + cs->offset, cs->size, cs->offset, options.limits, h.vertices,
                                   h.triangles, (h.flags & kFlagClersSeam) != 0, mesh,
                                   (h.flags & kFlagLersValence) != 0);
    if (!res.ok()) return res;
    std::vector<uint32_t> q;
    const Section* is = c.find(kSectionIrregular);
    const Section* pts = c.find(kSectionPatches);
    if (is && pts) {  // §2 a PRM: irregular triangles, patches, then the other vertices
      std::vector<uint8_t> cls, known;
      std::vector<uint32_t> vertex_corner;  // §10.2, built by the patches, reused by the positions
      res.status = read_irregular_triangles(data + is->offset, is->size, is->offset, mesh,
                                            (h.flags & kFlagLersValence) != 0, cls);
      if (!res.ok()) return res;
      res.status = read_patches(data + pts->offset, pts->size, pts->offset, mesh, h.frame.bits, h.bbox_min,
                                h.bbox_max, (h.flags & kFlagPatchContexts) != 0,
                                (h.flags & kFlagPatchGrids) != 0, cls, q, known, vertex_corner);
      if (!res.ok()) return res;
      res.status = read_positions(data + ps->offset, ps->size, ps->offset, mesh, h.bbox_min, h.bbox_max, q, &known,
                                  &vertex_corner);
    } else {
      res.status = read_positions(data + ps->offset, ps->size, ps->offset, mesh, h.bbox_min, h.bbox_max, q);
    }
    if (!res.ok()) return res;
    DecodedMesh& out = res.value;
    out.frame = h.frame;
    if (mesh.num_vertices == h.vertices) {  // no dummies: the closed mesh is the output (§6.7)
      out.triangles = std::move(mesh.corner_vertex);
      out.quantized = std::move(q);
    } else {
      out.triangles = std::move(mesh.output_triangles);
      out.quantized.resize(size_t{3} * h.vertices);
      for (uint32_t v = 0; v < mesh.num_vertices; ++v) {
        const uint32_t n = mesh.old_to_new[v];
        if (n == UINT32_MAX) continue;
        for (int k = 0; k < 3; ++k) out.quantized[3 * size_t{n} + k] = q[3 * size_t{v} + k];
      }
    }
    // §10.5 Output positions: o + q * s in double, rounded to float for float32 output.
    const size_t nq = out.quantized.size();
    const uint32_t* src = out.quantized.data();
    const double o0 = h.frame.origin[0], o1 = h.frame.origin[1], o2 = h.frame.origin[2], step = h.frame.step;
    if (options.positions == PositionOutput::float32) {
      out.positions_f32.resize(nq);
      float* dst = out.positions_f32.data();
      for (size_t i = 0; i < nq; i += 3) {
        dst[i] = static_cast<float>(dequantize(src[i], o0, step));
        dst[i + 1] = static_cast<float>(dequantize(src[i + 1], o1, step));
        dst[i + 2] = static_cast<float>(dequantize(src[i + 2], o2, step));
      }
    } else if (options.positions == PositionOutput::float64) {
      out.positions_f64.resize(nq);
      double* dst = out.positions_f64.data();
      for (size_t i = 0; i < nq; i += 3) {
        dst[i] = dequantize(src[i], o0, step);
        dst[i + 1] = dequantize(src[i + 1], o1, step);
        dst[i + 2] = dequantize(src[i + 2], o2, step);
      }
    }
  } catch (const std::bad_alloc&) {
    res.status = make_status(Error::out_of_memory, "4", 0, "out of memory");
  } catch (...) {
    res.status = make_status(Error::internal, "", 0, "unexpected exception");
  }
  if (!res.ok()) res.value = DecodedMesh{};
  return res;
}

Result<StreamInfo> inspect(const uint8_t* data, size_t size) {
  Result<StreamInfo> res;
  try {
    Container c;
    res.status = read_container(data, size, c);
    if (!res.ok()) return res;
    StreamInfo& s = res.value;
    s.version_major = c.header.version_major;
    s.version_minor = c.header.version_minor;
    s.flags = c.header.flags;
    s.vertices = c.header.vertices;
    s.triangles = c.header.triangles;
    s.frame = c.header.frame;
    s.bbox_min = c.header.bbox_min;
    s.bbox_max = c.header.bbox_max;
    s.header_bytes = c.header_bytes;
    for (const Section& sec : c.sections) s.sections.push_back({sec.id, section_name(sec.id), sec.offset, sec.size});
    s.crc = c.crc;
    s.total_bytes = size;
  } catch (const std::bad_alloc&) {
    res.status = make_status(Error::out_of_memory, "4", 0, "out of memory");
  } catch (...) {
    res.status = make_status(Error::internal, "", 0, "unexpected exception");
  }
  return res;
}

}  // namespace prm::codec
