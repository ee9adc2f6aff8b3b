#pragma once
// Periodic-orbit continuation: a periodic orbit of the stroboscopic map followed in
// one parameter by pseudo-arclength continuation on the shooting equations
//   G(y, lambda) = P^n(y; lambda) - y = 0,
// with Floquet multipliers at every point and the codimension-one bifurcations detected by
// test functions and located by bisection in arclength:
//   fold              the tangent's parameter component changes sign (a multiplier through +1)
//   period doubling   det(M + I) changes sign (a real multiplier through -1)
//   Neimark-Sacker    the number of complex multipliers outside the unit circle changes
//   grazing           the number of contacts per cycle changes (orbit_extent.hpp): an impact
//                     appears on the orbit (a closest approach x2 - x1 reaches 0) or vanishes
//                     (a peak penetration reaches 0); the map is not smooth there, and the
//                     branch goes on across it with the new impact count
// (after BifurcationKit's and AUTO's test functions). Unknowns are scaled: the state by the
// motion's scale (StateScale), the parameter by the length of its interval, so one step size
// serves every key. The period follows the forcing when the parameter is omega (the model at
// each lambda has its own period).
//
// Steps: a step is accepted when Newton converges within max_corrections and the tangent turns
// by less than kMaxTurn (continuation.cpp), else halved; on a smooth branch the turn shrinks with
// the step, so only a kink (a grazing) drives the step down to ds_min, where the branch is marked
// and continued across. The turn limit keeps a step from jumping onto a neighbouring branch.
//
// Branch switching at a period doubling: the fixed points of P^{2n} form two branches that cross
// there, the period-n orbit and the period-2n orbit born at it, whose tangent is (v, 0), v the
// eigenvector of the multiplier -1 of the period-n monodromy. The predictor y* + h v (parameter
// fixed) and the corrector on the hyperplane orthogonal to (v, 0) land on the 2n branch (the
// n branch crosses that hyperplane h/|t_n . (v,0)| away, the 2n branch O(h^2) away); a landing
// is accepted once |P^n(y) - y| is of the order h (a 2n orbit, not the n one). The 2n branch is
// then followed like any branch until it leaves the interval or rejoins a period-n orbit (the
// difference P^n(y) - y changes sign: the branch went through another period doubling of it and
// came back as the same orbit shifted by n periods).

#include <atomic>
#include <complex>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/analysis/point/point_solver.hpp"

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
  int pd_depth = 0;          // continue_branches: period-doubling generations switched onto (0: none)
  int max_branches = 32;     // continue_branches: branches at most, the first included
  // A flag the caller sets (non-zero) to stop: the walk ends before its next point (the point
  // being corrected is finished first), the branch or curve with stop = kStoppedOnRequest, and
  // no further branch or curve is started (a campaign's stop signal). nullptr: never.
  const std::atomic<int>* stop = nullptr;
};
std::string validate(const ContinuationOptions& o);

inline constexpr const char* kStoppedOnRequest = "stopped on request";
// Whether o.stop is set.
inline bool stop_requested(const ContinuationOptions& o) {
  return o.stop != nullptr && o.stop->load(std::memory_order_relaxed) != 0;
}

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
  std::vector<Eigen::Vector4d> strobe;          // the n states at the period starts, y first, physical
  int contacts = 0;                             // contacts over the cycle (orbit_extent.hpp)
  double graze_gap = 0.0;                       // how near the contact count is to changing, m
};

struct Bifurcation {
  BifurcationType type = BifurcationType::fold;
  BranchPoint at;            // the located point
};

struct Branch {
  int n = 1;                          // period of its orbits, forcing periods
  int parent = -1;                    // continue_branches: the branch it was switched from (-1: none)
  int born_at = -1;                   // ... and the index of that branch's period doubling
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

// The period-2n branch born at the period doubling `pd` of a period-n branch (options.n = n), in
// the same interval; its first point is the period doubling itself. Empty, with `stop` saying
// why, when no 2n orbit is found near it.
Branch switch_period_doubling(const PointAt& point_at, double from, double to, const Bifurcation& pd,
                              const ContinuationOptions& options);

// continue_orbit, then the doubled branches born at its period doublings, and theirs, to
// options.pd_depth generations and options.max_branches branches in all. The first branch is
// continue_orbit's; a doubled branch already found (born at another period doubling of the
// same parent, which it rejoins) is not followed twice.
std::vector<Branch> continue_branches(const PointAt& point_at, double from, double to, const Eigen::Vector4d& y0,
                                      const ContinuationOptions& options);

}  // namespace vibromap
