#include "vibromap/io/scene.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <type_traits>
#include <utility>

#include <toml++/toml.h>

#include "vibromap/core/text.hpp"

namespace vibromap {
namespace detail {

// A checked value of one key: `real` for real and integer keys, `integer` for integer
// keys, `choice` (index into SceneKey::choices) for choice keys.
struct KeyValue {
  double real = 0.0;
  long long integer = 0;
  int choice = 0;
};

// A Scene being read. [initial] keys are collected apart: a missing one defaults to the
// rest state, which depends on D, known only when every key has been read.
struct SceneDraft {
  Scene scene;
  std::array<std::optional<double>, 4> initial;
};

using Setter = void (*)(SceneDraft&, const KeyValue&);
using Getter = std::optional<KeyValue> (*)(const Scene&);  // nullopt: not set in this form

struct Accessors {
  Setter set;
  Getter get;
  long long int_max;  // integer keys: the largest value the field's type holds
};

// One row of the schema: the documentation view plus how to read and write the value.
struct Binding {
  SceneKey info;
  Accessors access;
  std::string_view unset_default;  // default_text when the default Scene does not set the key
};

}  // namespace detail

namespace {

using detail::Accessors;
using detail::Binding;
using detail::KeyValue;
using detail::SceneDraft;

constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------
// Accessors: the field a key reads and writes, named by a chain of member pointers.

template <auto... Members>
constexpr Accessors field() {
  using T = std::remove_cvref_t<decltype((std::declval<Scene&>().*....*Members))>;
  static_assert(std::is_arithmetic_v<T>);
  Accessors a{};
  a.set = [](SceneDraft& d, const KeyValue& v) {
    auto& f = (d.scene.*....*Members);
    if constexpr (std::is_floating_point_v<T>) {
      f = v.real;
    } else {
      f = static_cast<T>(v.integer);
    }
  };
  a.get = [](const Scene& s) -> std::optional<KeyValue> {
    const auto& f = (s.*....*Members);
    if constexpr (std::is_floating_point_v<T>) {
      return KeyValue{f, 0, 0};
    } else {
      return KeyValue{static_cast<double>(f), static_cast<long long>(f), 0};
    }
  };
  if constexpr (std::is_integral_v<T>) a.int_max = std::numeric_limits<T>::max();
  return a;
}

// A Spring or Damper member of Parameters given in form `Form` (k or omega, c or xi).
template <auto Member, auto Form>
constexpr Accessors either_form() {
  using T = std::remove_cvref_t<decltype(std::declval<Parameters&>().*Member)>;
  Accessors a{};
  a.set = [](SceneDraft& d, const KeyValue& v) { d.scene.params.*Member = T{Form, v.real}; };
  a.get = [](const Scene& s) -> std::optional<KeyValue> {
    const T& f = s.params.*Member;
    if (f.form != Form) return std::nullopt;
    return KeyValue{f.value, 0, 0};
  };
  return a;
}

template <int I>
constexpr Accessors initial_component() {
  Accessors a{};
  a.set = [](SceneDraft& d, const KeyValue& v) { d.initial[I] = v.real; };
  a.get = [](const Scene& s) -> std::optional<KeyValue> {
    if (!s.params.initial) return std::nullopt;
    return KeyValue{(*s.params.initial)[I], 0, 0};
  };
  return a;
}

// The values a choice key offers, in the order the scene lists them. Their names are the
// core's to_string(), so the scene, the summaries and the core spell them one way.
constexpr std::array kMethodValues = {Method::hybrid, Method::dopri5, Method::rk4};
constexpr std::array kSteadyValues = {SteadyMethod::shooting, SteadyMethod::integrate};

// The names of Values (static storage: SceneKey::choices holds views of them).
template <auto Values>
const std::vector<std::string>& enum_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto v : Values) n.push_back(to_string(v));
    return n;
  }();
  return names;
}

// An enum field chosen by name from Values (KeyValue::choice is the index into Values).
template <auto Values, auto... Members>
Accessors enum_field() {
  Accessors a{};
  a.set = [](SceneDraft& d, const KeyValue& v) {
    (d.scene.*....*Members) = Values.at(static_cast<std::size_t>(v.choice));
  };
  a.get = [](const Scene& s) -> std::optional<KeyValue> {
    for (std::size_t i = 0; i < Values.size(); ++i) {
      if (Values[i] == (s.*....*Members)) return KeyValue{0.0, 0, static_cast<int>(i)};
    }
    return std::nullopt;
  };
  return a;
}

// ---------------------------------------------------------------------------------------
// The schema. To add a section, write its rows in a function like these and list the
// function in bindings(); parsing, checks, `vibromap keys` and the reference scene follow.

constexpr Bounds gt(double lo) { return {lo, kInf, true, false}; }
constexpr Bounds ge(double lo) { return {lo, kInf, false, false}; }
constexpr Bounds any_finite() { return {-kInf, kInf, false, false}; }
constexpr Bounds interval(double lo, double hi, bool lo_open, bool hi_open) { return {lo, hi, lo_open, hi_open}; }

Binding row(std::string_view section, std::string_view key, SceneKeyType type, Bounds bounds,
            std::string_view unit, std::string_view meaning, Accessors access,
            std::string_view partner = {}, std::string_view unset_default = {}) {
  SceneKey info{section, key, type, bounds, {}, unit, meaning, partner, {}, false};
  return Binding{std::move(info), access, unset_default};
}

Binding real(std::string_view s, std::string_view k, Bounds b, std::string_view unit,
             std::string_view meaning, Accessors a, std::string_view partner = {},
             std::string_view unset_default = {}) {
  return row(s, k, SceneKeyType::real, b, unit, meaning, a, partner, unset_default);
}

Binding integer(std::string_view s, std::string_view k, Bounds b, std::string_view meaning, Accessors a) {
  return row(s, k, SceneKeyType::integer, b, "-", meaning, a);
}

Binding boolean(std::string_view s, std::string_view k, std::string_view meaning, Accessors a) {
  return row(s, k, SceneKeyType::boolean, any_finite(), "-", meaning, a);
}

// A choice key whose allowed strings are `names` (enum_names<Values>() of its accessor).
Binding choice(std::string_view s, std::string_view k, std::string_view meaning, Accessors a,
               const std::vector<std::string>& names) {
  Binding b = row(s, k, SceneKeyType::choice, any_finite(), "-", meaning, a);
  for (const std::string& n : names) b.info.choices.push_back(n);
  return b;
}

void add_system_keys(std::vector<Binding>& rows) {
  constexpr std::string_view s = "system";
  using P = Parameters;
  rows.push_back(real(s, "m1", gt(0), "kg", "main body mass", field<&Scene::params, &P::m1>()));
  rows.push_back(real(s, "m2", gt(0), "kg", "attached body mass", field<&Scene::params, &P::m2>()));
  rows.push_back(real(s, "k1", gt(0), "N/m", "main spring stiffness",
                      either_form<&P::spring1, Spring::Form::stiffness>(), "omega1", "m1*omega1^2"));
  rows.push_back(real(s, "omega1", gt(0), "rad/s", "main spring as partial frequency sqrt(k1/m1)",
                      either_form<&P::spring1, Spring::Form::frequency>(), "k1", "sqrt(k1/m1)"));
  rows.push_back(real(s, "k2", ge(0), "N/m", "coupling spring stiffness",
                      either_form<&P::spring2, Spring::Form::stiffness>(), "omega2", "m2*omega2^2"));
  rows.push_back(real(s, "omega2", ge(0), "rad/s", "coupling spring as partial frequency sqrt(k2/m2)",
                      either_form<&P::spring2, Spring::Form::frequency>(), "k2", "sqrt(k2/m2)"));
  rows.push_back(real(s, "xi1", ge(0), "-", "main damping ratio c1/(2 m1 omega1)",
                      either_form<&P::damper1, Damper::Form::ratio>(), "c1", "c1/(2*sqrt(m1*k1))"));
  rows.push_back(real(s, "c1", ge(0), "N s/m", "main damper coefficient",
                      either_form<&P::damper1, Damper::Form::coefficient>(), "xi1", "2*xi1*sqrt(m1*k1)"));
  rows.push_back(real(s, "xi2", ge(0), "-", "coupling damping ratio c2/(2 m2 omega2)",
                      either_form<&P::damper2, Damper::Form::ratio>(), "c2", "c2/(2*sqrt(m2*k2))"));
  rows.push_back(real(s, "c2", ge(0), "N s/m", "coupling damper coefficient",
                      either_form<&P::damper2, Damper::Form::coefficient>(), "xi2", "2*xi2*sqrt(m2*k2)"));
  rows.push_back(real(s, "D", ge(0), "m", "clearance between the bodies at rest",
                      field<&Scene::params, &P::D>()));
}

