#include "vibromap/core/analysis/point/point_solver.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>
#include <stdexcept>
#include <cmath>

#include "vibromap/core/analysis/point/lyapunov.hpp"
#include "vibromap/core/analysis/point/section.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"
#include "vibromap/core/analysis/point/steady_state.hpp"
#include "vibromap/core/integrate/free_flight.hpp"
#include "vibromap/core/model/keys.hpp"
#include "follow_check.hpp"
#include "found_orbits.hpp"
#include "trajectory_recorder.hpp"

namespace vibromap {

std::string validate(const AnalysisOptions& o) {
  PointOptions options;
  options.analysis = o;
  const std::vector<std::string> r = refusals(Parameters{}, options, "analysis");
  return r.empty() ? std::string() : r.front();
}

std::string to_string(SolveStatus s) {
  switch (s) {
    case SolveStatus::ok: return "ok";
    case SolveStatus::budget: return "budget";
    case SolveStatus::failed: return "failed";
    case SolveStatus::invalid_input: return "invalid-input";
  }
  return "unknown";
}

namespace {

constexpr int kShootingCandidates = 3;       // periods tried by Newton, most promising first
constexpr double kNewtonTolFactor = 10.0;     // auto Newton tolerance, in units of rtol
constexpr int kTransientTries = 3;            // shooting: transients of t, 3t, 9t periods before brute force
// Following, the transient is brute force's own path, so a later try costs only its Newton
// search and check: orbits reached after a long wander (a (3,3) after 100-1000 periods) are
// then taken when the state closes in on them, before the samples repeat to steady_tol.
constexpr int kFollowTries = 5;               // follow: t, 3t, 9t, 27t, 81t periods
// The transient only has to bring Newton a start inside its basin: it is integrated at this
// relative tolerance (or the scene's, when looser). Contacts are still found exactly (closed-
// form free flight) and resolved to 1e-4; every Newton evaluation that decides the answer
// runs at the scene's tolerance. At the default rtol 1e-10 this makes the transient's
// contacts ~10x cheaper.
constexpr double kTransientRtol = 1e-4;
// The cycle of the orbit found by Newton is measured (T_con, F_max, ...) at a tenth of the
// scene's tolerance: one cycle costs ~1.6x more, and the reported values then carry the
// orbit's error alone rather than a second integration error of the same size on top.
constexpr double kMeasureRtolFactor = 0.1;
constexpr double kMeasureRtolFloor = 1e-13;  // never asks dopri5 for less than this
constexpr std::size_t kExtrapolationIterates = 7;  // samples used to extrapolate Newton's start

// Everything solve_point needs while it runs.
struct Run {
  const Model& model;
  const PointOptions& options;
  Integrator& integrator;
  State u;
  ImpactRecorder impacts;
  SteadyStateDetector steady;
  IntegrationCounters shooting;  // work done by Newton's method (its own integrators)
};

// solver.max_steps is the budget of the whole run: the main integrator's steps and those of
// every integrator Newton's method and its checks make. An auxiliary integrator gets what is
// left; the main one is told what the others spent (charge_shooting) before it goes on.
long shooting_steps(const Run& r) { return r.shooting.steps + r.shooting.rejected; }
long steps_left(const Run& r) {
  const IntegrationCounters& c = r.integrator.counters();
  return r.options.integrator.max_steps - c.steps - c.rejected - shooting_steps(r);
}
IntegratorOptions budgeted(const Run& r) {
  IntegratorOptions o = r.options.integrator;
  o.max_steps = std::max(0L, steps_left(r));  // 0: the integrator stops before its first step
  return o;
}
// Runs work() charging its seconds and right-hand side evaluations (the run's integrator's and
// Newton's) to phase; returns what work() returns.
template <class Work>
auto timed(PhaseCost& phase, const Run& r, Work work) {
  const PhaseClock clock(phase, [&r] { return r.integrator.counters().rhs_evals + r.shooting.rhs_evals; });
  return work();
}
void charge_shooting(Run& r) {
  r.integrator.set_max_steps(std::max(0L, r.options.integrator.max_steps - shooting_steps(r)));
}

// A contact still open when the steady state is found either belongs to the steady cycle
// (integrate on until it closes) or has lasted longer than the cycle (permanent contact).
bool settle_open_contact(Run& r, int n, long j) {
  const auto& open = r.impacts.open_impact();
  if (!open) return true;
  if (open->period_in <= j - n) return false;
  const long closed_before = r.impacts.total_impacts();
  for (int i = 0; i < n && r.impacts.total_impacts() == closed_before; ++i) {
    if (r.integrator.advance_period(r.u, r.impacts) != IntegrationStatus::ok) return false;
    r.impacts.on_period_end(r.integrator.period() - 1, r.u);
  }
  return r.impacts.total_impacts() > closed_before;
}

std::vector<Impact> impacts_since(const ImpactRecorder& rec, long first_period, long last_period) {
  std::vector<Impact> out;
  for (const Impact& im : rec.impacts())
    if (im.period_in >= first_period && im.period_in <= last_period) out.push_back(im);
  return out;
}

void measure_impacts(PointSummary& s, const Model& model, double hertz_limit) {
  for (const Impact& im : s.impacts) {
    s.T_con = std::max(s.T_con, im.T_con);
    s.F_max = std::max(s.F_max, im.F_max);
    s.z_max = std::max(s.z_max, im.z_max);
    s.z_ratio = std::max(s.z_ratio, im.z_ratio);
  }
  s.k_con = s.T_con > 0.0 ? model.period() / s.T_con : 0.0;
  s.hertz_valid = s.z_ratio <= hertz_limit;
  // A diverging integration (rk4 with too few steps on a violent impact) can overflow a
  // measure while the state stays finite: the point has failed, and says which measure.
  const std::pair<const char*, double*> measures[] = {
      {"T_con", &s.T_con}, {"F_max", &s.F_max}, {"z_max", &s.z_max}, {"z_ratio", &s.z_ratio}, {"k_con", &s.k_con}};
  std::string overflowed;
  for (const auto& [name, value] : measures)
    if (!std::isfinite(*value)) {
      overflowed.append(overflowed.empty() ? "" : ", ").append(name);
      *value = std::numeric_limits<double>::quiet_NaN();
    }
  if (overflowed.empty()) return;
  s.status = SolveStatus::failed;
  s.message = "non-finite " + overflowed + ": the integration diverged (a finer solver setting may not)";
  s.regime = {RegimeKind::failed, 0, 0};
  s.hertz_valid = false;
}

// The regime of an n-periodic motion whose cycle is the periods j-n+1 .. j.
void classify_cycle(PointSummary& s, Run& r, int n, long j) {
  if (!settle_open_contact(r, n, j)) {
    s.regime = {RegimeKind::permanent_contact, n, 0};
    return;
  }
  s.impacts = impacts_since(r.impacts, j - n + 1, j);
  const int k = static_cast<int>(s.impacts.size());
  RegimeKind kind = RegimeKind::periodic;
  if (k == 0) kind = RegimeKind::no_contact;
  else if (k >= r.options.analysis.chatter_impacts * n) kind = RegimeKind::chatter;
  s.regime = {kind, n, k};
}

// A non-periodic motion is chaotic when its largest Lyapunov exponent is clearly positive,
// else quasi-periodic (lyapunov.hpp).
void tell_chaos(PointSummary& s, Run& r) {
  const LyapunovEstimate e =
      largest_lyapunov(r.model, budgeted(r), r.u, r.options.analysis.lyapunov_periods, r.shooting);
  if (!e.ok) return;
  s.lyapunov = e.exponent;
  s.regime.kind = e.chaotic() ? RegimeKind::chaotic : RegimeKind::quasi_periodic;
}

// Budget ran out without a period: chatter if impacts are dense, permanent contact if a
// contact never ended, unresolved if still settling, otherwise non-periodic.
void classify_unsettled(PointSummary& s, Run& r) {
  const long last = r.integrator.period() - 1;
  s.impacts = impacts_since(r.impacts, last, last);
  const auto& open = r.impacts.open_impact();
  const long window = std::min<long>(r.options.analysis.n_max, last + 1);
  const auto recent = impacts_since(r.impacts, last - window + 1, last);
  RegimeKind kind = RegimeKind::non_periodic;
  if (open && open->period_in <= last - window && recent.empty())
    kind = RegimeKind::permanent_contact;
  else if (static_cast<long>(recent.size()) >= r.options.analysis.chatter_impacts * window)
    kind = RegimeKind::chatter;
  else if (r.steady.still_converging())
    kind = RegimeKind::unresolved;
  s.regime = {kind, 0, 0};
  if (kind == RegimeKind::non_periodic && r.options.analysis.lyapunov && r.options.integrator.method != Method::rk4)
    tell_chaos(s, r);
}

void record_trajectory(PointSummary& s, Run& r) {
  const int periods = r.options.analysis.trajectory_periods;
  detail::TrajectoryRecorder rec(r.model, r.integrator.period(), r.options.analysis.trajectory_samples, s.trajectory);
  rec.on_event({ContactEvent::Kind::exit, r.integrator.period(), 0.0, r.u});  // the first sample, t = 0
  for (int i = 0; i < periods; ++i)
    if (r.integrator.advance_period(r.u, rec) != IntegrationStatus::ok) break;
}

std::string check_inputs(const Parameters& p, const PointOptions& o) {
  std::string msg;
  for (const auto& e : validate(p)) msg += (msg.empty() ? "" : "; ") + e;
  for (const auto& e : {validate(o.integrator), validate(o.analysis)})
    if (!e.empty()) msg += (msg.empty() ? "" : "; ") + e;
  return msg;
}

bool shooting_enabled(const PointOptions& o) {
  return o.analysis.steady != SteadyMethod::integrate && o.integrator.method != Method::rk4;
}

ShootingOptions shooting_options(const PointOptions& o, int n) {
  ShootingOptions so;
  so.n = n;
  // Adaptive steps make the period map rough at the level of the integration error, so the
  // residual cannot be pushed much below rtol.
  so.tol = newton_tolerance(o);
  so.max_iterations = o.analysis.newton_max_iterations;
  return so;
}

void record_shooting(PointSummary& s, const ShootingResult& sh) {
  s.floquet = sh.multipliers;
  s.stable = sh.stable() ? 1 : 0;
}

bool follows(const PointOptions& o) { return o.analysis.steady == SteadyMethod::follow; }

// Following, the answer must be the attractor the motion from the initial state goes to:
// where attractors coexist, a transient at a looser tolerance may take another way, so the
// transient is then integrated at the scene's tolerance (brute force's path, step by step).
double transient_rtol(const PointOptions& o) {
  return follows(o) ? o.integrator.rtol : std::max(o.integrator.rtol, kTransientRtol);
}

double measure_rtol(double rtol) { return std::max(kMeasureRtolFactor * rtol, std::min(rtol, kMeasureRtolFloor)); }

// Integrates one cycle of n periods from the orbit point y at measure_rtol, observing its
// impacts, and classifies it.
bool measure_cycle(PointSummary& s, Run& r, const State& y, int n) {
  r.u = y;
  r.integrator.reset(r.u);
  r.impacts.clear();
  const long first = r.integrator.period();
  charge_shooting(r);
  r.integrator.set_rtol(measure_rtol(r.options.integrator.rtol));
  bool ok = true;
  for (int i = 0; i < n && ok; ++i) {
    ok = r.integrator.advance_period(r.u, r.impacts) == IntegrationStatus::ok;
    if (ok) r.impacts.on_period_end(r.integrator.period() - 1, r.u);
  }
  r.integrator.set_rtol(r.options.integrator.rtol);
  if (ok) classify_cycle(s, r, n, first + n - 1);
  return ok;
}

// The Poincare section shooting works on (section.hpp): the system whose forcing periods
// start at the section's phase, and the transient's end carried there.
struct ShootingSection {
  Model model;
  double phase = 0.0;  // s in [0, T): the section's phase in the forcing period
  State transient_end;
};

// Newton's starting point for period n: the fixed point of P^n extrapolated from the
// transient's samples n periods apart (extrapolate_fixed_point), which sees the centre of
// a spiral approach; the last sample when there are too few.
State initial_guess(const Run& r, int n) {
  const auto& samples = r.steady.samples();
  std::vector<State> iterates;
  for (int i = static_cast<int>(samples.size()) - 1; i >= 0 && iterates.size() < kExtrapolationIterates; i -= n)
    iterates.insert(iterates.begin(), samples[static_cast<std::size_t>(i)]);
  if (iterates.empty() || !(iterates.back() - r.u).isZero()) return r.u;
  return extrapolate_fixed_point(iterates, StateScale(r.model));
}

// The section shooting works on: the quiet phase of the transient's recent impacts. All the
// impacts the recorder keeps (the last 2 n_max + 2 periods) count: a single period of a
// transient may have none, while they cluster around the phases of the orbit's.
std::optional<ShootingSection> choose_section(Run& r) {
  const long last = r.integrator.period() - 1;
  const double phase = section_phase(r.impacts.impacts(), r.impacts.open_impact(), 0, last, r.model.period());
  if (phase == 0.0) return ShootingSection{r.model, 0.0, r.u};
  const std::optional<State> end = state_at_phase(r.model, budgeted(r), r.u, phase, r.shooting);
  if (!end) return std::nullopt;
  return ShootingSection{shifted_model(r.model, phase), phase, *end};
}

// A state at phase 0 carried to the section, and back.
std::optional<State> to_section(Run& r, const ShootingSection& section, const State& u) {
  if (section.phase == 0.0) return u;
  return state_at_phase(r.model, budgeted(r), u, section.phase, r.shooting);
}
std::optional<State> from_section(Run& r, const ShootingSection& section, const State& y) {
  if (section.phase == 0.0) return y;
  return state_at_phase(section.model, budgeted(r), y, r.model.period() - section.phase, r.shooting);
}

// Newton for period n on the section: from the transient's end, then (when that fails) from
// the fixed point extrapolated from the transient; the orbit reduced to its least period.
// Not converged, or unstable, means no orbit.
ShootingResult find_orbit(PointSummary& s, Run& r, const ShootingSection& section, ShootingOptions& so,
                          const KnownOrbit& known) {
  ShootingResult sh = shoot(section.model, budgeted(r), section.transient_end, so, r.shooting, known);
  s.newton_iterations += sh.iterations;
  if (!sh.converged && !sh.known) {
    const std::optional<State> guess = to_section(r, section, initial_guess(r, so.n));
    if (!guess) return sh;
    sh = shoot(section.model, budgeted(r), *guess, so, r.shooting, known);
    s.newton_iterations += sh.iterations;
  }
  if (!sh.converged || !sh.stable()) return sh;
  if (const int d = least_period(section.model, budgeted(r), sh.y, so.n, detail::kShorterPeriodFactor * so.tol, r.shooting);
      d != so.n) {
    so.n = d;
    sh = shoot(section.model, budgeted(r), sh.y, so, r.shooting, known);
    s.newton_iterations += sh.iterations;
  }
  return sh;
}

// Shooting from the end of the transient: Newton for the candidate periods, most promising
// first; the first stable orbit that the transient is heading for is the answer. An
// unstable orbit is not an attractor, and no accepted orbit means brute-force integration
// takes over.
bool solve_by_shooting(PointSummary& s, Run& r) {
  if (steps_left(r) <= 0) return false;
  const std::optional<ShootingSection> section = choose_section(r);
  if (!section) return false;
  detail::FoundOrbits found(section->model);
  for (int n : r.steady.candidate_periods(kShootingCandidates)) {
    if (steps_left(r) <= 0) return false;
    ShootingOptions so = shooting_options(r.options, n);
    const ShootingResult sh =
        find_orbit(s, r, *section, so, [&](const State& y) { return found.near(so.n, y); });
    if (!sh.converged || found.contains(so.n, sh.y, detail::kShorterPeriodFactor * so.tol)) continue;
    found.add(so.n, sh.y, sh.multipliers);
    if (!sh.stable()) continue;
    if (follows(r.options) &&
        !detail::transient_approaches(section->model, section->transient_end, sh, so.n, so.tol, budgeted(r), r.shooting))
      continue;
    const std::optional<State> y = from_section(r, *section, sh.y);
    if (!y || !measure_cycle(s, r, *y, so.n)) return false;
    s.status = SolveStatus::ok;
    s.steady_method = r.options.analysis.steady;
    s.steady_residual = sh.residual;
    record_shooting(s, sh);
    return true;
  }
  return false;
}

// A motion that never reaches contact is the linear system's, decided in closed form without
// integrating: from the initial state it tends to the forcing's T-periodic response, which
// is the (1,0) orbit, with Floquet multipliers e^{lambda_j T} (the eigenvalues of e^{A T}).
// Taken only where the closed form is the integrator's own (hybrid) and the motion certainly
// never enters contact (FreeFlight::never_enters, a bound on z) and tends to the orbit (every
// multiplier inside the unit circle); otherwise the motion is followed as always. The cell
// then integrates nothing: periods, steps and Newton iterations are 0.
bool solve_without_contact(PointSummary& s, Run& r) {
  if (r.options.integrator.method != Method::hybrid) return false;
  const std::shared_ptr<const FreeFlight> flight = free_flight_of(r.model);
  if (!flight->valid() || !flight->never_enters(0.0, r.u)) return false;
  const double T = r.model.period();
  const std::vector<std::complex<double>>& mu = flight->multipliers();
  if (!(std::abs(mu.front()) < 1.0)) return false;
  const State y = flight->orbit(0.0);
  s.status = SolveStatus::ok;
  s.steady_method = r.options.analysis.steady;
  s.regime = {RegimeKind::no_contact, 1, 0};
  s.steady_residual = StateScale(r.model).distance(flight->propagate(0.0, y, T), y);
  s.floquet = mu;
  s.stable = 1;
  r.u = y;
  r.integrator.reset(r.u);
  return true;
}

// After brute force found an n-periodic motion: a few Newton iterations from it give the
// Floquet multipliers (stability) without changing the answer.
void add_stability(PointSummary& s, Run& r) {
  const int n = std::max(1, s.regime.n);
  const ShootingResult sh = shoot(r.model, budgeted(r), r.u, shooting_options(r.options, n), r.shooting);
  s.newton_iterations += sh.iterations;
  if (sh.converged) record_shooting(s, sh);
}

// The steady-state test's residual; NaN when it was never computed (fewer than two period ends
// to compare, as with analysis.max_periods = 1), where the detector holds infinity.
double residual_of(const SteadyStateDetector& steady) {
  const double r = steady.residual();
  return std::isfinite(r) ? r : std::numeric_limits<double>::quiet_NaN();
}

void fail(PointSummary& s, IntegrationStatus status, long period) {
  s.status = SolveStatus::failed;
  s.message = to_string(status) + " in forcing period " + std::to_string(period);
  s.regime = {RegimeKind::failed, 0, 0};
}

// Integrates (more) periods until the motion repeats or the budget runs out, then classifies.
void solve_by_integration(PointSummary& s, Run& r, ObserverList& observers, PeriodRun run) {
  const long budget = r.options.analysis.max_periods;
  if (run.status == IntegrationStatus::ok && !run.stopped && r.integrator.period() < budget)
    run = timed(s.phases.integrate, r,
                [&] { return integrate_periods(r.integrator, r.u, budget - r.integrator.period(), observers); });
  if (run.status == IntegrationStatus::step_underflow || run.status == IntegrationStatus::non_finite) {
    fail(s, run.status, r.integrator.period());
  } else if (run.stopped) {
    s.status = SolveStatus::ok;
    timed(s.phases.classify, r, [&] { classify_cycle(s, r, r.steady.period_n(), r.steady.detected_at()); });
    s.steady_residual = residual_of(r.steady);
    if (r.options.integrator.method != Method::rk4) timed(s.phases.floquet, r, [&] { add_stability(s, r); });
  } else {
    s.status = SolveStatus::budget;
    s.message = run.status == IntegrationStatus::step_limit ? "step budget (solver.max_steps) exhausted"
                                                            : "no period <= n_max within analysis.max_periods";
    timed(s.phases.classify, r, [&] { classify_unsettled(s, r); });
    s.steady_residual = residual_of(r.steady);
  }
}

}  // namespace

double steady_tolerance(const PointOptions& o) {
  if (o.analysis.steady_tol > 0.0) return o.analysis.steady_tol;
  return o.integrator.method == Method::rk4 ? 1e-9 : 100.0 * o.integrator.rtol;
}

double newton_tolerance(const PointOptions& o) {
  return o.analysis.newton_tol > 0.0 ? o.analysis.newton_tol : kNewtonTolFactor * o.integrator.rtol;
}

PointSummary measure_orbit(const Parameters& p, const PointOptions& options, const Eigen::Vector4d& y, int n) {
  const auto start = std::chrono::steady_clock::now();
  PointSummary s;
  s.T = p.period();
  const Model model(p);
  const auto integrator = make_integrator(model, options.integrator);
  Run r{model, options, *integrator, Model::to_internal(y), ImpactRecorder(model, 2L * n + 2),
        SteadyStateDetector(model, n, steady_tolerance(options)), {}};
  if (measure_cycle(s, r, Model::to_internal(y), n)) {
    s.status = SolveStatus::ok;
  } else {
    s.status = SolveStatus::failed;
    s.message = "the orbit's cycle could not be integrated";
    s.regime = {RegimeKind::failed, 0, 0};
  }
  measure_impacts(s, model, options.analysis.hertz_limit);
  s.periods = integrator->period();
  s.counters = integrator->counters();
  s.final_state = Model::to_physical(r.u);
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

std::string to_string(SteadyMethod m) {
  switch (m) {
    case SteadyMethod::follow: return "follow";
    case SteadyMethod::shooting: return "shooting";
    case SteadyMethod::integrate: break;
  }
  return "integrate";
}

PointSummary solve_point(const Parameters& p, const PointOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  PointSummary s;
  s.T = p.period();
  if (std::string err = check_inputs(p, options); !err.empty()) {
    s.status = SolveStatus::invalid_input;
    s.message = err;
    s.regime = {RegimeKind::failed, 0, 0};
    return s;
  }
  const Model model(p);
  const auto integrator = make_integrator(model, options.integrator);
  Run r{model, options, *integrator, Model::to_internal(p.initial_state()),
        ImpactRecorder(model, 2L * options.analysis.n_max + 2),
        SteadyStateDetector(model, options.analysis.n_max, steady_tolerance(options)), {}};
  integrator->reset(r.u);
  ObserverList observers{&r.impacts, &r.steady};

  // Shooting: a short transient, then Newton; brute force continues where it does not settle.
  PeriodRun run;
  bool solved = false;
  if (shooting_enabled(options)) {
    solved = timed(s.phases.classify, r, [&] { return solve_without_contact(s, r); });
    long transient = options.analysis.transient_periods;
    const int tries = follows(options) ? kFollowTries : kTransientTries;
    for (int attempt = 0; attempt < tries && !solved; ++attempt, transient *= 3) {
      const long periods = std::min(transient, options.analysis.max_periods) - integrator->period();
      if (periods <= 0) break;
      charge_shooting(r);
      integrator->set_rtol(transient_rtol(options));
      run = timed(s.phases.transient, r, [&] { return integrate_periods(*integrator, r.u, periods, observers); });
      // Shooting, its measurement and brute force, when it takes over, integrate at the
      // scene's tolerance; a steady state seen at the transient's tolerance is not one there.
      integrator->set_rtol(options.integrator.rtol);
      const bool settled = run.stopped;
      run.stopped = false;
      if (run.status != IntegrationStatus::ok) break;
      solved = timed(s.phases.newton, r, [&] { return solve_by_shooting(s, r); });
      if (settled) break;  // Newton had the best start a transient can give
    }
  }
  charge_shooting(r);
  if (!solved) solve_by_integration(s, r, observers, run);

  timed(s.phases.classify, r, [&] { measure_impacts(s, model, options.analysis.hertz_limit); });
  s.soft = is_soft(s.regime, s.stable, s.hertz_valid, s.k_con, options.analysis.soft_kcon);
  if (options.analysis.trajectory_periods > 0 && s.status != SolveStatus::failed) record_trajectory(s, r);
  s.periods = integrator->period();
  s.counters = integrator->counters();
  s.counters += r.shooting;
  s.final_state = Model::to_physical(r.u);
  if (options.analysis.fragility > 0.0) s.fragility = assess_fragility(p, options, s);
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace vibromap
