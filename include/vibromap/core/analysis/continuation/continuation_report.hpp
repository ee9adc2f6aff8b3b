#pragma once
// What a continuation found, with every point's cycle measured as `run` measures an orbit
// (measure_orbit, point_solver.hpp): the branches in one key (continuation.hpp) and the curves
// in two (curve_continuation.hpp). Plain data: the continuation campaign fills it
// (campaigns/continuation/), the branch and curve output prints it (io/branch_output.hpp).

#include <string>
#include <vector>

#include "vibromap/core/analysis/continuation/continuation.hpp"
#include "vibromap/core/analysis/continuation/curve_continuation.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"

namespace vibromap {

// A branch point with its cycle measured as `run` measures the orbit.
struct MeasuredPoint {
  BranchPoint point;
  PointSummary orbit;
};

struct ContinuationReport {
  int n = 1;                       // the start orbit's period, in forcing periods
  std::string start_regime;        // its regime's label at the start
  std::vector<Branch> branches;    // continue_branches: the first, then the switched ones
  std::vector<std::vector<MeasuredPoint>> measured;  // per branch, one per point
  int stop_signal = 0;  // the stop signal (SIGINT, SIGTERM, SIGUSR1) that ended the run early, 0: none
};

struct MeasuredCurve {
  Curve curve;
  std::vector<PointSummary> orbits;  // one per point
};

struct CurvesReport {
  ContinuationReport branch;          // the branch in P at the scene's Q
  double q0 = 0.0;                    // the scene's Q
  std::vector<MeasuredCurve> curves;  // in the order found (by spec, then along the branches)
  std::vector<std::string> skipped;   // starts not followed, and why
  bool branch_file = false;           // stopped before the first curve: the output holds the branch so far
                                      // (a branch file), not curves
  double wall_s = 0.0;                // the whole run, s
};

}  // namespace vibromap