void add_contact_keys(std::vector<Binding>& rows) {
  constexpr std::string_view s = "contact";
  using P = Parameters;
  const Bounds poisson = interval(-1.0, 0.5, true, true);
  rows.push_back(real(s, "E1", gt(0), "Pa", "Young's modulus of body 1", field<&Scene::params, &P::E1>()));
  rows.push_back(real(s, "E2", gt(0), "Pa", "Young's modulus of body 2", field<&Scene::params, &P::E2>()));
  rows.push_back(real(s, "nu1", poisson, "-", "Poisson ratio of body 1", field<&Scene::params, &P::nu1>()));
  rows.push_back(real(s, "nu2", poisson, "-", "Poisson ratio of body 2", field<&Scene::params, &P::nu2>()));
  rows.push_back(real(s, "R1", gt(0), "m", "radius of curvature of body 1 at the contact",
                      field<&Scene::params, &P::R1>()));
  rows.push_back(real(s, "R2", gt(0), "m", "radius of curvature of body 2 at the contact",
                      field<&Scene::params, &P::R2>()));
  rows.push_back(real(s, "q", gt(0), "-", "Hertz shape coefficient (0.319: circular contact)",
                      field<&Scene::params, &P::q>()));
}

void add_forcing_keys(std::vector<Binding>& rows) {
  constexpr std::string_view s = "forcing";
  using P = Parameters;
  rows.push_back(real(s, "F0", ge(0), "N", "force amplitude", field<&Scene::params, &P::F0>()));
  rows.push_back(real(s, "omega", gt(0), "rad/s", "forcing frequency (period T = 2 pi/omega)",
                      field<&Scene::params, &P::omega>()));
  rows.push_back(real(s, "lambda", ge(0), "-", "amplitude factor: F(t) = lambda F0 cos(omega t + phi0)",
                      field<&Scene::params, &P::lambda>()));
  rows.push_back(real(s, "phi0", any_finite(), "rad", "forcing phase at t = 0",
                      field<&Scene::params, &P::phi0>()));
}

void add_solver_keys(std::vector<Binding>& rows) {
  constexpr std::string_view s = "solver";
  using O = IntegratorOptions;
  constexpr auto opt = &Scene::options;
  constexpr auto integ = &PointOptions::integrator;
  rows.push_back(choice(s, "method",
                        "integration method: hybrid (closed-form free flight, dopri5 in contact), dopri5 "
                        "(adaptive, located contact events) or rk4 (the paper's fixed step)",
                        enum_field<kMethodValues, opt, integ, &O::method>(), enum_names<kMethodValues>()));
  rows.push_back(real(s, "rtol", interval(0.0, 0.1, true, true), "-", "hybrid, dopri5: relative local error tolerance",
                      field<opt, integ, &O::rtol>()));
  rows.push_back(real(s, "atol", gt(0), "m",
                      "hybrid, dopri5: absolute tolerance on x1 and z (on velocities: atol*omega)",
                      field<opt, integ, &O::atol>()));
  rows.push_back(real(s, "max_step", interval(0.0, 1.0, true, false), "-",
                      "hybrid, dopri5: largest step, as a fraction of the forcing period T",
                      field<opt, integ, &O::max_step>()));
  rows.push_back(integer(s, "rk4_steps", ge(1), "rk4: steps per forcing period", field<opt, integ, &O::rk4_steps>()));
  rows.push_back(integer(s, "max_steps", ge(1), "budget of steps (accepted + rejected) for the whole run",
                         field<opt, integ, &O::max_steps>()));
}

void add_analysis_keys(std::vector<Binding>& rows) {
  constexpr std::string_view s = "analysis";
  using A = AnalysisOptions;
  constexpr auto opt = &Scene::options;
  constexpr auto an = &PointOptions::analysis;
  rows.push_back(choice(s, "steady",
                        "how the steady motion is found: shooting (Newton on the stroboscopic map; gives "
                        "Floquet multipliers; falls back to integrate) or integrate (until samples repeat)",
                        enum_field<kSteadyValues, opt, an, &A::steady>(), enum_names<kSteadyValues>()));
  rows.push_back(integer(s, "transient_periods", ge(1), "shooting: forcing periods integrated before Newton starts",
                         field<opt, an, &A::transient_periods>()));
  rows.push_back(real(s, "newton_tol", ge(0), "-",
                      "shooting: scaled residual |P^n(y) - y| at which Newton stops; 0: auto, rtol",
                      field<opt, an, &A::newton_tol>()));
  rows.push_back(integer(s, "newton_max_iterations", interval(1, 1000, false, false),
                         "shooting: Newton iterations before falling back to integrate",
                         field<opt, an, &A::newton_max_iterations>()));
  rows.push_back(boolean(s, "basin_check",
                         "shooting: accept an orbit only when the transient is seen closing in on it (slower; "
                         "where attractors coexist, follows the one reached from the initial state)",
                         field<opt, an, &A::basin_check>()));
  rows.push_back(boolean(s, "lyapunov",
                         "estimate the largest Lyapunov exponent when no period is found (quasi-periodic "
                         "or chaotic); costs lyapunov_periods more periods",
                         field<opt, an, &A::lyapunov>()));
  rows.push_back(integer(s, "lyapunov_periods", ge(10), "forcing periods over which the Lyapunov exponent is averaged",
                         field<opt, an, &A::lyapunov_periods>()));
  rows.push_back(integer(s, "n_max", interval(1, 64, false, false), "largest period looked for, in forcing periods",
                         field<opt, an, &A::n_max>()));
  rows.push_back(integer(s, "max_periods", ge(1), "budget of forcing periods to reach steady state",
                         field<opt, an, &A::max_periods>()));
  rows.push_back(real(s, "steady_tol", ge(0), "-",
                      "steady-state tolerance (scaled max-norm); 0: auto, 100*rtol (rk4: 1e-9)",
                      field<opt, an, &A::steady_tol>()));
  rows.push_back(integer(s, "chatter_impacts", ge(1), "impacts per forcing period from which the motion is chatter",
                         field<opt, an, &A::chatter_impacts>()));
  rows.push_back(real(s, "hertz_limit", gt(0), "-", "z_max/R* above which Hertz theory is flagged invalid",
                      field<opt, an, &A::hertz_limit>()));
  rows.push_back(integer(s, "trajectory_periods", ge(0),
                         "forcing periods of steady motion kept as a trajectory (used by run --trajectory)",
                         field<opt, an, &A::trajectory_periods>()));
  rows.push_back(integer(s, "trajectory_samples", ge(10), "uniform samples per forcing period in a kept trajectory",
                         field<opt, an, &A::trajectory_samples>()));
}

void add_initial_keys(std::vector<Binding>& rows) {
  constexpr std::string_view s = "initial";
  rows.push_back(real(s, "x1", any_finite(), "m", "initial displacement of body 1 (any key unset: rest state)",
                      initial_component<0>(), {}, "0"));
  rows.push_back(real(s, "x2", any_finite(), "m", "initial displacement of body 2", initial_component<1>(), {}, "D"));
  rows.push_back(real(s, "v1", any_finite(), "m/s", "initial velocity of body 1", initial_component<2>(), {}, "0"));
  rows.push_back(real(s, "v2", any_finite(), "m/s", "initial velocity of body 2", initial_component<3>(), {}, "0"));
}

std::string default_text(const Binding& b, const Scene& defaults, bool& given);

const std::vector<Binding>& bindings() {
  static const std::vector<Binding> rows = [] {
    std::vector<Binding> r;
    add_system_keys(r);
    add_contact_keys(r);
    add_forcing_keys(r);
    add_solver_keys(r);
    add_analysis_keys(r);
    add_initial_keys(r);
    const Scene defaults;
    for (Binding& b : r) b.info.default_text = default_text(b, defaults, b.info.default_given);
    return r;
  }();
  return rows;
}

const Binding* find_binding(std::string_view section, std::string_view key) {
  for (const Binding& b : bindings()) {
    if (b.info.section == section && b.info.key == key) return &b;
  }
  return nullptr;
}

// The [sweep] section: its keys are the axes (sweep_axis_names(), each an inline table)
// and these options. They are not schema rows (an axis is a table, order and store are
// arrays): read_sweep() reads them, and an axis's values are checked against the range of
// the parameter's own row.
constexpr std::string_view kSweep = "sweep";
constexpr std::array<std::string_view, 4> kSweepOptionKeys = {"order", "store", "checkpoint_interval",
                                                               "progress_interval"};

const std::vector<std::string_view>& sweep_keys() {
  static const std::vector<std::string_view> keys = [] {
    std::vector<std::string_view> k = sweep_axis_names();
    k.insert(k.end(), kSweepOptionKeys.begin(), kSweepOptionKeys.end());
    return k;
  }();
  return keys;
}

// The [optimise] section: its keys are the free parameters (sweep_axis_names(), each an
// inline table { min, max[, scale] }) and these options. Like [sweep]'s, they are not schema
// rows: read_optimise() reads them, documented by optimise_rows().
constexpr std::string_view kOptimise = "optimise";
constexpr std::array<std::string_view, 17> kOptimiseOptionKeys = {
    "objective", "impact",   "regime",          "stability", "hertz_valid",  "algorithm", "seeds",   "map", "xtol_rel",
    "ftol_rel",  "max_evaluations", "max_time", "initial_step", "fd_step",   "barrier", "best", "verify_rtol"};

