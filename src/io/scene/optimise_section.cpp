// The [optimise] section of a scene: its keys are the free parameters (any parameter key,
// Key::is_parameter, by its name alone or in full, each an inline table { min, max[, scale] })
// and the options of optimise_rows(). read_optimise() reads them into OptimiseOptions, and a
// free parameter's box is checked against the range of the parameter's own key.

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "option_fields.hpp"
#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap::detail {
namespace {

std::string regime_allowed() { return "\"(n,k)\" with n, k >= 1, or \"any\" (any motion with an impact)"; }

void read_regime(OptimiseOptions& o, const KeyInfo&, const toml::node& node, const std::string& loc) {
  const auto* s = node.as_string();
  if (s != nullptr && s->get() == "any") {
    o.regime.reset();
    return;
  }
  try {
    if (s != nullptr) {
      const Regime r = parse_regime(s->get());
      if (r.kind == RegimeKind::periodic && r.n >= 1 && r.k >= 1) {
        o.regime = r;
        return;
      }
    }
  } catch (const std::invalid_argument&) {
    // falls through to the message
  }
  fail(cat(loc, ": must be ", regime_allowed()));
}

std::string algorithm_names_text() {
  std::vector<std::string> names;
  for (const Algorithm a : all_algorithms()) names.push_back(to_string(a));
  return join(views(names), ", ");
}

Algorithm read_algorithm_name(const std::string& name, const std::string& loc) {
  std::vector<std::string> names;
  for (const Algorithm a : all_algorithms()) names.push_back(to_string(a));
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string msg = cat(loc, ": unknown algorithm '", clip(name), "'");
    if (const auto hint = closest(name, views(names))) msg += cat(" (did you mean '", *hint, "'?)");
    fail(cat(msg, "; allowed: ", algorithm_names_text()));
  }
  return parse_algorithm(name);
}

void read_algorithms(OptimiseOptions& o, const KeyInfo&, const toml::node& node, const std::string& loc) {
  std::vector<std::string> names;
  if (const auto* s = node.as_string()) {
    names.push_back(s->get());
  } else {
    names = string_list(node, loc, cat("algorithms: ", algorithm_names_text()));
  }
  if (names.empty()) fail(cat(loc, ": give at least one algorithm (", algorithm_names_text(), ")"));
  o.algorithms.clear();
  for (const std::string& name : names) {
    const Algorithm a = read_algorithm_name(name, loc);
    if (std::find(o.algorithms.begin(), o.algorithms.end(), a) != o.algorithms.end())
      fail(cat(loc, ": algorithm ", name, " is listed twice"));
    o.algorithms.push_back(a);
  }
}

std::string law_names_text() {
  std::vector<std::string> names;
  for (const ContactLawKind k : all_contact_laws()) names.push_back(to_string(k));
  return join(views(names), ", ");
}

// [optimise] law: a law, a list of them, or "all" (the contact law as a categorical variable).
void read_laws(OptimiseOptions& o, const KeyInfo&, const toml::node& node, const std::string& loc) {
  std::vector<std::string> names;
  if (const auto* s = node.as_string()) {
    names.push_back(s->get());
  } else {
    names = string_list(node, loc, cat("contact laws: ", law_names_text(), ", or \"all\""));
  }
  if (names.size() == 1 && names.front() == "all") {
    o.laws = all_contact_laws();
    return;
  }
  o.laws.clear();  // an empty list: the scene's law
  for (const std::string& name : names) {
    std::vector<std::string> known;
    for (const ContactLawKind k : all_contact_laws()) known.push_back(to_string(k));
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string msg = cat(loc, ": unknown contact law '", clip(name), "'");
      if (const auto hint = closest(name, views(known))) msg += cat(" (did you mean '", *hint, "'?)");
      fail(cat(msg, "; allowed: ", law_names_text(), ", or \"all\""));
    }
    const ContactLawKind k = parse_contact_law(name);
    if (std::find(o.laws.begin(), o.laws.end(), k) != o.laws.end()) fail(cat(loc, ": contact law ", name, " is listed twice"));
    o.laws.push_back(k);
  }
}

std::string laws_text(const OptimiseOptions& o, const KeyInfo&) {
  std::vector<std::string> names;
  for (const ContactLawKind k : o.laws) names.push_back(toml_string(to_string(k)));
  return cat("[", join(views(names), ", "), "]");
}

