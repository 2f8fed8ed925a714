// prm render MESH -o view.png [--view front|back|left|right|top|bottom|iso] [--size WxH]: a picture of a mesh with
// flat shading and its face colours (software rasteriser, mesh_render.cpp), e.g. the relief layouts of paper Fig. 2.
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "json_report.h"
#include "mesh_render.h"
#include "prm/error.h"
#include "read_any_mesh.h"

namespace prm::cli {

namespace {

std::pair<int, int> parse_size(const std::string& s) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(s.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 1 || h < 1 ||
      w > 16384 || h > 16384)
    throw CLI::ValidationError("--size", "expected WxH with 1..16384 pixels each, got '" + s + "'");
  return {w, h};
}

}  // namespace

void add_render_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("render", "Draw a mesh to a PNG (flat shading, face colours, no GPU)");
  struct Options {
    std::string input, output, view = "iso", size = "800x800";
    int supersample = 3;
    double edges = 0;
    bool json = false;
  };
  auto opt = std::make_shared<Options>();
  cmd->add_option("input", opt->input, "Mesh file, .prm stream or glTF asset (compressed primitives are decoded); PLY face properties red/green/blue give the colours")->required();
  cmd->add_option("-o,--output", opt->output, "Output PNG")->required();
  cmd->add_option("--view", opt->view, "front (from +z), back, left (from -x), right, top (from +y), bottom, iso")
      ->check(CLI::IsMember({"front", "back", "left", "right", "top", "bottom", "iso"}));
  cmd->add_option("--size", opt->size, "Image size WxH in pixels (default 800x800)");
  cmd->add_option("--supersample", opt->supersample, "Samples per pixel along each axis (default 3)")
      ->check(CLI::Range(1, 8));
  cmd->add_option("--edges", opt->edges, "Darken triangle edges by this fraction (0..1; default 0: no edges)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--json", opt->json, kJsonFlagHelp);
  cmd->callback([opt] {
    RenderOptions ro;
    std::tie(ro.width, ro.height) = parse_size(opt->size);
    ro.view = parse_view(opt->view);
    ro.supersample = opt->supersample;
    ro.edge_darkening = opt->edges;
    const Mesh mesh = read_any_mesh(opt->input);
    const auto t0 = std::chrono::steady_clock::now();
    const Image img = render_mesh(mesh, ro);
    write_png(img, opt->output);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (opt->json) {
      JsonReport j("render");
      j.input(opt->input).output(opt->output).mesh_size(mesh.num_vertices(), mesh.num_faces()).seconds(ms / 1000);
      j["view"] = opt->view;
      j["width"] = img.width;
      j["height"] = img.height;
      j.print();
    } else {
      std::printf("%s: %zu faces, %s view, %dx%d -> %s; %.0f ms\n", opt->input.c_str(), mesh.num_faces(),
                  opt->view.c_str(), img.width, img.height, opt->output.c_str(), ms);
    }
  });
}

}  // namespace prm::cli
