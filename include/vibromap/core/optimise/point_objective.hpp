#pragma once
// The physics objective of `vibromap optimise`: one point solved by solve_point with the
// scene's options (the same solver as `vibromap run`), the regime kept as a constraint.
//
// Value (minimised): k_con (min_k_con), -T_con of impact `impact` of the steady cycle in time
// order (max_T_con), or F_max (min_F_max); NaN where undefined (no impact, no such impact).
//
// Feasibility measure, Evaluation::violation (<= 0 feasible), in bands so that a constrained
// algorithm sees "how far" a point is from the kept regime:
//   (-1, 0]  the kept regime, its orbit stable: max|mu| - 1 (the stability margin, continuous
//            in the parameters, reaching 0 where a Floquet multiplier leaves the unit circle);
//            0 when stability is unknown and the rule is if_known; -1 when the rule is ignored
//   (0, 1)   the kept regime but its orbit unstable: min(max|mu| - 1, 0.9); or stability unknown
//            when the rule is `required` (0.5)
// With OptimiseOptions::hertz_valid, a point of the kept regime that passes the stability rule
// has the Hertz margin z_ratio / hertz_limit - 1 as its violation instead of the stability
// margin (continuous; <= 0 where Hertz theory holds, capped at 0.9). One margin, not the
// larger of the two: their maximum has a kink where they cross, which spoils the
// finite-difference gradients of the constraint (slsqp, mma, gradient_projection). The
// stability margin of a damped orbit barely moves (|mu| ~ 0.97 at xi = 0.01) until a
// bifurcation, which then shows as a change of regime.
//   [1, 2)   another periodic regime (n,k): 1 + d/(1 + d), d = |n - n0| + |k - k0|
//   2        no periodic motion (chatter, no contact, permanent contact, non-periodic,
//            unresolved), or the objective undefined at a point of the kept regime
//   3        a failed solve (kFailedViolation)
// With no regime to keep (regime "any"), every solved point with the objective defined has
// violation -1 (with the stability rule still applied to periodic orbits).
// A point is feasible when violation <= 0 and the value is finite.
//
// With OptimiseOptions::min_soft_fraction > 0 (robust softness), a point that
// passes every constraint above is also censused (census_point with the scene's [census]
// options, K initial states) and must have soft_fraction >= min_soft_fraction, the total basin
// fraction of its soft attractors (stable, Hertz-valid, k_con <= soft_kcon). Where it falls
// short, the violation is the shortfall min_soft_fraction - soft_fraction, in (0, 0.9] (the
// band of a kept regime that misses a secondary constraint, as an unstable orbit); a census
// that fails is a failed point (3). Where it holds, the point keeps the continuous margin
// above: soft_fraction is a count over K states, a step function of the parameters, whose
// finite differences would be 0 or a spike of 1/(K h). The census runs only at points that
// pass every other constraint (the others cannot become feasible by it), once per point (the
// TrackedObjective's cache), and never when min_soft_fraction is 0, which leaves every
// evaluation bit for bit as without the key.
// The value stays the optimised orbit's (the one solve_point finds, whose regime, stability and
// Hertz margin the constraints judge), not a census attractor's: so the constraint only removes
// points and never changes a value, the objective stays continuous (the census's list of
// attractors changes in jumps with its draws), and several soft attractors leave no doubt about
// which k_con is meant. Whether the optimised orbit itself holds the soft basin is reported by
// the best points' re-check (multistart.hpp, SoftCheck::orbit_fraction).
//
// Measures recorded with every evaluation: k_con, T_con (longest impact, s), F_max (N),
// max_multiplier (largest |Floquet multiplier|; NaN when not computed), z_ratio (z_max/R*);
// with min_soft_fraction > 0 also soft_fraction (NaN where the census was not run).

#include <span>
#include <string>
#include <vector>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/model/parameters.hpp"
#include "vibromap/core/optimise/objective.hpp"
#include "vibromap/core/optimise/optimise_options.hpp"

namespace vibromap {

class PointObjective final : public Objective {
 public:
  // base: the scene's parameters; the free ones (optimise.variables) are replaced per point.
  // census: the census of a point when optimise.min_soft_fraction > 0 (the scene's [census]).
  PointObjective(const Parameters& base, const PointOptions& options, const OptimiseOptions& optimise,
                 const CensusOptions& census = {});

  Evaluation evaluate(std::span<const double> x) override;
  std::vector<std::string> measure_names() const override;

  // The base parameters with the free ones set to x (Key::set: k2 / omega2 keep their form).
  Parameters parameters_at(std::span<const double> x) const;

 private:
  Parameters base_;
  PointOptions options_;
  OptimiseOptions optimise_;
  CensusOptions census_;
};

// The evaluation of a solved point under the rules above (the core of PointObjective, exposed
// for tests); hertz_limit is the solve's [analysis] hertz_limit.
Evaluation evaluate_summary(const PointSummary& s, const OptimiseOptions& o,
                            double hertz_limit = AnalysisOptions{}.hertz_limit);

// The soft-fraction constraint (see above) applied to an evaluation that passed every other
// constraint, from the census of its point; sets the soft_fraction measure (index
// kSoftFractionMeasure). For o.min_soft_fraction > 0 only.
inline constexpr std::size_t kSoftFractionMeasure = 5;
// A sum of basin fractions this far below a minimum is rounding (count/K summed), not short.
inline constexpr double kSoftFractionRounding = 1e-12;
void apply_soft_fraction(Evaluation& e, const CensusSummary& census, const OptimiseOptions& o);

// Largest |Floquet multiplier| of a summary, NaN when none was computed.
double max_multiplier(const PointSummary& s);

// A fresh solve of p for verification: options with rtol `rtol` (atol scaled with it, auto
// Newton and steady-state tolerances; rk4 replaced by dopri5, which has a tolerance), steady
// state by `method`, and `trajectory_periods` periods of trajectory kept.
PointSummary resolve_point(const Parameters& p, PointOptions options, SteadyMethod method, double rtol,
                           int trajectory_periods = 0);

}  // namespace vibromap
