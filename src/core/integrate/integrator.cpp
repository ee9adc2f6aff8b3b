#include "vibromap/core/integrate/integrator.hpp"

#include <cmath>
#include <stdexcept>

#include "steppers.hpp"
#include "vibromap/core/integrate/free_flight.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/model/keys.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap {

std::string to_string(Method m) {
  switch (m) {
    case Method::hybrid: return "hybrid";
    case Method::dopri5: return "dopri5";
    case Method::rk4: return "rk4";
  }
  return "unknown";
}

std::string to_string(IntegrationStatus s) {
  switch (s) {
    case IntegrationStatus::ok: return "ok";
    case IntegrationStatus::step_limit: return "step budget exhausted";
    case IntegrationStatus::step_underflow: return "step size underflow";
    case IntegrationStatus::non_finite: return "non-finite state";
  }
  return "unknown";
}

std::string validate(const IntegratorOptions& o) {
  PointOptions options;
  options.integrator = o;
  const std::vector<std::string> r = refusals(Parameters{}, options, "solver");
  return r.empty() ? step_budget_error(o) : r.front();
}

std::string step_budget_error(const IntegratorOptions& o) {
  const auto budget = static_cast<double>(o.max_steps);
  if (o.method == Method::rk4) {
    if (o.rk4_steps <= budget) return {};
    return Key::find("solver.rk4_steps")
        ->info()
        .refusal(value_text(o.rk4_steps), cat("one forcing period takes more steps than the whole step budget "
                                              "(solver.max_steps = ", value_text(budget), ")"));
  }
  if (o.max_step * budget >= 1.0) return {};
  return Key::find("solver.max_step")
      ->info()
      .refusal(value_text(o.max_step),
               cat("a forcing period at this largest step takes more steps than the whole step budget "
                   "(solver.max_steps = ", value_text(budget), "): it must be at least 1/max_steps = ",
                   value_text(1.0 / budget)));
}

// The free-flight decomposition (an eigen-decomposition and two complex LU factorisations,
// ~4 us) costs as much as a forcing period of a rigid contact, and shooting makes a fresh
// integrator for every Newton evaluation of the same model. The last one made is therefore
// kept, per thread (no locks, no sharing across threads), and reused while the model's
// linear part, forcing and tolerance are the same (FreeFlight::describes): a sweep moves
// to the next cell by simply asking for another model.
std::shared_ptr<const FreeFlight> free_flight_of(const Model& model) {
  thread_local std::shared_ptr<const FreeFlight> last;
  if (!last || !last->describes(model)) last = std::make_shared<const FreeFlight>(model);
  return last;
}

std::unique_ptr<Integrator> make_integrator(const Model& model, const IntegratorOptions& options) {
  if (options.method == Method::rk4) return std::make_unique<detail::ClassicalRk4>(model, options);
  if (options.method == Method::hybrid) {
    auto flight = free_flight_of(model);
    if (flight->valid()) return std::make_unique<detail::Hybrid<1>>(model, options, std::move(flight));
  }
  return std::make_unique<detail::DormandPrince>(model, options);
}

std::unique_ptr<VariationalIntegrator> make_variational_integrator(const Model& model,
                                                                   const IntegratorOptions& options) {
  if (options.method != Method::dopri5) {
    auto flight = free_flight_of(model);
    if (flight->valid()) return std::make_unique<detail::Hybrid<5>>(model, options, std::move(flight));
  }
  return std::make_unique<detail::DormandPrinceVariational>(model, options);
}

}  // namespace vibromap

namespace vibromap {

PeriodRun integrate_periods(Integrator& integrator, State& u, long max_periods, Observer& obs) {
  PeriodRun run;
  while (run.periods < max_periods) {
    run.status = integrator.advance_period(u, obs);
    if (run.status != IntegrationStatus::ok) break;
    ++run.periods;
    if (!u.allFinite()) {
      run.status = IntegrationStatus::non_finite;
      break;
    }
    if (obs.on_period_end(integrator.period() - 1, u)) {
      run.stopped = true;
      break;
    }
  }
  return run;
}

}  // namespace vibromap
