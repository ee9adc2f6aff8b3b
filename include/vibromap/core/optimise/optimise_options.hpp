#pragma once
// What `vibromap optimise` does: the objective, the regime kept as a constraint,
// the free parameters and their box, where the starts come from, and the local algorithm
// with its stopping rules. The [optimise] section of a scene (io/scene/) fills it; every
// field has a valid default except the free variables, which a scene must name.
//
// Scaled variables: each free parameter is mapped to u in [0, 1] over its box, linearly or in
// log (Young's moduli span seven decades). Every length below that is "a fraction of the box"
// is measured in u, so one tolerance serves E1 (Pa) and m2 (kg) alike.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vibromap/core/analysis/point/regime.hpp"
#include "vibromap/core/grid.hpp"
#include "vibromap/core/model/contact_law.hpp"
#include "vibromap/core/model/keys.hpp"

namespace vibromap {

// The quantity optimised.
enum class ObjectiveKind {
  min_k_con,  // minimise k_con = T / T_con of the longest impact (the softest impact)
  max_T_con,  // maximise T_con of one impact of the steady cycle (OptimiseOptions::impact)
  min_F_max,  // minimise the largest peak contact force
};
std::string to_string(ObjectiveKind k);                  // "min_k_con", "max_T_con", "min_F_max"
ObjectiveKind parse_objective_kind(std::string_view s);  // throws std::invalid_argument
const std::vector<ObjectiveKind>& all_objective_kinds();
std::string objective_quantity(ObjectiveKind k);         // "k_con", "T_con", "F_max"
double objective_sense(ObjectiveKind k);                 // +1 minimised, -1 maximised (value = sense * quantity)

// The local algorithms. The five NLopt ones run through the multistart campaign's NLopt adaptor;
// gradient_projection is ours (gradient_projection.hpp), the source paper's method.
enum class Algorithm {
  bobyqa,               // NLopt LN_BOBYQA: derivative-free, bounds only (regime by a barrier value)
  cobyla,               // NLopt LN_COBYLA: derivative-free, regime as an inequality constraint
  sbplx,                // NLopt LN_SBPLX: derivative-free (Subplex), bounds only (barrier value)
  slsqp,                // NLopt LD_SLSQP: gradients by finite differences, inequality constraint
  mma,                  // NLopt LD_MMA: gradients by finite differences, inequality constraint
  gradient_projection,  // projected gradient on the box with constraint-residual correction
};
std::string to_string(Algorithm a);              // the names above
Algorithm parse_algorithm(std::string_view s);   // throws std::invalid_argument
const std::vector<Algorithm>& all_algorithms();
bool takes_constraints(Algorithm a);  // cobyla, slsqp, mma: the regime is an NLopt inequality constraint

// How the stability of the kept regime's orbit counts.
enum class StabilityRule {
  if_known,  // an orbit found unstable (Floquet) is infeasible; unknown stability is accepted
  required,  // only an orbit known to be stable is feasible
  ignored,   // stability does not matter
};
std::string to_string(StabilityRule r);              // "if_known", "required", "ignored"
StabilityRule parse_stability_rule(std::string_view s);  // throws std::invalid_argument
const std::vector<StabilityRule>& all_stability_rules();

// One free parameter and its box. Any parameter key may be free (Key::is_parameter: a real key
// of [system], [contact] or [forcing]); a spring or damper freed in one form (k2 or omega2) keeps
// that form.
struct FreeVariable {
  Key key;                           // the parameter
  double min = 0.0;                  // lower bound, SI units
  double max = 0.0;                  // upper bound, SI units (> min; both > 0 on a log scale)
  AxisScale scale = AxisScale::lin;  // lin: u = (x - min)/(max - min); log: the same in log x

  std::string_view name() const { return key.info().name; }  // "E1", "omega2"
};

// Empty when usable, else what is wrong (not a parameter key, bounds not finite, not increasing
// or outside the key's range, a log scale with min <= 0).
std::string validate(const FreeVariable& v);

// One local optimisation (one start).
struct LocalOptions {
  double xtol_rel = 1e-4;       // stop when a step moves every scaled variable by less than this (NLopt xtol_rel and xtol_abs on u), -
  double ftol_rel = 1e-6;       // stop when a step changes the objective by less than this, relative; 0: off, -
  long max_evaluations = 200;   // point solves per start, finite-difference ones included (cache hits are free), -
  double max_time = 0.0;        // wall time per start, s; 0: no limit (a limit makes results depend on the machine)
  double initial_step = 0.1;    // first step, fraction of the box (NLopt initial_step, BOBYQA's rhobeg), -
  double fd_step = 1e-4;        // finite-difference step of gradients, fraction of the box, -
  double barrier = 1e10;        // bobyqa, sbplx: the objective given for an infeasible point (finite: BOBYQA needs it), -
};
std::string validate(const LocalOptions& o);

struct OptimiseOptions {
  ObjectiveKind objective = ObjectiveKind::min_k_con;  // what to optimise
  int impact = 0;                                      // max_T_con: index of the impact in the steady cycle, time order, -
  std::optional<Regime> regime = Regime{RegimeKind::periodic, 1, 1};  // the regime to keep; nullopt: any with an impact
  StabilityRule stability = StabilityRule::if_known;   // how the orbit's stability counts
  bool hertz_valid = true;                             // keep Hertz theory valid: z_max/R* <= [analysis] hertz_limit
                                                       // (false: an explicit choice; its answers are flagged Hertz-invalid)
  std::vector<FreeVariable> variables;                 // the free parameters (at least one)
  std::vector<Algorithm> algorithms = {Algorithm::bobyqa};  // each seed is started with each algorithm
  // The contact law as a categorical free variable: every seed and algorithm is started once with
  // each law listed, and the answer is the best over them all; empty: the scene's law.
  std::vector<ContactLawKind> laws;
  int seeds = 4;                                       // starts per algorithm: the best cells of the seeding map, -
  std::string map;                                     // seeding map (HDF5); empty: the scene's [sweep], else its point
  LocalOptions local;                                  // the local algorithm's stopping rules
  int best = 3;                                        // best distinct points re-solved and reported, -
  double verify_rtol = 1e-12;                          // rtol of the re-solves of the best points, -
  // Robust softness: a point is feasible only when its soft attractors (census.hpp:
  // stable, Hertz-valid, k_con <= soft_kcon) hold at least this basin fraction, by a census of
  // the point with the scene's [census] options. 0: off (no census is run, the optimiser is
  // exactly as without it), -
  double min_soft_fraction = 0.0;
  // The best points' re-check census draws max(this, 4 K) initial states (K: [census]
  // initial_conditions), independent of the optimiser's; only with min_soft_fraction > 0, -
  int soft_check_initial_conditions = 512;
};

// Empty when usable, else the first problem found.
std::string validate(const OptimiseOptions& o);

}  // namespace vibromap