const std::vector<std::string_view>& optimise_keys() {
  static const std::vector<std::string_view> keys = [] {
    std::vector<std::string_view> k = sweep_axis_names();
    k.insert(k.end(), kOptimiseOptionKeys.begin(), kOptimiseOptionKeys.end());
    return k;
  }();
  return keys;
}

bool is_parameter_name(std::string_view name) {
  const auto& names = variable_parameter_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Every section: the schema's, then [sweep], then [optimise].
std::vector<std::string_view> all_sections() {
  std::vector<std::string_view> sections = scene_sections();
  sections.push_back(kOptimise);
  return sections;
}

bool is_axis_name(std::string_view name) {
  const auto& axes = sweep_axis_names();
  return std::find(axes.begin(), axes.end(), name) != axes.end();
}

// The section that has a key of this name, if any ([sweep] only for its own options).
std::optional<std::string_view> section_of(std::string_view key) {
  for (const Binding& b : bindings()) {
    if (b.info.key == key) return b.info.section;
  }
  if (std::find(kSweepOptionKeys.begin(), kSweepOptionKeys.end(), key) != kSweepOptionKeys.end()) return kSweep;
  if (std::find(kOptimiseOptionKeys.begin(), kOptimiseOptionKeys.end(), key) != kOptimiseOptionKeys.end())
    return kOptimise;
  return std::nullopt;
}

// The schema row of a swept parameter (its range and unit): E1 -> [contact] E1.
const SceneKey& axis_key(std::string_view name) { return find_binding(*section_of(name), name)->info; }

// The schema's sections, in order (without [sweep]).
std::vector<std::string_view> schema_sections() {
  std::vector<std::string_view> sections;
  for (const Binding& b : bindings()) {
    if (sections.empty() || sections.back() != b.info.section) sections.push_back(b.info.section);
  }
  return sections;
}

bool is_section(std::string_view name) {
  const auto sections = all_sections();
  return std::find(sections.begin(), sections.end(), name) != sections.end();
}

std::vector<std::string_view> keys_of(std::string_view section) {
  if (section == kSweep) return sweep_keys();
  if (section == kOptimise) return optimise_keys();
  std::vector<std::string_view> keys;
  for (const Binding& b : bindings()) {
    if (b.info.section == section) keys.push_back(b.info.key);
  }
  return keys;
}

bool has_key(std::string_view section, std::string_view key) {
  if (section == kSweep) return std::find(sweep_keys().begin(), sweep_keys().end(), key) != sweep_keys().end();
  if (section == kOptimise) return std::find(optimise_keys().begin(), optimise_keys().end(), key) != optimise_keys().end();
  return find_binding(section, key) != nullptr;
}

// The other key of an either-or pair (omega2 for k2, also as [sweep] axes and free
// parameters of [optimise]), or empty.
std::string_view partner_of(std::string_view section, std::string_view key) {
  if (section == kSweep || section == kOptimise) return is_axis_name(key) ? axis_key(key).partner : std::string_view{};
  const Binding* b = find_binding(section, key);
  return b != nullptr ? b->info.partner : std::string_view{};
}

// ---------------------------------------------------------------------------------------
// Text helpers.


// Shortest text that reads back to the same double ("0.1", "1e-10", "1000").
std::string shortest(double v) {
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), res.ptr);
}

// As shortest(), but always a TOML float ("1000.0").
std::string toml_float(double v) {
  std::string s = shortest(v);
  if (std::isfinite(v) && s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

std::string join(const std::vector<std::string_view>& items, std::string_view sep, std::string_view quote = {}) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += sep;
    out += quote;
    out += items[i];
    out += quote;
  }
  return out;
}

std::string unit_suffix(std::string_view unit) {
  return unit.empty() || unit == "-" ? std::string() : cat(" (", unit, ")");
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return std::string(s.substr(first, last - first + 1));
}

