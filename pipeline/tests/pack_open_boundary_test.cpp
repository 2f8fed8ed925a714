// Issue 22: `pack` keeps the boundary loops of an open surface. For each mesh: the decoded stream is an oriented
// 2-manifold with as many boundary loops as the input, every decoded boundary vertex lies near the input's boundary
// polyline, and the decoded mesh meets the target RMS error (measured here again, independently of pack's search).
// The cases are generated here: a height-field terrain, a flat plane, a closed mesh cut by a plane (the real open
// meshes are in pack_open_boundary_real_test.cpp, heavy).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "grid_sheet.h"
#include "open_boundary_check.h"
#include "prm/mesh_io.h"

namespace {

using prm::Mesh;
using prm::Vec3;
using prm::test::Measured;
using prm::test::pack_and_check;

Mesh height_field(int n, double (*h)(double, double)) {
  return prm::test::grid_sheet(n, [h](int, int, double x, double y) { return Vec3{x, y, h(x, y)}; });
}

// The faces of `closed` whose centroid lies below the plane z = the middle of its bounding box (unused vertices
// dropped): a closed scan cut open.
Mesh cut_below_middle(const Mesh& closed) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const Vec3& p : closed.positions) lo = std::min(lo, p[2]), hi = std::max(hi, p[2]);
  const double z = 0.5 * (lo + hi);
  Mesh cut;
  std::vector<uint32_t> id(closed.positions.size(), UINT32_MAX);
  for (const prm::Tri& t : closed.triangles) {
    const double c = (closed.positions[t[0]][2] + closed.positions[t[1]][2] + closed.positions[t[2]][2]) / 3;
    if (c > z) continue;
    prm::Tri u;
    for (int k = 0; k < 3; ++k) {
      if (id[t[k]] == UINT32_MAX) {
        id[t[k]] = static_cast<uint32_t>(cut.positions.size());
        cut.positions.push_back(closed.positions[t[k]]);
      }
      u[k] = id[t[k]];
    }
    cut.triangles.push_back(u);
  }
  return cut;
}

TEST(PackOpenBoundary, TerrainKeepsItsBorder) {
  const Mesh terrain = height_field(80, [](double x, double y) {
    return 0.08 * std::sin(5 * x) * std::cos(4 * y) + 0.05 * std::sin(11 * x + 3 * y);
  });
  const Measured m = pack_and_check("terrain 81x81", terrain, 2e-4);
  EXPECT_EQ(m.loops_in, 1u);
}

TEST(PackOpenBoundary, PlaneIsNotCappedByAFan) {
  const Mesh plane = height_field(30, [](double, double) { return 0.0; });
  // The flat plane is square to the frame: lattice points of its relief fall on its straight boundary, and the
  // separation then moves the boundary vertex beside such a point by one step (what else would flatten or turn a
  // triangle over). Its boundary RMS is 0.39 steps (2.08e-4 of the diagonal at 2e-4); allowed: 0.45 steps.
  const Measured m = pack_and_check("plane 31x31", plane, 2e-4, 0.45);
  EXPECT_EQ(m.loops_in, 1u);
}

TEST(PackOpenBoundary, ClosedScanCutByAPlane) {
  const Mesh spot = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  ASSERT_EQ(prm::validate_mesh(spot).boundary_loops, 0u);
  pack_and_check("spot cut at mid-height", cut_below_middle(spot), 2e-4);
}

TEST(PackOpenBoundary, FillHolesClosesEveryLoop) {
  const Mesh terrain = height_field(40, [](double x, double y) { return 0.1 * std::sin(4 * x + 2 * y); });
  prm::pipeline::PackOptions o;
  o.target_error = 5e-4;
  o.fill_holes = true;
  const prm::pipeline::PackResult r = prm::pipeline::pack(terrain, o);
  EXPECT_EQ(r.boundary_loops_in, 1u);
  EXPECT_EQ(r.repair.holes_filled, 1u);
  EXPECT_EQ(r.boundary_loops_out, 0u);
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  ASSERT_TRUE(decoded.ok());
  EXPECT_TRUE(prm::validate_mesh(prm::pipeline::to_mesh(decoded.value)).closed());
}

