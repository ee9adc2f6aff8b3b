#pragma once
// Solves one parameter point end to end: integrate from the initial state until the
// stroboscopic samples repeat (or the budget runs out), measure the impacts of the steady
// motion and classify its regime.
//
// Steady state: y_j = y(jT) are compared with y_{j-n} for n = 1..n_max in a scaled max-norm
// (positions over D + |x|, velocities over omega (D + |x|)); the regime's period is the least
// n for which ||y_i - y_{i-n}|| <= steady_tol holds for n consecutive samples. steady_tol
// defaults to 100 * rtol: an adaptive integrator's step-size jitter shows in the samples, so
// the test must not be tighter than the integration (docs/numerics.md).

#include <chrono>
#include <complex>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "vibromap/core/analysis/point/fragility.hpp"
#include "vibromap/core/analysis/point/impact.hpp"
#include "vibromap/core/analysis/point/regime.hpp"
#include "vibromap/core/integrate/integrator.hpp"
#include "vibromap/core/model/parameters.hpp"

namespace vibromap {

// How the steady motion is found.
enum class SteadyMethod {
  follow,     // the default: the motion the initial state settles into, as brute-force
              // integration from it finds it. The state is integrated at the scene's
              // tolerance (the same path as integrate); Newton's method on the stroboscopic map
              // proposes a stable orbit, and the answer is that orbit only once the state is
              // seen closing in on it as the orbit's linearisation predicts; otherwise
              // integration goes on until the samples repeat, as integrate does
  shooting,   // faster, and a different question: some stable periodic orbit near the end of a
              // short, loosely integrated transient (Newton with the monodromy matrix from the
              // variational equations; falls back to integrate when Newton fails or the orbit
              // is unstable). Where attractors coexist it may not be the motion from the
              // initial state; maps made this way say so
  integrate,  // brute force: integrate until the stroboscopic samples repeat
};
std::string to_string(SteadyMethod m);

struct AnalysisOptions {
  SteadyMethod steady = SteadyMethod::follow;  // steady-state method, follow | shooting | integrate
  int transient_periods = 10;  // shooting: periods integrated before Newton starts (tripled, twice, while it fails), -
  double newton_tol = 0.0;     // shooting: scaled residual ||P^n(y) - y|| to stop at; 0 = auto: 10 * rtol, -
  int newton_max_iterations = 20;  // shooting: Newton iterations before giving up, -
  bool lyapunov = false;       // estimate the largest Lyapunov exponent when no period is found
  int lyapunov_periods = 400;  // periods over which the Lyapunov exponent is averaged (after a quarter as many to align), -
  int n_max = 8;               // largest period looked for, in forcing periods, -
  long max_periods = 2000;     // budget of forcing periods to reach steady state, -
  double steady_tol = 0.0;     // steady-state tolerance (scaled max-norm); 0 = auto: 100 * rtol (rk4: 1e-9), -
  int chatter_impacts = 5;     // impacts per forcing period from which the motion is called chatter, -
  double hertz_limit = 0.05;   // z_max / R* above which Hertz theory is flagged as invalid, -
  double soft_kcon = 10.0;     // a motion is soft when periodic with impacts, stable, Hertz-valid and
                               // k_con <= this (is_soft, regime.hpp), -
  int trajectory_periods = 0;  // after steady state, integrate and keep this many periods (0: none), -
  int trajectory_samples = 2000;  // uniform samples per forcing period in a kept trajectory, -
  double fragility = 0.0;      // size of the perturbations of the initial state also followed to their steady
                               // state, in motion scales (fragility.hpp); 0: off, -
  int fragility_states = 4;    // perturbed initial states followed when fragility > 0 (fixed directions), -
};

// The largest budgets AnalysisOptions takes (each of these periods costs tens of steps at least).
inline constexpr long kMaxPeriodBudget = 100'000'000;   // max_periods
inline constexpr int kMaxTransientPeriods = 1'000'000;  // transient_periods (tripled twice at most)
inline constexpr int kMaxLyapunovPeriods = 10'000'000;  // lyapunov_periods

std::string validate(const AnalysisOptions& o);

enum class SolveStatus {
  ok,              // steady motion found and classified
  budget,          // the period or step budget ran out (regime unresolved, non-periodic or chatter)
  failed,          // numerical failure; see message
  invalid_input,   // the parameters or options are invalid; see message
};
std::string to_string(SolveStatus s);

// One sample of a kept trajectory (physical coordinates).
struct TrajectorySample {
  double t;        // time since the start of the kept window, s
  double x1, x2;   // displacements, m
  double v1, v2;   // velocities, m/s
  double Fc;       // contact force, N
  double F;        // external force, N
};

// What one phase of a point's solve cost: seconds (steady_clock) and right-hand side evaluations.
struct PhaseCost {
  double seconds = 0.0;
  long rhs_evals = 0;
};

// Where a point's solve went, phase by phase: the profile of a map (tests/benchmarks/profile_map.py).
// The phases and the setup before them make up wall_s; their evaluations make up counters.rhs_evals.
struct PhaseTimes {
  PhaseCost transient;  // the transients integrated before each shooting attempt
  PhaseCost newton;     // shooting: Newton on the period map, the follow checks, the cycle measured
  PhaseCost integrate;  // brute force: the motion followed until it repeats or the budget ends
  PhaseCost floquet;    // brute force's orbit: the Newton iterations that give its multipliers
  PhaseCost classify;   // the motion classified (chaos, by its Lyapunov exponent, included), its
                        // open contact settled and its impacts measured
};

// Adds what its scope costs to a phase: the seconds it lasts and the evaluations `evals()`
// counts over it.
template <class Evals>
class PhaseClock {
 public:
  PhaseClock(PhaseCost& cost, Evals evals)
      : cost_(cost), evals_(evals), first_(evals()), start_(std::chrono::steady_clock::now()) {}
  ~PhaseClock() {
    cost_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    cost_.rhs_evals += evals_() - first_;
  }
  PhaseClock(const PhaseClock&) = delete;
  PhaseClock& operator=(const PhaseClock&) = delete;