// Optimal-string-alignment edit distance (Levenshtein plus adjacent transpositions),
// case-insensitive: "omgea" is 1 from "omega".
std::size_t edit_distance(std::string_view a_in, std::string_view b_in) {
  const std::string a = lower(a_in), b = lower(b_in);
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

// The candidate closest to `name`, when it is close enough to be a likely typo.
std::optional<std::string_view> closest(std::string_view name, const std::vector<std::string_view>& candidates) {
  const std::size_t limit = name.size() <= 3 ? 1 : 2;
  std::optional<std::string_view> best;
  std::size_t best_d = limit + 1;
  for (std::string_view c : candidates) {
    const std::size_t d = edit_distance(name, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

// A TOML basic string: "..." with quotes, backslashes and control characters escaped.
std::string toml_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      std::array<char, 8> buf{};
      std::snprintf(buf.data(), buf.size(), "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buf.data();
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// A key as TOML text: bare when it can be, else quoted.
std::string toml_key(std::string_view k) {
  const bool bare = !k.empty() && std::all_of(k.begin(), k.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
  });
  return bare ? std::string(k) : toml_string(k);
}

// Where a key goes in an inline table's text: an axis's (or a free parameter's) fields in the
// order a person writes them (toml++ keeps a table's keys sorted), other keys after them in that sorted order.
std::size_t field_rank(std::string_view key) {
  constexpr std::array<std::string_view, 7> order = {"from", "to", "n", "values", "min", "max", "scale"};
  return static_cast<std::size_t>(std::find(order.begin(), order.end(), key) - order.begin());
}

std::string node_text(const toml::node& node);

std::string table_text(const toml::table& t) {
  std::vector<std::pair<std::string_view, const toml::node*>> items;
  for (auto&& [k, v] : t) items.emplace_back(k.str(), &v);
  std::stable_sort(items.begin(), items.end(),
                   [](const auto& a, const auto& b) { return field_rank(a.first) < field_rank(b.first); });
  std::string out = "{";
  for (std::size_t i = 0; i < items.size(); ++i) {
    out += cat(i > 0 ? ", " : " ", toml_key(items[i].first), " = ", node_text(*items[i].second));
  }
  return out + (items.empty() ? "}" : " }");
}

// A value as TOML text; floats in their shortest round-trip form (toml++ prints 17 digits),
// arrays and tables (also nested) as inline ones.
std::string node_text(const toml::node& node) {
  if (const auto* f = node.as_floating_point()) return toml_float(f->get());
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* s = node.as_string()) return toml_string(s->get());
  if (const auto* a = node.as_array()) {
    std::string out = "[";
    for (std::size_t i = 0; i < a->size(); ++i) out += cat(i > 0 ? ", " : "", node_text(*a->get(i)));
    return out + "]";
  }
  if (const auto* t = node.as_table()) return table_text(*t);
  std::ostringstream os;
  os << toml::node_view<const toml::node>(node);
  return os.str();
}

// node_text() cut to a length fit for a one-line message.
std::string clipped_text(const toml::node& node) {
  constexpr std::size_t kMax = 100;
  std::string s = node_text(node);
  if (s.size() > kMax) s = cat(s.substr(0, kMax - 4), " ...");
  return s;
}

std::string value_text(const SceneKey& k, const KeyValue& v) {
  switch (k.type) {
    case SceneKeyType::real: return toml_float(v.real);
    case SceneKeyType::integer: return std::to_string(v.integer);
    case SceneKeyType::choice: return toml_string(k.choices.at(static_cast<std::size_t>(v.choice)));
    case SceneKeyType::boolean: return v.integer != 0 ? "true" : "false";
  }
  return {};
}

std::string default_text(const Binding& b, const Scene& defaults, bool& given) {
  const auto v = b.access.get(defaults);
  given = v.has_value();
  return given ? value_text(b.info, *v) : std::string(b.unset_default);
}

// ---------------------------------------------------------------------------------------
// Reading a scene: parse, apply overrides, check the structure, read and check each key.

[[noreturn]] void fail(const std::string& message) { throw SceneError(message); }

struct Context {
  std::string path;
  std::map<std::string, std::string, std::less<>> overrides;  // "section.key" -> "--set ..." as given
  std::vector<std::string> override_list;                     // in command-line order
};

std::string where(const Context& ctx, const toml::node& node) {
  const auto line = node.source().begin.line;
  return line > 0 ? ctx.path + ":" + std::to_string(line) : ctx.path;
}

// "file:3: [system] m2 = -5" or "file: --set system.m2=-5".
std::string locate(const Context& ctx, std::string_view section, std::string_view key, const toml::node& node) {
  const auto it = ctx.overrides.find(cat(section, ".", key));
  if (it != ctx.overrides.end()) return ctx.path + ": " + it->second;
  return cat(where(ctx, node), ": [", section, "] ", key, " = ", clipped_text(node));
}

std::string locate(const Context& ctx, const SceneKey& k, const toml::node& node) {
  return locate(ctx, k.section, k.key, node);
}

[[noreturn]] void fail_unknown_key(const std::string& loc, std::string_view section, std::string_view key) {
  std::string msg = cat(loc, ": unknown key '", key, "' in [", section, "]");
  const auto keys = keys_of(section);
  const auto home = section_of(key);
  if (home && section == kSweep) {
    msg += cat(" (", key, " cannot be swept)");
  } else if (home && section == kOptimise && is_parameter_name(key)) {
    msg += cat(" (", key, " cannot be a free parameter)");
  } else if (home) {
    msg += cat(" (it belongs in [", *home, "])");
  } else if (const auto hint = closest(key, keys)) {
    msg += cat(" (did you mean '", *hint, "'?)");
  }
  fail(cat(msg, "; keys of [", section, "]: ", join(keys, ", ")));
}

[[noreturn]] void fail_unknown_section(const std::string& loc, std::string_view name) {
  std::string msg = cat(loc, ": unknown section [", name, "]");
  if (const auto hint = closest(name, all_sections())) msg += cat(" (did you mean [", *hint, "]?)");
  fail(cat(msg, "; sections: ", join(all_sections(), ", ")));
}

[[noreturn]] void fail_key_outside_section(const std::string& loc, std::string_view key) {
  if (const auto home = section_of(key)) {
    fail(cat(loc, ": key '", key, "' is outside any section: put it under [", *home, "]"));
  }
  fail_unknown_section(loc, key);
}

toml::table parse_toml(std::string_view text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& pos = e.source().begin;
    fail(cat(path, ":", std::to_string(pos.line), ":", std::to_string(pos.column), ": malformed TOML: ",
             e.description()));
  }
}

// Reads an override's value as TOML ("310", "1e-8", "\"rk4\""), else as a string ("rk4").
void assign_override_value(toml::table& section, std::string_view key, const std::string& raw) {
  try {
    const toml::table parsed = toml::parse("v = " + raw);
    const toml::node* node = parsed.get("v");
    if (parsed.size() == 1 && node != nullptr) {
      node->visit([&](const auto& n) { section.insert_or_assign(key, n); });
      return;
    }
  } catch (const toml::parse_error&) {
    // not a TOML value: a bare string
  }
  section.insert_or_assign(key, raw);
}

void apply_override(toml::table& table, const std::string& given, Context& ctx) {
  const std::string option = "--set " + given;
  const auto eq = given.find('=');
  const std::string name = trim(std::string_view(given).substr(0, std::min(eq, given.size())));
  const auto dot = name.find('.');
  if (eq == std::string::npos || dot == std::string::npos || dot == 0 || dot + 1 == name.size()) {
    const auto home = section_of(name);
    const std::string example = home ? cat(*home, ".", name, "=...") : std::string("system.m2=310");
    fail(cat(ctx.path, ": ", option, ": expected section.key=value (e.g. --set ", example, ")"));
  }
  const std::string section = name.substr(0, dot), key = name.substr(dot + 1);
  if (!is_section(section)) fail_unknown_section(ctx.path + ": " + option, section);
  if (!has_key(section, key)) fail_unknown_key(ctx.path + ": " + option, section, key);
  if (!table.contains(section)) table.insert(section, toml::table{});
  toml::table* sec = table.get_as<toml::table>(section);
  if (sec == nullptr) fail(where(ctx, *table.get(section)) + ": '" + section + "' must be a section [" + section + "]");
  assign_override_value(*sec, key, trim(std::string_view(given).substr(eq + 1)));
  if (const auto partner = partner_of(section, key); !partner.empty()) sec->erase(partner);  // --set replaces the other form
  ctx.overrides[name] = option;
  ctx.override_list.push_back(option);
}

void check_structure(const toml::table& table, const Context& ctx) {
  for (auto&& [name, node] : table) {
    if (!is_section(name.str())) {
      if (node.is_table() || node.is_array_of_tables()) fail_unknown_section(where(ctx, node), name.str());
      fail_key_outside_section(where(ctx, node), name.str());
    }
    const toml::table* sec = node.as_table();
    if (sec == nullptr) {
      fail(cat(where(ctx, node), ": '", name.str(), "' must be a section [", name.str(), "], not a value"));
    }
    for (auto&& [key, value] : *sec) {
      if (!has_key(name.str(), key.str())) fail_unknown_key(where(ctx, value), name.str(), key.str());
    }
  }
}

void check_pair(const toml::table& section, const SceneKey& k, const Context& ctx, const toml::node& node) {
  if (k.partner.empty() || !section.contains(k.partner)) return;
  const Binding* other = find_binding(k.section, k.partner);
  fail(cat(where(ctx, node), ": [", k.section, "] both ", k.key, " and ", k.partner, " given: give only one (",
           k.key, " in ", k.unit, ", or ", k.partner, " in ", other->info.unit, ")"));
}

std::optional<double> number_of(const toml::node& node) {
  if (const auto* f = node.as_floating_point()) return f->get();
  if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
  return std::nullopt;
}

double read_real(const SceneKey& k, const toml::node& node, const std::string& loc) {
  const std::optional<double> x = number_of(node);
  const bool unbounded = !std::isfinite(k.bounds.lo) && !std::isfinite(k.bounds.hi);
  const std::string requirement = unbounded ? "a finite number" : cat("a finite number ", k.allowed());
  if (!x || !std::isfinite(*x)) fail(cat(loc, ": must be ", requirement, unit_suffix(k.unit)));
  if (!k.bounds.contains(*x)) fail(loc + ": must be " + k.allowed() + unit_suffix(k.unit));
  return *x;
}

long long read_integer(const Binding& b, const toml::node& node, const std::string& loc) {
  const SceneKey& k = b.info;
  std::optional<long long> n;
  if (const auto* i = node.as_integer()) n = i->get();
  if (const auto* f = node.as_floating_point()) {
    const double v = f->get();  // a whole float such as 2000.0 is accepted
    if (std::isfinite(v) && v == std::trunc(v) && std::abs(v) < 9.0e18) n = static_cast<long long>(v);
  }
  if (!n || !k.bounds.contains(static_cast<double>(*n))) fail(loc + ": must be " + k.allowed());
  if (*n > b.access.int_max) fail(loc + ": must be at most " + std::to_string(b.access.int_max));
  return *n;
}

int read_choice(const SceneKey& k, const toml::node& node, const std::string& loc) {
  const auto* s = node.as_string();
  if (s != nullptr) {
    for (std::size_t i = 0; i < k.choices.size(); ++i) {
      if (k.choices[i] == s->get()) return static_cast<int>(i);
    }
  }
  std::string msg = loc + ": must be " + k.allowed();
  if (s != nullptr) {
    if (const auto hint = closest(s->get(), k.choices)) msg += cat(" (did you mean \"", *hint, "\"?)");
  }
  fail(msg);
}

long long read_boolean(const SceneKey& k, const toml::node& node, const std::string& loc) {
  if (const auto* b = node.as_boolean()) return b->get() ? 1 : 0;
  fail(loc + ": must be " + k.allowed());
}

KeyValue read_value(const Binding& b, const toml::node& node, const std::string& loc) {
  KeyValue v;
  switch (b.info.type) {
    case SceneKeyType::real: v.real = read_real(b.info, node, loc); break;
    case SceneKeyType::integer:
      v.integer = read_integer(b, node, loc);
      v.real = static_cast<double>(v.integer);
      break;
    case SceneKeyType::choice: v.choice = read_choice(b.info, node, loc); break;
    case SceneKeyType::boolean: v.integer = read_boolean(b.info, node, loc); break;
  }
  return v;
}

// ---------------------------------------------------------------------------------------
// Reading the [sweep] section.

constexpr int kMaxAxisPoints = 1'000'000;  // per axis: a typo such as n = 1e9 fails, not allocates 8 GB
constexpr double kMaxCells = 1e12;         // far beyond any run; keeps the flat cell index exact

constexpr std::string_view kAxisForms = "{ from, to, n[, scale] } or { values[, scale] }";

// [sweep]'s scalar keys, documented as schema rows are, with the SweepOptions field each sets.
struct SweepInterval {
  SceneKey info;
  double SweepOptions::*field;
};

const std::vector<SweepInterval>& sweep_intervals() {
  static const std::vector<SweepInterval> rows = [] {
    const SweepOptions defaults;
    auto interval_row = [&](std::string_view key, std::string_view meaning, double SweepOptions::*f) {
      return SweepInterval{{kSweep, key, SceneKeyType::real, gt(0), {}, "s", meaning, {}, toml_float(defaults.*f), true},
                           f};
    };
    return std::vector<SweepInterval>{
        interval_row("checkpoint_interval", "seconds between checkpoints of the map file",
                     &SweepOptions::checkpoint_interval),
        interval_row("progress_interval", "seconds between progress lines when stderr is not a terminal",
                     &SweepOptions::progress_interval)};
  }();
  return rows;
}

// The dataset names of the storable quantities, in cell_result.hpp's order.
const std::vector<std::string>& quantity_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Quantity q : all_quantities()) n.push_back(to_string(q));
    return n;
  }();
  return names;
}

std::vector<std::string_view> views(const std::vector<std::string>& strings) {
  return {strings.begin(), strings.end()};
}

