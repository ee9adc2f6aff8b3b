// The scales the model derives from the keys (parameters.hpp: derived_scale_error), each listed
// once with the keys it is derived from, and the refusal that names the key which made one
// overflow (keys.hpp: derived_refusal). Every key lies in its table range when these are asked,
// yet products and quotients of in-range keys can leave the doubles: lambda = 1.8e308 makes
// lambda F0 infinite, restitution = 5e-324 makes Flores' chi infinite, omega1 = 1e-200 makes
// k1 = m1 omega1^2 zero.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "vibromap/core/model/hertz_contact.hpp"
#include "vibromap/core/model/keys.hpp"
#include "vibromap/core/model/parameters.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap {
namespace {

// One derived scale: what it is (with its unit), its value at a point, whether it must also be
// positive (a stiffness the equations divide by), and the keys it is derived from.
struct DerivedScale {
  std::string_view what;
  double (*value)(const Parameters&);
  bool positive;
  std::vector<std::string_view> inputs;
};

double k1_of(const Parameters& p) { return p.spring1.stiffness(p.m1); }
double k2_of(const Parameters& p) { return p.spring2.stiffness(p.m2); }
double c1_of(const Parameters& p) { return p.damper1.coefficient(p.m1, k1_of(p)); }
double c2_of(const Parameters& p) { return p.damper2.coefficient(p.m2, k2_of(p)); }
double period_of(const Parameters& p) { return p.period(); }
double contact_stiffness_of(const Parameters& p) {
  return HertzContact(p.E1, p.E2, p.nu1, p.nu2, p.R1, p.R2, p.q).stiffness();
}
double chi_of(const Parameters& p) { return p.damping_factor(); }

// In the order the model derives them: a scale's inputs' own scales come first, so the first
// refusal names the root of the overflow.
const std::vector<DerivedScale>& derived_scales() {
  static const std::vector<DerivedScale> scales = {
      {"the main spring's stiffness k1 = m1 omega1^2 (N/m)", k1_of, true, {"system.m1", "system.k1", "system.omega1"}},
      {"the coupling spring's stiffness k2 = m2 omega2^2 (N/m)", k2_of, false,
       {"system.m2", "system.k2", "system.omega2"}},
      {"the main damper's coefficient c1 = 2 xi1 sqrt(m1 k1) (N s/m)", c1_of, false,
       {"system.xi1", "system.c1", "system.m1", "system.k1", "system.omega1"}},
      {"the coupling damper's coefficient c2 = 2 xi2 sqrt(m2 k2) (N s/m)", c2_of, false,
       {"system.xi2", "system.c2", "system.m2", "system.k2", "system.omega2"}},
      {"the forcing period T = 2 pi / omega (s)", period_of, false, {"forcing.omega"}},
      {"the force amplitude lambda F0 (N)", force_amplitude, false, {"forcing.lambda", "forcing.F0"}},
      {"the motion's length scale L = max(D, lambda F0 / k1) (m)", motion_length, false,
       {"forcing.lambda", "forcing.F0", "system.m1", "system.k1", "system.omega1"}},
      {"the motion's speed scale omega L (m/s)", motion_speed, false,
       {"forcing.omega", "system.D", "forcing.lambda", "forcing.F0", "system.m1", "system.k1", "system.omega1"}},
      {"the fastest natural frequency omega_n (rad/s)", fastest_natural_frequency, false,
       {"system.m1", "system.m2", "system.k1", "system.omega1", "system.k2", "system.omega2"}},
      {"the fastest damping rate of the dampers (1/s)", fastest_damping_rate, false,
       {"system.m1", "system.m2", "system.xi1", "system.c1", "system.xi2", "system.c2", "system.k1", "system.omega1",
        "system.k2", "system.omega2"}},
      {"the contact stiffness K (N/m^1.5)", contact_stiffness_of, false,
       {"contact.E1", "contact.E2", "contact.nu1", "contact.nu2", "contact.R1", "contact.R2", "contact.q"}},
      {"the contact's damping factor chi (-)", chi_of, false, {"contact.restitution", "contact.damping"}},
  };
  return scales;
}

// A candidate key: its value as given at the point and at the default point.
struct Culprit {
  Key key;
  double value;
  double fallback;
};

// How far a value lies from the default: decades apart for two positive values, else its
// absolute difference.
double distance(double v, double d) {
  return v > 0.0 && d > 0.0 ? std::abs(std::log(v / d)) : std::abs(v - d);
}

// The point with one key changed.
Parameters with(const Parameters& p, Key key, double v) {
  Parameters q = p;
  key.set(q, v);
  return q;
}

// The value between `good` (ok) and `bad` (not) where ok() turns: bisected in decades when both
// are positive, else linearly; returns the last good value.
double boundary(const Parameters& p, Key key, double good, double bad,
                const std::function<bool(const Parameters&)>& ok) {
  const bool decades = good > 0.0 && bad > 0.0;
  for (int i = 0; i < 80; ++i) {
    const double mid = decades ? std::sqrt(good) * std::sqrt(bad) : 0.5 * good + 0.5 * bad;
    if (mid == good || mid == bad) break;
    (ok(with(p, key, mid)) ? good : bad) = mid;
  }
  return good;
}

// The bound in the fewest digits (three at least) that still lie on the allowed side.
std::string bound_text(const Parameters& p, Key key, double bound, const std::function<bool(const Parameters&)>& ok) {
  for (int digits = 3; digits < 17; ++digits) {
    char text[40];
    std::snprintf(text, sizeof text, "%.*g", digits, bound);
    if (ok(with(p, key, std::strtod(text, nullptr)))) return text;
  }
  return shortest(bound);
}

}  // namespace

std::string derived_refusal(const Parameters& p, const std::vector<std::string_view>& inputs, std::string_view what,
                            const std::function<bool(const Parameters&)>& ok, std::string_view fault) {
  if (ok(p)) return {};
  const Parameters defaults;
  const PointOptions unused;
  std::optional<Culprit> fixable, any;
  for (const std::string_view name : inputs) {
    const Key key = Key::at(name);
    const std::optional<double> v = key.stored(p, unused);
    if (!v) continue;  // given by its partner (k1 by omega1) or left unset
    const Culprit c{key, *v, key.value(defaults)};
    const double far = distance(c.value, c.fallback);
    if (!any || far > distance(any->value, any->fallback)) any = c;
    if (ok(with(p, key, c.fallback)) && (!fixable || far > distance(fixable->value, fixable->fallback))) fixable = c;
  }
  if (!any) return cat(what, " is ", fault);
  const Culprit& c = fixable ? *fixable : *any;
  const KeyInfo& info = c.key.info();
  std::string need = cat("makes ", what, " ", fault);
  if (fixable) {
    const double bound = boundary(p, c.key, c.fallback, c.value, ok);
    need += cat("; with the other keys as given it must be ", c.value > c.fallback ? "at most " : "at least ",
                bound_text(p, c.key, bound, ok), info.unit_suffix());
  }
  return info.refusal(value_text(c.value), need);
}

std::string derived_scale_error(const Parameters& p) {
  for (const DerivedScale& s : derived_scales()) {
    const auto ok = [&s](const Parameters& q) {
      const double v = s.value(q);
      return std::isfinite(v) && (!s.positive || v > 0.0);
    };
    if (std::string r = derived_refusal(p, s.inputs, s.what, ok, s.positive ? "zero or not finite" : "not finite");
        !r.empty())
      return r;
  }
  return {};
}

}  // namespace vibromap
