// The decoding half of the C API (prm/prm.h) over prm/codec.h: version, status names, inspect, decode into caller or
// library buffers. Nothing throws out of here.
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>
#include <vector>

#include "c_api_shared.h"

using namespace prm::codec;

namespace {

// The C enum mirrors Error value for value: a new Error goes into prm_status (prm/prm.h) too, at the same value.
static_assert(static_cast<int>(PRM_ERROR_INTERNAL) == static_cast<int>(Error::internal),
              "prm_status (prm/prm.h) no longer mirrors prm::codec::Error (prm/codec.h)");
static_assert(static_cast<int>(Error::internal) < static_cast<int>(PRM_ERROR_BUFFER_TOO_SMALL),
              "the C API's own statuses must stay above prm::codec::Error's values");

DecodeOptions decode_options(const prm_decode_limits* limits, PositionOutput positions) {
  DecodeOptions o;
  if (limits) {
    o.limits.max_vertices = limits->max_vertices;
    o.limits.max_triangles = limits->max_triangles;
  }
  o.positions = positions;
  return o;
}

void copy_frame(const Frame& f, prm_frame& out) {
  out.bits = f.bits;
  for (int k = 0; k < 3; ++k) out.origin[k] = f.origin[static_cast<size_t>(k)];
  out.step = f.step;
}

// prm_decode_mesh's result: the public struct, and the decoder's own vectors its pointers point into (no copy of
// the positions, quantized coordinates and indices). prm_mesh_free gets back here from the public struct, its first
// member (a standard-layout class: the two are pointer-interconvertible).
struct OwnedMesh {
  prm_mesh mesh;
  DecodedMesh decoded;
};
static_assert(std::is_standard_layout<OwnedMesh>::value && offsetof(OwnedMesh, mesh) == 0,
              "prm_mesh_free casts a prm_mesh* back to its OwnedMesh");

// A non-null pointer for an empty vector too (the struct's contract).
template <typename T>
T* data_or_empty(std::vector<T>& v) {
  static T empty{};
  return v.empty() ? &empty : v.data();
}

}  // namespace

