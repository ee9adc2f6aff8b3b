#pragma once
// Curves in two parameters (`vibromap continue --curve KIND --param2 Q ...`): one
// process, no farm.
//   branch    the branch in P over [A, B] at the scene's Q, as `continue` follows it
//             (continuation_run.hpp)
//   starts    every point of each KIND on it: its located bifurcations of that type (every
//             grazing: an impact appearing or vanishing), or for level:NAME=VALUE where NAME
//             crosses VALUE between two points, located by Newton on the extended system
//   curves    each start continued in (P, Q) both ways while Q in [C, D] and P in [A, B]
//             (core/analysis/continuation/curve_continuation.hpp); a start on a curve already found is not
//             followed again
//   measure   every curve point's cycle measured as `run` measures an orbit (measure_orbit)
//   output    the curve file (io/curve_file.hpp), when asked (instead of the branch file); a run
//             stopped by a signal before its first curve writes the branch so far there instead
//             (a branch file, CurvesReport::branch_file)

#include <string>
#include <vector>

#include "vibromap/campaigns/continuation/continuation_run.hpp"
#include "vibromap/core/analysis/continuation/curve_continuation.hpp"

namespace vibromap {

struct CurveConfig {
  std::vector<CurveSpec> specs;  // at least one
  double from2 = 0.0, to2 = 0.0; // Q's range, from2 < to2
};

// Throws SceneError (Q not a model parameter, C >= D, the scene's Q outside [C, D], no
// periodic orbit at the start) before any solve, and IoError (the file).
CurvesReport run_curves(const Scene& scene, const Axis& axis, const Axis& axis2, const ContinuationConfig& config,
                        const CurveConfig& curves);

}  // namespace vibromap
