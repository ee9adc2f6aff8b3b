#pragma once
// Gradient projection with constraint-residual correction: the source paper's optimiser,
// written here (it names the method, not its details; this is our interpretation, after
// J. B. Rosen, "The gradient projection method for nonlinear programming, Part II:
// nonlinear constraints", J. SIAM 9 (1961) 514-532).
//
// It works in the scaled variables u in [0, 1]^n (box.hpp) from a feasible seed, on a
// TrackedObjective (so it shares the NLopt adaptor's cache, budget and best-feasible rule):
//
//   1. gradient: forward differences of the value and of the violation c (<= 0 feasible)
//      in u, step fd_step, from the same stencil (fd_gradient);
//   2. direction: d = -grad f with the components pushing out of the box at an active bound
//      set to 0 (those variables are held). When the step about to be taken is predicted to
//      cross the regime boundary (c + step n . d/|d|_inf > 0, n = grad c restricted to the
//      variables not held), d is projected on the tangent space of both together,
//      d -= (d . n / |n|^2) n (Rosen's projection), kept when it is still a descent direction;
//   3. line search: the trial u + s, s = step d/|d|_inf (step = the largest change of any
//      scaled variable), projected on the box. A trial that leaves the feasible regime is
//      corrected back toward feasibility (the constraint-residual correction): while its
//      violation is continuous (c < 1: the kept regime, unstable or beyond the Hertz limit),
//      by Rosen's restoration step s -= (c(trial) + restore_margin) grad c / |grad c|^2 with
//      grad c from step 1 (at most max_restorations times); otherwise (another regime: c
//      jumps) to 90 % of the crossing the linearised residual c(u) + grad c . s predicts,
//      when that lies inside the step, else by halving the step toward the last feasible
//      point u; at most max_corrections corrections in all. A feasible trial is accepted
//      under Armijo's rule f(trial) <= f(u) + armijo grad f . (trial - u); otherwise the step
//      is halved and the trial repeated (backtracking);
//   4. an accepted step doubles the next step's length (at most max_step); the run stops
//      when an accepted step moves every variable by less than xtol_rel ("XTOL_REACHED"),
//      changes f by less than ftol_rel |f| ("FTOL_REACHED"), when backtracking shrinks the
//      step below xtol_rel ("XTOL_REACHED"), when the projected gradient is zero
//      ("GRADIENT_ZERO"), or when the tracker's budget is spent.
//
// The iterate is always feasible, so the best point is one of its iterates (or a better
// feasible stencil point the tracker saw).

#include <span>

#include "vibromap/core/optimise/local_optimiser.hpp"

namespace vibromap {

struct GradientProjectionOptions {
  double armijo = 1e-4;          // sufficient-decrease constant of the line search, -
  int max_corrections = 6;       // corrections toward feasibility per trial point, -
  int max_restorations = 2;      // of which Rosen restoration steps along -grad c, -
  double restore_margin = 1e-3;  // a restoration aims at c = -restore_margin (inside the boundary), violation units
  double max_step = 0.5;         // largest step, fraction of the box, -
};

// Runs from scaled u0 with the tracker's LocalOptions (xtol_rel, ftol_rel, initial_step,
// fd_step; budget in the tracker).
StopReason run_gradient_projection(TrackedObjective& f, std::span<const double> u0,
                                   const GradientProjectionOptions& options = {});

}  // namespace vibromap
