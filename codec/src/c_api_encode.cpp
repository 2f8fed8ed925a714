// The encoding half of the C API (prm/prm.h) over prm/codec.h (prm_codec only). Nothing throws out of here.
#include <cstdlib>
#include <cstring>
#include <new>

#include "c_api_shared.h"

using namespace prm::codec;

extern "C" {

void prm_encode_options_default(prm_encode_options* options) {
  if (!options) return;
  const EncodeOptions d;
  options->position_bits = d.position_bits;
  options->seam_context = d.seam_context;
}

prm_status prm_encode(const float* positions, size_t vertices, const uint32_t* indices, size_t triangles,
                      const prm_encode_options* options, uint8_t** data, size_t* size, prm_error* error) {
  if (!data || !size) return set_error(error, PRM_ERROR_INVALID_ARGUMENT, "", 0, "prm_encode: data or size is NULL");
  *data = nullptr;
  *size = 0;
  if ((!positions && vertices) || (!indices && triangles))
    return set_error(error, PRM_ERROR_INVALID_ARGUMENT, "", 0, "prm_encode: positions or indices is NULL");
  try {
    EncodeOptions o;
    if (options) {
      o.position_bits = options->position_bits;
      o.seam_context = options->seam_context;
    }
    const Result<std::vector<uint8_t>> r = encode(positions, vertices, indices, triangles, o);
    if (!r.ok()) return set_error(error, r.status);
    uint8_t* out = static_cast<uint8_t*>(std::malloc(r.value.size()));
    if (!out) return set_error(error, PRM_ERROR_OUT_OF_MEMORY, "", 0, "out of memory");
    std::memcpy(out, r.value.data(), r.value.size());
    *data = out;
    *size = r.value.size();
    return set_ok(error);
  } catch (const std::bad_alloc&) {
    return set_error(error, PRM_ERROR_OUT_OF_MEMORY, "", 0, "out of memory");
  } catch (...) {
    return set_error(error, PRM_ERROR_INTERNAL, "", 0, "unexpected exception");
  }
}

}  // extern "C"
