#include "vibromap/io/scene/keys.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

// The key catalogue: one row per scene key, each with the accessors that read and write its
// field of a Scene. To add a section, write its rows in a function like add_system_keys and
// list the function in bindings(); parsing, checks, `vibromap keys` and the reference scene
// follow.

namespace vibromap {
namespace detail {
namespace {

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
// The rows, section by section.

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

std::string default_text(const Binding& b, const Scene& defaults, bool& given) {
  const auto v = b.access.get(defaults);
  given = v.has_value();
  return given ? value_text(b.info, *v) : std::string(b.unset_default);
}

}  // namespace

Bounds gt(double lo) { return {lo, kInf, true, false}; }
Bounds ge(double lo) { return {lo, kInf, false, false}; }
Bounds any_finite() { return {-kInf, kInf, false, false}; }
Bounds interval(double lo, double hi, bool lo_open, bool hi_open) { return {lo, hi, lo_open, hi_open}; }

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

// ---------------------------------------------------------------------------------------
// Sections and their keys.

bool is_parameter_name(std::string_view name) {
  const auto& names = variable_parameter_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::vector<std::string_view> all_sections() {
  std::vector<std::string_view> sections = scene_sections();
  sections.push_back(kOptimise);
  return sections;
}

bool is_axis_name(std::string_view name) {
  const auto& axes = sweep_axis_names();
  return std::find(axes.begin(), axes.end(), name) != axes.end();
}

std::optional<std::string_view> section_of(std::string_view key) {
  for (const Binding& b : bindings()) {
    if (b.info.key == key) return b.info.section;
  }
  const auto has = [&](const std::vector<std::string_view>& keys) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
  };
  if (has(sweep_option_keys())) return kSweep;
  if (has(optimise_option_keys())) return kOptimise;
  return std::nullopt;
}

const SceneKey& axis_key(std::string_view name) { return find_binding(*section_of(name), name)->info; }

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

std::string_view partner_of(std::string_view section, std::string_view key) {
  if (section == kSweep || section == kOptimise) return is_axis_name(key) ? axis_key(key).partner : std::string_view{};
  const Binding* b = find_binding(section, key);
  return b != nullptr ? b->info.partner : std::string_view{};
}

}  // namespace detail

using detail::Binding;
using detail::join;
using detail::shortest;

std::string parameter_override(std::string_view name, double value) {
  const auto home = detail::section_of(name);
  if (!home || (*home != "system" && *home != "contact" && *home != "forcing"))
    throw std::invalid_argument(cat("parameter_override: '", name, "' is not a parameter key"));
  return cat(*home, ".", name, "=", detail::toml_float(value));
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
    for (const Binding& b : detail::bindings()) k.push_back(b.info);
    return k;
  }();
  return keys;
}

std::vector<std::string_view> scene_sections() {
  std::vector<std::string_view> sections = detail::schema_sections();
  sections.push_back(detail::kSweep);
  return sections;
}

}  // namespace vibromap
