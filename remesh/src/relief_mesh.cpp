#include "relief_mesh.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "prm/error.h"

namespace prm::remesh {

std::vector<std::array<int32_t, 3>> face_adjacency(const Mesh& mesh) {
  struct HalfEdge {
    uint32_t lo, hi;
    int32_t face;
    int8_t corner;
  };
  std::vector<HalfEdge> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = mesh.triangles[f][static_cast<size_t>(k)], b = mesh.triangles[f][static_cast<size_t>((k + 1) % 3)];
      edges.push_back({std::min(a, b), std::max(a, b), static_cast<int32_t>(f), static_cast<int8_t>(k)});
    }
  std::sort(edges.begin(), edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi;
  });
  std::vector<std::array<int32_t, 3>> opp(mesh.triangles.size(), {-1, -1, -1});
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    if (j - i > 2)
      throw InputError("non-manifold edge (" + std::to_string(edges[i].lo) + ", " + std::to_string(edges[i].hi) +
                       ") is shared by " + std::to_string(j - i) + " faces");
    if (j - i == 2) {
      opp[static_cast<size_t>(edges[i].face)][static_cast<size_t>(edges[i].corner)] = edges[i + 1].face;
      opp[static_cast<size_t>(edges[i + 1].face)][static_cast<size_t>(edges[i + 1].corner)] = edges[i].face;
    }
    i = j;
  }
  return opp;
}

std::array<double, 3> lattice_family(const QuantFrame& frame, const HexLattice& lattice, int pair, const Vec3& p) {
  const int u = pair_u(pair), w = pair_w(pair);
  const auto ab = lattice.to_lattice(frame.to_quant(p[static_cast<size_t>(u)], u),
                                     frame.to_quant(p[static_cast<size_t>(w)], w));
  return {ab[0], ab[1], ab[0] + ab[1]};
}

namespace {

double frac_distance(double x) { return std::abs(x - std::nearbyint(x)); }

bool vertex_generic(const std::array<double, 3>& F) {
  return frac_distance(F[0]) >= kGenericMargin && frac_distance(F[1]) >= kGenericMargin &&
         frac_distance(F[2]) >= kGenericMargin;
}

// Every crossing of the edge (Fa, Fb) with a grid line keeps its other family values off integers.
// On failure, *bad_t is the parameter of the offending crossing.
bool edge_generic(const std::array<double, 3>& Fa, const std::array<double, 3>& Fb, double* bad_t) {
  for (int f = 0; f < 3; ++f) {
    const double lo = std::min(Fa[f], Fb[f]), hi = std::max(Fa[f], Fb[f]);
    for (double c = std::ceil(lo); c < hi; c += 1.0) {
      const double t = (c - Fa[f]) / (Fb[f] - Fa[f]);
      for (int g = 0; g < 3; ++g) {
        if (g == f) continue;
        if (frac_distance(Fa[g] + t * (Fb[g] - Fa[g])) < kGenericMargin) {
          *bad_t = t;
          return false;
        }
      }
    }
  }
  return true;
}

}  // namespace

size_t make_generic(Mesh& refined, const std::vector<int32_t>& face_relief, const std::vector<int>& relief_axis,
                    const std::vector<std::array<int32_t, 3>>& adjacency, const QuantFrame& frame,
                    const std::vector<HexLattice>& lattices, const std::vector<int>& relief_grid) {
  const size_t nv = refined.positions.size();
  if (lattices.size() > 10) throw std::invalid_argument("make_generic: more than 10 lattices");
  // Lattice slots 3 g + pair used around each vertex (bit mask).
  auto slot_of = [&](int32_t r) {
    return 3 * relief_grid[static_cast<size_t>(r)] + axis_pair(relief_axis[static_cast<size_t>(r)]);
  };
  std::vector<uint32_t> slots(nv, 0);
  for (size_t f = 0; f < refined.triangles.size(); ++f) {
    const int slot = slot_of(face_relief[f]);
    for (uint32_t v : refined.triangles[f]) slots[v] |= 1u << slot;
  }
  int64_t finest = lattices[0].A;
  for (const HexLattice& l : lattices) finest = std::min(finest, l.A);
  std::mt19937_64 rng(0x5eed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  // A nudge of a few margins in lattice units: far below one quantization step.
  const double nudge = 8.0 * kGenericMargin * static_cast<double>(finest) * frame.step;
  std::vector<uint8_t> moved(nv, 0);
  size_t moved_count = 0;
  double scale = 1.0;  // grows when a configuration resists
  auto nudge_vertex = [&](uint32_t v) {
    for (double& c : refined.positions[v]) c += scale * nudge * uni(rng);
    if (!moved[v]) {
      moved[v] = 1;
      ++moved_count;
    }
  };
  auto generic_vertex = [&](uint32_t v) {
    for (int s = 0; s < 3 * static_cast<int>(lattices.size()); ++s)
      if ((slots[v] >> s) & 1)
        if (!vertex_generic(lattice_family(frame, lattices[static_cast<size_t>(s / 3)], s % 3, refined.positions[v])))
          return false;
    return true;
  };
  for (int round = 0; round < 64; ++round) {
    scale = static_cast<double>(int64_t{1} << (round / 4));
    bool clean = true;
    for (uint32_t v = 0; v < nv; ++v)
      for (int attempt = 0; attempt < 64 && !generic_vertex(v); ++attempt) {
        nudge_vertex(v);
        clean = false;
      }
    for (size_t f = 0; f < refined.triangles.size(); ++f) {
      const int pair = axis_pair(relief_axis[static_cast<size_t>(face_relief[f])]);
      const HexLattice& lattice = lattices[static_cast<size_t>(relief_grid[static_cast<size_t>(face_relief[f])])];
      for (int k = 0; k < 3; ++k) {
        const int32_t g = adjacency[f][static_cast<size_t>(k)];
        // Each edge once per relief side: the face with the smaller index, or the only face.
        if (g >= 0 && g < static_cast<int32_t>(f) && face_relief[static_cast<size_t>(g)] == face_relief[f]) continue;
        const uint32_t a = refined.triangles[f][static_cast<size_t>(k)];
        const uint32_t b = refined.triangles[f][static_cast<size_t>((k + 1) % 3)];
        const uint32_t lo = std::min(a, b), hi = std::max(a, b);
        double bad_t = 0;
        if (!edge_generic(lattice_family(frame, lattice, pair, refined.positions[lo]),
                          lattice_family(frame, lattice, pair, refined.positions[hi]), &bad_t)) {
          nudge_vertex(bad_t < 0.5 ? lo : hi);
          clean = false;
        }
      }
    }
    if (clean) return moved_count;
  }
  throw std::runtime_error("make_generic: could not move the mesh off the grid lines");
}

void prepare_view(ReliefMeshView& view) {
  if (view.opposite.empty()) view.opposite = face_adjacency(*view.mesh);
}

std::array<double, 3> ReliefMeshView::F(int slot, int32_t v) const {
  return lattice_family(frame, lattices[static_cast<size_t>(slot / 3)], slot % 3, position(v));
}

}  // namespace prm::remesh
