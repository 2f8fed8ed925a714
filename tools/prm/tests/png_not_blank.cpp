// prm_png_not_blank IMAGE.png: exit 0 when the PNG decodes (stb_image, libstb-dev) and holds at least two colours
// covering at least 1% of its pixels each, i.e. `prm render` drew something on the background; 1 otherwise.
#include <cstdio>
#include <map>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#endif
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: prm_png_not_blank IMAGE.png\n");
    return 2;
  }
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load(argv[1], &w, &h, &n, 3);
  if (!px) {
    std::fprintf(stderr, "%s: not a PNG stb_image reads: %s\n", argv[1], stbi_failure_reason());
    return 1;
  }
  std::map<unsigned, size_t> count;
  for (size_t i = 0; i < static_cast<size_t>(w) * h; ++i)
    ++count[(px[3 * i] << 16) | (px[3 * i + 1] << 8) | px[3 * i + 2]];
  stbi_image_free(px);
  size_t big = 0;
  for (const auto& [colour, c] : count) big += c * 100 >= static_cast<size_t>(w) * h;
  std::printf("%s: %dx%d, %zu colours, %zu of them on 1%% of the pixels or more\n", argv[1], w, h, count.size(), big);
  return big >= 2 ? 0 : 1;
}
