#pragma once
// Periodic-orbit continuation (issue #12): a periodic orbit of the stroboscopic map followed in
// one parameter by pseudo-arclength continuation on the shooting equations
//   G(y, lambda) = P^n(y; lambda) - y = 0,
// with Floquet multipliers at every point and the codimension-one bifurcations detected by
// test functions and located by bisection in arclength:
//   fold              the tangent's parameter component changes sign (a multiplier through +1)
//   period doubling   det(M + I) changes sign (a real multiplier through -1)
//   Neimark-Sacker    the number of complex multipliers outside the unit circle changes
//   grazing           the orbit's closest approach x2 - x1 (orbit_extent.hpp) crosses zero:
//                     an impact appears on the orbit or vanishes; the map is not smooth there,
//                     and the branch goes on across it when Newton converges on the far side
// (after BifurcationKit's and AUTO's test functions). Unknowns are scaled: the state by the
// motion's scale (StateScale), the parameter by the length of its interval, so one step size
// serves every key. The period follows the forcing when the parameter is omega (the model at
// each lambda has its own period). Branch switching is not handled here yet.

#include <complex>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/analysis/point_solver.hpp"

namespace vibromap {

struct ContinuationOptions {
  int n = 1;                 // period of the orbit, forcing periods
  double ds = 0.01;          // first step along the branch (scaled arclength)
  double ds_min = 1e-7;      // smallest step before the continuation gives up
  double ds_max = 0.05;      // largest step
  int max_points = 5000;     // points on the branch at most
  int max_corrections = 10;  // Newton iterations of one corrector
  double tol = 1e-9;         // scaled residual |P^n(y) - y| of a point
  double locate_tol = 1e-9;  // bifurcations located to this fraction of the parameter interval
};
std::string validate(const ContinuationOptions& o);

enum class BifurcationType { fold, period_doubling, neimark_sacker, grazing };
std::string to_string(BifurcationType t);  // "fold", "period-doubling", "neimark-sacker", "grazing"

struct BranchPoint {
  double param = 0.0;
  Eigen::Vector4d y = Eigen::Vector4d::Zero();  // the orbit's state at a period start, physical
  std::vector<std::complex<double>> multipliers;  // largest |mu| first
  bool stable = false;                          // every |mu| < 1
  double residual = 0.0;                        // scaled |P^n(y) - y|
  double x1_max = 0.0, x2_max = 0.0;            // the largest displacements over the cycle, m
  double clearance_min = 0.0;                   // the least x2 - x1 over the cycle, m (< 0: contact)
};

struct Bifurcation {
  BifurcationType type = BifurcationType::fold;
  BranchPoint at;            // the located point
};

struct Branch {
  std::vector<BranchPoint> points;    // in arclength order, the start first
  std::vector<Bifurcation> bifurcations;
  std::string stop;                   // why it ended: "reached the end of the interval", ...
  IntegrationCounters counters;
};

// The point (parameters and options) at parameter value lambda.
using PointAt = std::function<std::pair<Parameters, PointOptions>(double lambda)>;

// Follows the period-n orbit through y0 (physical, at a period start) at lambda = from, towards
// `to`, until the parameter leaves [min(from, to), max(from, to)], max_points, or a step below
// ds_min. y0 need not be exact: it is first corrected at lambda = from (Newton). The branch is
// empty with `stop` saying why when that correction fails.
Branch continue_orbit(const PointAt& point_at, double from, double to, const Eigen::Vector4d& y0,
                      const ContinuationOptions& options);

}  // namespace vibromap
