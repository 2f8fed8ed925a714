// The single translation unit that compiles stb_image_write (Debian's libstb-dev), for `prm render`.
#include "mesh_render.h"
#include "prm/error.h"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#endif
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace prm::cli {

void write_png(const Image& image, const std::string& path) {
  stbi_write_png_compression_level = 9;
  if (!stbi_write_png(path.c_str(), image.width, image.height, 3, image.rgb.data(), image.width * 3))
    throw IoError("cannot write PNG '" + path + "'");
}

}  // namespace prm::cli
