#include "vibromap/core/analysis/point/accuracy.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "vibromap/core/text.hpp"

namespace vibromap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The default study's settings (see accuracy.hpp).
constexpr std::array kRk4Exponents = {11, 12, 13, 14, 15};  // steps per period 2^e
constexpr std::array kTolerances = {1e-6, 1e-8, 1e-10, 1e-12};
constexpr double kReferenceRtol = 1e-13;

// "1e-8" rather than printf's "1e-08"; other mantissas keep 3 digits ("2.5e-7").
std::string tolerance_text(double x) {
  std::array<char, 32> buf{};
  std::snprintf(buf.data(), buf.size(), "%.3g", x);
  std::string s(buf.data());
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string exponent = s.substr(e + 1);
  std::string sign;
  if (!exponent.empty() && (exponent[0] == '-' || exponent[0] == '+')) {
    if (exponent[0] == '-') sign = "-";
    exponent.erase(0, 1);
  }
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  std::string out = s.substr(0, e);
  out += "e";
  out += sign;
  out += exponent;
  return out;
}

bool has_impact(const PointSummary& s) {
  return !s.impacts.empty() && s.T_con > 0.0 && std::isfinite(s.T_con);
}

bool usable(const PointSummary& s) {
  return s.status == SolveStatus::ok || s.status == SolveStatus::budget;
}

// Why the relative errors of a case are undefined, or empty when they are defined.
std::string undefined_error_reason(const PointSummary& s, const PointSummary& reference) {
  if (!usable(reference)) {
    std::string why = "no errors: the reference did not solve (";
    why += to_string(reference.status);
    why += ")";
    return why;
  }
  if (!usable(s)) {
    std::string why = "no errors: ";
    why += s.message.empty() ? to_string(s.status) : s.message;
    return why;
  }
  if (!has_impact(reference)) return "no errors: the reference has no impact";
  if (!has_impact(s)) return "no errors: no impact";
  return {};
}

// Options of `base` for one tolerance of an adaptive method. atol keeps base's atol/rtol.
PointOptions adaptive(const PointOptions& base, Method method, SteadyMethod steady, double rtol) {
  PointOptions o = base;
  o.integrator.method = method;
  o.integrator.atol = base.integrator.atol * (rtol / base.integrator.rtol);
  o.integrator.rtol = rtol;
  o.analysis.steady = steady;
  return o;
}

// base with what the study must not inherit: no trajectory or Lyapunov exponent (not timed
// here), and steady-state and Newton tolerances tied to each case's own tolerance.
PointOptions study_base(const PointOptions& base) {
  PointOptions o = base;
  o.analysis.trajectory_periods = 0;
  o.analysis.lyapunov = false;
  o.analysis.steady_tol = 0.0;
  o.analysis.newton_tol = 0.0;
  return o;
}

}  // namespace

double relative_error(double value, double reference) {
  if (!std::isfinite(value) || !std::isfinite(reference) || reference == 0.0) return kNaN;
  return std::abs(value - reference) / std::abs(reference);
}

std::string setting_label(const IntegratorOptions& options) {
  if (options.method == Method::rk4) {
    const int n = options.rk4_steps;
    std::string out;
    if (n > 0 && (n & (n - 1)) == 0) {
      out = "2^";
      out += std::to_string(static_cast<int>(std::lround(std::log2(n))));
    } else {
      out = std::to_string(n);
    }
    out += " steps/T";
    return out;
  }
  std::string out = "rtol ";
  out += tolerance_text(options.rtol);
  return out;
}

AccuracyRow accuracy_row(const AccuracyCase& c, const PointSummary& s, const PointSummary& reference) {
  AccuracyRow r;
  r.label = c.method_label;
  r.setting = setting_label(c.options.integrator);
  r.method = c.options.integrator.method;
  r.steady = c.options.analysis.steady;
  const bool rk4 = r.method == Method::rk4;
  r.rtol = rk4 ? kNaN : c.options.integrator.rtol;
  r.atol = rk4 ? kNaN : c.options.integrator.atol;
  r.rk4_steps = rk4 ? c.options.integrator.rk4_steps : 0;
  r.status = s.status;
  r.regime = s.regime.label();
  r.regime_matches = s.regime == reference.regime;
  r.steady_used = s.steady_method;
  r.newton_iterations = s.newton_iterations;
  r.wall_s = s.wall_s;
  r.rhs_evals = s.counters.rhs_evals;
  r.steps = s.counters.steps;
  r.periods = s.periods;
  r.T_con = s.T_con;
  r.F_max = s.F_max;
  r.k_con = s.k_con;
  r.note = undefined_error_reason(s, reference);
  const bool defined = r.note.empty();
  r.rel_err_T_con = defined ? relative_error(s.T_con, reference.T_con) : kNaN;
  r.rel_err_F_max = defined ? relative_error(s.F_max, reference.F_max) : kNaN;
  r.rel_err_k_con = defined ? relative_error(s.k_con, reference.k_con) : kNaN;
  if (!r.regime_matches) {
    if (!r.note.empty()) r.note += "; ";
    r.note += "regime differs from the reference's ";
    r.note += reference.regime.label();
  }
  return r;
}

std::vector<AccuracyCase> default_accuracy_cases(const PointOptions& base_in) {
  const PointOptions base = study_base(base_in);
  std::vector<AccuracyCase> cases;
  for (const int e : kRk4Exponents) {
    PointOptions o = base;
    o.integrator.method = Method::rk4;
    o.integrator.rk4_steps = 1 << e;
    o.analysis.steady = SteadyMethod::integrate;
    cases.push_back({"rk4", o});
  }
  for (const double rtol : kTolerances) {
    cases.push_back({"dopri5", adaptive(base, Method::dopri5, SteadyMethod::integrate, rtol)});
  }
  for (const double rtol : kTolerances) {
    cases.push_back({"hybrid+shooting", adaptive(base, Method::hybrid, SteadyMethod::shooting, rtol)});
  }
  return cases;
}

AccuracyCase default_accuracy_reference(const PointOptions& base) {
  return {"reference", adaptive(study_base(base), Method::dopri5, SteadyMethod::integrate, kReferenceRtol)};
}

AccuracyReport run_accuracy(const Parameters& p, const std::vector<AccuracyCase>& cases,
                            const AccuracyCase& reference, const AccuracyProgress& progress) {
  const std::size_t total = cases.size() + 1;
  AccuracyReport report;
  const PointSummary ref = solve_point(p, reference.options);
  report.reference = accuracy_row(reference, ref, ref);
  if (progress) progress(report.reference, 1, total);
  if (!usable(ref) || !has_impact(ref)) {
    report.unsolved = cat(std::to_string(cases.size()), " cases not solved: the reference ",
                          usable(ref) ? "has no impact" : "ended " + to_string(ref.status) + " " + ref.regime.label(),
                          ", so there is no error to measure");
    return report;
  }
  for (const AccuracyCase& c : cases) {
    report.rows.push_back(accuracy_row(c, solve_point(p, c.options), ref));
    if (progress) progress(report.rows.back(), report.rows.size() + 1, total);
  }
  return report;
}

}  // namespace vibromap
