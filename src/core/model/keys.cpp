// The key table: see include/vibromap/core/model/keys.hpp. One row per key of a point, each
// with the accessors that read and write its field (key_accessors.hpp); to add a key, write its
// row in the function of its section (add_system_keys, ...), and the scene, `vibromap keys`,
// the checks and every command that names keys follow. The numeric options of the other
// sections are option_keys.cpp's.

#include "vibromap/core/model/keys.hpp"

#include <algorithm>
#include <map>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "vibromap/core/analysis/point/impact.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "key_accessors.hpp"
#include "vibromap/core/analysis/point/steady_state.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap {
namespace {

using namespace detail;  // the accessors (key_accessors.hpp)

constexpr double kInf = std::numeric_limits<double>::infinity();

// The values a choice key offers, in the order the scene lists them (a sweep axis over
// contact.law stores the index). Their names are the core's to_string().
constexpr std::array kMethodValues = {Method::hybrid, Method::dopri5, Method::rk4};
constexpr std::array kSteadyValues = {SteadyMethod::follow, SteadyMethod::shooting, SteadyMethod::integrate};
constexpr std::array kLawValues = {ContactLawKind::hertz, ContactLawKind::hunt_crossley,
                                   ContactLawKind::lankarani_nikravesh, ContactLawKind::flores,
                                   ContactLawKind::gonthier};

// ---------------------------------------------------------------------------------------
// The rows, section by section.

struct Row {
  KeyInfo info;
  Accessors access;
};

using B = Bounds;

// `unset_default`: the default's text when the default point does not set the key in this form.
Row real(std::string_view s, std::string_view k, Bounds b, std::string_view unit, std::string_view meaning,
         Accessors a, std::string_view partner = {}, std::string_view unset_default = {}) {
  return {KeyInfo{s, k, KeyType::real, b, {}, unit, meaning, partner, std::string(unset_default)}, a};
}

Row integer(std::string_view s, std::string_view k, Bounds b, std::string_view meaning, Accessors a) {
  return {KeyInfo{s, k, KeyType::integer, b, {}, "-", meaning}, a};
}

Row boolean(std::string_view s, std::string_view k, std::string_view meaning, Accessors a) {
  return {KeyInfo{s, k, KeyType::boolean, B::finite(), {}, "-", meaning}, a};
}

// A choice key whose allowed names are enum_names<Values>() of its accessor.
Row choice(std::string_view s, std::string_view k, std::string_view meaning, Accessors a,
           const std::vector<std::string>& names) {
  Row r{KeyInfo{s, k, KeyType::choice, B::finite(), {}, "-", meaning}, a};
  for (const std::string& n : names) r.info.choices.push_back(n);
  return r;
}

void add_system_keys(std::vector<Row>& rows) {
  constexpr std::string_view s = "system";
  using P = Parameters;
  const std::size_t first = rows.size();
  rows.push_back(real(s, "m1", B::above(0), "kg", "main body mass", field<&P::m1>()));
  rows.push_back(real(s, "m2", B::above(0), "kg", "attached body mass", field<&P::m2>()));
  rows.push_back(real(s, "k1", B::above(0), "N/m", "main spring stiffness",
                      either_form<&P::spring1, Spring::Form::stiffness>(), "omega1", "m1*omega1^2"));
  rows.push_back(real(s, "omega1", B::above(0), "rad/s", "main spring as partial frequency sqrt(k1/m1)",
                      either_form<&P::spring1, Spring::Form::frequency>(), "k1", "sqrt(k1/m1)"));
  rows.push_back(real(s, "k2", B::at_least(0), "N/m", "coupling spring stiffness",
                      either_form<&P::spring2, Spring::Form::stiffness>(), "omega2", "m2*omega2^2"));
  rows.push_back(real(s, "omega2", B::at_least(0), "rad/s", "coupling spring as partial frequency sqrt(k2/m2)",
                      either_form<&P::spring2, Spring::Form::frequency>(), "k2", "sqrt(k2/m2)"));
  rows.push_back(real(s, "xi1", B::at_least(0), "-", "main damping ratio c1/(2 m1 omega1)",
                      either_form<&P::damper1, Damper::Form::ratio>(), "c1", "c1/(2*sqrt(m1*k1))"));
  rows.push_back(real(s, "c1", B::at_least(0), "N s/m", "main damper coefficient",
                      either_form<&P::damper1, Damper::Form::coefficient>(), "xi1", "2*xi1*sqrt(m1*k1)"));
  rows.push_back(real(s, "xi2", B::at_least(0), "-", "coupling damping ratio c2/(2 m2 omega2)",
                      either_form<&P::damper2, Damper::Form::ratio>(), "c2", "c2/(2*sqrt(m2*k2))"));
  rows.push_back(real(s, "c2", B::at_least(0), "N s/m", "coupling damper coefficient",
                      either_form<&P::damper2, Damper::Form::coefficient>(), "xi2", "2*xi2*sqrt(m2*k2)"));
  // At most 1e6 m: a larger clearance is no contact at all, and the state scales built on D
  // (the census box D +- L, the basins plane) must stay finite.
  // The masses, springs and dampers above set omega / omega_n and the damping rate that
  // frequency_ratio_error bounds (with forcing.omega).
  for (std::size_t i = first; i < rows.size(); ++i) rows[i].info.frequency_rule = true;
  rows.push_back(real(s, "D", B::between(0.0, 1e6), "m", "clearance between the bodies at rest", field<&P::D>()));
}

void add_contact_keys(std::vector<Row>& rows) {
  constexpr std::string_view s = "contact";
  using P = Parameters;
  const Bounds poisson = B::between(-1.0, 0.5, true, true);
  // Radii from 1 nm to 1000 km: R* and z_max/R* stay normal numbers (R2 = 5e-324 made
  // z_max/R* infinite).
  const Bounds radius = B::between(1e-9, 1e6);
  rows.push_back(real(s, "E1", B::above(0), "Pa", "Young's modulus of body 1", field<&P::E1>()));
  rows.push_back(real(s, "E2", B::above(0), "Pa", "Young's modulus of body 2", field<&P::E2>()));
  rows.push_back(real(s, "nu1", poisson, "-", "Poisson ratio of body 1", field<&P::nu1>()));
  rows.push_back(real(s, "nu2", poisson, "-", "Poisson ratio of body 2", field<&P::nu2>()));
  rows.push_back(real(s, "R1", radius, "m", "radius of curvature of body 1 at the contact", field<&P::R1>()));
  rows.push_back(real(s, "R2", radius, "m", "radius of curvature of body 2 at the contact", field<&P::R2>()));
  rows.push_back(real(s, "q", B::above(0), "-", "Hertz shape coefficient (0.319: circular contact)", field<&P::q>()));
  rows.push_back(choice(s, "law",
                        "contact law: hertz (elastic), or K z^1.5 (1 + chi w/v_in) with chi calibrated from restitution",
                        enum_field<kLawValues, &P::law>(), enum_names<kLawValues>()));
  rows.push_back(real(s, "restitution", B::between(0.0, 1.0, true, false), "-",
                      "restitution e the damping chi is calibrated for (1: elastic)", field<&P::restitution>()));
  rows.push_back(real(s, "damping", B::at_least(0), "-",
                      "damping factor chi of a damped law given directly (replaces the calibration from restitution)",
                      damping_field(), {}, "chi(restitution)"));
}

void add_forcing_keys(std::vector<Row>& rows) {
  constexpr std::string_view s = "forcing";
  using P = Parameters;
  rows.push_back(real(s, "F0", B::at_least(0), "N", "force amplitude", field<&P::F0>()));
  rows.push_back(real(s, "omega", B::above(0), "rad/s", "forcing frequency (period T = 2 pi/omega)", field<&P::omega>()));
  rows.back().info.frequency_rule = true;
  rows.push_back(real(s, "lambda", B::at_least(0), "-", "amplitude factor: F(t) = lambda F0 cos(omega t + phi0)",
                      field<&P::lambda>()));
  // A phase is meaningful modulo 2 pi; the phase omega t + phi0 is summed in doubles, so a huge
  // phi0 swallows omega t (at 1e308 the force is constant and the free flight's closed form,
  // which assumes it turns at omega, disagrees with the vector field: impacts without end).
  // 1000 rad (159 turns) keeps the sum within 1.2e-13 rad.
  rows.push_back(real(s, "phi0", B::between(-1e3, 1e3), "rad", "forcing phase at t = 0", field<&P::phi0>()));
}

void add_solver_keys(std::vector<Row>& rows) {
  constexpr std::string_view s = "solver";
  using O = IntegratorOptions;
  constexpr auto integ = &PointOptions::integrator;
  rows.push_back(choice(s, "method",
                        "integration method: hybrid (closed-form free flight, dopri5 in contact), dopri5 "
                        "(adaptive, located contact events) or rk4 (the paper's fixed step)",
                        enum_field<kMethodValues, integ, &O::method>(), enum_names<kMethodValues>()));
  rows.push_back(real(s, "rtol", B::between(0.0, 0.1, true, true), "-", "hybrid, dopri5: relative local error tolerance",
                      field<integ, &O::rtol>()));
  rows.push_back(real(s, "atol", B::above(0), "m",
                      "hybrid, dopri5: absolute tolerance on x1 and z (on velocities: atol*omega)",
                      field<integ, &O::atol>()));
  rows.push_back(real(s, "max_step", B::between(0.0, 1.0, true, false), "-",
                      "hybrid, dopri5: largest step, as a fraction of the forcing period T", field<integ, &O::max_step>()));
  rows.push_back(integer(s, "rk4_steps", B::at_least(1), "rk4: steps per forcing period", field<integ, &O::rk4_steps>()));
  rows.push_back(integer(s, "max_steps", B::between(1, static_cast<double>(kMaxStepBudget)),
                         "budget of steps (accepted + rejected) for the whole run (a step costs about 1-2 us: "
                         "1e10 is some hours)",
                         field<integ, &O::max_steps>()));
}

void add_analysis_keys(std::vector<Row>& rows) {
  constexpr std::string_view s = "analysis";
  using A = AnalysisOptions;
  constexpr auto an = &PointOptions::analysis;
  rows.push_back(choice(s, "steady",
                        "how the steady motion is found: follow (the motion the initial state settles into, as "
                        "brute-force integration finds it, stopped early once it is seen closing in on a stable "
                        "orbit found by Newton), shooting (faster: some stable orbit, not necessarily the motion "
                        "from the initial state; maps say so) or integrate (brute force, until samples repeat)",
                        enum_field<kSteadyValues, an, &A::steady>(), enum_names<kSteadyValues>()));
  rows.push_back(integer(s, "transient_periods", B::between(1, kMaxTransientPeriods),
                         "follow, shooting: forcing periods integrated before Newton starts",
                         field<an, &A::transient_periods>()));
  rows.push_back(real(s, "newton_tol", B::at_least(0), "-",
                      "shooting and continue: scaled residual |P^n(y) - y| at which Newton stops; 0: auto, 10 rtol",
                      field<an, &A::newton_tol>()));
  rows.push_back(integer(s, "newton_max_iterations", B::between(1, 1000),
                         "shooting: Newton iterations before falling back to integrate",
                         field<an, &A::newton_max_iterations>()));
  rows.push_back(boolean(s, "lyapunov",
                         "estimate the largest Lyapunov exponent when no period is found (quasi-periodic "
                         "or chaotic); costs lyapunov_periods more periods",
                         field<an, &A::lyapunov>()));
  rows.push_back(integer(s, "lyapunov_periods", B::between(10, kMaxLyapunovPeriods),
                         "forcing periods over which the Lyapunov exponent is averaged", field<an, &A::lyapunov_periods>()));
  rows.push_back(integer(s, "n_max", B::between(1, SteadyStateDetector::kMaxN),
                         "largest period looked for, in forcing periods", field<an, &A::n_max>()));
  rows.push_back(integer(s, "max_periods", B::between(1, static_cast<double>(kMaxPeriodBudget)),
                         "budget of forcing periods to reach steady state", field<an, &A::max_periods>()));
  rows.push_back(real(s, "steady_tol", B::at_least(0), "-",
                      "steady-state tolerance (scaled max-norm); 0: auto, 100*rtol (rk4: 1e-9)", field<an, &A::steady_tol>()));
  rows.push_back(integer(s, "chatter_impacts", B::between(1, ImpactRecorder::kMaxChatterImpacts), "impacts per forcing period from which the motion is chatter",
                         field<an, &A::chatter_impacts>()));
  rows.push_back(real(s, "hertz_limit", B::above(0), "-", "z_max/R* above which Hertz theory is flagged invalid",
                      field<an, &A::hertz_limit>()));
  rows.push_back(real(s, "soft_kcon", B::above(0), "-",
                      "a motion is soft when periodic with impacts, stable, Hertz-valid (z_max/R* <= hertz_limit) "
                      "and k_con <= this; one definition for run, maps, census, optimiser and pictures",
                      field<an, &A::soft_kcon>()));
  rows.push_back(integer(s, "trajectory_periods", B::at_least(0),
                         "forcing periods of steady motion kept as a trajectory (used by run --trajectory)",
                         field<an, &A::trajectory_periods>()));
  rows.push_back(integer(s, "trajectory_samples", B::at_least(10), "uniform samples per forcing period in a kept trajectory",
                         field<an, &A::trajectory_samples>()));
  // At most a tenth of the motion's scale: a perturbation, not another initial state (a census
  // box is one scale wide). Left out of a run's identity while off, so maps made before the key
  // existed resume.
  rows.push_back(real(s, "fragility", B::between(0.0, kMaxFragility), "-",
                      "size of the perturbations of the initial state also followed to their steady state (motion "
                      "scales: dx/L, dv/(omega L)); the point is fragile when one ends on another attractor; 0: off",
                      field<an, &A::fragility>()));
  rows.back().info.identity_at_default = false;
  rows.push_back(integer(s, "fragility_states", B::between(1, kMaxFragilityStates),
                         "perturbed initial states followed when fragility > 0 (fixed directions +-h_i)",
                         field<an, &A::fragility_states>()));
  rows.back().info.identity_at_default = false;
}

void add_initial_keys(std::vector<Row>& rows) {
  constexpr std::string_view s = "initial";
  rows.push_back(real(s, "x1", B::finite(), "m", "initial displacement of body 1 (any key unset: rest state)",
                      initial_component<0>(), {}, "0"));
  rows.push_back(real(s, "x2", B::finite(), "m", "initial displacement of body 2", initial_component<1>(), {}, "D"));
  rows.push_back(real(s, "v1", B::finite(), "m/s", "initial velocity of body 1", initial_component<2>(), {}, "0"));
  rows.push_back(real(s, "v2", B::finite(), "m/s", "initial velocity of body 2", initial_component<3>(), {}, "0"));
}

const std::vector<Row>& rows() {
  static const std::vector<Row> table = [] {
    std::vector<Row> r;
    add_system_keys(r);
    add_contact_keys(r);
    add_forcing_keys(r);
    add_solver_keys(r);
    add_analysis_keys(r);
    add_initial_keys(r);
    const Parameters params;
    const PointOptions options;
    for (Row& row : r) {
      const std::optional<double> v = row.access.stored(params, options);
      row.info.default_given = v.has_value();
      if (v) row.info.default_text = row.info.scene_text(*v);
    }
    return r;
  }();
  return table;
}

const Row& row(std::size_t index) { return rows()[index]; }

bool is_model_section(std::string_view s) { return s == "system" || s == "contact" || s == "forcing"; }

}  // namespace


