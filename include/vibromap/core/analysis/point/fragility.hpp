#pragma once
// Fragility of a point's answer: whether small perturbations of the initial state settle into
// the same attractor as the initial state itself (analysis.fragility, docs/model.md).
//
// With analysis.fragility = eps > 0, solve_point also follows fragility_states initial states
// x0 + eps u_i, each exactly as the initial state is followed (the same solver, options and
// budgets), and compares where they end with where x0 ends. The perturbation is measured in
// motion scales as the census box is: u_i is a unit vector (Euclidean) of (dx1/L, dx2/L,
// dv1/(omega L), dv2/(omega L)), L = max(D, lambda F0 / k1). The directions are fixed, the same
// at every point: +h1, -h1, +h2, -h2, ..., h_i the rows of the 4 x 4 Hadamard matrix over 2
// (every coordinate moved by eps/2 in each), so at most 8 states.
//
// Two answers are the same attractor (same_steady_state) when
//  - both are periodic (a period n > 0 found) with the same n, and their n stroboscopic states
//    (at forcing phase 0) agree up to a cyclic shift within the census's orbit tolerance
//    (same_orbit_tolerance: scaled max-norm max(1e-6, 1000 Newton tolerances)), each cycle
//    refined by Newton from where its motion ended;
//  - neither is periodic and both have the same regime kind (non-periodic and non-periodic,
//    chatter and chatter, ...: a non-periodic set is not compared beyond its kind, as the
//    census does);
// so unresolved (the budget ended while still settling) differs from everything but unresolved.
// The point is fragile when any perturbed state ends elsewhere. The point's reported answer
// stays the initial state's: fragility adds a flag and what the perturbations reached.

#include <vector>

#include <Eigen/Core>

#include "vibromap/core/analysis/point/regime.hpp"
#include "vibromap/core/integrate/integrator.hpp"
#include "vibromap/core/model/parameters.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap {

struct PointOptions;  // point_solver.hpp

inline constexpr double kMaxFragility = 0.1;     // largest analysis.fragility, motion scales
inline constexpr int kMaxFragilityStates = 8;    // largest analysis.fragility_states: +-h_i, i = 1..4

// Where one initial state (the point's own, or a perturbed one) ended.
struct SteadyEnd {
  Eigen::Vector4d x0 = Eigen::Vector4d::Zero();  // the initial state (x1, x2, v1, v2), m and m/s
  Regime regime;                                 // its regime (n > 0: periodic)
  bool settled = false;                          // a period was found (status ok and n > 0)
  std::vector<Eigen::Vector4d> strobe;           // settled: the n states of its cycle at forcing phase 0
  bool same = true;                              // the same attractor as the point's own initial state
};

struct Fragility {
  double size = 0.0;             // analysis.fragility the point was assessed with; 0: not assessed
  bool fragile = false;          // a perturbed state ended on another attractor
  SteadyEnd own;                 // the initial state's end, as compared
  std::vector<SteadyEnd> perturbed;  // one per direction, in order +h1, -h1, +h2, ...
  long periods = 0;              // forcing periods the perturbed states and the cycles' refinement took
  IntegrationCounters counters;  // their integration work (not in the point's own counters)
};

// Direction i (0-based, < kMaxFragilityStates) of the perturbations, a unit vector in motion scales.
Eigen::Vector4d fragility_direction(int i);

// Whether two ends are the same attractor of the point (p, options), by the rule above.
bool same_steady_state(const Parameters& p, const PointOptions& options, const SteadyEnd& a, const SteadyEnd& b);

// The orbit tolerance of the census and of fragility: two cycles of one period closer than this
// (scaled max-norm, StateScale) are one orbit. Newton solutions from different starts differ by
// about tol / (1 - |mu|), distinct orbits by far more.
double same_orbit_tolerance(const PointOptions& options);
// Whether the cycles a and b (states at period starts, internal coordinates) are one orbit: as
// many states, equal up to a cyclic shift within tol in the scaled distance of `model`.
bool same_cycle(const Model& model, const std::vector<State>& a, const std::vector<State>& b, double tol);

}  // namespace vibromap
