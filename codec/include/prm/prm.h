/* prm/prm.h: the C API of the PRM mesh codec, for C programs and for bindings (Python, Rust, C#, JS).
 *
 * A C99 header (also valid C++) over the C++ library (prm/codec.h). Every function returns a prm_status
 * (PRM_OK = 0) and, when `error` is not NULL, fills it with the error's name, message, byte offset and spec section
 * (spec/prm-format.md §4.4). No function throws, aborts or keeps global state; the decoding functions are in
 * prm_decoder, the encoding ones in prm_codec only.
 *
 * Decoding, with caller buffers:               Decoding, with library buffers:
 *   prm_stream_info info;                         prm_mesh* mesh = NULL;
 *   prm_inspect(data, size, &info, &err);         prm_decode_mesh(data, size, NULL, &mesh, &err);
 *   float* xyz = malloc(12 * info.vertices);      ... mesh->positions, mesh->indices ...
 *   uint32_t* idx = malloc(12 * info.triangles);  prm_mesh_free(mesh);
 *   prm_decode(data, size, NULL, xyz, 3 * info.vertices, idx, 3 * info.triangles, &err);
 */
#ifndef PRM_PRM_H
#define PRM_PRM_H

#include <stddef.h>
#include <stdint.h>

#include "prm/export.h"
#include "prm/version.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The error codes: prm::codec::Error (prm/codec.h, spec §4.4) with the same values, then the C API's own. */
typedef enum prm_status {
  PRM_OK = 0,
  PRM_ERROR_INVALID_ARGUMENT = 1, /* an option or argument out of range, a NULL pointer, a mesh that is not valid */
  PRM_ERROR_DEGENERATE_TRIANGLE = 2,
  PRM_ERROR_NON_MANIFOLD_EDGE = 3,
  PRM_ERROR_INCONSISTENT_ORIENTATION = 4,
  PRM_ERROR_NON_MANIFOLD_VERTEX = 5,
  PRM_ERROR_TRUNCATED = 6,
  PRM_ERROR_BAD_MAGIC = 7,
  PRM_ERROR_UNSUPPORTED_VERSION = 8,
  PRM_ERROR_BAD_HEADER = 9,
  PRM_ERROR_BAD_SECTION = 10,
  PRM_ERROR_UNSUPPORTED_FEATURE = 11,
  PRM_ERROR_COUNT_EXCEEDS_LIMIT = 12,
  PRM_ERROR_COUNT_EXCEEDS_STREAM = 13,
  PRM_ERROR_BAD_CONNECTIVITY = 14,
  PRM_ERROR_NON_MANIFOLD_RESULT = 15,
  PRM_ERROR_BAD_POSITION = 16,
  PRM_ERROR_TRAILING_BYTES = 17,
  PRM_ERROR_CRC_MISMATCH = 18,
  PRM_ERROR_OUT_OF_MEMORY = 19,
  PRM_ERROR_INTERNAL = 20,
  PRM_ERROR_BUFFER_TOO_SMALL = 64 /* a caller buffer holds fewer elements than the stream decodes to */
} prm_status;

/* Where and why a call failed. Caller-owned; the message is truncated to fit. */
typedef struct prm_error {
  prm_status status;
  const char* name;        /* stable lower_snake name, e.g. "count_exceeds_stream"; static storage */
  uint64_t byte_offset;    /* decoder: offset in the stream where the problem was detected */
  char spec_section[16];   /* the spec section whose rule was broken, e.g. "6.4"; "" if none */
  char message[256];       /* human-readable, names the field or the mesh element */
} prm_error;

/* The library's version: PRM_VERSION_NUMBER of the headers it was built with, and "MAJOR.MINOR.PATCH". */
PRM_API uint32_t prm_version(void);
PRM_API const char* prm_version_string(void);
/* The name of a status ("ok", "truncated", "buffer_too_small", ...; "unknown" for other values). */
PRM_API const char* prm_status_name(int status);

/* §10.1 The quantization frame: a coordinate q decodes to origin[k] + q * step. */
typedef struct prm_frame {
  int bits; /* 8..20 */
  double origin[3];
  double step;
} prm_frame;

/* §3 The container of a stream: the counts a decoder will output, read from the header (after checking the magic,
 * the version, the header, the section framing and the CRC; the sections are not decoded). */
typedef struct prm_stream_info {
  uint32_t version_major, version_minor; /* the bitstream's format version (§3.2) */
  uint32_t flags;
  size_t vertices;  /* decoded vertices: positions hold 3 * vertices values */
  size_t triangles; /* decoded triangles: indices hold 3 * triangles values */
  prm_frame frame;
  uint32_t bbox_min[3], bbox_max[3]; /* quantized */
  size_t total_bytes;
} prm_stream_info;

/* §4.1 Limits on what a decode may allocate; NULL: the defaults (2^26 vertices, 2^27 triangles). */
typedef struct prm_decode_limits {
  uint64_t max_vertices;
  uint64_t max_triangles;
} prm_decode_limits;
PRM_API void prm_decode_limits_default(prm_decode_limits* limits);

PRM_API prm_status prm_inspect(const uint8_t* data, size_t size, prm_stream_info* info, prm_error* error);

/* Decodes into caller buffers: positions[3 * vertices] (float, §10.5) and indices[3 * triangles] (counter-clockwise
 * vertex indices, the order of §6.6). Capacities count elements (floats, uint32s). positions or indices may be NULL
 * (with capacity 0) to skip that output. A buffer smaller than the stream's output: PRM_ERROR_BUFFER_TOO_SMALL and
 * nothing written. */
PRM_API prm_status prm_decode(const uint8_t* data, size_t size, const prm_decode_limits* limits, float* positions,
                              size_t positions_capacity, uint32_t* indices, size_t indices_capacity, prm_error* error);

/* A decoded mesh in library buffers, freed by prm_mesh_free. */
typedef struct prm_mesh {
  size_t vertices, triangles;
  float* positions;    /* 3 per vertex, o + q * s rounded to float (§10.5) */
  uint32_t* quantized; /* 3 per vertex, the exact quantized coordinates */
  uint32_t* indices;   /* 3 per triangle */
  prm_frame frame;
} prm_mesh;
/* On success *mesh is a new mesh; on failure *mesh is NULL. */
PRM_API prm_status prm_decode_mesh(const uint8_t* data, size_t size, const prm_decode_limits* limits, prm_mesh** mesh,
                                   prm_error* error);
PRM_API void prm_mesh_free(prm_mesh* mesh); /* NULL is allowed */

/* Encoding (prm_codec only). */
typedef struct prm_encode_options {
  int position_bits; /* 8..20 (default 12) */
  int seam_context;  /* §6.5.2: -1 the smaller section of with and without (default), 0 never, 1 always */
} prm_encode_options;
PRM_API void prm_encode_options_default(prm_encode_options* options);

/* Encodes triangles indices[3 * triangles] over positions[3 * vertices] (an oriented 2-manifold, possibly with
 * boundaries: prm/codec.h), quantized in the reference frame of §10.1. options may be NULL (the defaults). On success
 * *data is a new buffer of *size bytes, freed by prm_free; on failure *data is NULL and *size 0. */
PRM_API prm_status prm_encode(const float* positions, size_t vertices, const uint32_t* indices, size_t triangles,
                              const prm_encode_options* options, uint8_t** data, size_t* size, prm_error* error);
/* Frees a buffer the library allocated (prm_encode's stream); NULL is allowed. In prm_decoder too. */
PRM_API void prm_free(void* data);

#ifdef __cplusplus
}
#endif

#endif /* PRM_PRM_H */