void read_map_path(OptimiseOptions& o, const KeyInfo&, const toml::node& node, const std::string& loc) {
  const auto* s = node.as_string();
  if (s == nullptr || s->get().empty()) fail(cat(loc, ": must be the path of a map file (HDF5), a non-empty string"));
  o.map = s->get();
}

std::string regime_text(const OptimiseOptions& o, const KeyInfo&) { return o.regime ? o.regime->label() : "any"; }

std::string algorithms_text(const OptimiseOptions& o, const KeyInfo&) {
  std::vector<std::string> names;
  for (const Algorithm a : o.algorithms) names.push_back(to_string(a));
  return join(views(names), ", ");
}

std::string map_text(const OptimiseOptions& o, const KeyInfo&) { return o.map.empty() ? "(none)" : toml_string(o.map); }

// A documentation row: type, allowed range, unit, meaning, default as text.
OptimiseRow optimise_row(std::string_view key, KeyType type, Bounds bounds, std::string_view unit,
                         std::string_view meaning, std::string default_text, RowAccess<OptimiseOptions> access) {
  return {{kOptimise, key, type, bounds, {}, unit, meaning, {}, std::move(default_text), true}, access.read, access.text, {}};
}

// A numeric option: its row is the key table's (option_keys(), core/model/keys.hpp).
OptimiseRow numeric_row(std::string_view key, std::string default_text, RowAccess<OptimiseOptions> access) {
  KeyInfo info = option_key(cat(kOptimise, ".", key));
  info.default_text = std::move(default_text);
  return {std::move(info), access.read, access.text, {}};
}

template <class Enum>
OptimiseRow optimise_choice(std::string_view key, std::string_view meaning, const std::vector<Enum>& values, Enum def,
                            RowAccess<OptimiseOptions> read) {
  static const std::vector<std::string> names = [&] {  // static storage: KeyInfo::choices holds views
    std::vector<std::string> n;
    for (const Enum v : values) n.push_back(to_string(v));
    return n;
  }();
  OptimiseRow r = optimise_row(key, KeyType::choice, Bounds::finite(), "-", meaning, toml_string(to_string(def)), read);
  for (const std::string& n : names) r.info.choices.push_back(n);
  return r;
}

void add_optimise_goal_rows(std::vector<OptimiseRow>& rows, const OptimiseOptions& d) {
  using O = OptimiseOptions;
  rows.push_back(optimise_choice(
      "objective",
      "what to optimise: min_k_con (the softest impact: k_con = T/T_con of the longest), max_T_con (the duration "
      "of impact `impact`), min_F_max (the peak contact force)",
      all_objective_kinds(), d.objective, choice_field<O, parse_objective_kind, &O::objective>()));
  rows.push_back(numeric_row("impact", std::to_string(d.impact), integer_field<O, &O::impact>()));
  rows.push_back(optimise_row("regime", KeyType::choice, Bounds::finite(), "-",
                              "the regime to keep, a constraint (never traded for a better objective); \"any\": "
                              "any motion with an impact",
                              toml_string(d.regime->label()), {read_regime, regime_text}));
  rows.back().allowed_text = "\"(n,k)\" or \"any\"";
  rows.push_back(optimise_choice(
      "stability",
      "the kept orbit's Floquet stability: if_known (an orbit found unstable is infeasible), required (only one "
      "known stable is feasible) or ignored",
      all_stability_rules(), d.stability, choice_field<O, parse_stability_rule, &O::stability>()));
  rows.push_back(optimise_row("hertz_valid", KeyType::boolean, Bounds::finite(), "-",
                              "keep Hertz theory valid, z_max/R* <= [analysis] hertz_limit, as a constraint (the "
                              "default: beyond it the force law the answer was computed with does not hold); false is "
                              "an explicit choice whose answers are flagged Hertz-invalid",
                              d.hertz_valid ? "true" : "false", bool_field<O, &O::hertz_valid>()));
  rows.push_back(optimise_row("algorithm", KeyType::choice, Bounds::finite(), "-",
                              "local algorithm, or a list of them, each started from every seed: bobyqa, cobyla, "
                              "sbplx (NLopt, derivative-free), slsqp, mma (NLopt, finite-difference gradients), "
                              "gradient_projection (the source paper's method)",
                              toml_string(to_string(d.algorithms.front())), {read_algorithms, algorithms_text}));
  rows.back().allowed_text = "a name or a list of names";
  rows.push_back(optimise_row("law", KeyType::choice, Bounds::finite(), "-",
                              "the contact law as a categorical free variable: every seed and algorithm is started "
                              "once with each law listed (hertz, hunt-crossley, lankarani-nikravesh, flores, "
                              "gonthier, or \"all\"), and the best point over them all is the answer; [] (the "
                              "default): the scene's [contact] law",
                              "[]", {read_laws, laws_text}));
  rows.back().allowed_text = "a law, a list of laws, [] or \"all\"";
  rows.push_back(numeric_row("seeds", std::to_string(d.seeds), integer_field<O, &O::seeds>()));
  rows.push_back(optimise_row("map", KeyType::choice, Bounds::finite(), "-",
                              "seeding map (HDF5 from vibromap sweep; a path from the current directory); not "
                              "given: the scene's [sweep] runs first into OUTPUT_map.h5, or, without [sweep], the "
                              "scene's point is the one seed",
                              "(none)", {read_map_path, map_text}));
  rows.back().allowed_text = "a path";
}

