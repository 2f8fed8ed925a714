/* Decodes a .prm stream into caller arrays with the C API (prm/prm.h): counts first, then the arrays. */
#include <stdio.h>
#include <stdlib.h>

#include "prm/prm.h"

int main(int argc, char** argv) {
  static uint8_t data[1 << 24];
  FILE* f = argc == 2 ? fopen(argv[1], "rb") : NULL;
  size_t size = f ? fread(data, 1, sizeof data, f) : 0;
  prm_stream_info info;
  prm_error err;
  float* xyz;
  uint32_t* idx;
  if (!f) return fprintf(stderr, "usage: decode_arrays_c FILE.prm\n"), 1;
  fclose(f);
  if (prm_inspect(data, size, &info, &err) != PRM_OK) return fprintf(stderr, "%s: %s\n", err.name, err.message), 2;
  xyz = (float*)malloc(3 * sizeof(float) * info.vertices + 1);
  idx = (uint32_t*)malloc(3 * sizeof(uint32_t) * info.triangles + 1);
  if (prm_decode(data, size, NULL, xyz, 3 * info.vertices, idx, 3 * info.triangles, &err) != PRM_OK)
    return fprintf(stderr, "%s: %s (byte %lu, spec section %s)\n", err.name, err.message,
                   (unsigned long)err.byte_offset, err.spec_section), 2;
  printf("prm %s: %lu vertices, %lu triangles, first vertex %g %g %g\n", prm_version_string(),
         (unsigned long)info.vertices, (unsigned long)info.triangles, xyz[0], xyz[1], xyz[2]);
  free(xyz);
  free(idx);
  return 0;
}
