/* The C API (prm/prm.h) from C: every conformance vector decodes to its recorded hash through both decoding calls,
 * every invalid one fails with its recorded error, decoded meshes encode again and round trip, and the error paths
 * (truncated stream, buffer too small, NULL arguments, bad options) return the right status.
 * Usage: prm_c_api_test CONFORMANCE_DIR */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "prm/prm.h"

static int failures = 0;
#define CHECK(cond, ...)                                          \
  do {                                                            \
    if (!(cond)) {                                                \
      ++failures;                                                 \
      fprintf(stderr, "%s:%d: CHECK(%s) failed: ", __FILE__, __LINE__, #cond); \
      fprintf(stderr, __VA_ARGS__);                               \
      fprintf(stderr, "\n");                                      \
    }                                                             \
  } while (0)

static unsigned char* read_file(const char* path, size_t* size) {
  FILE* f = fopen(path, "rb");
  unsigned char* data;
  long n;
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  n = ftell(f);
  fseek(f, 0, SEEK_SET);
  data = (unsigned char*)malloc((size_t)n + 1);
  if (data && fread(data, 1, (size_t)n, f) != (size_t)n) {
    free(data);
    data = NULL;
  }
  fclose(f);
  if (data) data[n] = 0;
  *size = (size_t)n;
  return data;
}

/* The string value of "key": "value" in a flat JSON object, or "". */
static void json_string(const char* json, const char* key, char* out, size_t cap) {
  char pattern[64];
  const char* p;
  size_t n = 0;
  sprintf(pattern, "\"%s\": \"", key);
  out[0] = 0;
  p = strstr(json, pattern);
  if (!p) return;
  p += strlen(pattern);
  while (p[n] && p[n] != '"' && n + 1 < cap) ++n;
  memcpy(out, p, n);
  out[n] = 0;
}
static unsigned long json_number(const char* json, const char* key) {
  char pattern[64];
  const char* p;
  sprintf(pattern, "\"%s\": ", key);
  p = strstr(json, pattern);
  return p ? strtoul(p + strlen(pattern), NULL, 10) : 0;
}

/* The conformance vectors' hash: FNV-1a 64 over the little-endian bytes of the triangles, then the positions. */
static unsigned long long fnv1a64(const uint32_t* words, size_t n, unsigned long long h) {
  size_t i;
  int b;
  for (i = 0; i < n; ++i)
    for (b = 0; b < 4; ++b) {
      h ^= (words[i] >> (8 * b)) & 0xFF;
      h *= 1099511628211ull;
    }
  return h;
}

/* Encodes mesh m again (float positions, 12 bits) and checks the decoded result: same counts, every vertex within
 * a quantization step of an input vertex. */
static void round_trip(const char* name, const prm_mesh* m) {
  uint8_t* stream = NULL;
  size_t size = 0, v, w;
  prm_mesh* back = NULL;
  prm_error err;
  prm_encode_options options;
  prm_encode_options_default(&options);
  CHECK(prm_encode(m->positions, m->vertices, m->indices, m->triangles, &options, &stream, &size, &err) == PRM_OK,
        "%s: encode: %s: %s", name, err.name, err.message);
  if (!stream) return;
  CHECK(prm_decode_mesh(stream, size, NULL, &back, &err) == PRM_OK, "%s: decode again: %s", name, err.message);
  if (back) {
    CHECK(back->vertices == m->vertices && back->triangles == m->triangles, "%s: counts %lu %lu", name,
          (unsigned long)back->vertices, (unsigned long)back->triangles);
    for (v = 0; v < back->vertices; ++v) {
      double best = 1e300;
      for (w = 0; w < m->vertices; ++w) {
        const double dx = back->positions[3 * v] - m->positions[3 * w];
        const double dy = back->positions[3 * v + 1] - m->positions[3 * w + 1];
        const double dz = back->positions[3 * v + 2] - m->positions[3 * w + 2];
        const double d = dx * dx + dy * dy + dz * dz; /* squared */
        if (d < best) best = d;
      }
      if (best > back->frame.step * back->frame.step) {
        CHECK(0, "%s: decoded vertex %lu is sqrt(%g) from the input (step %g)", name, (unsigned long)v, best,
              back->frame.step);
        break;
      }
    }
  }
  prm_mesh_free(back);
  prm_free(stream);
}

static const char* const kValid[] = {"001-tetrahedron", "002-genus1-plate", "003-holes", "004-components",
                                     "005-icosphere", "006-general-1.3-seam-context", "010-prm-1.1-pillow",
                                     "011-prm-1.2-difference-depth3", "012-prm-1.2-difference-depth0",
                                     "013-prm-1.2-prediction", "014-prm-1.2-prediction-offlattice",
                                     "015-prm-1.3-seam-context", "016-prm-1.4-patch-contexts",
                                     "017-prm-1.4-patch-contexts-depth3"};
static const char* const kInvalid[] = {"100-truncated", "101-crc", "102-magic", "103-major-version",
                                       "104-reserved-flag", "105-short"};

static void check_valid(const char* dir, const char* name) {
  char path[1024], want[64], got[64];
  size_t size = 0, json_size = 0, i;
  unsigned long long h;
  unsigned char* data;
  char* json;
  prm_stream_info info;
  prm_mesh* m = NULL;
  prm_error err;
  float* xyz;
  uint32_t* idx;
  sprintf(path, "%s/vectors/%s/stream.prm", dir, name);
  data = read_file(path, &size);
  sprintf(path, "%s/vectors/%s/vector.json", dir, name);
  json = (char*)read_file(path, &json_size);
  CHECK(data && json, "%s: cannot read the vector", name);
  if (!data || !json) return;
  /* Counts first, from the header. */
  CHECK(prm_inspect(data, size, &info, &err) == PRM_OK, "%s: inspect: %s", name, err.message);
  CHECK(info.vertices == json_number(json, "vertices") && info.triangles == json_number(json, "triangles"),
        "%s: inspect counts", name);
  CHECK(info.total_bytes == size, "%s: total bytes", name);
  /* Library buffers: the exact decoded mesh. */
  CHECK(prm_decode_mesh(data, size, NULL, &m, &err) == PRM_OK, "%s: decode: %s", name, err.message);
  if (m) {
    CHECK(m->vertices == info.vertices && m->triangles == info.triangles, "%s: decoded counts", name);
    json_string(json, "fnv1a64", want, sizeof want);
    h = fnv1a64(m->indices, 3 * m->triangles, 1469598103934665603ull); /* the vectors' basis */
    sprintf(got, "0x%016llx", fnv1a64(m->quantized, 3 * m->vertices, h));
    CHECK(strcmp(got, want) == 0, "%s: hash %s, vector.json %s", name, got, want);
    /* Caller buffers: the same arrays. */
    xyz = (float*)malloc(sizeof(float) * 3 * info.vertices + 1);
    idx = (uint32_t*)malloc(sizeof(uint32_t) * 3 * info.triangles + 1);
    CHECK(prm_decode(data, size, NULL, xyz, 3 * info.vertices, idx, 3 * info.triangles, &err) == PRM_OK,
          "%s: decode into buffers: %s", name, err.message);
    CHECK(memcmp(xyz, m->positions, sizeof(float) * 3 * m->vertices) == 0, "%s: positions differ", name);
    CHECK(memcmp(idx, m->indices, sizeof(uint32_t) * 3 * m->triangles) == 0, "%s: indices differ", name);
    for (i = 0; i < 3 * m->vertices; ++i)
      if (xyz[i] != (float)(m->frame.origin[i % 3] + m->quantized[i] * m->frame.step)) {
        CHECK(0, "%s: position %lu is not o + q s (spec 10.5)", name, (unsigned long)i);
        break;
      }
    /* A buffer one element short: refused, nothing decoded. */
    if (info.vertices > 0) {
      CHECK(prm_decode(data, size, NULL, xyz, 3 * info.vertices - 1, idx, 3 * info.triangles, &err) ==
                PRM_ERROR_BUFFER_TOO_SMALL && strcmp(err.name, "buffer_too_small") == 0,
            "%s: short position buffer", name);
      CHECK(prm_decode(data, size, NULL, NULL, 0, idx, 3 * info.triangles - 1, &err) == PRM_ERROR_BUFFER_TOO_SMALL,
            "%s: short index buffer", name);
    }
    /* The caller's limits (spec 4.1). */
    if (info.vertices > 1) {
      prm_decode_limits limits;
      prm_mesh* none = m;
      prm_decode_limits_default(&limits);
      limits.max_vertices = info.vertices - 1;
      CHECK(prm_decode_mesh(data, size, &limits, &none, &err) == PRM_ERROR_COUNT_EXCEEDS_LIMIT && none == NULL &&
                strcmp(err.spec_section, "4.1") == 0,
            "%s: limits: %s", name, err.name);
    }
    if (m->vertices >= 3) round_trip(name, m);
    free(xyz);
    free(idx);
  }
  /* Truncated: every proper prefix fails (with a status and a message), never crashes. */
  for (i = 0; i < size; i += 1 + size / 64) {
    prm_mesh* t = NULL;
    const prm_status s = prm_decode_mesh(data, i, NULL, &t, &err);
    CHECK(s != PRM_OK && t == NULL && err.message[0] != 0, "%s: the first %lu bytes decode", name, (unsigned long)i);
  }
  prm_mesh_free(m);
  free(data);
  free(json);
}

static void check_invalid(const char* dir, const char* name) {
  char path[1024], want_error[64], want_section[16];
  size_t size = 0, json_size = 0;
  unsigned char* data;
  char* json;
  prm_mesh* m = NULL;
  prm_error err;
  sprintf(path, "%s/invalid/%s/stream.prm", dir, name);
  data = read_file(path, &size);
  sprintf(path, "%s/invalid/%s/vector.json", dir, name);
  json = (char*)read_file(path, &json_size);
  CHECK(data && json, "%s: cannot read the vector", name);
  if (!data || !json) return;
  json_string(json, "error", want_error, sizeof want_error);
  json_string(json, "spec_section", want_section, sizeof want_section);
  CHECK(prm_decode_mesh(data, size, NULL, &m, &err) != PRM_OK && m == NULL, "%s: decodes", name);
  CHECK(strcmp(err.name, want_error) == 0, "%s: error %s, vector.json %s", name, err.name, want_error);
  CHECK(strcmp(prm_status_name(err.status), want_error) == 0, "%s: status name", name);
  /* The section a decoder cites is only a SHOULD (spec 4.4): one is named. */
  CHECK(err.spec_section[0] != 0 && err.message[0] != 0, "%s: no section or message (vector.json: %s)", name,
        want_section);
  free(data);
  free(json);
}

static void check_arguments(void) {
  const float tri[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint32_t one[] = {0, 1, 2}, bad[] = {0, 1, 7};
  const uint8_t bytes[8] = {0};
  uint8_t* stream = (uint8_t*)&failures; /* must be reset to NULL on failure */
  size_t size = 99;
  prm_error err;
  prm_stream_info info;
  prm_mesh* m = NULL;
  prm_encode_options options;
  CHECK(prm_version() == PRM_VERSION_NUMBER, "version %u", (unsigned)prm_version());
  CHECK(strcmp(prm_version_string(), PRM_VERSION_STRING) == 0, "version string %s", prm_version_string());
  CHECK(strcmp(prm_status_name(PRM_OK), "ok") == 0 && strcmp(prm_status_name(-1), "unknown") == 0 &&
            strcmp(prm_status_name(63), "unknown") == 0 &&
            strcmp(prm_status_name(PRM_ERROR_CRC_MISMATCH), "crc_mismatch") == 0,
        "status names");
  /* NULL arguments. */
  CHECK(prm_inspect(NULL, 0, &info, &err) == PRM_ERROR_INVALID_ARGUMENT, "inspect NULL data");
  CHECK(prm_inspect(bytes, sizeof bytes, NULL, &err) == PRM_ERROR_INVALID_ARGUMENT, "inspect NULL info");
  CHECK(prm_decode(NULL, 0, NULL, NULL, 0, NULL, 0, &err) == PRM_ERROR_INVALID_ARGUMENT, "decode NULL data");
  CHECK(prm_decode(bytes, sizeof bytes, NULL, NULL, 9, NULL, 0, &err) == PRM_ERROR_INVALID_ARGUMENT,
        "decode NULL buffer with a capacity");
  CHECK(prm_decode_mesh(bytes, sizeof bytes, NULL, NULL, &err) == PRM_ERROR_INVALID_ARGUMENT, "decode_mesh NULL");
  CHECK(prm_decode_mesh(bytes, sizeof bytes, NULL, &m, NULL) != PRM_OK && m == NULL, "NULL error is allowed");
  CHECK(prm_encode(tri, 3, one, 1, NULL, NULL, &size, &err) == PRM_ERROR_INVALID_ARGUMENT, "encode NULL out");
  CHECK(prm_encode(NULL, 3, one, 1, NULL, &stream, &size, &err) == PRM_ERROR_INVALID_ARGUMENT && stream == NULL &&
            size == 0,
        "encode NULL positions");
  /* Options and meshes the encoder refuses, with the spec section. */
  prm_encode_options_default(&options);
  CHECK(options.position_bits == 12 && options.seam_context == -1, "default options");
  options.position_bits = 21;
  CHECK(prm_encode(tri, 3, one, 1, &options, &stream, &size, &err) == PRM_ERROR_INVALID_ARGUMENT &&
            strcmp(err.spec_section, "10.1") == 0 && stream == NULL,
        "bits 21: %s (%s)", err.message, err.spec_section);
  CHECK(prm_encode(tri, 3, bad, 1, NULL, &stream, &size, &err) != PRM_OK && stream == NULL && err.message[0],
        "index out of range: %s", err.name);
  /* A one-triangle stream decodes to that triangle. */
  CHECK(prm_encode(tri, 3, one, 1, NULL, &stream, &size, &err) == PRM_OK, "one triangle: %s", err.message);
  CHECK(prm_decode_mesh(stream, size, NULL, &m, &err) == PRM_OK && m && m->vertices == 3 && m->triangles == 1,
        "one triangle back");
  /* One byte changed in the middle: an error naming where (or, rarely, another valid mesh: never a crash). */
  if (stream && size > 20) {
    prm_mesh* t = NULL;
    stream[size / 2] ^= 0x40;
    CHECK(prm_decode_mesh(stream, size, NULL, &t, &err) == PRM_ERROR_CRC_MISMATCH && t == NULL, "flipped bit: %s",
          err.name);
  }
  prm_mesh_free(m);
  prm_free(stream);
  prm_free(NULL);
  prm_mesh_free(NULL);
}

int main(int argc, char** argv) {
  size_t i;
  if (argc != 2) {
    fprintf(stderr, "usage: prm_c_api_test CONFORMANCE_DIR\n");
    return 1;
  }
  for (i = 0; i < sizeof kValid / sizeof kValid[0]; ++i) check_valid(argv[1], kValid[i]);
  for (i = 0; i < sizeof kInvalid / sizeof kInvalid[0]; ++i) check_invalid(argv[1], kInvalid[i]);
  check_arguments();
  if (failures) {
    fprintf(stderr, "prm_c_api_test: %d failures\n", failures);
    return 1;
  }
  printf("prm_c_api_test: %lu valid and %lu invalid vectors, round trips and error paths: ok\n",
         (unsigned long)(sizeof kValid / sizeof kValid[0]), (unsigned long)(sizeof kInvalid / sizeof kInvalid[0]));
  return 0;
}
