#pragma once
// The branch file of `vibromap continue -o` (issue #12): one periodic-orbit branch and its
// bifurcations, HDF5, written whole (tmp + rename), readable by postprocess/plot_branch.py.
//   /point                 1-D int32 coordinate 0..P-1 (arclength order)
//   /param                 (point) float64: the key's value, with units and long_name
//   /stable                (point) int8: 1 every |mu| < 1, else 0
//   /x1, /x2, /v1, /v2     (point) float64: the orbit's state at a period start (m, m/s)
//   /x1_max, /x2_max, /clearance_min   (point) float64, m: the cycle's extent (orbit_extent.hpp)
//   /T_con, /k_con, /F_max (point) float64 (s, 1, N), /impacts (point) int32: per cycle
//   /multiplier            1-D int32 coordinate 0..3
//   /multiplier_re, /multiplier_im     (point, multiplier) float64: Floquet multipliers, largest |mu| first
//   /bifurcation           1-D int32 coordinate 0..B-1
//   /bifurcation_type      (bifurcation) int8, flags 0 fold, 1 period_doubling, 2 neimark_sacker, 3 grazing
//   /bifurcation_param, /bifurcation_x1, /bifurcation_x2, /bifurcation_v1, /bifurcation_v2  (bifurcation)
// Root attributes: title, Conventions, vibromap_version, scene, key, units, n, stop.

#include <string>
#include <vector>

#include "vibromap/core/analysis/continuation.hpp"
#include "vibromap/core/grid.hpp"

namespace vibromap {

struct BranchCycle {      // what `continue` measures on each point's cycle
  double T_con = 0.0, k_con = 0.0, F_max = 0.0;
  int impacts = 0;
};

struct BranchData {
  Axis axis;                         // the key (values unused): key, name, units, long_name
  int n = 1;
  Branch branch;
  std::vector<BranchCycle> cycles;   // one per branch point
  std::string scene_text;
};

// Throws IoError naming the path; leaves no file behind on failure.
void write_branch(const std::string& path, const BranchData& data);

}  // namespace vibromap