extern "C" {

uint32_t prm_version(void) { return library_version(); }
const char* prm_version_string(void) { return library_version_string(); }

const char* prm_status_name(int status) {
  if (status == PRM_ERROR_BUFFER_TOO_SMALL) return "buffer_too_small";
  if (status < 0 || status >= PRM_ERROR_BUFFER_TOO_SMALL) return "unknown";
  return error_name(static_cast<Error>(status));  // "unknown" for a value Error does not have
}

void prm_decode_limits_default(prm_decode_limits* limits) {
  if (!limits) return;
  const DecodeLimits d;
  limits->max_vertices = d.max_vertices;
  limits->max_triangles = d.max_triangles;
}

prm_status prm_inspect(const uint8_t* data, size_t size, prm_stream_info* info, prm_error* error) {
  if (!data || !info) return set_error(error, PRM_ERROR_INVALID_ARGUMENT, "", 0, "prm_inspect: data or info is NULL");
  const Result<StreamInfo> r = inspect(data, size);  // never throws
  if (!r.ok()) return set_error(error, r.status);
  const StreamInfo& s = r.value;
  std::memset(info, 0, sizeof *info);
  info->version_major = s.version_major;
  info->version_minor = s.version_minor;
  info->flags = s.flags;
  info->vertices = s.vertices;
  info->triangles = s.triangles;
  copy_frame(s.frame, info->frame);
  for (int k = 0; k < 3; ++k) {
    info->bbox_min[k] = s.bbox_min[static_cast<size_t>(k)];
    info->bbox_max[k] = s.bbox_max[static_cast<size_t>(k)];
  }
  info->total_bytes = static_cast<size_t>(s.total_bytes);
  return set_ok(error);
}

prm_status prm_decode(const uint8_t* data, size_t size, const prm_decode_limits* limits, float* positions,
                      size_t positions_capacity, uint32_t* indices, size_t indices_capacity, prm_error* error) {
  if (!data) return set_error(error, PRM_ERROR_INVALID_ARGUMENT, "", 0, "prm_decode: data is NULL");
  if ((!positions && positions_capacity) || (!indices && indices_capacity))
    return set_error(error, PRM_ERROR_INVALID_ARGUMENT, "", 0, "prm_decode: a NULL buffer with a nonzero capacity");
  try {
    // The header's counts first: a buffer too small fails before the sections are decoded.
    const Result<StreamInfo> info = inspect(data, size);
    if (!info.ok()) return set_error(error, info.status);
    const size_t nv = 3 * size_t{info.value.vertices}, nt = 3 * size_t{info.value.triangles};
    if ((positions && positions_capacity < nv) || (indices && indices_capacity < nt))
      return set_error(error, PRM_ERROR_BUFFER_TOO_SMALL, "", 0,
                       ("prm_decode: the stream decodes to " + std::to_string(nv) + " coordinates and " +
                        std::to_string(nt) + " indices, more than the buffers hold")
                           .c_str());
    const PositionOutput output = positions ? PositionOutput::float32 : PositionOutput::quantized_only;
    const Result<DecodedMesh> r = decode(data, size, decode_options(limits, output));
    if (!r.ok()) return set_error(error, r.status);
    if (positions && !r.value.positions_f32.empty())
      std::memcpy(positions, r.value.positions_f32.data(), r.value.positions_f32.size() * sizeof(float));
    if (indices && !r.value.triangles.empty())
      std::memcpy(indices, r.value.triangles.data(), r.value.triangles.size() * sizeof(uint32_t));
    return set_ok(error);
  } catch (const std::bad_alloc&) {
    return set_error(error, PRM_ERROR_OUT_OF_MEMORY, "4", 0, "out of memory");
  } catch (...) {
    return set_error(error, PRM_ERROR_INTERNAL, "", 0, "unexpected exception");
  }
}

prm_status prm_decode_mesh(const uint8_t* data, size_t size, const prm_decode_limits* limits, prm_mesh** mesh,
                           prm_error* error) {
  if (!mesh) return set_error(error, PRM_ERROR_INVALID_ARGUMENT, "", 0, "prm_decode_mesh: mesh is NULL");
  *mesh = nullptr;
  if (!data) return set_error(error, PRM_ERROR_INVALID_ARGUMENT, "", 0, "prm_decode_mesh: data is NULL");
  try {
    Result<DecodedMesh> r = decode(data, size, decode_options(limits, PositionOutput::float32));
    if (!r.ok()) return set_error(error, r.status);
    OwnedMesh* owned = new (std::nothrow) OwnedMesh{};
    if (!owned) return set_error(error, PRM_ERROR_OUT_OF_MEMORY, "4", 0, "out of memory");
    owned->decoded = std::move(r.value);  // the vectors move: the mesh's arrays are the decoder's own
    DecodedMesh& d = owned->decoded;
    prm_mesh* m = &owned->mesh;
    m->vertices = d.num_vertices();
    m->triangles = d.num_triangles();
    copy_frame(d.frame, m->frame);
    m->positions = data_or_empty(d.positions_f32);
    m->quantized = data_or_empty(d.quantized);
    m->indices = data_or_empty(d.triangles);
    *mesh = m;
    return set_ok(error);
  } catch (const std::bad_alloc&) {
    return set_error(error, PRM_ERROR_OUT_OF_MEMORY, "4", 0, "out of memory");
  } catch (...) {
    return set_error(error, PRM_ERROR_INTERNAL, "", 0, "unexpected exception");
  }
}

void prm_mesh_free(prm_mesh* mesh) {
  if (!mesh) return;
  delete reinterpret_cast<OwnedMesh*>(mesh);  // only prm_decode_mesh makes a prm_mesh
}

void prm_free(void* data) { std::free(data); }

}  // extern "C"
