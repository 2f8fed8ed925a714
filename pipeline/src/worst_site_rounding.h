#pragma once

#include <cstdint>
#include <vector>

#include "prm/codec.h"
#include "prm/mesh.h"
#include "prm/metro_distance.h"
#include "prm/remesh/resample.h"

namespace prm::pipeline {

// Issue 22 (h22t): the decoded stream's worst places past `aim` (model units; the decoded mesh's pr>in samples as
// the reference's Metro takes them) are where the refinement left a face near its bound and the rounding to the
// stream's step (and the heights' rate-distortion freedom) took it past: the horse at 1.3e-4, a face 1.06x the
// refinement's bound unrounded, 1.20x decoded. Around each such place (the faces whose centroid lies within a grid
// size of it, and the faces around their vertices), each vertex's quantized point is moved by one step (a lattice
// vertex along its relief's axis only: its height) where the worst of those faces' dense probes then comes down, in
// up to two passes; no face may turn over or turn away from the input. The PRM's positions of the vertices of the
// places that changed are set to their quantized points and `held` marks them (PrmOptions::rounded_heights: the
// encoder keeps them there). When no decoded sample is as far as the stream's `max` (model units), the max is the
// input's (in>pr): the input's samples past the aim make places too, the decoded mesh's nearest point to them, and
// their distances to the place's faces are weighed with the probes (the horse at 1.3e-4 and effort 9: its tail's
// tip, 1.099e-3 -> below 1.04e-3). missed_reach: at such an in>pr place an irregular vertex moves by up to this many
// steps along each axis (1: one step, as elsewhere). Returns the number of moves (0: nothing changed, the PRM is as it
// was).
size_t round_worst_sites(remesh::PrmMesh& prm, const codec::DecodedMesh& decoded, const Mesh& decoded_mesh,
                         const std::vector<uint32_t>& vertex_order, const MetroReference& reference, double aim,
                         double max, std::vector<uint8_t>& held, int missed_reach = 1);

// missed_reach where the search has no other attempt to keep instead when the stream passes the bound (pack.cpp;
// h22homer): homer at 2e-4, an input point at the bottom of a slit between two fingers, narrower than a step there,
// that the mesh bridges. The refinement's moves and splits there turn a face away from the input (a face across the
// slit faces a wall), and one-step moves of the bridge's vertices stopped 2.04e-3 from it (model units; the aim
// 1.91e-3), each further step turning a face away; moves of up to two steps pass over those places: 1.49e-3, the
// stream 8.53x -> 7.16x the target. Not where the search has another attempt: at effort 4 the horse at 2e-4 then
// kept its first attempt at 7.99x, 5,628 B, instead of refining the other, 7.48x and 5,490 B.
constexpr int kAloneMissedReach = 2;
// A stream whose max lies between this share of the bound and the bound is rounded towards this share of it (pack.cpp;
// h22homer: refined_elephant at 2e-4, a pr>in place at 7.998x the target, the margin any change could tip).
constexpr double kRoundMargin = 0.99;

}  // namespace prm::pipeline
