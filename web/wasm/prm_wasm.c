/* web/wasm/prm_wasm.c: what the JavaScript module (web/src/prm_decoder.js) calls in the WebAssembly decoder.
 *
 * A thin layer over the C API's decoding half (codec/include/prm/prm.h, the prm_decoder target): one decode call,
 * then accessors so that JavaScript never depends on the C structs' layout. Nothing else of the codec goes in. */
#include <stdlib.h>

#include "prm/prm.h"

#define PRM_WASM_EXPORT __attribute__((used, visibility("default")))

/* Decodes data[0, size) (spec/prm-format.md §2) with the caller limits max_vertices, max_triangles (0: the
 * defaults of §4.1). Returns the mesh, or NULL with *error filled (its name, byte offset, section, message). */
PRM_WASM_EXPORT prm_mesh* prm_wasm_decode(const uint8_t* data, size_t size, double max_vertices, double max_triangles,
                                          prm_error* error) {
  prm_decode_limits limits;
  prm_decode_limits_default(&limits);
  if (max_vertices > 0) limits.max_vertices = (uint64_t)max_vertices;
  if (max_triangles > 0) limits.max_triangles = (uint64_t)max_triangles;
  prm_mesh* mesh = NULL;
  if (prm_decode_mesh(data, size, &limits, &mesh, error) != PRM_OK) return NULL;
  return mesh;
}

PRM_WASM_EXPORT size_t prm_wasm_mesh_vertices(const prm_mesh* m) { return m->vertices; }
PRM_WASM_EXPORT size_t prm_wasm_mesh_triangles(const prm_mesh* m) { return m->triangles; }
PRM_WASM_EXPORT const float* prm_wasm_mesh_positions(const prm_mesh* m) { return m->positions; }
PRM_WASM_EXPORT const uint32_t* prm_wasm_mesh_quantized(const prm_mesh* m) { return m->quantized; }
PRM_WASM_EXPORT const uint32_t* prm_wasm_mesh_indices(const prm_mesh* m) { return m->indices; }
/* §10.1 the quantization frame */
PRM_WASM_EXPORT int prm_wasm_mesh_bits(const prm_mesh* m) { return m->frame.bits; }
PRM_WASM_EXPORT double prm_wasm_mesh_origin(const prm_mesh* m, int k) { return m->frame.origin[k]; }
PRM_WASM_EXPORT double prm_wasm_mesh_step(const prm_mesh* m) { return m->frame.step; }
PRM_WASM_EXPORT void prm_wasm_mesh_free(prm_mesh* m) { prm_mesh_free(m); }

/* The error record (§4.4), allocated by the caller's module instance. */
PRM_WASM_EXPORT prm_error* prm_wasm_error_new(void) { return (prm_error*)calloc(1, sizeof(prm_error)); }
PRM_WASM_EXPORT void prm_wasm_error_free(prm_error* e) { free(e); }
PRM_WASM_EXPORT int prm_wasm_error_status(const prm_error* e) { return (int)e->status; }
PRM_WASM_EXPORT const char* prm_wasm_error_name(const prm_error* e) { return e->name ? e->name : ""; }
PRM_WASM_EXPORT double prm_wasm_error_offset(const prm_error* e) { return (double)e->byte_offset; }
PRM_WASM_EXPORT const char* prm_wasm_error_section(const prm_error* e) { return e->spec_section; }
PRM_WASM_EXPORT const char* prm_wasm_error_message(const prm_error* e) { return e->message; }
