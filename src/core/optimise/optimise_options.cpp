#include "vibromap/core/optimise/optimise_options.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "vibromap/core/text.hpp"

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

std::string validate(const FreeVariable& v) {
  const std::string name(v.name());
  if (!v.key.is_parameter())
    return cat(v.key.full_name(), " cannot be free: a free parameter is a real key of [system], [contact] or [forcing]");
  if (!std::isfinite(v.min) || !std::isfinite(v.max)) return name + ": bounds must be finite";
  if (!(v.min < v.max)) return name + ": min must be < max";
  if (v.scale == AxisScale::log && v.min <= 0.0) return name + ": a log scale needs min > 0";
  for (const double x : {v.min, v.max})
    if (std::string r = v.key.check(x); !r.empty()) return cat("the box of ", name, " reaches ", r);
  return {};
}

std::string validate(const LocalOptions& o) {
  const std::pair<std::string_view, double> numbers[] = {
      {"optimise.xtol_rel", o.xtol_rel},         {"optimise.ftol_rel", o.ftol_rel},
      {"optimise.max_evaluations", static_cast<double>(o.max_evaluations)},
      {"optimise.max_time", o.max_time},         {"optimise.initial_step", o.initial_step},
      {"optimise.fd_step", o.fd_step},           {"optimise.barrier", o.barrier}};
  for (const auto& [name, v] : numbers)
    if (std::string r = check_option(name, v); !r.empty()) return r;
  return {};
}

std::string validate(const OptimiseOptions& o) {
  if (o.variables.empty()) return "no free parameters";
  for (std::size_t i = 0; i < o.variables.size(); ++i) {
    if (std::string e = validate(o.variables[i]); !e.empty()) return e;
    for (std::size_t j = 0; j < i; ++j)
      if (o.variables[i].key == o.variables[j].key) return cat(o.variables[i].name(), " is free twice");
    for (std::size_t j = 0; j < i; ++j)
      if (o.variables[j].name() == o.variables[i].key.info().partner)
        return cat(o.variables[j].name(), " and ", o.variables[i].name(), " are both free: free only one");
  }
  if (o.algorithms.empty()) return "no algorithm";
  for (std::size_t i = 0; i < o.laws.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (o.laws[i] == o.laws[j]) return "law " + to_string(o.laws[i]) + " is listed twice";
  const std::pair<std::string_view, double> numbers[] = {
      {"optimise.impact", o.impact},           {"optimise.seeds", o.seeds},
      {"optimise.best", o.best},               {"optimise.verify_rtol", o.verify_rtol},
      {"optimise.min_soft_fraction", o.min_soft_fraction},
      {"optimise.soft_check_initial_conditions", o.soft_check_initial_conditions}};
  for (const auto& [name, v] : numbers)
    if (std::string r = check_option(name, v); !r.empty()) return r;
  return validate(o.local);
}

}  // namespace vibromap
