// The checks of issue 22's open-boundary tests: pack an open mesh keeping its holes, decode, and check the loops,
// the manifold, the boundary's place and the RMS error (pack_open_boundary_test.cpp, pack_open_boundary_real_test.cpp).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "prm/boundary_deviation.h"
#include "prm/mesh_validate.h"
#include "prm/metro_distance.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack.h"
#include "prm/vec3.h"

namespace prm::test {

using prm::Mesh;
using prm::Vec3;

using prm::BoundaryDeviation;
using prm::boundary_deviation;

struct Measured {
  size_t loops_in = 0, loops_out = 0;
  double rms = 0, max = 0;                            // fractions of the diagonal
  double boundary = 0, boundary_rms = 0;              // boundary vertices to the input's boundary: max, RMS (same)
  double boundary_steps = 0, boundary_rms_steps = 0;  // the same in quantization steps
};

// Packs `input` at `target` keeping its holes, through the remesher (mode prm: mode auto may code a small input as
// it is, which keeps its boundary trivially), and checks the result; returns what it measured. The RMS distance of
// the decoded boundary vertices to the input's boundary must be within the target, or within `rms_steps`
// quantization steps where a case needs that (see below).
inline Measured pack_and_check(const std::string& name, const Mesh& input, double target, double rms_steps = 0) {
  SCOPED_TRACE(name);
  Measured m;
  prm::pipeline::PackOptions o;
  o.target_error = target;
  o.mode = prm::pipeline::PackMode::prm;
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  EXPECT_TRUE(decoded.ok()) << decoded.status.message;
  if (!decoded.ok()) return m;
  const Mesh out = prm::pipeline::to_mesh(decoded.value);
  const prm::MeshReport before = prm::validate_mesh(r.repaired ? r.repaired_input : input);
  const prm::MeshReport after = prm::validate_mesh(out);
  m.loops_in = before.boundary_loops;
  m.loops_out = after.boundary_loops;
  EXPECT_GT(m.loops_in, 0u);
  EXPECT_EQ(r.repair.holes_filled, 0u);
  EXPECT_FALSE(r.boundary_fallback) << (r.repair.notes.empty() ? std::string() : r.repair.notes.back());
  EXPECT_EQ(r.mode, prm::pipeline::PackMode::prm);
  EXPECT_EQ(r.boundary_loops_in, m.loops_in);
  EXPECT_EQ(r.boundary_loops_out, m.loops_out);
  EXPECT_EQ(m.loops_out, m.loops_in);
  EXPECT_TRUE(after.manifold() && after.oriented()) << after.non_manifold_edges << " non-manifold edges, "
                                                    << after.non_manifold_vertices << " pinched vertices";
  EXPECT_EQ(after.components, before.components);
  const prm::DistanceReport d = prm::metro_distance(r.repaired ? r.repaired_input : input, out);
  m.rms = d.rel(d.rms);
  m.max = d.rel(d.max);
  EXPECT_LE(m.rms, target);
  // The boundary vertices are the input's boundary vertices and the grid's crossings of its boundary edges, never
  // moved by the remesher: only the quantization moves them. Each is coded at the quantization point within two
  // steps per coordinate nearest the input's boundary polyline (plain rounding: up to half a step per coordinate,
  // RMS about 0.4 step from the polyline), and the separation of quantized vertices moves another corner first; a
  // boundary vertex it must move goes to a free point nearest the polyline, up to three steps away per coordinate
  // (quantized_separation.h). So: the RMS within the target (the measure the target error uses), the maximum within
  // 3 sqrt(3) steps. (The stream's step is larger than an RMS target of 2e-4: at 11 bits about 5e-4 of the
  // diagonal, so the maximum is within the quantization, not within the target.)
  const BoundaryDeviation dev = boundary_deviation(r.repaired ? r.repaired_input : input, out);
  const double step = r.remesh.prm.frame.step;
  m.boundary = d.rel(dev.max);
  m.boundary_rms = d.rel(dev.rms);
  m.boundary_steps = dev.max / step;
  m.boundary_rms_steps = dev.rms / step;
  EXPECT_LE(dev.rms, std::max(target * d.diagonal, rms_steps * step))
      << "boundary RMS deviation " << m.boundary_rms << " of the diagonal, " << m.boundary_rms_steps << " steps";
  EXPECT_LE(dev.max, std::max(target * d.diagonal, 3.0 * std::sqrt(3.0) * step))
      << "boundary deviation " << m.boundary << " of the diagonal, " << m.boundary_steps << " steps";
  std::printf("%s: boundary loops %zu in, %zu out; %zu -> %u vertices; RMS %.3e, max %.3e of the diagonal; "
              "boundary vertices to the input's boundary: RMS %.3e, max %.3e of the diagonal (%.2f, %.2f steps of "
              "%d bits, step %.3e of the diagonal); %zu bytes\n",
              name.c_str(), m.loops_in, m.loops_out, input.num_vertices(), r.report.vertices, m.rms, m.max,
              m.boundary_rms, m.boundary, m.boundary_rms_steps, m.boundary_steps, r.bits, d.rel(step),
              r.stream.size());
  return m;
}

}  // namespace prm::test