// ---------------------------------------------------------------------------------------
// Bounds and KeyInfo.

Bounds Bounds::above(double lo) { return {lo, kInf, true, false}; }
Bounds Bounds::at_least(double lo) { return {lo, kInf, false, false}; }
Bounds Bounds::finite() { return {-kInf, kInf, false, false}; }
Bounds Bounds::between(double lo, double hi, bool lo_open, bool hi_open) { return {lo, hi, lo_open, hi_open}; }

bool Bounds::contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool above_lo = lo_open ? v > lo : v >= lo;
  const bool below_hi = hi_open ? v < hi : v <= hi;
  return above_lo && below_hi;
}

std::string Bounds::to_string() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi) return cat("in ", lo_open ? "(" : "[", shortest(lo), ", ", shortest(hi), hi_open ? ")" : "]");
  if (has_lo) return cat(lo_open ? "> " : ">= ", shortest(lo));
  if (has_hi) return cat(hi_open ? "< " : "<= ", shortest(hi));
  return "finite";
}

std::string KeyInfo::full_name() const { return cat(section, ".", name); }

std::string KeyInfo::allowed() const {
  switch (type) {
    case KeyType::real: return bounds.to_string();
    case KeyType::integer: return "an integer " + bounds.to_string();
    case KeyType::choice: {
      std::string list;
      for (const std::string_view c : choices) list += cat(list.empty() ? "" : ", ", "\"", c, "\"");
      return "one of " + list;
    }
    case KeyType::boolean: return "true or false";
  }
  return {};
}

