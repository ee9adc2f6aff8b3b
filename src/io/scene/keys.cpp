#include "vibromap/io/scene/keys.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "scene_internal.hpp"
#include "vibromap/core/analysis/point/steady_state.hpp"
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
// Accessors: the field a key reads and writes, named by a chain of member pointers that starts
// at a member of Parameters or of PointOptions.

template <class T, class C>
C member_class(T C::*);

// The object a chain starts from: `params` for a member of Parameters, else `options`.
template <auto First, class P, class O>
auto& chain_root(P& params, O& options) {
  if constexpr (std::is_same_v<decltype(member_class(First)), Parameters>) {
    return params;
  } else {
    return options;
  }
}

template <auto First, auto... Rest, class P, class O>
auto& member(P& params, O& options) {
  return ((chain_root<First>(params, options).*First).*....*Rest);
}

template <auto... Members>
constexpr Accessors field() {
  using T = std::remove_cvref_t<decltype(member<Members...>(std::declval<Parameters&>(),
                                                            std::declval<PointOptions&>()))>;
  static_assert(std::is_arithmetic_v<T>);
  Accessors a{};
  a.set = [](Parameters& p, PointOptions& o, const KeyValue& v) {
    auto& f = member<Members...>(p, o);
    if constexpr (std::is_floating_point_v<T>) {
      f = v.real;
    } else {
      f = static_cast<T>(v.integer);
    }
  };
  a.get = [](const Parameters& p, const PointOptions& o) -> std::optional<KeyValue> {
    const auto& f = member<Members...>(p, o);
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
  a.set = [](Parameters& p, PointOptions&, const KeyValue& v) { p.*Member = T{Form, v.real}; };
  a.get = [](const Parameters& p, const PointOptions&) -> std::optional<KeyValue> {
    const T& f = p.*Member;
    if (f.form != Form) return std::nullopt;
    return KeyValue{f.value, 0, 0};
  };
  return a;
}

// Component I of the initial state; the first one set fills the others from the rest state
// (0, D, 0, 0).
template <int I>
constexpr Accessors initial_component() {
  Accessors a{};
  a.set = [](Parameters& p, PointOptions&, const KeyValue& v) {
    if (!p.initial) p.initial = p.initial_state();
    (*p.initial)[I] = v.real;
  };
  a.get = [](const Parameters& p, const PointOptions&) -> std::optional<KeyValue> {
    if (!p.initial) return std::nullopt;
    return KeyValue{(*p.initial)[I], 0, 0};
  };
  a.component = I;
  return a;
}

// The values a choice key offers, in the order the scene lists them. Their names are the
// core's to_string(), so the scene, the summaries and the core spell them one way.
constexpr std::array kMethodValues = {Method::hybrid, Method::dopri5, Method::rk4};
constexpr std::array kSteadyValues = {SteadyMethod::follow, SteadyMethod::shooting, SteadyMethod::integrate};
// In all_contact_laws() order: a [sweep] axis over contact.law stores this index.
constexpr std::array kLawValues = {ContactLawKind::hertz, ContactLawKind::hunt_crossley,
                                   ContactLawKind::lankarani_nikravesh, ContactLawKind::flores,
                                   ContactLawKind::gonthier};

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
  a.set = [](Parameters& p, PointOptions& o, const KeyValue& v) {
    member<Members...>(p, o) = Values.at(static_cast<std::size_t>(v.choice));
  };
  a.get = [](const Parameters& p, const PointOptions& o) -> std::optional<KeyValue> {
    for (std::size_t i = 0; i < Values.size(); ++i) {
      if (Values[i] == member<Members...>(p, o)) return KeyValue{0.0, 0, static_cast<int>(i)};
    }
    return std::nullopt;
  };
  return a;
}

