// Issue 21: effort 0's first grid predicted from the input surface (bench/README.md "pack effort", twelfth round).
// A constant grid per target error (kGridPerTargetError) meets the target at 0.77-0.94 of it on horse, venus and
// bunny_zipper but misses on the feline (1.54x), which then remeshes twice. These statistics of the input are cheap
// (one pass over its edges, about 0.05 s on a 50k-vertex model) and predict the grid that meets the target.
#pragma once

#include "prm/mesh.h"

namespace prm::pipeline {

// Per interior edge of the input (faces f, g with nonzero areas; dihedral angle theta, length l, centroid distance d).
// Lengths are in units of `unit` (target error x bounding-box diagonal); curvatures in units of 1 / diagonal.
struct SurfaceGridStatistics {
  double kappa_rms = 0;   // sqrt(sum theta^2 l / d / area) x diagonal: the RMS curvature (remesh::measure_relief_detail)
  double kappa_abs = 0;   // sum theta l / area x diagonal: the mean absolute curvature
  double edge_mean = 0;   // the mean edge length / unit
  // The grid g / unit at which sqrt(sum theta^2 l g^3 min(g / d, 1) / area) = unit. An empirical model, fitted
  // as it is (kFirstGridFit): an edge coarser than the grid (d > g) counts as a smooth bend, g^4 kappa^2 over its
  // area ~ l d with kappa = theta / d; one finer than the grid (d < g) as g^3 theta^2 l, less than that by d / g
  // (detail finer than the grid weighs less). The other way round (max instead of min: fine edges smooth, coarse
  // ones creases) was meant first and was not measured.
  double model_grid = 0;
  size_t edges = 0;       // the interior edges counted
};
// Zeros when the mesh has no interior edge between faces of nonzero area.
SurfaceGridStatistics surface_grid_statistics(const Mesh& input, double unit, double diagonal);

// The grid (model units) predicted to meet target error x diagonal: exp(a) model_grid^b edge_mean^c x unit, with
// kFirstGridFit's coefficients; 0 when the statistics are zeros.
double predict_first_grid(const SurfaceGridStatistics& s, double unit);

// Least squares in log over 16 meshes (the four paper models at their Table 1 targets; spot, feline_5k, igea,
// rocker-arm and CGAL's armadillo, camel, bunny00, elephant, man, dino, bull, cow at 2e-4) of the grid each needs
// at effort 0 (bench/first_grid_study.py): leave-one-out, predicted / needed is 0.87-1.34 (RMS of its log 0.124);
// the constant 32 gives 0.82-1.97 (0.351), a constant fitted the same way leave-one-out 0.66-1.69 (0.306).
constexpr double kFirstGridFit[3] = {2.136, 1.157, -0.343};

}  // namespace prm::pipeline