// The general path (mode auto keeps it for the cut spot: 1,648 vertices coded as they are) holds the boundary within
// the target too: its bit depth is the smallest whose decoded boundary vertices lie at an RMS distance of at most
// the target from the input's boundary (at the depth the surface's RMS alone would take, 3.06e-4 of the diagonal).
TEST(PackOpenBoundary, GeneralStreamKeepsItsBoundaryWithinTheTarget) {
  const Mesh spot = prm::read_mesh(std::string(PRM_SHARED_MESHES) + "/spot.obj");
  const Mesh cut = cut_below_middle(spot);
  prm::pipeline::PackOptions o;
  o.target_error = 2e-4;
  o.mode = prm::pipeline::PackMode::general;
  const prm::pipeline::PackResult r = prm::pipeline::pack(cut, o);
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  ASSERT_TRUE(decoded.ok());
  const Mesh out = prm::pipeline::to_mesh(decoded.value);
  EXPECT_EQ(prm::validate_mesh(out).boundary_loops, 1u);
  const double diagonal = prm::validate_mesh(cut).diagonal;
  const prm::BoundaryDeviation dev = prm::boundary_deviation(cut, out);
  EXPECT_LE(dev.rms, o.target_error * diagonal);
  EXPECT_LE(prm::metro_distance(cut, out).rms, o.target_error * diagonal);
  std::printf("spot cut, general path: %d bits, %zu bytes, boundary RMS %.3e max %.3e of the diagonal\n", r.bits,
              r.stream.size(), dev.rms / diagonal, dev.max / diagonal);
}

// The fallback when the remesher cannot keep an open boundary (a broken invariant, std::logic_error): pack fills
// the holes instead and says so. No known mesh triggers it, so the attempt is given here: it throws on the open
// path and runs pack's own (mode prm) when asked to fill. A closed input's error, and std::invalid_argument, are
// not caught.
TEST(PackOpenBoundary, FallsBackToFillingWhenTheBoundaryCannotBeKept) {
  const Mesh terrain = height_field(40, [](double x, double y) { return 0.1 * std::sin(4 * x + 2 * y); });
  prm::pipeline::PackOptions o;
  o.target_error = 5e-4;
  o.mode = prm::pipeline::PackMode::prm;
  int open_attempts = 0;
  auto attempt = [&](const Mesh& m, const prm::pipeline::PackOptions& po) {
    if (!po.fill_holes) {
      ++open_attempts;
      throw std::logic_error("test: a broken seam invariant");
    }
    return prm::pipeline::pack(m, po);
  };
  const prm::pipeline::PackResult r = prm::pipeline::detail::pack_keeping_boundary_or_filling(terrain, o, attempt);
  EXPECT_EQ(open_attempts, 1);
  EXPECT_TRUE(r.boundary_fallback);
  EXPECT_EQ(r.boundary_loops_in, 1u);
  EXPECT_EQ(r.repair.holes_filled, 1u);
  EXPECT_EQ(r.boundary_loops_out, 0u);
  ASSERT_FALSE(r.repair.notes.empty());
  EXPECT_NE(r.repair.notes.back().find("could not keep the open boundary (test: a broken seam invariant)"),
            std::string::npos)
      << r.repair.notes.back();
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  ASSERT_TRUE(decoded.ok());
  EXPECT_TRUE(prm::validate_mesh(prm::pipeline::to_mesh(decoded.value)).closed());

  auto always_throws = [](const Mesh&, const prm::pipeline::PackOptions&) -> prm::pipeline::PackResult {
    throw std::logic_error("test: a broken invariant");
  };
  const Mesh tet = [] {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    return m;
  }();
  EXPECT_THROW(prm::pipeline::detail::pack_keeping_boundary_or_filling(tet, o, always_throws), std::logic_error);
  auto refuses = [](const Mesh&, const prm::pipeline::PackOptions&) -> prm::pipeline::PackResult {
    throw std::invalid_argument("test: a bad option");
  };
  EXPECT_THROW(prm::pipeline::detail::pack_keeping_boundary_or_filling(terrain, o, refuses), std::invalid_argument);
}

}  // namespace