double axis_end(const toml::table& axis, std::string_view field, const std::string& loc) {
  const std::optional<double> x = number_of(*axis.get(field));
  if (!x || !std::isfinite(*x)) fail(cat(loc, ": ", field, " must be a finite number"));
  return *x;
}

int axis_count(const toml::node& node, const std::string& loc) {
  const std::optional<double> x = number_of(node);  // a whole float such as 23.0 is accepted
  if (!x || *x != std::trunc(*x) || *x < 1.0 || *x > kMaxAxisPoints) {
    fail(cat(loc, ": n must be an integer in [1, ", std::to_string(kMaxAxisPoints), "]"));
  }
  return static_cast<int>(*x);
}

AxisScale axis_scale(const toml::table& axis, const std::string& loc) {
  const toml::node* node = axis.get("scale");
  if (node == nullptr) return AxisScale::lin;
  const auto* s = node->as_string();
  if (s != nullptr && (s->get() == "lin" || s->get() == "log")) return parse_axis_scale(s->get());
  std::string msg = cat(loc, ": scale must be one of \"lin\", \"log\"");
  if (s != nullptr) {
    if (const auto hint = closest(s->get(), {"lin", "log"})) msg += cat(" (did you mean \"", *hint, "\"?)");
  }
  fail(msg);
}

// The axis's table, with no field but from, to, n, values and scale.
const toml::table& axis_table(std::string_view name, const toml::node& node, const std::string& loc) {
  const toml::table* t = node.as_table();
  if (t == nullptr) fail(cat(loc, ": axis ", name, " must be an inline table ", kAxisForms));
  const std::vector<std::string_view> fields = {"from", "to", "n", "values", "scale"};
  for (auto&& [key, value] : *t) {
    if (std::find(fields.begin(), fields.end(), key.str()) != fields.end()) continue;
    std::string msg = cat(loc, ": unknown field '", key.str(), "' in axis ", name);
    if (const auto hint = closest(key.str(), fields)) msg += cat(" (did you mean '", *hint, "'?)");
    fail(cat(msg, "; an axis is ", kAxisForms));
  }
  return *t;
}

std::vector<double> range_points(std::string_view name, const toml::table& axis, AxisScale scale,
                                 const std::string& loc) {
  for (const std::string_view field : {"from", "to", "n"}) {
    if (!axis.contains(field)) fail(cat(loc, ": axis ", name, " lacks '", field, "': an axis is ", kAxisForms));
  }
  const double from = axis_end(axis, "from", loc), to = axis_end(axis, "to", loc);
  const int n = axis_count(*axis.get("n"), loc);
  if (scale == AxisScale::log && (from <= 0.0 || to <= 0.0)) {
    fail(cat(loc, ": a log axis needs from > 0 and to > 0"));
  }
  if (n > 1 && from == to) fail(cat(loc, ": from = to with n = ", std::to_string(n), " repeats a point"));
  return axis_points(from, to, n, scale);
}

std::vector<double> listed_points(const toml::node& node, const std::string& loc) {
  const toml::array* a = node.as_array();
  if (a == nullptr) fail(cat(loc, ": values must be an array of finite numbers"));
  if (a->empty()) fail(cat(loc, ": values is empty: give at least one point"));
  std::vector<double> v;
  for (const toml::node& e : *a) {
    const std::optional<double> x = number_of(e);
    if (!x || !std::isfinite(*x)) fail(cat(loc, ": values must be finite numbers, not ", node_text(e)));
    v.push_back(*x);
  }
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  if (const auto it = std::adjacent_find(sorted.begin(), sorted.end()); it != sorted.end()) {
    fail(cat(loc, ": values repeat ", shortest(*it), ": give each point once"));
  }
  return v;
}

// Every point within the range the parameter's own key allows (E1 > 0, ...).
void check_axis_range(const Axis& axis, const std::string& loc) {
  const SceneKey& k = axis_key(axis.name);
  for (const double v : axis.values) {
    if (axis.scale == AxisScale::log && v <= 0.0) fail(cat(loc, ": a log axis needs values > 0"));
    if (!k.bounds.contains(v)) {
      fail(cat(loc, ": axis ", axis.name, " reaches ", shortest(v), ", outside the range of [", k.section, "] ",
               k.key, ": must be ", k.allowed(), unit_suffix(k.unit)));
    }
  }
}

Axis read_axis(std::string_view name, const toml::node& node, const std::string& loc) {
  const toml::table& t = axis_table(name, node, loc);
  Axis axis;
  axis.name = std::string(name);
  axis.scale = axis_scale(t, loc);
  const SceneKey& k = axis_key(name);
  axis.key = cat(k.section, ".", k.key);
  axis.units = k.unit == "-" ? "1" : std::string(k.unit);
  axis.long_name = std::string(k.meaning);
  const toml::node* values = t.get("values");
  if (values != nullptr && (t.contains("from") || t.contains("to") || t.contains("n"))) {
    fail(cat(loc, ": axis ", name, " gives both values and from/to/n: an axis is ", kAxisForms));
  }
  axis.values = values != nullptr ? listed_points(*values, loc) : range_points(name, t, axis.scale, loc);
  check_axis_range(axis, loc);
  if (const std::string err = validate_axis(axis); !err.empty()) fail(cat(loc, ": ", err));
  return axis;
}

// The axes given, in the canonical order.
std::vector<Axis> read_axes(const toml::table& sweep, const Context& ctx) {
  if (sweep.contains("k2") && sweep.contains("omega2")) {
    fail(cat(where(ctx, *sweep.get("omega2")), ": [sweep] both k2 and omega2 given as axes: sweep only one "
             "(k2 in N/m, or omega2 in rad/s)"));
  }
  std::vector<Axis> axes;
  for (const std::string_view name : sweep_axis_names()) {
    if (const toml::node* node = sweep.get(name)) axes.push_back(read_axis(name, *node, locate(ctx, kSweep, name, *node)));
  }
  if (axes.empty()) {
    fail(cat(where(ctx, sweep), ": [sweep] has no axes: give at least one of ",
             join(sweep_axis_names(), ", "), " as NAME = ", kAxisForms));
  }
  return axes;
}

std::vector<std::string> string_list(const toml::node& node, const std::string& loc, std::string_view what) {
  const toml::array* a = node.as_array();
  std::vector<std::string> out;
  for (std::size_t i = 0; a != nullptr && i < a->size(); ++i) {
    const auto* s = a->get(i)->as_string();
    if (s == nullptr) break;
    out.push_back(s->get());
  }
  if (a == nullptr || out.size() != a->size()) fail(cat(loc, ": must be an array of strings (", what, ")"));
  return out;
}

// Reorders the axes as `order` lists them: each axis exactly once.
void apply_order(std::vector<Axis>& axes, const toml::node& node, const std::string& loc) {
  std::vector<std::string_view> given;
  for (const Axis& a : axes) given.push_back(a.name);
  const std::string axes_text = join(given, ", ");
  std::vector<Axis> ordered;
  for (const std::string& name : string_list(node, loc, cat("the axes: ", axes_text))) {
    const auto is_named = [&](const Axis& a) { return a.name == name; };
    const auto it = std::find_if(axes.begin(), axes.end(), is_named);
    if (it == axes.end()) {
      std::string msg = cat(loc, ": '", name, "' is not an axis of this sweep");
      if (const auto hint = closest(name, given)) msg += cat(" (did you mean '", *hint, "'?)");
      fail(cat(msg, "; axes: ", axes_text));
    }
    if (std::any_of(ordered.begin(), ordered.end(), is_named)) fail(cat(loc, ": axis ", name, " is listed twice"));
    ordered.push_back(*it);
  }
  for (const std::string_view name : given) {
    const auto named = [&](const Axis& a) { return a.name == name; };
    if (std::none_of(ordered.begin(), ordered.end(), named)) {
      fail(cat(loc, ": axis ", name, " is missing: order must list every axis once (", axes_text, ")"));
    }
  }
  axes = std::move(ordered);
}

std::vector<Quantity> read_store(const toml::node& node, const std::string& loc) {
  const std::string allowed = join(views(quantity_names()), ", ");
  std::vector<Quantity> store;
  for (const std::string& name : string_list(node, loc, cat("quantities: ", allowed))) {
    const auto& names = quantity_names();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      std::string msg = cat(loc, ": unknown quantity '", name, "'");
      if (const auto hint = closest(name, views(names))) msg += cat(" (did you mean '", *hint, "'?)");
      fail(cat(msg, "; allowed: ", allowed));
    }
    const Quantity q = parse_quantity(name);
    if (std::find(store.begin(), store.end(), q) != store.end()) fail(cat(loc, ": quantity ", name, " is listed twice"));
    store.push_back(q);
  }
  return store;
}

void check_grid_size(const std::vector<Axis>& axes, const Context& ctx) {
  double cells = 1.0;
  for (const Axis& a : axes) cells *= static_cast<double>(a.values.size());
  if (cells > kMaxCells) {
    fail(cat(ctx.path, ": [sweep] the grid has ", shortest(cells), " cells: at most ", shortest(kMaxCells)));
  }
}