void add_optimise_stopping_rows(std::vector<OptimiseRow>& rows, const OptimiseOptions& d) {
  using O = OptimiseOptions;
  using L = LocalOptions;
  constexpr auto local = &O::local;
  const LocalOptions& l = d.local;
  rows.push_back(numeric_row("xtol_rel", float_text(l.xtol_rel), real_field<O, local, &L::xtol_rel>()));
  rows.push_back(numeric_row("ftol_rel", float_text(l.ftol_rel), real_field<O, local, &L::ftol_rel>()));
  rows.push_back(numeric_row("max_evaluations", std::to_string(l.max_evaluations),
                             integer_field<O, local, &L::max_evaluations>()));
  rows.push_back(numeric_row("max_time", float_text(l.max_time), real_field<O, local, &L::max_time>()));
  rows.push_back(numeric_row("initial_step", float_text(l.initial_step), real_field<O, local, &L::initial_step>()));
  rows.push_back(numeric_row("fd_step", float_text(l.fd_step), real_field<O, local, &L::fd_step>()));
  rows.push_back(numeric_row("barrier", float_text(l.barrier), real_field<O, local, &L::barrier>()));
  rows.push_back(numeric_row("best", std::to_string(d.best), integer_field<O, &O::best>()));
  rows.push_back(numeric_row("verify_rtol", float_text(d.verify_rtol), real_field<O, &O::verify_rtol>()));
}

void add_optimise_soft_rows(std::vector<OptimiseRow>& rows, const OptimiseOptions& d) {
  using O = OptimiseOptions;
  rows.push_back(numeric_row("min_soft_fraction", float_text(d.min_soft_fraction), real_field<O, &O::min_soft_fraction>()));
  rows.push_back(numeric_row("soft_check_initial_conditions", std::to_string(d.soft_check_initial_conditions),
                             integer_field<O, &O::soft_check_initial_conditions>()));
}

}  // namespace

const std::vector<OptimiseRow>& optimise_rows() {
  static const std::vector<OptimiseRow> rows = [] {
    const OptimiseOptions defaults;
    std::vector<OptimiseRow> r;
    add_optimise_goal_rows(r, defaults);
    add_optimise_stopping_rows(r, defaults);
    add_optimise_soft_rows(r, defaults);
    return r;
  }();
  return rows;
}

const std::vector<std::string_view>& optimise_option_keys() {
  static const std::vector<std::string_view> keys = [] {
    std::vector<std::string_view> k;
    for (const OptimiseRow& row : optimise_rows()) k.push_back(row.info.name);
    return k;
  }();
  return keys;
}

const std::vector<std::string_view>& optimise_keys() {
  static const std::vector<std::string_view> keys = [] {
    std::vector<std::string_view> k;
    for (const Key p : Key::all())
      if (p.is_parameter()) k.push_back(p.info().name);
    k.insert(k.end(), optimise_option_keys().begin(), optimise_option_keys().end());
    return k;
  }();
  return keys;
}

bool is_optimise_option(std::string_view key) {
  return std::find(optimise_option_keys().begin(), optimise_option_keys().end(), key) != optimise_option_keys().end();
}