std::string KeyInfo::unit_suffix() const { return unit == "-" ? std::string() : cat(" (", unit, ")"); }

bool KeyInfo::is_numeric() const { return type == KeyType::real || type == KeyType::integer; }

std::string KeyInfo::scene_text(double v) const {
  switch (type) {
    case KeyType::real: return float_text(v);
    case KeyType::integer: return std::to_string(static_cast<long long>(v));
    case KeyType::choice: return cat("\"", choices.at(static_cast<std::size_t>(v)), "\"");
    case KeyType::boolean: return v != 0.0 ? "true" : "false";
  }
  return {};
}

std::string KeyInfo::requirement(double v, long long int_max) const {
  switch (type) {
    case KeyType::real: {
      const bool unbounded = !std::isfinite(bounds.lo) && !std::isfinite(bounds.hi);
      if (!std::isfinite(v)) return cat("must be a finite number", unbounded ? "" : cat(" ", allowed()), unit_suffix());
      return bounds.contains(v) ? std::string() : cat("must be ", allowed(), unit_suffix());
    }
    case KeyType::integer:
      if (!(std::isfinite(v) && v == std::trunc(v) && bounds.contains(v))) return cat("must be ", allowed());
      if (v > static_cast<double>(int_max)) return cat("must be at most ", std::to_string(int_max));
      return {};
    case KeyType::choice: {
      const bool index = v >= 0.0 && v < static_cast<double>(choices.size()) && v == std::trunc(v);
      return index ? std::string() : cat("must be ", allowed());
    }
    case KeyType::boolean: return v == 0.0 || v == 1.0 ? std::string() : cat("must be ", allowed());
  }
  return {};
}