std::optional<SweepOptions> read_sweep(const toml::table& table, const Context& ctx) {
  const toml::table* sec = table.get_as<toml::table>(kSweep);
  if (sec == nullptr) return std::nullopt;
  SweepOptions sweep;
  sweep.axes = read_axes(*sec, ctx);
  if (const toml::node* node = sec->get("order")) apply_order(sweep.axes, *node, locate(ctx, kSweep, "order", *node));
  if (const toml::node* node = sec->get("store")) sweep.store = read_store(*node, locate(ctx, kSweep, "store", *node));
  for (const SweepInterval& row : sweep_intervals()) {
    if (const toml::node* node = sec->get(row.info.key)) sweep.*row.field = read_real(row.info, *node, locate(ctx, row.info, *node));
  }
  check_grid_size(sweep.axes, ctx);
  return sweep;
}

// ---------------------------------------------------------------------------------------
// Reading the [optimise] section.

constexpr std::string_view kVariableForm = "{ min, max[, scale] }";

// [optimise]'s keys other than the free parameters: the documentation row and how the key is
// read into OptimiseOptions.
struct OptimiseRow {
  SceneKey info;
  void (*read)(OptimiseOptions&, const SceneKey&, const toml::node&, const std::string& loc);
  std::string_view allowed_text = {};  // what is allowed, when info.allowed() cannot say it

  std::string allowed() const { return allowed_text.empty() ? info.allowed() : std::string(allowed_text); }
};

template <auto... Members>
void read_real_field(OptimiseOptions& o, const SceneKey& k, const toml::node& node, const std::string& loc) {
  (o.*....*Members) = read_real(k, node, loc);
}

template <auto... Members>
void read_integer_field(OptimiseOptions& o, const SceneKey& k, const toml::node& node, const std::string& loc) {
  const std::optional<double> x = number_of(node);  // a whole float such as 200.0 is accepted
  const bool whole = x && std::isfinite(*x) && *x == std::trunc(*x);
  if (!whole || !k.bounds.contains(*x)) fail(cat(loc, ": must be ", k.allowed()));
  using T = std::remove_cvref_t<decltype((o.*....*Members))>;
  (o.*....*Members) = static_cast<T>(*x);
}

template <auto Member>
void read_bool_field(OptimiseOptions& o, const SceneKey& k, const toml::node& node, const std::string& loc) {
  o.*Member = read_boolean(k, node, loc) != 0;
}

template <auto Parse, auto Member>
void read_choice_field(OptimiseOptions& o, const SceneKey& k, const toml::node& node, const std::string& loc) {
  o.*Member = Parse(k.choices.at(static_cast<std::size_t>(read_choice(k, node, loc))));
}

std::string regime_allowed() { return "\"(n,k)\" with n, k >= 1, or \"any\" (any motion with an impact)"; }

void read_regime(OptimiseOptions& o, const SceneKey&, const toml::node& node, const std::string& loc) {
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
    std::string msg = cat(loc, ": unknown algorithm '", name, "'");
    if (const auto hint = closest(name, views(names))) msg += cat(" (did you mean '", *hint, "'?)");
    fail(cat(msg, "; allowed: ", algorithm_names_text()));
  }
  return parse_algorithm(name);
}

