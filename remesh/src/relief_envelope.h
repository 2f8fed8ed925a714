// Paper §2.1: the relief of v is where d_v is the largest of the six fields. Along an edge the fields are linear,
// so the labels along it are the pieces of the upper envelope of six lines; its breakpoints are the zero crossings
// of the differences d_v - d_w, where the edge is split.
#pragma once

#include <array>
#include <cstdint>

#include "relief_axes.h"

namespace prm::remesh {

// The labelled pieces of one edge from endpoint a (t = 0) to endpoint b (t = 1): piece i has axis[i] on
// [start[i], start[i + 1]) with start[0] = 0 and start[count] = 1. count == 0: every field is 0 all along the
// edge (it lies in all A_v), so the edge says nothing about the label.
struct EdgeEnvelope {
  int count = 0;
  std::array<double, kReliefAxes + 1> start{};
  std::array<int8_t, kReliefAxes> axis{};
};

// Tie rule: where several fields are equal and largest, the label goes to the one that is largest just after the
// point (the larger slope towards b), then to the lowest axis index; every piece therefore has a positive field
// inside it (paper §2.1: a face of A_v, where d_v = 0, never takes label v from an edge).
// Snapping: pieces shorter than `snap` (a fraction of the edge; at least 1e-6) are removed; an end piece gives its length to its
// neighbour (the crossing moves onto the vertex), an inner piece's neighbours meet at its middle. Computed from the
// edge's two value sets only, so both faces of the edge see the same split points.
EdgeEnvelope upper_envelope(const AxisValues& a, const AxisValues& b, double snap);

}  // namespace prm::remesh
