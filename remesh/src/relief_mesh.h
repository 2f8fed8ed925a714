// The refined mesh seen by the resampler: positions, relief labels, face adjacency and lattice coordinates.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "prm/mesh.h"
#include "prm/remesh/lattice.h"

namespace prm::remesh {

// Minimum distance (in lattice units) between a vertex or an edge crossing and any other grid line.
// Float error in lattice coordinates is below 1e-10; this margin keeps every side test far from it.
constexpr double kGenericMargin = 1e-6;

struct ReliefMeshView {
  const Mesh* mesh = nullptr;
  const std::vector<int32_t>* face_relief = nullptr;  // relief id per face
  const std::vector<int>* relief_axis = nullptr;      // axis 0..5 per relief id
  const std::vector<int32_t>* source_face = nullptr;  // input face per refined face (may be null: identity)
  QuantFrame frame;
  // The lattices (a grid size per relief, spec §8.4.2): lattices[g] for the reliefs with relief_grid[r] = g.
  std::vector<HexLattice> lattices;
  std::vector<int> relief_grid;                       // per relief id: an index into lattices
  std::vector<std::array<int32_t, 3>> opposite;       // face across edge (k, k+1) of each face, -1 if none

  int32_t relief(int32_t f) const { return (*face_relief)[static_cast<size_t>(f)]; }
  const HexLattice& lattice(int32_t r) const { return lattices[static_cast<size_t>(relief_grid[static_cast<size_t>(r)])]; }
  // The slot of relief r's lattice and axis pair: reliefs of one slot share their grid lines.
  int slot(int32_t r) const {
    return 3 * relief_grid[static_cast<size_t>(r)] + axis_pair((*relief_axis)[static_cast<size_t>(r)]);
  }
  int32_t source(int32_t f) const { return source_face ? (*source_face)[static_cast<size_t>(f)] : f; }
  const Vec3& position(int32_t v) const { return mesh->positions[static_cast<size_t>(v)]; }
  // The family values (alpha, beta, alpha+beta) of vertex v in the lattice of slot 3 g + pair (slot()), computed
  // when asked (the same function of the same position every time: 72 bytes a vertex and lattice not stored).
  std::array<double, 3> F(int slot, int32_t v) const;
};

// Face adjacency across edges; throws prm::InputError on a non-manifold edge.
std::vector<std::array<int32_t, 3>> face_adjacency(const Mesh& mesh);

// Family values of a point in the lattice of axis pair `pair`.
std::array<double, 3> lattice_family(const QuantFrame& frame, const HexLattice& lattice, int pair, const Vec3& p);

// Moves vertices by tiny amounts (far below quantization) until no vertex and no edge crossing lies within
// kGenericMargin of a grid line of any lattice its reliefs use (relief r's: lattices[relief_grid[r]]). Returns the
// number of vertices moved.
size_t make_generic(Mesh& refined, const std::vector<int32_t>& face_relief, const std::vector<int>& relief_axis,
                    const std::vector<std::array<int32_t, 3>>& adjacency, const QuantFrame& frame,
                    const std::vector<HexLattice>& lattices, const std::vector<int>& relief_grid);

// Fills view.opposite (unless the caller has).
void prepare_view(ReliefMeshView& view);

}  // namespace prm::remesh
