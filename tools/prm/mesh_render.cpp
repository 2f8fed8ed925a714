#include "mesh_render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "prm/vec3.h"

namespace prm::cli {

View parse_view(const std::string& name) {
  static const std::pair<const char*, View> names[] = {{"front", View::Front}, {"back", View::Back},
                                                       {"left", View::Left},   {"right", View::Right},
                                                       {"top", View::Top},     {"bottom", View::Bottom},
                                                       {"iso", View::Iso}};
  for (const auto& [n, v] : names)
    if (name == n) return v;
  throw std::invalid_argument("unknown view '" + name + "' (front, back, left, right, top, bottom, iso)");
}

namespace {

// Screen basis: right r, up u, and c towards the camera (r x u = c), so depth p.c grows towards the viewer.
struct Basis {
  Vec3 r, u, c;
};

Basis view_basis(View view) {
  switch (view) {
    case View::Front: return {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case View::Back: return {{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
    case View::Right: return {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}};
    case View::Left: return {{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}};
    case View::Top: return {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
    case View::Bottom: return {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}};
    case View::Iso: break;
  }
  const Vec3 c = normalized(Vec3{1, 1, 1});
  const Vec3 u = normalized(Vec3{0, 1, 0} - c * c[1]);
  return {cross(u, c), u, c};
}

}  // namespace

Image render_mesh(const Mesh& mesh, const RenderOptions& options) {
  if (options.width < 1 || options.height < 1 || options.supersample < 1)
    throw std::invalid_argument("render: image size and supersampling must be positive");
  const int ss = options.supersample;
  const int W = options.width * ss, H = options.height * ss;
  const Basis b = view_basis(options.view);

  // Fit the projected bounding box into the image with a small margin.
  std::vector<std::array<double, 3>> sp(mesh.positions.size());  // screen x, y (y down), depth
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3& p = mesh.positions[i];
    sp[i] = {dot(p, b.r), dot(p, b.u), dot(p, b.c)};
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], sp[i][static_cast<size_t>(k)]);
      hi[k] = std::max(hi[k], sp[i][static_cast<size_t>(k)]);
    }
  }
  const double margin = 0.04;
  const double ext_x = std::max(hi[0] - lo[0], 1e-300), ext_y = std::max(hi[1] - lo[1], 1e-300);
  const double scale = std::min(W * (1 - 2 * margin) / ext_x, H * (1 - 2 * margin) / ext_y);
  const double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
  for (auto& s : sp) {
    s[0] = 0.5 * W + (s[0] - cx) * scale;
    s[1] = 0.5 * H - (s[1] - cy) * scale;
  }

  const Property* red = mesh.find_face_property("red");
  const Property* green = mesh.find_face_property("green");
  const Property* blue = mesh.find_face_property("blue");
  const bool coloured = red && green && blue;
  // A head light a little above and to the right of the camera.
  const Vec3 light = normalized(b.c + b.u * 0.5 + b.r * 0.3);

  std::vector<float> depth(static_cast<size_t>(W) * static_cast<size_t>(H), -std::numeric_limits<float>::infinity());
  std::vector<std::array<uint8_t, 3>> colour(depth.size(), options.background);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& t = mesh.triangles[f];
    const Vec3 n = normalized(triangle_normal_area2(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]));
    // Faces seen from behind (open meshes, flipped triangles) are drawn darker.
    const double facing = dot(n, b.c);
    const double diffuse = std::abs(dot(n, light));
    const double shade = (0.3 + 0.7 * diffuse) * (facing < 0 ? 0.6 : 1.0);
    std::array<uint8_t, 3> base = options.default_colour;
    if (coloured) base = {static_cast<uint8_t>(red->values[f]), static_cast<uint8_t>(green->values[f]),
                          static_cast<uint8_t>(blue->values[f])};
    std::array<uint8_t, 3> lit{};
    for (size_t k = 0; k < 3; ++k) lit[k] = static_cast<uint8_t>(std::clamp(base[k] * shade, 0.0, 255.0));
    std::array<uint8_t, 3> dark{};
    for (size_t k = 0; k < 3; ++k) dark[k] = static_cast<uint8_t>(lit[k] * (1 - options.edge_darkening));

    const auto& A = sp[t[0]];
    const auto& B = sp[t[1]];
    const auto& C = sp[t[2]];
    const double area = (B[0] - A[0]) * (C[1] - A[1]) - (C[0] - A[0]) * (B[1] - A[1]);
    if (area == 0 || !std::isfinite(area)) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({A[0], B[0], C[0]}))));
    const int x1 = std::min(W - 1, static_cast<int>(std::ceil(std::max({A[0], B[0], C[0]}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({A[1], B[1], C[1]}))));
    const int y1 = std::min(H - 1, static_cast<int>(std::ceil(std::max({A[1], B[1], C[1]}))));
    const double inv = 1.0 / area;
    // Edge lengths in samples, to turn edge functions into distances for the optional edge lines.
    const double la = std::hypot(C[0] - B[0], C[1] - B[1]), lb = std::hypot(A[0] - C[0], A[1] - C[1]),
                 lc = std::hypot(B[0] - A[0], B[1] - A[1]);
    const double line = 0.6 * ss;
    for (int y = y0; y <= y1; ++y) {
      const double py = y + 0.5;
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5;
        // Barycentric weights from edge functions; the sign of `area` folds both orientations into one test.
        const double wa = ((B[0] - px) * (C[1] - py) - (C[0] - px) * (B[1] - py)) * inv;
        const double wb = ((C[0] - px) * (A[1] - py) - (A[0] - px) * (C[1] - py)) * inv;
        const double wc = 1 - wa - wb;
        if (wa < 0 || wb < 0 || wc < 0) continue;
        const float z = static_cast<float>(wa * A[2] + wb * B[2] + wc * C[2]);
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(W) + static_cast<size_t>(x);
        if (z <= depth[i]) continue;
        depth[i] = z;
        bool edge = false;
        if (options.edge_darkening > 0) {
          const double a2 = std::abs(area);
          edge = wa * a2 / la < line || wb * a2 / lb < line || wc * a2 / lc < line;
        }
        colour[i] = edge ? dark : lit;
      }
    }
  }

  // Box filter down to the output size.
  Image img;
  img.width = options.width;
  img.height = options.height;
  img.rgb.resize(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 3);
  const int n = ss * ss;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      int sum[3] = {0, 0, 0};
      for (int dy = 0; dy < ss; ++dy)
        for (int dx = 0; dx < ss; ++dx) {
          const auto& c = colour[static_cast<size_t>(y * ss + dy) * static_cast<size_t>(W) + static_cast<size_t>(x * ss + dx)];
          for (size_t k = 0; k < 3; ++k) sum[k] += c[k];
        }
      for (size_t k = 0; k < 3; ++k)
        img.rgb[(static_cast<size_t>(y) * static_cast<size_t>(img.width) + static_cast<size_t>(x)) * 3 + k] =
            static_cast<uint8_t>((sum[k] + n / 2) / n);
    }
  return img;
}

}  // namespace prm::cli