void read_algorithms(OptimiseOptions& o, const SceneKey&, const toml::node& node, const std::string& loc) {
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

void read_map_path(OptimiseOptions& o, const SceneKey&, const toml::node& node, const std::string& loc) {
  const auto* s = node.as_string();
  if (s == nullptr || s->get().empty()) fail(cat(loc, ": must be the path of a map file (HDF5), a non-empty string"));
  o.map = s->get();
}

// A documentation row: type, allowed range, unit, meaning, default as text.
OptimiseRow optimise_row(std::string_view key, SceneKeyType type, Bounds bounds, std::string_view unit,
                         std::string_view meaning, std::string default_text,
                         void (*read)(OptimiseOptions&, const SceneKey&, const toml::node&, const std::string&)) {
  return {{kOptimise, key, type, bounds, {}, unit, meaning, {}, std::move(default_text), true}, read, {}};
}

template <class Enum>
OptimiseRow optimise_choice(std::string_view key, std::string_view meaning, const std::vector<Enum>& values, Enum def,
                            void (*read)(OptimiseOptions&, const SceneKey&, const toml::node&, const std::string&)) {
  static const std::vector<std::string> names = [&] {  // static storage: SceneKey::choices holds views
    std::vector<std::string> n;
    for (const Enum v : values) n.push_back(to_string(v));
    return n;
  }();
  OptimiseRow r = optimise_row(key, SceneKeyType::choice, any_finite(), "-", meaning, toml_string(to_string(def)), read);
  for (const std::string& n : names) r.info.choices.push_back(n);
  return r;
}

void add_optimise_goal_rows(std::vector<OptimiseRow>& rows, const OptimiseOptions& d) {
  using O = OptimiseOptions;
  rows.push_back(optimise_choice(
      "objective",
      "what to optimise: min_k_con (the softest impact: k_con = T/T_con of the longest), max_T_con (the duration "
      "of impact `impact`), min_F_max (the peak contact force)",
      all_objective_kinds(), d.objective, read_choice_field<parse_objective_kind, &O::objective>));
  rows.push_back(optimise_row("impact", SceneKeyType::integer, interval(0, 1000, false, false), "-",
                              "max_T_con: which impact of the steady cycle, in time order (0: the first)",
                              std::to_string(d.impact), read_integer_field<&O::impact>));
  rows.push_back(optimise_row("regime", SceneKeyType::choice, any_finite(), "-",
                              "the regime to keep, a constraint (never traded for a better objective); \"any\": "
                              "any motion with an impact",
                              toml_string(d.regime->label()), read_regime));
  rows.back().allowed_text = "\"(n,k)\" or \"any\"";
  rows.push_back(optimise_choice(
      "stability",
      "the kept orbit's Floquet stability: if_known (an orbit found unstable is infeasible), required (only one "
      "known stable is feasible) or ignored",
      all_stability_rules(), d.stability, read_choice_field<parse_stability_rule, &O::stability>));
  rows.push_back(optimise_row("hertz_valid", SceneKeyType::boolean, any_finite(), "-",
                              "also keep Hertz theory valid, z_max/R* <= [analysis] hertz_limit, as a constraint "
                              "(seeding needs hertz_valid or z_ratio in the map)",
                              d.hertz_valid ? "true" : "false", read_bool_field<&O::hertz_valid>));
  rows.push_back(optimise_row("algorithm", SceneKeyType::choice, any_finite(), "-",
                              "local algorithm, or a list of them, each started from every seed: bobyqa, cobyla, "
                              "sbplx (NLopt, derivative-free), slsqp, mma (NLopt, finite-difference gradients), "
                              "gradient_projection (the source paper's method)",
                              toml_string(to_string(d.algorithms.front())), read_algorithms));
  rows.back().allowed_text = "a name or a list of names";
  rows.push_back(optimise_row("seeds", SceneKeyType::integer, interval(1, 1e6, false, false), "-",
                              "starts per algorithm: the best cells of the seeding map that keep the regime inside "
                              "the box", std::to_string(d.seeds), read_integer_field<&O::seeds>));
  rows.push_back(optimise_row("map", SceneKeyType::choice, any_finite(), "-",
                              "seeding map (HDF5 from vibromap sweep; a path from the current directory); not "
                              "given: the scene's [sweep] runs first into OUTPUT_map.h5, or, without [sweep], the "
                              "scene's point is the one seed",
                              "(none)", read_map_path));
  rows.back().allowed_text = "a path";
}

void add_optimise_stopping_rows(std::vector<OptimiseRow>& rows, const OptimiseOptions& d) {
  using O = OptimiseOptions;
  using L = LocalOptions;
  constexpr auto local = &O::local;
  const LocalOptions& l = d.local;
  const auto real_row = [&](std::string_view key, Bounds b, std::string_view unit, std::string_view meaning,
                            double def, auto read) {
    rows.push_back(optimise_row(key, SceneKeyType::real, b, unit, meaning, toml_float(def), read));
  };
  real_row("xtol_rel", interval(0.0, 1.0, true, true), "-",
           "stop when a step moves every scaled variable by less than this fraction of its box", l.xtol_rel,
           read_real_field<local, &L::xtol_rel>);
  real_row("ftol_rel", interval(0.0, 1.0, false, true), "-",
           "stop when a step changes the objective by less than this, relative (0: off)", l.ftol_rel,
           read_real_field<local, &L::ftol_rel>);
  rows.push_back(optimise_row("max_evaluations", SceneKeyType::integer, interval(1, 1e9, false, false), "-",
                              "point solves per start, finite-difference ones included (cache hits are free)",
                              std::to_string(l.max_evaluations), read_integer_field<local, &L::max_evaluations>));
  real_row("max_time", ge(0), "s", "wall time per start; 0: no limit (a limit makes results depend on the machine)",
           l.max_time, read_real_field<local, &L::max_time>);
  real_row("initial_step", interval(0.0, 1.0, true, false), "-",
           "first step, a fraction of the box (NLopt initial_step, BOBYQA's rhobeg)", l.initial_step,
           read_real_field<local, &L::initial_step>);
  real_row("fd_step", interval(0.0, 0.1, true, false), "-",
           "finite-difference step of the gradients (slsqp, mma, gradient_projection), a fraction of the box",
           l.fd_step, read_real_field<local, &L::fd_step>);
  real_row("barrier", gt(0), "-",
           "bobyqa, sbplx: the objective given for a point outside the kept regime (plus its violation; finite, "
           "as BOBYQA needs)",
           l.barrier, read_real_field<local, &L::barrier>);
  rows.push_back(optimise_row("best", SceneKeyType::integer, interval(1, 1000, false, false), "-",
                              "best distinct points re-solved from scratch (integrate from rest and shooting) and "
                              "reported", std::to_string(d.best), read_integer_field<&O::best>));
  real_row("verify_rtol", interval(0.0, 0.1, true, true), "-", "rtol of those re-solves", d.verify_rtol,
           read_real_field<&O::verify_rtol>);
}

const std::vector<OptimiseRow>& optimise_rows() {
  static const std::vector<OptimiseRow> rows = [] {
    const OptimiseOptions defaults;
    std::vector<OptimiseRow> r;
    add_optimise_goal_rows(r, defaults);
    add_optimise_stopping_rows(r, defaults);
    return r;
  }();
  return rows;
}

// A free parameter's box: { min, max[, scale] }, inside the range of the parameter's own key.
FreeVariable read_variable(std::string_view name, const toml::node& node, const std::string& loc) {
  const toml::table* t = node.as_table();
  if (t == nullptr) fail(cat(loc, ": free parameter ", name, " must be an inline table ", kVariableForm));
  const std::vector<std::string_view> fields = {"min", "max", "scale"};
  for (auto&& [key, value] : *t) {
    if (std::find(fields.begin(), fields.end(), key.str()) != fields.end()) continue;
    std::string msg = cat(loc, ": unknown field '", key.str(), "' in free parameter ", name);
    if (const auto hint = closest(key.str(), fields)) msg += cat(" (did you mean '", *hint, "'?)");
    fail(cat(msg, "; a free parameter is ", kVariableForm));
  }
  for (const std::string_view field : {"min", "max"}) {
    if (!t->contains(field)) fail(cat(loc, ": free parameter ", name, " lacks '", field, "': give ", kVariableForm));
  }
  FreeVariable v{std::string(name), axis_end(*t, "min", loc), axis_end(*t, "max", loc), axis_scale(*t, loc)};
  if (!(v.min < v.max)) fail(cat(loc, ": min must be < max"));
  if (v.scale == AxisScale::log && v.min <= 0.0) fail(cat(loc, ": a log scale needs min > 0"));
  const SceneKey& k = axis_key(name);
  for (const double x : {v.min, v.max}) {
    if (!k.bounds.contains(x)) {
      fail(cat(loc, ": the box of ", name, " reaches ", shortest(x), ", outside the range of [", k.section, "] ", k.key,
               ": must be ", k.allowed(), unit_suffix(k.unit)));
    }
  }
  return v;
}

std::vector<FreeVariable> read_variables(const toml::table& sec, const Context& ctx) {
  if (sec.contains("k2") && sec.contains("omega2")) {
    fail(cat(where(ctx, *sec.get("omega2")), ": [optimise] both k2 and omega2 given as free parameters: free only "
             "one (k2 in N/m, or omega2 in rad/s)"));
  }
  std::vector<FreeVariable> vars;
  for (const std::string_view name : sweep_axis_names()) {
    if (const toml::node* node = sec.get(name)) vars.push_back(read_variable(name, *node, locate(ctx, kOptimise, name, *node)));
  }
  if (vars.empty()) {
    fail(cat(where(ctx, sec), ": [optimise] has no free parameters: give at least one of ",
             join(sweep_axis_names(), ", "), " as NAME = ", kVariableForm));
  }
  return vars;
}

std::optional<OptimiseOptions> read_optimise(const toml::table& table, const Context& ctx) {
  const toml::table* sec = table.get_as<toml::table>(kOptimise);
  if (sec == nullptr) return std::nullopt;
  OptimiseOptions o;
  o.variables = read_variables(*sec, ctx);
  for (const OptimiseRow& row : optimise_rows()) {
    if (const toml::node* node = sec->get(row.info.key)) row.read(o, row.info, *node, locate(ctx, row.info, *node));
  }
  if (const std::string err = validate(o); !err.empty()) fail(cat(ctx.path, ": [optimise] ", err));
  return o;
}

SceneDraft read_values(const toml::table& table, const Context& ctx) {
  SceneDraft draft;
  for (const Binding& b : bindings()) {
    const toml::table* sec = table.get_as<toml::table>(b.info.section);
    const toml::node* node = sec != nullptr ? sec->get(b.info.key) : nullptr;
    if (node == nullptr) continue;
    check_pair(*sec, b.info, ctx, *node);
    b.access.set(draft, read_value(b, *node, locate(ctx, b.info, *node)));
  }
  draft.scene.sweep = read_sweep(table, ctx);
  draft.scene.optimise = read_optimise(table, ctx);
  return draft;
}

// The scene as TOML, keys in schema order, preceded by its source and overrides.
std::string scene_text(const toml::table& table, const Context& ctx) {
  std::ostringstream os;
  os << "# scene: " << ctx.path << "\n";
  if (!ctx.override_list.empty()) {
    os << "# overrides:";
    for (const std::string& o : ctx.override_list) os << " " << o;
    os << "\n";
  }
  for (std::string_view section : all_sections()) {
    const toml::table* sec = table.get_as<toml::table>(section);
    if (sec == nullptr || sec->empty()) continue;
    os << "\n[" << section << "]\n";
    for (std::string_view key : keys_of(section)) {
      if (const toml::node* node = sec->get(key)) os << key << " = " << node_text(*node) << "\n";
    }
  }
  return os.str();
}

Scene finish(SceneDraft draft, const toml::table& table, const Context& ctx) {
  Scene& scene = draft.scene;
  const auto& init = draft.initial;
  if (std::any_of(init.begin(), init.end(), [](const auto& v) { return v.has_value(); })) {
    const Eigen::Vector4d rest(0.0, scene.params.D, 0.0, 0.0);
    Eigen::Vector4d x;
    for (int i = 0; i < 4; ++i) x[i] = init[static_cast<std::size_t>(i)].value_or(rest[i]);
    scene.params.initial = x;
  }
  // The schema's checks cover validate(); this keeps the two in step if the core adds one.
  if (const auto errors = validate(scene.params); !errors.empty()) fail(ctx.path + ": " + errors.front());
  scene.path = ctx.path;
  scene.text = scene_text(table, ctx);
  return std::move(draft.scene);
}

std::string read_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(path + ": cannot read scene: no such file");
  if (fs::is_directory(path, ec)) fail(path + ": cannot read scene: is a directory");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  if (!in) fail(path + ": cannot read scene file");
  return os.str();
}

// ---------------------------------------------------------------------------------------
// Writers.

std::string column(std::string_view s, std::size_t width) {
  std::string out(s);
  if (out.size() < width) out.append(width - out.size(), ' ');
  return out;
}

void write_reference_key(std::ostream& os, const SceneKey& k) {
  std::string lhs = cat(k.key, " = ", k.default_text);
  if (!k.default_given) lhs = cat("# ", k.key, " = (", k.default_text, ")");
  os << column(lhs, 26) << "  # " << k.meaning << unit_suffix(k.unit) << ", " << k.allowed();
  if (!k.partner.empty()) os << "; or give " << k.partner;
  os << "\n";
}

// One row of `vibromap keys`.
struct KeyRow {
  std::string name, default_text, unit, allowed, meaning;
};

KeyRow key_row(const SceneKey& k) {
  std::string meaning(k.meaning);
  if (!k.partner.empty()) meaning += cat("; or give ", k.partner);
  return {cat(k.section, ".", k.key), k.default_text, std::string(k.unit), k.allowed(), meaning};
}

void write_key_table(std::ostream& os, const std::vector<KeyRow>& rows) {
  std::array<std::size_t, 4> w{3, 7, 4, 7};  // key, default, unit, allowed
  for (const KeyRow& r : rows) {
    w[0] = std::max(w[0], r.name.size());
    w[1] = std::max(w[1], r.default_text.size());
    w[2] = std::max(w[2], r.unit.size());
    w[3] = std::max(w[3], r.allowed.size());
  }
  os << column("key", w[0]) << "  " << column("default", w[1]) << "  " << column("unit", w[2]) << "  "
     << column("allowed", w[3]) << "  meaning\n";
  for (const KeyRow& r : rows) {
    os << column(r.name, w[0]) << "  " << column(r.default_text, w[1]) << "  " << column(r.unit, w[2]) << "  "
       << column(r.allowed, w[3]) << "  " << r.meaning << "\n";
  }
}

