#include "nlopt_adaptor.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "vibromap/core/integrate/cancel.hpp"

namespace vibromap {
namespace {

// Objective calls (cache hits included) allowed per solve of the budget before the run is
// stopped: an algorithm that only revisits cached points would otherwise never end.
constexpr long kCallsPerSolve = 50;
// Restarts from the best feasible point after a run ends normally (see run_nlopt).
constexpr int kRestarts = 3;

nlopt_algorithm nlopt_id(Algorithm a) {
  switch (a) {
    case Algorithm::bobyqa: return NLOPT_LN_BOBYQA;
    case Algorithm::cobyla: return NLOPT_LN_COBYLA;
    case Algorithm::sbplx: return NLOPT_LN_SBPLX;
    case Algorithm::slsqp: return NLOPT_LD_SLSQP;
    case Algorithm::mma: return NLOPT_LD_MMA;
    case Algorithm::gradient_projection: break;
  }
  throw std::invalid_argument("run_nlopt: " + to_string(a) + " is not an NLopt algorithm");
}

// The one checking helper for NLopt's set-up calls.
void check(nlopt_result r, const char* what) {
  if (r < 0) throw std::runtime_error(std::string("NLopt ") + what + " failed: " + nlopt_result_to_string(r));
}

struct NloptDeleter {
  void operator()(nlopt_opt opt) const { nlopt_destroy(opt); }
};
using NloptHandle = std::unique_ptr<std::remove_pointer_t<nlopt_opt>, NloptDeleter>;

// What the callbacks share.
struct Context {
  TrackedObjective& f;
  Algorithm algorithm;
  nlopt_opt opt = nullptr;
  std::string forced;  // why this layer stopped NLopt ("" while it runs)
  bool cancelled = false;  // an evaluation was cancelled (core/integrate/cancel.hpp): rethrown after NLopt returns
};

// The number NLopt minimises at an evaluated point (see nlopt_adaptor.hpp).
double objective_value(const Evaluation& e, const Context& c) {
  const double barrier = c.f.options().barrier;
  if (takes_constraints(c.algorithm)) return std::isfinite(e.value) ? e.value : barrier;
  return e.feasible ? e.value : barrier + e.violation;
}

// Stops NLopt for our budget (`reason`; default: the tracker's) and gives it a harmless answer.
double force_stop(Context& c, unsigned n, double* grad, double answer, const std::string& reason = {}) {
  if (c.forced.empty()) c.forced = reason.empty() ? c.f.budget_reason() : reason;
  nlopt_force_stop(c.opt);
  if (grad != nullptr) std::fill(grad, grad + n, 0.0);
  return answer;
}

// Evaluates at u for NLopt: the value (objective or constraint) and, when asked, its
// finite-difference gradient. `pick` selects the value or the violation.
template <class Pick, class PickGradient>
double answer(Context& c, unsigned n, const double* u, double* grad, Pick pick, PickGradient pick_gradient) {
  const double fallback = c.f.options().barrier;
  if (c.f.calls() > kCallsPerSolve * c.f.options().max_evaluations)
    return force_stop(c, n, grad, fallback, "MAXCALLS_REACHED");
  const std::span<const double> point(u, n);
  const std::optional<Evaluation> e = c.f.evaluate(point);
  if (!e) return force_stop(c, n, grad, fallback);
  if (grad != nullptr) {
    const std::optional<FdGradient> g = fd_gradient(c.f, point, *e, c.f.options().fd_step);
    if (!g) return force_stop(c, n, grad, pick(*e));
    const std::vector<double>& d = pick_gradient(*g);
    std::copy(d.begin(), d.end(), grad);
  }
  return pick(*e);
}

// A callback's answer; a Cancelled evaluation stops NLopt (an exception must not cross its C
// frames) and is rethrown by run_once once nlopt_optimize has returned.
template <class Answer>
double guarded(Context& c, unsigned n, double* grad, Answer answer_now) {
  if (c.cancelled) return force_stop(c, n, grad, c.f.options().barrier, "CANCELLED");
  try {
    return answer_now();
  } catch (const Cancelled&) {
    c.cancelled = true;
    return force_stop(c, n, grad, c.f.options().barrier, "CANCELLED");
  }
}

double objective_callback(unsigned n, const double* u, double* grad, void* data) {
  Context& c = *static_cast<Context*>(data);
  return guarded(c, n, grad, [&] {
    return answer(
        c, n, u, grad, [&](const Evaluation& e) { return objective_value(e, c); },
        [](const FdGradient& g) -> const std::vector<double>& { return g.value; });
  });
}

double constraint_callback(unsigned n, const double* u, double* grad, void* data) {
  Context& c = *static_cast<Context*>(data);
  return guarded(c, n, grad, [&] {
    return answer(
        c, n, u, grad, [](const Evaluation& e) { return e.violation; },
        [](const FdGradient& g) -> const std::vector<double>& { return g.violation; });
  });
}

NloptHandle make_optimiser(Context& c, unsigned n) {
  NloptHandle opt(nlopt_create(nlopt_id(c.algorithm), n));
  if (!opt) throw std::runtime_error("NLopt nlopt_create failed for " + to_string(c.algorithm));
  c.opt = opt.get();
  const LocalOptions& o = c.f.options();
  check(nlopt_set_lower_bounds1(c.opt, 0.0), "set_lower_bounds");
  check(nlopt_set_upper_bounds1(c.opt, 1.0), "set_upper_bounds");
  check(nlopt_set_min_objective(c.opt, objective_callback, &c), "set_min_objective");
  if (takes_constraints(c.algorithm))
    check(nlopt_add_inequality_constraint(c.opt, constraint_callback, &c, 0.0), "add_inequality_constraint");
  check(nlopt_set_xtol_rel(c.opt, o.xtol_rel), "set_xtol_rel");
  check(nlopt_set_xtol_abs1(c.opt, o.xtol_rel), "set_xtol_abs");
  if (o.ftol_rel > 0.0) check(nlopt_set_ftol_rel(c.opt, o.ftol_rel), "set_ftol_rel");
  // What is left of the start's time (restarts share it); the tracker enforces it as well.
  if (o.max_time > 0.0) check(nlopt_set_maxtime(c.opt, std::max(o.max_time - c.f.elapsed(), 1e-3)), "set_maxtime");
  return opt;
}

// One NLopt run from u0 with the given initial step.
StopReason run_once(TrackedObjective& f, const std::vector<double>& u0, Algorithm algorithm, double initial_step) {
  Context c{f, algorithm, nullptr, {}};
  const NloptHandle opt = make_optimiser(c, static_cast<unsigned>(u0.size()));
  check(nlopt_set_initial_step1(c.opt, initial_step), "set_initial_step");
  std::vector<double> u = u0;
  for (double& v : u) v = std::clamp(v, 0.0, 1.0);
  double minimum = 0.0;
  const nlopt_result r = nlopt_optimize(c.opt, u.data(), &minimum);
  if (c.cancelled) throw Cancelled{};
  // u and minimum are NLopt's answer; the tracker's best feasible evaluation is ours.
  if (!c.forced.empty()) return {c.forced, static_cast<int>(r)};
  return {nlopt_result_to_string(r), static_cast<int>(r)};
}

double best_value(const TrackedObjective& f) {
  return f.best() ? f.history()[*f.best()].result.value : std::numeric_limits<double>::infinity();
}

}  // namespace

StopReason run_nlopt(TrackedObjective& f, std::span<const double> u0, Algorithm algorithm) {
  const LocalOptions& o = f.options();
  double step = o.initial_step;
  StopReason stop = run_once(f, {u0.begin(), u0.end()}, algorithm, step);
  // Restarts from the best feasible point with a tenth of the step, while they improve it:
  // a barrier (bobyqa, sbplx) or a jumping constraint can end a run short of the boundary.
  for (int i = 0; i < kRestarts && f.best() && !f.exhausted() && stop.nlopt_code > 0; ++i) {
    const double before = best_value(f);
    step = std::max(0.1 * step, 10.0 * o.xtol_rel);
    const std::vector<double> from = f.box().to_scaled(f.history()[*f.best()].x);
    stop = run_once(f, from, algorithm, step);
    if (!(best_value(f) < before - o.ftol_rel * std::abs(before))) break;
  }
  return stop;
}

}  // namespace vibromap
