// The remesher's options that `prm remesh` and `prm pack` share, added once for both.
#pragma once

#include <CLI/CLI.hpp>

namespace prm::cli {

// --error-flip-weight (remesh::SeamOptions::error_flip_weight) and --interpolate-heights (the negation of
// ResampleOptions::fit_heights), in that order.
inline void add_remesher_options(CLI::App* cmd, double& error_flip_weight, bool& interpolate_heights) {
  cmd->add_option("--error-flip-weight", error_flip_weight,
                  "Flips of irregular edges (seams) that bring the surface closer to the input: a flip that moves valences away from 6 must gain at least this many mean triangle errors per unit of (valence - 6)^2 (default 2; 0: valences not weighed; -1: no such flips)")
      ->check(CLI::Range(-1.0, 1e6));
  cmd->add_flag("--interpolate-heights", interpolate_heights,
                "Keep the lattice vertices on the input surface (no least-squares heights; for comparison)");
}

}  // namespace prm::cli