std::string KeyInfo::refusal(std::string_view value, std::string_view requirement) const {
  return cat("[", section, "] ", name, " = ", value, ": ", requirement);
}

std::string value_text(double v) { return shortest(v); }

// ---------------------------------------------------------------------------------------
// Key.

const std::vector<Key>& Key::all() {
  static const std::vector<Key> keys = [] {
    std::vector<Key> k;
    for (std::size_t i = 0; i < rows().size(); ++i) k.push_back(Key(i));
    return k;
  }();
  return keys;
}

std::optional<Key> Key::find(std::string_view name) {
  const auto dot = name.find('.');
  std::optional<Key> found;
  for (const Key k : all()) {
    const KeyInfo& i = k.info();
    if (dot != std::string_view::npos) {
      if (i.section == name.substr(0, dot) && i.name == name.substr(dot + 1)) return k;
      continue;
    }
    if (i.name != name) continue;
    if (found) return std::nullopt;  // several sections have it: name the section
    found = k;
  }
  return found;
}

Key Key::at(std::string_view name) {
  if (const std::optional<Key> k = find(name)) return *k;
  throw std::invalid_argument(cat("'", clip(name), "' names no key (section.name, or a name only one section has)"));
}

const KeyInfo& Key::info() const { return row(index_).info; }

