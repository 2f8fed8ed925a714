// Issue 21: effort 0's first grid from the input surface (first_grid.h). The statistics against closed forms on a
// sphere and a cube; the model grid in its two regimes: every centroid distance above the grid (g^2 kappa_rms = unit,
// g ~ unit^(1/2)) and every one below it (g^3 sum theta^2 l / area = unit^2, g ~ unit^(2/3)).
#include <gtest/gtest.h>

#include <cmath>

#include "prm/mesh.h"
#include "prm/pipeline/first_grid.h"
#include "prm/pipeline/pack.h"
#include "test_meshes.h"

namespace prm::pipeline {
namespace {

constexpr double kPi = 3.14159265358979323846;

Mesh unit_cube() {  // outward-oriented, two triangles a side; vertex x + 2y + 4z
  Mesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

TEST(FirstGrid, SphereCurvatureAndTheModelsTwoRegimes) {
  const Mesh sphere = prm::test::icosphere(5, 2.0);
  const double diagonal = 2 * std::sqrt(3.0) * 2.0;  // the bounding box of a sphere of radius 2
  auto stats = [&](double target) { return surface_grid_statistics(sphere, target * diagonal, diagonal); };
  const SurfaceGridStatistics fine = stats(1e-5);
  ASSERT_GT(fine.edges, 0u);
  // Per edge theta ~ d / r: sum theta^2 l / d ~ sum d l / r^2 = 2 area / r^2, so kappa_rms ~ sqrt(2) / r.
  EXPECT_NEAR(fine.kappa_rms / diagonal, std::sqrt(2.0) / 2.0, 0.03 * std::sqrt(2.0) / 2.0);
  // Fine targets, every centroid distance above the grid: g^2 kappa_rms = unit, exactly.
  const double unit = 1e-5 * diagonal, g = fine.model_grid * unit;
  EXPECT_NEAR(g, std::sqrt(unit * diagonal / fine.kappa_rms), 1e-6 * g);
  EXPECT_NEAR(stats(2e-5).model_grid * 2 / fine.model_grid, std::sqrt(2.0), 1e-6);
  // Coarse targets, every centroid distance below the grid: g grows as unit^(2/3).
  EXPECT_NEAR(stats(2e-2).model_grid * 2 / stats(1e-2).model_grid, std::pow(2.0, 2.0 / 3.0), 1e-6);
  EXPECT_GT(predict_first_grid(fine, unit), 0);
}

TEST(FirstGrid, CubeStatisticsAndPrediction) {
  const Mesh cube = unit_cube();
  const double diagonal = std::sqrt(3.0), unit = 1e-3 * diagonal;
  const SurfaceGridStatistics s = surface_grid_statistics(cube, unit, diagonal);
  EXPECT_EQ(s.edges, 18u);  // 12 creases, 6 flat diagonals
  EXPECT_NEAR(s.edge_mean * unit, (12 + 6 * std::sqrt(2.0)) / 18, 1e-12);
  EXPECT_NEAR(s.kappa_abs / diagonal, 12 * (kPi / 2) / 6, 1e-9);
  // The grid is far below every centroid distance (at least 1/3): g^2 kappa_rms = unit.
  const double g = std::sqrt(unit * diagonal / s.kappa_rms);
  EXPECT_NEAR(s.model_grid * unit, g, 1e-6 * g);
  const double expected = std::exp(kFirstGridFit[0]) * std::pow(g / unit, kFirstGridFit[1]) *
                          std::pow(s.edge_mean, kFirstGridFit[2]) * unit;
  EXPECT_NEAR(predict_first_grid(s, unit), expected, 1e-6 * expected);
}

TEST(FirstGrid, NoInteriorEdgeGivesNoPrediction) {
  Mesh one;
  one.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  one.triangles = {{0, 1, 2}};
  const SurfaceGridStatistics s = surface_grid_statistics(one, 1e-3, std::sqrt(2.0));
  EXPECT_EQ(s.edges, 0u);
  EXPECT_EQ(predict_first_grid(s, 1e-3), 0.0);
}

TEST(FirstGrid, OnlyEffortZeroPredictsItsFirstGrid) {
  for (int effort = kMinEffort; effort <= kMaxEffort; ++effort)
    EXPECT_EQ(effort_plan(effort).first_grid_gate, effort == 0 ? 0.9 : 0.0) << "effort " << effort;
}

}  // namespace
}  // namespace prm::pipeline
