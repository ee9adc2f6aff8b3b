#pragma once
// What the library drivers (odeint_solver.hpp, cvode_solver.hpp) share: the options taken from
// a scene, the result row, and the bookkeeping that turns a driver's contact events and
// period ends into impacts and a steady-state verdict exactly as vibromap judges them.
//
// Clocks. A driver's own clock restarts at 0 at every contact event (it is re-initialised
// there anyway), so the exit time of an impact *is* its duration T_con: no digits are lost to
// absolute time (docs/numerics.md, "Time"). The Tracker keeps the in-period time
// of the driver's origin, tau0, so the forcing is F(tau0 + t) and the next period end is at
// driver time T - tau0; at a period end tau0 drops by T (the driver's clock runs on).
//
// Steady state: vibromap's own SteadyStateDetector (scaled max-norm on y(jT), period n <= n_max,
// tolerance 100 * rtol unless the scene sets analysis.steady_tol). The steady impacts are those
// entered in the last n periods; a contact still open at detection is followed to its exit.

#include <algorithm>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "vibromap/core/analysis/point/steady_state.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap::bench {

// Integration and steady-state settings a library run takes from the scene.
struct LibraryOptions {
  double rtol = 1e-10;      // relative tolerance
  double atol = 1e-13;      // absolute tolerance on x1 and z, m (on v1 and w: atol * omega)
  double max_step = 0.0;    // largest step, s (the scene's solver.max_step * T)
  long max_steps = 0;       // budget of steps over the whole run
  long max_periods = 2000;  // budget of forcing periods to reach steady state
  int n_max = 8;            // largest period looked for
  double steady_tol = 0.0;  // scaled max-norm tolerance on the stroboscopic samples
};

inline LibraryOptions library_options(const Scene& scene, double rtol) {
  const auto& in = scene.options.integrator;
  const auto& an = scene.options.analysis;
  LibraryOptions o;
  o.rtol = rtol;
  o.atol = in.atol;
  o.max_step = in.max_step * scene.params.period();
  o.max_steps = in.max_steps;
  o.max_periods = an.max_periods;
  o.n_max = an.n_max;
  o.steady_tol = an.steady_tol > 0.0 ? an.steady_tol : 100.0 * rtol;  // like vibromap
  return o;
}

// One solve, as a row of the table.
struct RunResult {
  std::string status = "ok";  // ok | budget | no-impact | permanent-contact | failed
  std::string message;        // why, when status is not ok
  std::string regime;         // "(n,k)" when steady
  long periods = 0;           // forcing periods integrated
  long rhs_evals = 0;         // right-hand side evaluations (CVODE BDF: + Jacobians, see there)
  double T_con = 0.0;         // longest steady impact, s
};

// What a driver's advance() stopped at.
struct Happening {
  enum class Kind { period_end, event, failed };
  Kind kind = Kind::failed;
  double t = 0.0;  // driver time
  State u;         // state there
  std::string message;
};

class Tracker {
 public:
  Tracker(const Model& model, const LibraryOptions& o)
      : T_(model.period()), steady_(model, o.n_max, o.steady_tol) {}

  double tau_origin() const { return tau0_; }
  double next_period_end() const { return T_ - tau0_; }  // driver time
  long period() const { return period_; }                // current (0-based) forcing period
  ContactMode mode() const { return open_ ? ContactMode::contact : ContactMode::free; }
  void set_mode(ContactMode m) { if (m == ContactMode::contact) open_ = period_; }

  // A contact entry or exit at driver time t; the driver's clock restarts at 0 there.
  void on_event(double t) {
    if (open_) {
      impacts_.push_back({*open_, t});
      open_.reset();
    } else {
      open_ = period_;
    }
    tau0_ += t;
  }

  // The state at the end of the current period; true once the samples repeat.
  bool on_period_end(const State& u) {
    const bool steady = steady_.on_period_end(period_, u);
    ++period_;
    tau0_ -= T_;
    return steady;
  }

  const SteadyStateDetector& steady() const { return steady_; }
  bool contact_open() const { return open_.has_value(); }
  long open_since() const { return open_.value_or(-1); }

  // Longest impact entered in periods [first, last], and how many there were.
  std::pair<double, int> longest_impact(long first, long last) const {
    double longest = 0.0;
    int count = 0;
    for (const Impact& im : impacts_) {
      if (im.period_in < first || im.period_in > last) continue;
      longest = std::max(longest, im.T_con);
      ++count;
    }
    return {longest, count};
  }

 private:
  struct Impact {
    long period_in;
    double T_con;
  };
  double T_;
  double tau0_ = 0.0;
  long period_ = 0;
  std::optional<long> open_;
  std::vector<Impact> impacts_;
  SteadyStateDetector steady_;
};

// Hands one happening to the tracker; restarts the driver at an event with z set to exactly
// 0 (the root finder's residual) and the contact mode switched, as vibromap does.
template <class Driver>
bool handle(Driver& d, Tracker& tr, Happening h, bool& steady) {
  if (h.kind == Happening::Kind::failed) return false;
  if (h.kind == Happening::Kind::period_end) {
    steady = tr.on_period_end(h.u);
    return true;
  }
  tr.on_event(h.t);
  h.u[1] = 0.0;
  d.restart(h.u, tr.mode(), tr.tau_origin());
  return true;
}

// After steady state: follow a contact still open to its exit (within n more periods).
template <class Driver>
std::string close_open_contact(Driver& d, Tracker& tr, int n, Happening& h) {
  if (!tr.contact_open()) return {};
  const long detected = tr.period() - 1;
  if (tr.open_since() <= detected - n) return "permanent-contact";
  bool steady = false;
  while (tr.contact_open() && tr.period() <= detected + n) {
    h = d.advance(tr.next_period_end());
    if (!handle(d, tr, h, steady)) return "failed";
  }
  return tr.contact_open() ? "permanent-contact" : "";
}

// Integrates from the rest state until the stroboscopic samples repeat (or the period budget
// runs out), then measures the steady impacts. A library failure is a status, not an abort.
template <class Driver>
RunResult run_to_steady(Driver& d, const Model& model, const LibraryOptions& o) {
  RunResult r;
  try {
    Tracker tr(model, o);
    const State u0 = Model::to_internal(model.parameters().initial_state());
    tr.set_mode(u0[1] > 0.0 ? ContactMode::contact : ContactMode::free);
    d.restart(u0, tr.mode(), 0.0);
    bool steady = false;
    Happening h;
    while (!steady && tr.period() < o.max_periods) {
      h = d.advance(tr.next_period_end());
      if (!handle(d, tr, h, steady)) break;
    }
    r.periods = tr.period();
    if (h.kind == Happening::Kind::failed) {
      r.status = "failed";
      r.message = h.message;
    } else if (!steady) {
      r.status = "budget";
      r.message = "no period <= n_max within " + std::to_string(o.max_periods) + " periods";
    } else {
      const int n = tr.steady().period_n();
      const long j = tr.steady().detected_at();
      const std::string open = close_open_contact(d, tr, n, h);
      r.periods = tr.period();
      const auto [longest, k] = tr.longest_impact(j - n + 1, j);
      r.regime = "(" + std::to_string(n) + "," + std::to_string(k) + ")";
      r.T_con = longest;
      if (!open.empty()) {
        r.status = open;
        r.message = h.message;
      } else if (k == 0) {
        r.status = "no-impact";
      }
    }
  } catch (const std::exception& e) {  // odeint throws when its step-size search fails
    r.status = "failed";
    r.message = e.what();
  }
  r.rhs_evals = d.rhs_evals();
  return r;
}

}  // namespace vibromap::bench
