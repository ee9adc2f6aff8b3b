#include "vibromap/core/optimise/optimise_options.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace vibromap {
namespace {

// Names of an enum's values, in enum order, for to_string and parse alike.
constexpr std::array<std::pair<ObjectiveKind, std::string_view>, 3> kObjectiveNames = {{
    {ObjectiveKind::min_k_con, "min_k_con"},
    {ObjectiveKind::max_T_con, "max_T_con"},
    {ObjectiveKind::min_F_max, "min_F_max"},
}};
constexpr std::array<std::pair<Algorithm, std::string_view>, 6> kAlgorithmNames = {{
    {Algorithm::bobyqa, "bobyqa"},
    {Algorithm::cobyla, "cobyla"},
    {Algorithm::sbplx, "sbplx"},
    {Algorithm::slsqp, "slsqp"},
    {Algorithm::mma, "mma"},
    {Algorithm::gradient_projection, "gradient_projection"},
}};
constexpr std::array<std::pair<StabilityRule, std::string_view>, 3> kStabilityNames = {{
    {StabilityRule::if_known, "if_known"},
    {StabilityRule::required, "required"},
    {StabilityRule::ignored, "ignored"},
}};

template <class Enum, std::size_t N>
std::string name_of(const std::array<std::pair<Enum, std::string_view>, N>& names, Enum e) {
  for (const auto& [value, name] : names)
    if (value == e) return std::string(name);
  return "unknown";
}

template <class Enum, std::size_t N>
Enum parse_name(const std::array<std::pair<Enum, std::string_view>, N>& names, std::string_view s,
                std::string_view what) {
  std::string allowed;
  for (const auto& [value, name] : names) {
    if (name == s) return value;
    allowed.append(allowed.empty() ? "" : ", ").append(name);
  }
  std::string msg = "unknown ";
  msg.append(what).append(" '").append(s).append("' (allowed: ").append(allowed).append(")");
  throw std::invalid_argument(msg);
}

template <class Enum, std::size_t N>
std::vector<Enum> values_of(const std::array<std::pair<Enum, std::string_view>, N>& names) {
  std::vector<Enum> v;
  for (const auto& entry : names) v.push_back(entry.first);
  return v;
}

}  // namespace

std::string to_string(ObjectiveKind k) { return name_of(kObjectiveNames, k); }
ObjectiveKind parse_objective_kind(std::string_view s) { return parse_name(kObjectiveNames, s, "objective"); }
const std::vector<ObjectiveKind>& all_objective_kinds() {
  static const std::vector<ObjectiveKind> v = values_of(kObjectiveNames);
  return v;
}

std::string objective_quantity(ObjectiveKind k) {
  switch (k) {
    case ObjectiveKind::min_k_con: return "k_con";
    case ObjectiveKind::max_T_con: return "T_con";
    case ObjectiveKind::min_F_max: return "F_max";
  }
  return "unknown";
}

double objective_sense(ObjectiveKind k) { return k == ObjectiveKind::max_T_con ? -1.0 : 1.0; }

std::string to_string(Algorithm a) { return name_of(kAlgorithmNames, a); }
Algorithm parse_algorithm(std::string_view s) { return parse_name(kAlgorithmNames, s, "algorithm"); }
const std::vector<Algorithm>& all_algorithms() {
  static const std::vector<Algorithm> v = values_of(kAlgorithmNames);
  return v;
}

bool takes_constraints(Algorithm a) {
  return a == Algorithm::cobyla || a == Algorithm::slsqp || a == Algorithm::mma;
}

std::string to_string(StabilityRule r) { return name_of(kStabilityNames, r); }
StabilityRule parse_stability_rule(std::string_view s) { return parse_name(kStabilityNames, s, "stability rule"); }
const std::vector<StabilityRule>& all_stability_rules() {
  static const std::vector<StabilityRule> v = values_of(kStabilityNames);
  return v;
}

const std::vector<std::string_view>& free_parameter_names() {
  static const std::vector<std::string_view> names = {"E1", "E2", "R1", "R2", "m2", "k2", "omega2", "restitution"};
  return names;
}

std::string validate(const FreeVariable& v) {
  const auto& names = free_parameter_names();
  if (std::find(names.begin(), names.end(), v.name) == names.end()) {
    std::string allowed;
    for (const std::string_view n : names) allowed += (allowed.empty() ? "" : ", ") + std::string(n);
    return "unknown free parameter '" + v.name + "' (allowed: " + allowed + ")";
  }
  if (!std::isfinite(v.min) || !std::isfinite(v.max)) return v.name + ": bounds must be finite";
  if (!(v.min < v.max)) return v.name + ": min must be < max";
  if (v.scale == AxisScale::log && v.min <= 0.0) return v.name + ": a log scale needs min > 0";
  return {};
}

std::string validate(const LocalOptions& o) {
  if (!(o.xtol_rel > 0.0 && o.xtol_rel < 1.0)) return "xtol_rel must be in (0, 1)";
  if (!(o.ftol_rel >= 0.0 && o.ftol_rel < 1.0)) return "ftol_rel must be in [0, 1)";
  if (o.max_evaluations < 1) return "max_evaluations must be >= 1";
  if (!(o.max_time >= 0.0 && std::isfinite(o.max_time))) return "max_time must be >= 0";
  if (!(o.initial_step > 0.0 && o.initial_step <= 1.0)) return "initial_step must be in (0, 1]";
  if (!(o.fd_step > 0.0 && o.fd_step <= 0.1)) return "fd_step must be in (0, 0.1]";
  if (!(o.barrier > 0.0 && std::isfinite(o.barrier))) return "barrier must be finite and > 0";
  return {};
}

std::string validate(const OptimiseOptions& o) {
  if (o.variables.empty()) return "no free parameters";
  for (std::size_t i = 0; i < o.variables.size(); ++i) {
    if (std::string e = validate(o.variables[i]); !e.empty()) return e;
    for (std::size_t j = 0; j < i; ++j)
      if (o.variables[i].name == o.variables[j].name) return o.variables[i].name + " is free twice";
  }
  const auto is_free = [&](std::string_view n) {
    return std::any_of(o.variables.begin(), o.variables.end(), [&](const FreeVariable& v) { return v.name == n; });
  };
  if (is_free("k2") && is_free("omega2")) return "k2 and omega2 are both free: free only one";
  if (o.impact < 0) return "impact must be >= 0";
  if (o.algorithms.empty()) return "no algorithm";
  for (std::size_t i = 0; i < o.laws.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (o.laws[i] == o.laws[j]) return "law " + to_string(o.laws[i]) + " is listed twice";
  if (o.seeds < 1) return "seeds must be >= 1";
  if (o.best < 1) return "best must be >= 1";
  if (!(o.verify_rtol > 0.0 && o.verify_rtol < 0.1)) return "verify_rtol must be in (0, 0.1)";
  if (!(o.min_soft_fraction >= 0.0 && o.min_soft_fraction <= 1.0)) return "min_soft_fraction must be in [0, 1]";
  if (o.soft_check_initial_conditions < 1 || o.soft_check_initial_conditions > 1'000'000)
    return "soft_check_initial_conditions must be in [1, 1000000]";
  return validate(o.local);
}

}  // namespace vibromap
