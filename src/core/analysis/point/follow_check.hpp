#pragma once
// Internal to solve_point (point_solver.cpp): the check that the motion from the initial
// state heads for an orbit Newton found (analysis.steady = "follow").

#include "vibromap/core/analysis/point/shooting.hpp"
#include "vibromap/core/integrate/integrator.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap::detail {

inline constexpr double kShorterPeriodFactor = 100;  // P^d(y) = y within this many Newton tolerances

// Newton may converge to another stable orbit than the one the motion from the initial
// state is heading for (coexisting attractors). The transient is therefore integrated on,
// cycle by cycle, and compared with the orbit's linearisation over windows of 20 periods:
// with delta_0 its offset from the orbit at the same phase of the cycle and M the monodromy,
// the offset J cycles later is compared with M^J delta_0 (a spiral approach passes: M^J holds
// the rotation). One window that ends at any cycle, closing in and within 1 % of |delta_0| of
// the prediction, accepts the orbit; so do 2 rounds in a row (the windows that end at 20, 40,
// ... periods) within a quarter of |delta_0|. A round that moves away from the orbit refuses
// it; a round that neither follows nor moves away (still far, nonlinear) defers to the next,
// up to 6 rounds; undecided means refused, and brute force takes over.
// A transient that ends on the orbit (within Newton's tolerance, as close as Newton itself
// puts it) is on it: nothing to check (every no-contact cell at rest, a settled transient).
// model: the section's system; transient_end: the transient's end on it; sh: Newton's orbit of
// period n, found to tol; budget: the scene's integrator options (its rtol) with what is left
// of the run's step budget. counters accumulates the check's work.
bool transient_approaches(const Model& model, const State& transient_end, const ShootingResult& sh, int n, double tol,
                          const IntegratorOptions& budget, IntegrationCounters& counters);

}  // namespace vibromap::detail