// The damping factor given directly (Parameters::damping, unset: calibrated from e).
constexpr Accessors damping_field() {
  Accessors a{};
  a.set = [](Parameters& p, PointOptions&, const KeyValue& v) { p.damping = v.real; };
  a.get = [](const Parameters& p, const PointOptions&) -> std::optional<KeyValue> {
    if (!p.damping) return std::nullopt;
    return KeyValue{*p.damping, 0, 0};
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
  rows.push_back(real(s, "m1", gt(0), "kg", "main body mass", field<&P::m1>()));
  rows.push_back(real(s, "m2", gt(0), "kg", "attached body mass", field<&P::m2>()));
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
  // At most 1e6 m: a larger clearance is no contact at all, and the state scales built on D
  // (the census box D +- L, the basins plane) must stay finite.
  rows.push_back(real(s, "D", interval(0.0, 1e6, false, false), "m", "clearance between the bodies at rest",
                      field<&P::D>()));
}

void add_contact_keys(std::vector<Binding>& rows) {
  constexpr std::string_view s = "contact";
  using P = Parameters;
  const Bounds poisson = interval(-1.0, 0.5, true, true);
  // Radii from 1 nm to 1000 km: R* and z_max/R* stay normal numbers (R2 = 5e-324 made
  // z_max/R* infinite).
  const Bounds kRadius = interval(1e-9, 1e6, false, false);
  rows.push_back(real(s, "E1", gt(0), "Pa", "Young's modulus of body 1", field<&P::E1>()));
  rows.push_back(real(s, "E2", gt(0), "Pa", "Young's modulus of body 2", field<&P::E2>()));
  rows.push_back(real(s, "nu1", poisson, "-", "Poisson ratio of body 1", field<&P::nu1>()));
  rows.push_back(real(s, "nu2", poisson, "-", "Poisson ratio of body 2", field<&P::nu2>()));
  rows.push_back(real(s, "R1", kRadius, "m", "radius of curvature of body 1 at the contact",
                      field<&P::R1>()));
  rows.push_back(real(s, "R2", kRadius, "m", "radius of curvature of body 2 at the contact",
                      field<&P::R2>()));
  rows.push_back(real(s, "q", gt(0), "-", "Hertz shape coefficient (0.319: circular contact)",
                      field<&P::q>()));
  rows.push_back(choice(s, "law",
                        "contact law: hertz (elastic), or K z^1.5 (1 + chi w/v_in) with chi calibrated from restitution",
                        enum_field<kLawValues, &P::law>(), enum_names<kLawValues>()));
  rows.push_back(real(s, "restitution", interval(0.0, 1.0, true, false), "-",
                      "restitution e the damping chi is calibrated for (1: elastic)",
                      field<&P::restitution>()));
  rows.push_back(real(s, "damping", ge(0), "-",
                      "damping factor chi of a damped law given directly (replaces the calibration from restitution)",
                      damping_field(), {}, "chi(restitution)"));
}

void add_forcing_keys(std::vector<Binding>& rows) {
  constexpr std::string_view s = "forcing";
  using P = Parameters;
  rows.push_back(real(s, "F0", ge(0), "N", "force amplitude", field<&P::F0>()));
  rows.push_back(real(s, "omega", gt(0), "rad/s", "forcing frequency (period T = 2 pi/omega)",
                      field<&P::omega>()));
  rows.push_back(real(s, "lambda", ge(0), "-", "amplitude factor: F(t) = lambda F0 cos(omega t + phi0)",
                      field<&P::lambda>()));
  // A phase is meaningful modulo 2 pi; the phase omega t + phi0 is summed in doubles, so a huge
  // phi0 swallows omega t (at 1e308 the force is constant and the free flight's closed form,
  // which assumes it turns at omega, disagrees with the vector field: impacts without end).
  // 1000 rad (159 turns) keeps the sum within 1.2e-13 rad.
  rows.push_back(real(s, "phi0", interval(-1e3, 1e3, false, false), "rad", "forcing phase at t = 0",
                      field<&P::phi0>()));
}

void add_solver_keys(std::vector<Binding>& rows) {
  constexpr std::string_view s = "solver";
  using O = IntegratorOptions;
  constexpr auto integ = &PointOptions::integrator;
  rows.push_back(choice(s, "method",
                        "integration method: hybrid (closed-form free flight, dopri5 in contact), dopri5 "
                        "(adaptive, located contact events) or rk4 (the paper's fixed step)",
                        enum_field<kMethodValues, integ, &O::method>(), enum_names<kMethodValues>()));
  rows.push_back(real(s, "rtol", interval(0.0, 0.1, true, true), "-", "hybrid, dopri5: relative local error tolerance",
                      field<integ, &O::rtol>()));
  rows.push_back(real(s, "atol", gt(0), "m",
                      "hybrid, dopri5: absolute tolerance on x1 and z (on velocities: atol*omega)",
                      field<integ, &O::atol>()));
  rows.push_back(real(s, "max_step", interval(0.0, 1.0, true, false), "-",
                      "hybrid, dopri5: largest step, as a fraction of the forcing period T",
                      field<integ, &O::max_step>()));
  rows.push_back(integer(s, "rk4_steps", ge(1), "rk4: steps per forcing period", field<integ, &O::rk4_steps>()));
  rows.push_back(integer(s, "max_steps", interval(1, kMaxStepBudget, false, false),
                         "budget of steps (accepted + rejected) for the whole run (a step costs about 1-2 us: "
                         "1e10 is some hours)",
                         field<integ, &O::max_steps>()));
}

void add_analysis_keys(std::vector<Binding>& rows) {
  constexpr std::string_view s = "analysis";
  using A = AnalysisOptions;
  constexpr auto an = &PointOptions::analysis;
  rows.push_back(choice(s, "steady",
                        "how the steady motion is found: follow (the motion the initial state settles into, as "
                        "brute-force integration finds it, stopped early once it is seen closing in on a stable "
                        "orbit found by Newton), shooting (faster: some stable orbit, not necessarily the motion "
                        "from the initial state; maps say so) or integrate (brute force, until samples repeat)",
                        enum_field<kSteadyValues, an, &A::steady>(), enum_names<kSteadyValues>()));
  rows.push_back(integer(s, "transient_periods", interval(1, kMaxTransientPeriods, false, false),
                         "follow, shooting: forcing periods integrated before Newton starts",
                         field<an, &A::transient_periods>()));
  rows.push_back(real(s, "newton_tol", ge(0), "-",
                      "shooting and continue: scaled residual |P^n(y) - y| at which Newton stops; 0: auto, 10 rtol",
                      field<an, &A::newton_tol>()));
  rows.push_back(integer(s, "newton_max_iterations", interval(1, 1000, false, false),
                         "shooting: Newton iterations before falling back to integrate",
                         field<an, &A::newton_max_iterations>()));
  rows.push_back(boolean(s, "lyapunov",
                         "estimate the largest Lyapunov exponent when no period is found (quasi-periodic "
                         "or chaotic); costs lyapunov_periods more periods",
                         field<an, &A::lyapunov>()));
  rows.push_back(integer(s, "lyapunov_periods", interval(10, kMaxLyapunovPeriods, false, false),
                         "forcing periods over which the Lyapunov exponent is averaged",
                         field<an, &A::lyapunov_periods>()));
  rows.push_back(integer(s, "n_max", interval(1, SteadyStateDetector::kMaxN, false, false), "largest period looked for, in forcing periods",
                         field<an, &A::n_max>()));
  rows.push_back(integer(s, "max_periods", interval(1, kMaxPeriodBudget, false, false),
                         "budget of forcing periods to reach steady state",
                         field<an, &A::max_periods>()));
  rows.push_back(real(s, "steady_tol", ge(0), "-",
                      "steady-state tolerance (scaled max-norm); 0: auto, 100*rtol (rk4: 1e-9)",
                      field<an, &A::steady_tol>()));
  rows.push_back(integer(s, "chatter_impacts", ge(1), "impacts per forcing period from which the motion is chatter",
                         field<an, &A::chatter_impacts>()));
  rows.push_back(real(s, "hertz_limit", gt(0), "-", "z_max/R* above which Hertz theory is flagged invalid",
                      field<an, &A::hertz_limit>()));
  rows.push_back(real(s, "soft_kcon", gt(0), "-",
                      "a motion is soft when periodic with impacts, stable, Hertz-valid (z_max/R* <= hertz_limit) "
                      "and k_con <= this; one definition for run, maps, census, optimiser and pictures",
                      field<an, &A::soft_kcon>()));
  rows.push_back(integer(s, "trajectory_periods", ge(0),
                         "forcing periods of steady motion kept as a trajectory (used by run --trajectory)",
                         field<an, &A::trajectory_periods>()));
  rows.push_back(integer(s, "trajectory_samples", ge(10), "uniform samples per forcing period in a kept trajectory",
                         field<an, &A::trajectory_samples>()));
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
  const auto v = b.access.get(defaults.params, defaults.options);
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

const Binding* find_key(std::string_view name) {
  if (const auto dot = name.find('.'); dot != std::string_view::npos)
    return find_binding(name.substr(0, dot), name.substr(dot + 1));
  const Binding* found = nullptr;
  for (const Binding& b : bindings()) {
    if (b.info.key != name) continue;
    if (found != nullptr) return nullptr;  // several sections have it: name the section
    found = &b;
  }
  return found;
}

std::size_t index_of(const Binding& b) { return static_cast<std::size_t>(&b - bindings().data()); }

std::string full_key(const SceneKey& k) { return cat(k.section, ".", k.key); }

std::string pair_advice(const SceneKey& a, const SceneKey& b) {
  const auto in_unit = [](const SceneKey& k) {
    return k.unit == "-" ? cat(k.key, " dimensionless") : cat(k.key, " in ", k.unit);
  };
  return cat("(", in_unit(a), ", or ", in_unit(b), ")");
}

bool is_numeric(const SceneKey& k) { return k.type == SceneKeyType::real || k.type == SceneKeyType::integer; }

bool is_categorical_axis(const SceneKey& k) {
  return k.type == SceneKeyType::choice && (k.section == "system" || k.section == "contact" || k.section == "forcing");
}

KeyValue numeric_value(const SceneKey& k, double v) {
  KeyValue kv;
  kv.real = v;
  if (k.type == SceneKeyType::integer) kv.integer = static_cast<long long>(v);
  return kv;
}

}  // namespace detail

using detail::Binding;
using detail::join;

std::string parameter_override(std::string_view name, double value) {
  const auto home = detail::section_of(name);
  if (!home || (*home != "system" && *home != "contact" && *home != "forcing"))
    throw std::invalid_argument(cat("parameter_override: '", name, "' is not a parameter key"));
  return cat(*home, ".", name, "=", detail::toml_float(value));
}

std::vector<std::string> optimised_overrides(const Parameters& p, const OptimiseOptions& o) {
  std::vector<std::string> out;
  for (const FreeVariable& f : o.variables) out.push_back(parameter_override(f.name, get_parameter(p, f.name)));
  if (!o.laws.empty()) out.push_back("contact.law=" + to_string(p.law));
  return out;
}

PointSetter point_setter(std::string_view key) {
  const auto dot = key.find('.');
  const Binding* b = dot == std::string_view::npos ? nullptr : detail::find_key(key);
  if (b == nullptr) throw std::invalid_argument(cat("point_setter: '", clip(key), "' is not a scene key (section.key)"));
  if (detail::is_categorical_axis(b->info)) {
    return [b](Parameters& p, PointOptions& o, double v) {
      detail::KeyValue kv;
      kv.choice = static_cast<int>(v);
      b->access.set(p, o, kv);
    };
  }
  if (!detail::is_numeric(b->info))
    throw std::invalid_argument(cat("point_setter: ", key, " is not a real or integer key"));
  return [b](Parameters& p, PointOptions& o, double v) { b->access.set(p, o, detail::numeric_value(b->info, v)); };
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