namespace {

// A free parameter's box: { min, max[, scale] }, inside the range of the parameter's own key.
FreeVariable read_variable(Key key, std::string_view name, const toml::node& node, const std::string& loc) {
  const toml::table* t = node.as_table();
  if (t == nullptr) fail(cat(loc, ": free parameter ", name, " must be an inline table ", kVariableForm));
  const std::vector<std::string_view> fields = {"min", "max", "scale"};
  for (auto&& [field, value] : *t) {
    if (std::find(fields.begin(), fields.end(), field.str()) != fields.end()) continue;
    std::string msg = cat(loc, ": unknown field '", field.str(), "' in free parameter ", name);
    if (const auto hint = closest(field.str(), fields)) msg += cat(" (did you mean '", *hint, "'?)");
    fail(cat(msg, "; a free parameter is ", kVariableForm));
  }
  for (const std::string_view field : {"min", "max"}) {
    if (!t->contains(field)) fail(cat(loc, ": free parameter ", name, " lacks '", field, "': give ", kVariableForm));
  }
  FreeVariable v{key, axis_end(*t, "min", loc), axis_end(*t, "max", loc), axis_scale(*t, loc)};
  if (!(v.min < v.max)) fail(cat(loc, ": min must be < max"));
  if (v.scale == AxisScale::log && v.min <= 0.0) fail(cat(loc, ": a log scale needs min > 0"));
  for (const double x : {v.min, v.max})
    if (const std::string r = key.check(x); !r.empty()) fail(cat(loc, ": the box reaches ", r));
  return v;
}

// The free parameters in the default order of axes (key_rank), each once and never both keys of a pair.
std::vector<FreeVariable> read_variables(const toml::table& sec, const Context& ctx) {
  std::vector<std::pair<FreeVariable, std::string>> found;  // with the name as given
  for_each_key_entry(sec, is_optimise_option, [&](std::string given, std::string, const toml::node& node) {
    const std::string loc = locate(ctx, kOptimise, given, node);
    const std::optional<Key> key = free_parameter(given);
    if (!key) fail(cat(origin(ctx, kOptimise, given, node), ": ", clip(given), " cannot be a free parameter of [optimise]: ",
                       "free parameters are the real keys of [system], [contact] and [forcing] (see 'vibromap keys')"));
    for (const auto& [other, other_given] : found) {
      if (other.key == *key)
        fail(cat(where(ctx, node), ": [optimise] ", key->full_name(), " is free twice (as ", clip(other_given), " and ",
                 clip(given), "): give each free parameter once"));
      if (other.name() == key->info().partner)
        fail(cat(where(ctx, node), ": [optimise] both ", other.name(), " and ", key->info().name,
                 " given as free parameters: free only one ", pair_advice(other.key.info(), key->info())));
    }
    found.emplace_back(read_variable(*key, given, node, loc), given);
  });
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return key_rank(a.first.key) < key_rank(b.first.key); });
  std::vector<FreeVariable> vars;
  for (auto& [v, given] : found) vars.push_back(v);
  if (vars.empty()) {
    fail(cat(where(ctx, sec), ": [optimise] has no free parameters: give at least one real key of [system], [contact] ",
             "or [forcing] (E1, m2, omega2, \"forcing.omega\", ...) as NAME = ", kVariableForm));
  }
  return vars;
}

}  // namespace

std::optional<OptimiseOptions> read_optimise(const toml::table& table, const Context& ctx) {
  const toml::table* sec = table.get_as<toml::table>(kOptimise);
  if (sec == nullptr) return std::nullopt;
  OptimiseOptions o;
  o.variables = read_variables(*sec, ctx);
  read_rows(o, optimise_rows(), *sec, ctx);
  if (const std::string err = validate(o); !err.empty()) fail(cat(ctx.path, ": [optimise] ", err));
  return o;
}

std::vector<std::string> optimise_lines(const OptimiseOptions& o) {
  std::vector<std::string> lines;
  for (const FreeVariable& v : o.variables) {
    lines.push_back(cat("optimise.", v.name(), " = { min = ", shortest(v.min), ", max = ", shortest(v.max),
                        ", scale = ", to_string(v.scale), " }"));
  }
  for (std::string& line : row_lines(kOptimise, o, optimise_rows())) lines.push_back(std::move(line));
  return lines;
}

}  // namespace vibromap::detail
