// A small software rasteriser for `prm render`: orthographic views of a mesh, z-buffer, flat shading with the
// faces' own colours (PLY face properties red/green/blue, as `prm reliefs` writes them). No GPU, no display.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "prm/mesh.h"

namespace prm::cli {

// Standard views. y is up in every view except top/bottom; front looks along -z (the camera sits on +z).
enum class View { Front, Back, Left, Right, Top, Bottom, Iso };

// Parses "front", "back", "left", "right", "top", "bottom", "iso"; throws std::invalid_argument otherwise.
View parse_view(const std::string& name);

struct RenderOptions {
  View view = View::Iso;
  int width = 800, height = 800;
  int supersample = 3;                               // samples per pixel along each axis (anti-aliasing)
  std::array<uint8_t, 3> background{255, 255, 255};
  std::array<uint8_t, 3> default_colour{200, 200, 200};  // faces without colour properties
  double edge_darkening = 0.0;  // > 0: draw triangle edges darker (0..1), for close-ups of the triangulation
};

struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // row-major, top row first, 3 bytes per pixel
};

Image render_mesh(const Mesh& mesh, const RenderOptions& options);

// Writes an 8-bit RGB PNG; throws prm::IoError when the file cannot be written.
void write_png(const Image& image, const std::string& path);

}  // namespace prm::cli