std::string store_text(const std::vector<Quantity>& store) {
  std::vector<std::string> names;
  for (const Quantity q : store) names.push_back(to_string(q));
  return cat("[", join(views(names), ", ", "\""), "]");
}

// The [sweep] rows of `vibromap keys`: one per axis, then order, store and the intervals.
std::vector<KeyRow> sweep_rows() {
  std::vector<KeyRow> rows;
  for (const std::string_view name : sweep_axis_names()) {
    const SceneKey& k = axis_key(name);
    std::string meaning = cat("grid axis over [", k.section, "] ", name, ": ", kAxisForms, ", scale \"lin\" or \"log\"");
    if (!k.partner.empty()) meaning += cat("; or give ", k.partner);
    rows.push_back({cat(kSweep, ".", name), "(not swept)", std::string(k.unit), cat("values ", k.allowed()), meaning});
  }
  rows.push_back({"sweep.order", cat("(", join(sweep_axis_names(), ", "), ")"), "-", "every axis once",
                  "axis order, the first axis slowest in the flat cell index"});
  rows.push_back({"sweep.store", store_text(SweepOptions{}.store), "-", "quantity names",
                  cat("optional per-cell quantities, any of ", join(views(quantity_names()), ", "),
                      " (status, regime, n, k, wall time and residual are always stored)")});
  for (const SweepInterval& row : sweep_intervals()) rows.push_back(key_row(row.info));
  return rows;
}

// The [optimise] rows of `vibromap keys`: one per free parameter, then the options.
std::vector<KeyRow> optimise_doc_rows() {
  std::vector<KeyRow> rows;
  for (const std::string_view name : sweep_axis_names()) {
    const SceneKey& k = axis_key(name);
    std::string meaning = cat("free parameter [", k.section, "] ", name, " and its box: ", kVariableForm,
                              ", scale \"lin\" or \"log\"");
    if (!k.partner.empty()) meaning += cat("; or free ", k.partner);
    rows.push_back({cat(kOptimise, ".", name), "(fixed)", std::string(k.unit), cat("bounds ", k.allowed()), meaning});
  }
  for (const OptimiseRow& row : optimise_rows()) {
    KeyRow r = key_row(row.info);
    r.allowed = row.allowed();
    rows.push_back(std::move(r));
  }
  return rows;
}

// A commented example [optimise] section: without the leading "# ", its lines parse.
void write_reference_optimise(std::ostream& os) {
  os << "\n# An optimisation for `vibromap optimise`: the values above are the base point and the free\n"
        "# parameters move inside their box (any of E1, E2, R1, R2, m2, k2|omega2, as NAME = { min, max[,\n"
        "# scale] }, scale \"lin\" (default) or \"log\"). The starts are the best cells of a map: `map`, or\n"
        "# the scene's [sweep] run first, or else the scene's point. [optimise] has no default: uncomment\n"
        "# and edit this example (jobs/paper/optimise_box.toml is a whole job).\n"
        "#\n"
        "# [optimise]\n"
        "# m2 = { min = 100.0, max = 310.0 }\n"
        "# E1 = { min = 2e4, max = 2.1e11, scale = \"log\" }\n";
  const auto line = [&](const std::string& lhs, std::string_view comment) {
    os << "# " << column(lhs, 44) << "  # " << comment << "\n";
  };
  for (const OptimiseRow& row : optimise_rows()) {
    const SceneKey& k = row.info;
    const std::string lhs = k.key == "map" ? std::string("map = \"box.h5\"") : cat(k.key, " = ", k.default_text);
    line(lhs, cat(k.meaning, unit_suffix(k.unit), ", ", row.allowed()));
  }
}

// A commented example [sweep] section: without the leading "# ", its lines parse.
void write_reference_sweep(std::ostream& os) {
  os << "\n# A grid for `vibromap sweep` over some of E1, E2, R1, R2, m2, k2|omega2; a scene without\n"
        "# [sweep] is one point, and the values above are the base of every cell. [sweep] has no\n"
        "# default: uncomment and edit this example. An axis is { from, to, n[, scale] } (n points,\n"
        "# ends exact, scale \"lin\" (default) or \"log\") or { values = [...][, scale] }; its values\n"
        "# must be allowed for the parameter's key above (E1 > 0, ...). Give k2 or omega2, not both.\n"
        "#\n"
        "# [sweep]\n"
        "# E1 = { from = 2e4, to = 2.1e11, n = 23, scale = \"log\" }\n"
        "# E2 = { values = [2e4, 1e6, 2.1e11] }\n";
  const auto line = [&](const std::string& lhs, std::string_view comment) {
    os << "# " << column(lhs, 44) << "  # " << comment << "\n";
  };
  line("order = [\"E1\", \"E2\"]", cat("axis order, first slowest; default ", join(sweep_axis_names(), ", ")));
  line(cat("store = ", store_text(SweepOptions{}.store)),
       cat("optional per-cell quantities, any of ", join(views(quantity_names()), ", ")));
  for (const SweepInterval& row : sweep_intervals()) {
    const SceneKey& k = row.info;
    line(cat(k.key, " = ", k.default_text), cat(k.meaning, unit_suffix(k.unit), ", ", k.allowed()));
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Public API.

std::string parameter_override(std::string_view name, double value) {
  const auto home = section_of(name);
  if (!home || (*home != "system" && *home != "contact" && *home != "forcing"))
    throw std::invalid_argument(cat("parameter_override: '", name, "' is not a parameter key"));
  return cat(*home, ".", name, "=", toml_float(value));
}

bool Bounds::contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Bounds::to_string() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi) {
    return std::string("in ") + (lo_open ? "(" : "[") + shortest(lo) + ", " + shortest(hi) + (hi_open ? ")" : "]");
  }
  if (has_lo) return (lo_open ? "> " : ">= ") + shortest(lo);
  if (has_hi) return (hi_open ? "< " : "<= ") + shortest(hi);
  return "finite";
}

std::string SceneKey::allowed() const {
  switch (type) {
    case SceneKeyType::real: return bounds.to_string();
    case SceneKeyType::integer: return "an integer " + bounds.to_string();
    case SceneKeyType::choice: return "one of " + join(choices, ", ", "\"");
    case SceneKeyType::boolean: return "true or false";
  }
  return {};
}

const std::vector<SceneKey>& scene_keys() {
  static const std::vector<SceneKey> keys = [] {
    std::vector<SceneKey> k;
    for (const Binding& b : bindings()) k.push_back(b.info);
    return k;
  }();
  return keys;
}

std::vector<std::string_view> scene_sections() {
  std::vector<std::string_view> sections = schema_sections();
  sections.push_back(kSweep);
  return sections;
}

Scene parse_scene(std::string_view text, const std::string& path, const std::vector<std::string>& overrides) {
  Context ctx{path, {}, {}};
  toml::table table = parse_toml(text, path);
  for (const std::string& o : overrides) apply_override(table, o, ctx);
  check_structure(table, ctx);
  return finish(read_values(table, ctx), table, ctx);
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_scene(read_file(path), path, overrides);
}

void write_scene_keys(std::ostream& os) {
  std::vector<KeyRow> rows;
  for (const SceneKey& k : scene_keys()) rows.push_back(key_row(k));
  write_key_table(os, rows);
  os << "\n[sweep] (only in a sweep scene: a grid around the point above; example in jobs/reference.toml)\n";
  write_key_table(os, sweep_rows());
  os << "\n[optimise] (only in an optimisation scene: free parameters around the point above; example in "
        "jobs/reference.toml)\n";
  write_key_table(os, optimise_doc_rows());
}

void write_scene_key_summary(std::ostream& os) {
  for (std::string_view section : all_sections()) {
    std::string line = cat("  ", column(cat("[", section, "]"), 11));
    const auto keys = keys_of(section);
    for (const std::string_view key : keys) {
      const std::string_view partner = partner_of(section, key);
      const bool partner_first =
          !partner.empty() && std::find(keys.begin(), keys.end(), partner) < std::find(keys.begin(), keys.end(), key);
      if (partner_first) continue;
      line += cat(" ", key, partner.empty() ? "" : "|", partner);
    }
    os << line << "\n";
  }
}

void write_reference_scene(std::ostream& os) {
  os << "# vibromap reference scene: every key with its default value (SI units).\n"
        "# Generated by `vibromap keys --toml`; each line says what the key means and what\n"
        "# it allows. Commented-out keys have no plain default: the other form of a pair\n"
        "# (give k1 or omega1, xi1 or c1, ..., not both) and [initial], which defaults to\n"
        "# the rest state (x1, x2, v1, v2) = (0, D, 0, 0); set any subset of it.\n";
  for (std::string_view section : schema_sections()) {
    os << "\n[" << section << "]\n";
    for (const SceneKey& k : scene_keys()) {
      if (k.section == section) write_reference_key(os, k);
    }
  }
  write_reference_optimise(os);
  write_reference_sweep(os);
}

}  // namespace vibromap

