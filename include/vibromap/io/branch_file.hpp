#pragma once
// The branch file of `vibromap continue -o`: the periodic-orbit branches and their
// bifurcations, HDF5, written whole (tmp + rename), readable by vibromap.plot (postprocess/vibromap). The
// points of every branch share one dimension (CF's indexed ragged layout): point_branch says
// whose each is; branch 0 is the one followed from the start, the others were switched onto at
// a period doubling (branch_parent, branch_born_at: the parent's bifurcation index).
//   /point                 1-D int32 coordinate 0..P-1 (by branch, each in arclength order)
//   /point_branch          (point) int32: the branch of each point
//   /branch                1-D int32 coordinate 0..NB-1
//   /branch_n, /branch_parent (-1: none), /branch_born_at (-1: none)   (branch) int32
//   /strobe                1-D int32 coordinate 0..S-1, S the largest period n
//   /strobe_x1             (point, strobe) float64, m: x1 at the n period starts (NaN beyond n)
//   /bifurcation_branch    (bifurcation) int32: the branch it was located on
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
// Root attributes: title, Conventions, vibromap_version, scene, key, units, n and stop (of branch 0),
// stops (one line per branch), version (kBranchFormat's, io/file_format.hpp), attribute_checksum
// (the CRC-32 of every attribute, written last: src/io/attribute_seal.hpp).

#include <string>
#include <vector>

#include "vibromap/core/analysis/continuation/continuation.hpp"
#include "vibromap/core/grid.hpp"

namespace vibromap {

struct BranchCycle {      // what `continue` measures on each point's cycle
  double T_con = 0.0, k_con = 0.0, F_max = 0.0;
  int impacts = 0;
};

struct BranchData {
  Axis axis;                                   // the key (values unused): key, name, units, long_name
  std::vector<Branch> branches;                // continue_branches: the first, then the switched ones
  std::vector<std::vector<BranchCycle>> cycles;  // per branch, one per point
  std::string scene_text;
};

// Throws IoError naming the path; leaves no file behind on failure.
void write_branch(const std::string& path, const BranchData& data);

}  // namespace vibromap