bool Key::is_parameter() const { return info().type == KeyType::real && is_model_section(info().section); }

bool Key::is_categorical() const { return info().type == KeyType::choice && is_model_section(info().section); }

bool Key::is_axis() const { return info().is_numeric() || is_categorical(); }

int Key::component() const { return row(index_).access.component; }

long long Key::int_max() const { return row(index_).access.int_max; }

std::string Key::requirement(double v) const { return info().requirement(v, int_max()); }

std::string Key::check(double v) const {
  const std::string need = requirement(v);
  if (need.empty()) return need;
  const KeyInfo& i = info();
  const bool index = i.type == KeyType::choice && v >= 0.0 && v < static_cast<double>(i.choices.size());
  return i.refusal(index ? cat("\"", i.choices[static_cast<std::size_t>(v)], "\"") : value_text(v), need);
}

void Key::set(Parameters& p, PointOptions& o, double v) const { row(index_).access.set(p, o, v); }

void Key::set(Parameters& p, double v) const {
  if (row(index_).access.value == nullptr)
    throw std::logic_error(cat("Key::set: ", full_name(), " is not a key of Parameters"));
  PointOptions unused;
  row(index_).access.set(p, unused, v);
}

std::optional<double> Key::stored(const Parameters& p, const PointOptions& o) const {
  return row(index_).access.stored(p, o);
}

