#pragma once
// Integrators of the vibro-impact equations over whole forcing periods, with contact entry
// and exit as located events.
//
// Contract: advance_period() takes the state u at the start of a forcing period (local time
// tau = 0) and returns it at tau = T exactly, so stroboscopic samples need no interpolation
// and time is always measured from the start of the current period (docs/numerics.md: absolute time
// loses digits). Every accepted step is shown to the Observer with its dense output; every
// contact entry and exit is shown as a ContactEvent at its located time. The integrator
// stops early only on a numerical failure or the step budget, reported as a status, never
// by an exception; the one exception is a stop asked from outside: inside a CancelScope whose
// flag is set (cancel.hpp) the step loops throw Cancelled within kCancelPollSteps steps.
//
// Methods:
//  - hybrid (default): between impacts the system is linear with harmonic forcing, so the
//    free flight is propagated in closed form (FreeFlight: modal matrix exponential plus the
//    harmonic particular solution) and contact entry is found on that closed form with steps
//    that provably cannot pass a root; only the contact phase is integrated, by dopri5.
//  - dopri5: Dormand-Prince 5(4) with Shampine's 4th-order dense output and Hairer's PI step
//    control (Hairer, Norsett, Wanner, "Solving ODEs I", 2nd ed., II.4-II.6). The contact
//    mode (force on/off) is frozen within a step, entry/exit are located on the dense output
//    and the step is redone to end exactly at the event, so no step straddles the kink of
//    z^(3/2) at z = 0 and the method keeps its order.
//  - rk4: the source paper's classical fixed-step RK4 with the contact force always in the
//    right-hand side; events are located afterwards on a cubic Hermite interpolant. Kept as
//    the reference method: its order collapses at contact and it is unstable on a rigid
//    contact for h > ~T/2^11 (docs/numerics.md).

#include <memory>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "vibromap/core/integrate/observer.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap {

enum class Method { hybrid, dopri5, rk4 };
std::string to_string(Method m);

struct IntegratorOptions {
  Method method = Method::hybrid;  // integration method, hybrid | dopri5 | rk4
  double rtol = 1e-10;             // hybrid, dopri5: relative local error tolerance, -
  double atol = 1e-13;             // hybrid, dopri5: absolute tolerance on x1 and z (m); on v1 and w: atol*omega (m/s)
  double max_step = 1.0 / 32.0;    // hybrid, dopri5: largest step, as a fraction of the forcing period T, -
  int rk4_steps = 16384;           // rk4: steps per forcing period, -
  long max_steps = 20'000'000;     // budget of steps (accepted + rejected) for the whole run, - (<= kMaxStepBudget)
};

// The largest step budget: a step costs about 1-2 us, so 1e10 steps are some hours of one core.
inline constexpr long kMaxStepBudget = 10'000'000'000;

// Returns an empty string when the options are valid, else what is wrong.
std::string validate(const IntegratorOptions& o);
// The rule that combines the solver's keys (validate() applies it after each key's own check):
// one forcing period must fit in the step budget at the largest step allowed (max_step, a
// fraction of T; rk4: rk4_steps). A smaller step spends any point's whole budget in its first
// period of contact: minutes for a map or an optimisation that end unresolved. Empty when it holds.
std::string step_budget_error(const IntegratorOptions& o);

enum class IntegrationStatus {
  ok,              // period completed
  step_limit,      // the step budget ran out
  step_underflow,  // the step size fell below 1e-13 T: the problem cannot be resolved
  non_finite,      // the state became NaN or infinite
};
std::string to_string(IntegrationStatus s);

struct IntegrationCounters {
  long steps = 0;      // accepted steps
  long rejected = 0;   // rejected steps
  long rhs_evals = 0;  // evaluations of the right-hand side
  long events = 0;     // located contact entries and exits
  IntegrationCounters& operator+=(const IntegrationCounters& c) {
    steps += c.steps;
    rejected += c.rejected;
    rhs_evals += c.rhs_evals;
    events += c.events;
    return *this;
  }
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Advances u (internal coordinates, see system.hpp) by one forcing period; reports steps
  // and events to obs. On a status other than ok, u is the last good state.
  virtual IntegrationStatus advance_period(State& u, Observer& obs) = 0;
  // Sets the state's contact mode from u: used at the start and after an external reset.
  // A contact in progress at u has no remembered entry: a dissipative law's v_in is then
  // Model::entry_speed(u).
  void reset(const State& u) { mode_ = u[1] > 0.0 ? ContactMode::contact : ContactMode::free; restart(u); }

  // Changes the relative tolerance from the next step on (adaptive methods; rk4 ignores it).
  virtual void set_rtol(double /*rtol*/) {}
  // Changes the step budget (IntegratorOptions::max_steps) from the next step on.
  virtual void set_max_steps(long max_steps) = 0;

  ContactMode mode() const { return mode_; }
  long period() const { return period_; }  // forcing periods completed so far
  const IntegrationCounters& counters() const { return counters_; }

 protected:
  virtual void restart(const State& /*u*/) {}
  ContactMode mode_ = ContactMode::free;
  long period_ = 0;
  IntegrationCounters counters_;
};

// An integrator that also carries the variational solution: jacobian() is d u / d u0, the
// derivative of the current state with respect to the state at the last reset_jacobian()
// (over whole periods: the monodromy matrix of the stroboscopic map). Free flights contribute
// e^{A dt} exactly; contact phases integrate Phi' = J(u) Phi with the state; contact events
// need no saltation jump because the Hertz force vanishes at z = 0. With a dissipative law
// the contact's v_in depends on the entry state, and Phi carries that too (dp5_engine.hpp).
class VariationalIntegrator : public Integrator {
 public:
  virtual const Eigen::Matrix4d& jacobian() const = 0;
  virtual void reset_jacobian() = 0;
};

class FreeFlight;
// The closed-form free flight of `model` (free_flight.hpp), shared: the last one made on this
// thread while the model's linear part, forcing and tolerance stay the same.
std::shared_ptr<const FreeFlight> free_flight_of(const Model& model);

// The integrator of options.method; hybrid falls back to dopri5 when the free flight has no
// usable closed form (FreeFlight::valid()).
std::unique_ptr<Integrator> make_integrator(const Model& model, const IntegratorOptions& options);
// The same with the variational equations (rk4 is not offered: hybrid or dopri5 are used).
std::unique_ptr<VariationalIntegrator> make_variational_integrator(const Model& model,
                                                                   const IntegratorOptions& options);

}  // namespace vibromap

namespace vibromap {

struct PeriodRun {
  IntegrationStatus status = IntegrationStatus::ok;
  long periods = 0;      // periods completed in this call
  bool stopped = false;  // the observer asked to stop
};

// Advances u period by period, showing each period's end state to obs, until obs asks to
// stop, max_periods have run, or the integrator reports a failure.
PeriodRun integrate_periods(Integrator& integrator, State& u, long max_periods, Observer& obs);

}  // namespace vibromap
