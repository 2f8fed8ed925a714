#include "prm/pipeline/codec_bridge.h"

#include <algorithm>
#include <array>
#include <string>
#include <unordered_map>

#include "prm/error.h"

namespace prm::pipeline {

namespace {

std::vector<uint32_t> flat_triangles(const Mesh& mesh) {
  std::vector<uint32_t> tris;
  tris.reserve(mesh.triangles.size() * 3);
  for (const Tri& t : mesh.triangles) tris.insert(tris.end(), t.begin(), t.end());
  return tris;
}

bool has_prm_frame(const Mesh& mesh) {
  for (const std::string& c : mesh.comments)
    if (c.rfind("prm-frame", 0) == 0) return true;
  return false;
}

}  // namespace

codec::Result<std::vector<uint8_t>> encode_prm_mesh(const remesh::PrmMesh& prm, codec::EncodeReport* report,
                                                    const codec::PrmOptions& given) {
  const Mesh& m = prm.mesh;
  std::vector<uint32_t> q(m.positions.size() * 3);
  for (size_t v = 0; v < m.positions.size(); ++v)
    for (int a = 0; a < 3; ++a)
      q[3 * v + static_cast<size_t>(a)] = prm.frame.quantize(m.positions[v][a], a);
  const std::vector<uint32_t> tris = flat_triangles(m);
  codec::PrmOptions options = given;
  options.grid = prm.lattice.A;
  // §8.4.2 The reliefs' other grid sizes (format 1.5; with PrmOptions::patch_grids off the stream has one grid, the
  // other reliefs' triangles coded as irregular).
  options.extra_grids.clear();
  for (size_t r = 0; r < prm.relief_axis.size(); ++r) {
    const int64_t g = prm.grid_of(r);
    if (g != options.grid && std::find(options.extra_grids.begin(), options.extra_grids.end(), g) ==
                                 options.extra_grids.end())
      options.extra_grids.push_back(g);
  }
  std::vector<double> unrounded;
  if (options.height_tolerance >= 0.5 && options.height_lambda > 0 && !options.unrounded) {
    unrounded.resize(q.size());
    for (size_t v = 0; v < m.positions.size(); ++v)
      for (int a = 0; a < 3; ++a)
      {
        // As exact as the rounding was (a coordinate the frame clamped stays on its step).
        const double x = prm.frame.to_quant(m.positions[v][a], a), r = q[3 * v + static_cast<size_t>(a)];
        unrounded[3 * v + static_cast<size_t>(a)] = std::clamp(x, r - 0.5, r + 0.5);
      }
    options.unrounded = unrounded.data();
  }
  return codec::encode_prm(q.data(), m.positions.size(), tris.data(), m.triangles.size(), prm.frame,
                           options, report);
}

codec::Result<std::vector<uint8_t>> encode_any_mesh(const Mesh& mesh, int bits, codec::EncodeReport* report,
                                                    bool* was_prm, int max_minor) {
  if (was_prm) *was_prm = false;
  if (has_prm_frame(mesh)) {
    const int seam = max_minor >= codec::kFormatMinorSeam ? -1 : 0;  // -1: the encoder's choice
    const remesh::PrmMesh prm = remesh::load_prm_labels(mesh);  // throws InputError on inconsistent labels
    if (was_prm) *was_prm = true;
    codec::PrmOptions po;
    po.seam_context = seam;
    po.patch_contexts = max_minor >= codec::kFormatMinorPatchContexts;
    po.patch_grids = max_minor >= codec::kFormatMinorPatchGrids;
    return encode_prm_mesh(prm, report, po);
  }
  return encode_general_mesh(mesh, bits, report, max_minor);
}

codec::Result<std::vector<uint8_t>> encode_general_mesh(const Mesh& mesh, int bits, codec::EncodeReport* report,
                                                        int max_minor) {
  const std::vector<uint32_t> tris = flat_triangles(mesh);
  codec::EncodeOptions eo;
  eo.position_bits = bits;
  eo.seam_context = max_minor >= codec::kFormatMinorSeam ? -1 : 0;  // -1: the encoder's choice
  return codec::encode(mesh.positions.empty() ? nullptr : mesh.positions[0].data(), mesh.positions.size(),
                       tris.data(), mesh.triangles.size(), eo, report);
}

Mesh to_mesh(const codec::DecodedMesh& decoded) {
  Mesh m;
  const size_t n = decoded.num_vertices();
  m.positions.resize(n);
  for (size_t v = 0; v < n; ++v)
    for (int a = 0; a < 3; ++a)
      m.positions[v][a] = decoded.frame.to_real(decoded.quantized[3 * v + static_cast<size_t>(a)], a);
  m.triangles.resize(decoded.num_triangles());
  for (size_t t = 0; t < m.triangles.size(); ++t)
    m.triangles[t] = {decoded.triangles[3 * t], decoded.triangles[3 * t + 1], decoded.triangles[3 * t + 2]};
  return m;
}

size_t count_zero_area_triangles(const codec::DecodedMesh& decoded) {
  size_t zero = 0;
  auto at = [&](uint32_t v, int a) { return static_cast<int64_t>(decoded.quantized[3 * size_t{v} + static_cast<size_t>(a)]); };
  for (size_t t = 0; t < decoded.num_triangles(); ++t) {
    const uint32_t* c = &decoded.triangles[3 * t];
    int64_t d1[3], d2[3];
    for (int a = 0; a < 3; ++a) {
      d1[a] = at(c[1], a) - at(c[0], a);
      d2[a] = at(c[2], a) - at(c[0], a);
    }
    // Quantized coordinates have at most 20 bits (spec §3.3): the products fit in 64 bits.
    zero += d1[1] * d2[2] == d1[2] * d2[1] && d1[2] * d2[0] == d1[0] * d2[2] && d1[0] * d2[1] == d1[1] * d2[0];
  }
  return zero;
}

size_t count_coincident_vertices(const codec::DecodedMesh& decoded) {
  struct PointHash {
    size_t operator()(const std::array<uint32_t, 3>& p) const {
      return (size_t{p[0]} * 73856093u) ^ (size_t{p[1]} * 19349663u) ^ (size_t{p[2]} * 83492791u);
    }
  };
  std::unordered_map<std::array<uint32_t, 3>, uint32_t, PointHash> at;
  const size_t nv = decoded.num_vertices();
  at.reserve(nv);
  for (size_t v = 0; v < nv; ++v)
    ++at[{decoded.quantized[3 * v], decoded.quantized[3 * v + 1], decoded.quantized[3 * v + 2]}];
  size_t coincident = 0;
  for (const auto& [p, n] : at) coincident += n > 1 ? n : 0;
  return coincident;
}

}  // namespace prm::pipeline