double Key::value(const Parameters& p) const {
  const Deriver derive = row(index_).access.value;
  if (derive == nullptr) throw std::logic_error(cat("Key::value: ", full_name(), " is not a key of Parameters"));
  return derive(p);
}

namespace {

// The keys of one section, in table order: refusals() runs for every point a sweep solves, and
// a pass over the whole table comparing section names cost ~15 % of a trivial cell.
const std::vector<Key>& keys_of_section(std::string_view section) {
  static const std::map<std::string_view, std::vector<Key>, std::less<>> by_section = [] {
    std::map<std::string_view, std::vector<Key>, std::less<>> m;
    for (const Key k : Key::all()) m[k.info().section].push_back(k);
    return m;
  }();
  static const std::vector<Key> none;
  const auto it = by_section.find(section);
  return it == by_section.end() ? none : it->second;
}

}  // namespace

std::vector<std::string> refusals(const Parameters& p, const PointOptions& o, std::string_view section) {
  std::vector<std::string> out;
  for (const Key k : keys_of_section(section)) {
    if (const std::optional<double> v = k.stored(p, o))
      if (std::string r = k.check(*v); !r.empty()) out.push_back(std::move(r));
  }
  return out;
}

// The checks of a point's Parameters: every key of the model sections and [initial] against the
// table, then the rules that combine keys (parameters.hpp).
std::vector<std::string> validate(const Parameters& p) {
  const PointOptions unused;
  std::vector<std::string> errors;
  for (const std::string_view section : {"system", "contact", "forcing", "initial"})
    for (std::string& r : refusals(p, unused, section)) errors.push_back(std::move(r));
  if (p.damping && *p.damping != 0.0 && p.law == ContactLawKind::hertz)
    errors.push_back(Key::find("contact.damping")->info().refusal(
        value_text(*p.damping), "needs a dissipative contact law (contact.law), not hertz"));
  if (errors.empty())
    if (std::string e = derived_scale_error(p); !e.empty()) errors.push_back(std::move(e));
  if (errors.empty())
    if (std::string e = frequency_ratio_error(p); !e.empty()) errors.push_back(std::move(e));
  return errors;
}

// ---------------------------------------------------------------------------------------
// Axes.

Axis make_axis(Key key, std::vector<double> values, AxisScale scale) {
  if (!key.is_axis()) throw std::logic_error(cat("make_axis: ", key.full_name(), " cannot be an axis"));
  const KeyInfo& i = key.info();
  Axis axis{key.full_name(), std::string(i.name), i.unit == "-" ? "1" : std::string(i.unit), std::string(i.meaning),
            {}, scale, {}};
  if (key.is_categorical())
    for (const std::string_view c : i.choices) axis.categories.emplace_back(c);
  for (const double v : values)
    if (std::string r = key.check(v); !r.empty()) throw std::invalid_argument(r);
  axis.values = std::move(values);
  if (const std::string err = validate_axis(axis); !err.empty()) throw std::invalid_argument(err);
  return axis;
}

Axis make_axis(Key key, double from, double to, int n, AxisScale scale) {
  return make_axis(key, axis_points(from, to, n, scale), scale);
}

}  // namespace vibromap