 private:
  PhaseCost& cost_;
  Evals evals_;
  long first_;
  std::chrono::steady_clock::time_point start_;
};

struct PointSummary {
  SolveStatus status = SolveStatus::invalid_input;
  std::string message;          // why, when status != ok
  Regime regime;
  double T = 0.0;               // forcing period, s
  double T_con = 0.0;           // duration of the longest impact of the steady motion, s
  double k_con = 0.0;           // T / T_con (0 without impacts), -
  double F_max = 0.0;           // largest peak contact force, N
  double z_max = 0.0;           // largest peak penetration, m
  double z_ratio = 0.0;         // largest z_max / R*, -
  bool hertz_valid = true;      // z_ratio <= hertz_limit
  bool soft = false;            // is_soft (regime.hpp): periodic with impacts, stable, Hertz-valid, k_con <= soft_kcon
  std::vector<Impact> impacts;  // impacts of one steady cycle (nT), in time order
  double steady_residual = 0.0; // scaled ||y_j - y_{j-n}|| at the end (shooting: Newton residual; NaN where
                                // never computed: fewer than two period ends), -
  SteadyMethod steady_method = SteadyMethod::integrate;  // what produced the answer: follow (Newton's orbit, seen
                                                        // reached from the initial state), shooting or integrate
  int newton_iterations = 0;    // shooting: Newton iterations spent (0 when not used)
  // Floquet multipliers of the periodic orbit (eigenvalues of the monodromy matrix over nT);
  // empty when not computed. stable: 1 all |mu| < 1, 0 some |mu| > 1, -1 unknown.
  std::vector<std::complex<double>> floquet;
  int stable = -1;
  double lyapunov = std::numeric_limits<double>::quiet_NaN();  // largest Lyapunov exponent, 1/s (when asked)
  long periods = 0;             // forcing periods integrated
  IntegrationCounters counters;
  double wall_s = 0.0;          // solve time, s
  PhaseTimes phases;            // where wall_s went
  Eigen::Vector4d final_state = Eigen::Vector4d::Zero();  // (x1, x2, v1, v2) at the last period end
  std::vector<TrajectorySample> trajectory;  // only when trajectory_periods > 0
  Fragility fragility;          // analysis.fragility > 0: what perturbations of the initial state reach
};

struct PointOptions {
  IntegratorOptions integrator;
  AnalysisOptions analysis;
};

PointSummary solve_point(const Parameters& p, const PointOptions& options);

// What perturbations of p's initial state reach, against `own` (solve_point's answer for p):
// fragility.hpp. Not assessed (size 0) when analysis.fragility is 0 or own is invalid input.
// solve_point calls it when analysis.fragility > 0.
Fragility assess_fragility(const Parameters& p, const PointOptions& options, const PointSummary& own);

// The tolerances solve_point works to when the scene leaves them automatic (0): the
// steady-state test's (100 rtol; rk4 1e-9) and Newton's (10 rtol).
double steady_tolerance(const PointOptions& o);
double newton_tolerance(const PointOptions& o);

// The cycle of n periods through the orbit point y (physical (x1, x2, v1, v2) at a period
// start) measured as solve_point measures the orbit it finds: impacts at a tenth of the
// tolerance, regime, T_con, k_con, F_max, z_ratio. Floquet multipliers are not computed.
// status is failed when the integration fails, else ok.
PointSummary measure_orbit(const Parameters& p, const PointOptions& options, const Eigen::Vector4d& y, int n);

}  // namespace vibromap
