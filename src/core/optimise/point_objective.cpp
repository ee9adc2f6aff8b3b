#include "vibromap/core/optimise/point_objective.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace vibromap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kUnstableCap = 0.9;         // violation of an unstable orbit of the kept regime, at most
constexpr double kUnknownRequired = 0.5;     // violation of unknown stability when it is required
constexpr double kNoPeriodicMotion = 2.0;    // violation of a non-periodic or impact-free point
constexpr double kIgnoredStability = -1.0;   // violation of a feasible point when stability is ignored
constexpr double kLeastShortfall = 1e-6;     // violation of a soft fraction short by less (never 0: infeasible)

// The value minimised, or nullopt where it is undefined.
std::optional<double> objective_value(const PointSummary& s, const OptimiseOptions& o) {
  if (s.impacts.empty() || !(s.T_con > 0.0)) return std::nullopt;
  switch (o.objective) {
    case ObjectiveKind::min_k_con: return s.k_con;
    case ObjectiveKind::max_T_con:
      if (static_cast<std::size_t>(o.impact) >= s.impacts.size()) return std::nullopt;
      return -s.impacts[static_cast<std::size_t>(o.impact)].T_con;
    case ObjectiveKind::min_F_max: return s.F_max;
  }
  return std::nullopt;
}

// Distance of a regime from the kept one, as the violation bands of point_objective.hpp.
double regime_distance(const Regime& got, const Regime& want) {
  if (got == want) return 0.0;
  if (got.kind != RegimeKind::periodic) return kNoPeriodicMotion;
  const double d = std::abs(got.n - want.n) + std::abs(got.k - want.k);
  return 1.0 + d / (1.0 + d);
}

// The stability band for a point of the kept regime.
double stability_violation(const PointSummary& s, StabilityRule rule) {
  if (rule == StabilityRule::ignored || s.regime.kind != RegimeKind::periodic) return kIgnoredStability;
  const double mu = max_multiplier(s);
  if (s.stable == 1) return std::isfinite(mu) ? std::clamp(mu - 1.0, -1.0, 0.0) : 0.0;
  if (s.stable == 0) return std::isfinite(mu) ? std::clamp(mu - 1.0, 1e-6, kUnstableCap) : kUnstableCap;
  return rule == StabilityRule::required ? kUnknownRequired : 0.0;
}

// The Hertz band for a point of the kept regime: z_max/R* against the limit.
double hertz_violation(const PointSummary& s, double hertz_limit) {
  return std::clamp(s.z_ratio / hertz_limit - 1.0, -1.0, kUnstableCap);
}

}  // namespace

double max_multiplier(const PointSummary& s) {
  if (s.floquet.empty()) return kNaN;
  double m = 0.0;
  for (const auto& mu : s.floquet) m = std::max(m, std::abs(mu));
  return m;
}

Evaluation evaluate_summary(const PointSummary& s, const OptimiseOptions& o, double hertz_limit) {
  Evaluation e;
  e.regime = s.regime;
  e.stable = s.stable;
  e.measures = {s.k_con, s.T_con, s.F_max, max_multiplier(s), s.z_ratio};
  if (s.status == SolveStatus::failed || s.status == SolveStatus::invalid_input) {
    e.violation = kFailedViolation;
    e.message = s.message;
    return e;
  }
  const std::optional<double> value = objective_value(s, o);
  if (value) e.value = *value;
  const double away = o.regime ? regime_distance(s.regime, *o.regime) : 0.0;
  if (away > 0.0) {
    e.violation = away;
    e.message = "regime " + s.regime.label() + ", not " + o.regime->label();
  } else if (!value) {
    e.violation = kNoPeriodicMotion;
    e.message = "the objective is undefined (no such impact)";
  } else {
    e.violation = stability_violation(s, o.stability);
    if (e.violation > 0.0) e.message = s.stable == 0 ? "the orbit is unstable" : "the orbit's stability is unknown";
    if (o.hertz_valid && e.violation <= 0.0) {  // the Hertz margin replaces the stability margin (see the header)
      e.violation = hertz_violation(s, hertz_limit);
      if (e.violation > 0.0) e.message = "Hertz theory does not hold (z_max/R* above hertz_limit)";
    }
  }
  e.feasible = e.violation <= 0.0 && std::isfinite(e.value);
  return e;
}

void apply_soft_fraction(Evaluation& e, const CensusSummary& census, const OptimiseOptions& o) {
  e.measures.resize(std::max(e.measures.size(), kSoftFractionMeasure + 1), kNaN);
  if (census.status != SolveStatus::ok) {
    e.violation = kFailedViolation;
    e.feasible = false;
    e.message = "the census failed: " + census.message;
    return;
  }
  e.measures[kSoftFractionMeasure] = census.soft_fraction;
  const double shortfall = o.min_soft_fraction - census.soft_fraction;
  if (shortfall <= kSoftFractionRounding) return;  // feasible: keeps its continuous margin (see the header)
  e.violation = std::clamp(shortfall, kLeastShortfall, kUnstableCap);
  e.feasible = false;
  std::ostringstream os;
  os << "the soft attractors' basin fraction " << census.soft_fraction << " (census of " << census.K
     << " initial states) is below min_soft_fraction " << o.min_soft_fraction;
  e.message = os.str();
}

PointObjective::PointObjective(const Parameters& base, const PointOptions& options, const OptimiseOptions& optimise,
                               const CensusOptions& census)
    : base_(base), options_(options), optimise_(optimise), census_(census) {
  census_.labels = false;
}

std::vector<std::string> PointObjective::measure_names() const {
  std::vector<std::string> names = {"k_con", "T_con", "F_max", "max_multiplier", "z_ratio"};
  if (optimise_.min_soft_fraction > 0.0) names.emplace_back("soft_fraction");
  return names;
}

Parameters PointObjective::parameters_at(std::span<const double> x) const {
  if (x.size() != optimise_.variables.size()) throw std::invalid_argument("parameters_at: wrong number of values");
  Parameters p = base_;
  for (std::size_t i = 0; i < x.size(); ++i) optimise_.variables[i].key.set(p, x[i]);
  return p;
}

Evaluation PointObjective::evaluate(std::span<const double> x) {
  const Parameters p = parameters_at(x);
  Evaluation e = evaluate_summary(solve_point(p, options_), optimise_, options_.analysis.hertz_limit);
  if (optimise_.min_soft_fraction > 0.0) {
    e.measures.resize(kSoftFractionMeasure + 1, kNaN);
    if (e.feasible) apply_soft_fraction(e, census_point(p, options_, census_), optimise_);
  }
  return e;
}

PointSummary resolve_point(const Parameters& p, PointOptions options, SteadyMethod method, double rtol,
                           int trajectory_periods) {
  IntegratorOptions& in = options.integrator;
  if (in.method == Method::rk4) in.method = Method::dopri5;
  in.atol *= rtol / in.rtol;
  in.rtol = rtol;
  options.analysis.steady = method;
  options.analysis.newton_tol = 0.0;
  options.analysis.steady_tol = 0.0;
  options.analysis.trajectory_periods = trajectory_periods;
  return solve_point(p, options);
}

}  // namespace vibromap
