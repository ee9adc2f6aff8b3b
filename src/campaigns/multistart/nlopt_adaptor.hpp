#pragma once
// Internal to the multistart campaign. The NLopt adaptor: runs LN_BOBYQA, LN_COBYLA, LN_SBPLX, LD_SLSQP or LD_MMA (Steven G.
// Johnson, The NLopt nonlinear-optimization package, https://github.com/stevengj/nlopt) on a
// TrackedObjective in the scaled variables u in [0, 1]^n. NLopt's header stays in
// nlopt_adaptor.cpp: nothing outside this campaign sees it.
//
// Feasibility (the regime kept):
//  - cobyla, slsqp, mma take the regime as one inequality constraint c(u) <= 0 with
//    c = Evaluation::violation, a feasibility measure that is continuous inside one regime
//    (the stability margin max|mu| - 1 of the kept orbit) and jumps to >= 1 outside it
//    (point_objective.hpp). The objective they see at an infeasible point is its value when
//    finite (k_con of another regime), else the barrier.
//  - bobyqa and sbplx take bounds only: an infeasible point gets the barrier value
//    LocalOptions::barrier + violation (default 1e10 + c), finite because BOBYQA's quadratic
//    model cannot take HUGE_VAL; the added violation still ranks infeasible points.
// Gradients (slsqp, mma): forward differences in u with LocalOptions::fd_step (fd_gradient),
// for the objective and the constraint from the same cached stencil.
// Stopping: xtol_rel is given to NLopt both as xtol_rel and as xtol_abs on u (a fraction of
// the box: u near 0 would make a purely relative test far too tight), ftol_rel as is,
// max_time as maxtime; max_evaluations is enforced by the tracker, which counts solves (not
// cache hits) and ends the run with nlopt_force_stop, reported as "MAXEVAL_REACHED".

#include <span>

#include "vibromap/core/optimise/local_optimiser.hpp"

namespace vibromap {

// Runs the NLopt algorithm `algorithm` (not gradient_projection) from scaled u0. Throws
// std::invalid_argument for gradient_projection, std::runtime_error when NLopt refuses the
// set-up (a bug, not a result).
StopReason run_nlopt(TrackedObjective& f, std::span<const double> u0, Algorithm algorithm);

}  // namespace vibromap
