#include "vibromap/core/model/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace vibromap {

double Damper::coefficient(double mass, double stiffness) const {
  return form == Form::coefficient ? value : 2.0 * value * std::sqrt(mass * stiffness);
}

Eigen::Vector4d Parameters::initial_state() const {
  return initial ? *initial : Eigen::Vector4d(0.0, D, 0.0, 0.0);
}

double Parameters::period() const { return 2.0 * std::numbers::pi / omega; }

double Parameters::damping_factor() const { return damping ? *damping : contact_law(law).chi(restitution); }

const std::vector<std::string_view>& variable_parameter_names() {
  static const std::vector<std::string_view> names = {"E1", "E2", "R1", "R2", "m2", "k2", "omega2",
                                                      "m1", "k1", "omega1", "nu1", "nu2", "D", "F0",
                                                      "omega", "xi1", "xi2", "c1", "c2",
                                                      "restitution", "damping", "law"};
  return names;
}

namespace {
double* plain_field(Parameters& p, std::string_view name) {
  if (name == "E1") return &p.E1;
  if (name == "E2") return &p.E2;
  if (name == "R1") return &p.R1;
  if (name == "R2") return &p.R2;
  if (name == "m1") return &p.m1;
  if (name == "m2") return &p.m2;
  if (name == "nu1") return &p.nu1;
  if (name == "nu2") return &p.nu2;
  if (name == "D") return &p.D;
  if (name == "F0") return &p.F0;
  if (name == "omega") return &p.omega;
  if (name == "restitution") return &p.restitution;
  return nullptr;
}

// Spring/damper pair fields: which spring or damper, and the form the name stands for.
struct PairField {
  bool is_spring;
  int body;  // 1 or 2
  bool first_form;  // k / c (true) or omega / xi (false)
};
std::optional<PairField> pair_field(std::string_view name) {
  if (name == "k1") return PairField{true, 1, true};
  if (name == "k2") return PairField{true, 2, true};
  if (name == "omega1") return PairField{true, 1, false};
  if (name == "omega2") return PairField{true, 2, false};
  if (name == "c1") return PairField{false, 1, true};
  if (name == "c2") return PairField{false, 2, true};
  if (name == "xi1") return PairField{false, 1, false};
  if (name == "xi2") return PairField{false, 2, false};
  return std::nullopt;
}
}  // namespace

void set_parameter(Parameters& p, std::string_view name, double value) {
  if (double* f = plain_field(p, name)) {
    *f = value;
    return;
  }
  if (name == "damping") {
    p.damping = value;
    return;
  }
  if (name == "law") {
    const double i = std::round(value);
    if (!(i >= 0.0 && i < static_cast<double>(all_contact_laws().size())) || i != value)
      throw std::invalid_argument("law index " + std::to_string(value) + " names no contact law");
    p.law = all_contact_laws()[static_cast<std::size_t>(i)];
    return;
  }
  const auto pf = pair_field(name);
  if (!pf) throw std::invalid_argument("unknown parameter '" + std::string(name) + "'");
  if (pf->is_spring) {
    Spring& s = pf->body == 1 ? p.spring1 : p.spring2;
    s = {pf->first_form ? Spring::Form::stiffness : Spring::Form::frequency, value};
  } else {
    Damper& d = pf->body == 1 ? p.damper1 : p.damper2;
    d = {pf->first_form ? Damper::Form::coefficient : Damper::Form::ratio, value};
  }
}

double get_parameter(const Parameters& p, std::string_view name) {
  if (double* f = plain_field(const_cast<Parameters&>(p), name)) return *f;
  if (name == "damping") return p.damping_factor();
  if (name == "law") return static_cast<double>(p.law);
  const auto pf = pair_field(name);
  if (!pf) throw std::invalid_argument("unknown parameter '" + std::string(name) + "'");
  const double m = pf->body == 1 ? p.m1 : p.m2;
  const Spring& s = pf->body == 1 ? p.spring1 : p.spring2;
  const double k = s.stiffness(m);
  if (pf->is_spring) return pf->first_form ? k : std::sqrt(k / m);
  const double c = (pf->body == 1 ? p.damper1 : p.damper2).coefficient(m, k);
  return pf->first_form ? c : c / (2.0 * std::sqrt(m * k));
}

namespace {
// The largest eigenvalue of M^-1 A, M = diag(m1, m2), A = [[a1 + a2, -a2], [-a2, a2]] (the
// springs' K or the dampers' C): the larger root of l^2 - 2 h l + P = 0, in a form that does not
// square h.
double largest_mode_rate(double a1, double a2, double m1, double m2) {
  const double h = 0.5 * ((a1 + a2) / m1 + a2 / m2);
  if (!(h > 0.0)) return 0.0;
  const double P = (a1 / m1) * (a2 / m2);
  return h * (1.0 + std::sqrt(std::max(0.0, 1.0 - (P / h) / h)));
}
}  // namespace

double fastest_natural_frequency(const Parameters& p) {
  const double k1 = p.spring1.stiffness(p.m1), k2 = p.spring2.stiffness(p.m2);
  return std::sqrt(largest_mode_rate(k1, k2, p.m1, p.m2));
}

double fastest_damping_rate(const Parameters& p) {
  const double k1 = p.spring1.stiffness(p.m1), k2 = p.spring2.stiffness(p.m2);
  const double c1 = p.damper1.coefficient(p.m1, k1), c2 = p.damper2.coefficient(p.m2, k2);
  return largest_mode_rate(c1, c2, p.m1, p.m2);
}

std::string frequency_ratio_error(const Parameters& p) {
  const double wn = fastest_natural_frequency(p);
  const double ratio = p.omega / wn;
  std::ostringstream os;
  os << std::setprecision(3);
  if (!(ratio >= kMinFrequencyRatio && ratio <= kMaxFrequencyRatio)) {
    os << "forcing.omega = " << p.omega << " rad/s is " << ratio << " times omega_n = " << wn
       << " rad/s, the fastest natural frequency of m1 and m2 on their springs "
       << "(k1, k2): omega/omega_n must be in [" << kMinFrequencyRatio << ", " << kMaxFrequencyRatio
       << "], i.e. forcing.omega in [" << kMinFrequencyRatio * wn << ", " << kMaxFrequencyRatio * wn
       << "] rad/s with these masses and springs";
    return os.str();
  }
  const double rate = fastest_damping_rate(p);
  if (!(rate / p.omega <= kMaxFrequencyRatio)) {
    os << "the dampers (c1|xi1, c2|xi2) damp m1 and m2 at up to " << rate << " 1/s, " << rate / p.omega
       << " times forcing.omega = " << p.omega << " rad/s: at most " << kMaxFrequencyRatio
       << " times (a forcing period would take more than 10^4 of the integrator's steps), i.e. c1 and c2 "
       << "at most " << std::setprecision(3) << kMaxFrequencyRatio * p.omega / rate
       << " times their values here";
    return os.str();
  }
  return {};
}

std::vector<std::string> validate(const Parameters& p) {
  std::vector<std::string> errors;
  auto need = [&](bool ok, const char* name, double v, const char* allowed) {
    if (ok) return;
    std::ostringstream os;
    os << name << " = " << v << ": must be " << allowed;
    errors.push_back(os.str());
  };
  auto positive = [&](const char* name, double v) { need(std::isfinite(v) && v > 0.0, name, v, "> 0"); };
  auto non_negative = [&](const char* name, double v) { need(std::isfinite(v) && v >= 0.0, name, v, ">= 0"); };
  auto finite = [&](const char* name, double v) { need(std::isfinite(v), name, v, "finite"); };

  positive("m1", p.m1);
  positive("m2", p.m2);
  positive(p.spring1.form == Spring::Form::stiffness ? "k1" : "omega1", p.spring1.value);
  non_negative(p.spring2.form == Spring::Form::stiffness ? "k2" : "omega2", p.spring2.value);
  non_negative(p.damper1.form == Damper::Form::coefficient ? "c1" : "xi1", p.damper1.value);
  non_negative(p.damper2.form == Damper::Form::coefficient ? "c2" : "xi2", p.damper2.value);
  non_negative("D", p.D);
  positive("E1", p.E1);
  positive("E2", p.E2);
  need(std::isfinite(p.nu1) && p.nu1 > -1.0 && p.nu1 < 0.5, "nu1", p.nu1, "in (-1, 0.5)");
  need(std::isfinite(p.nu2) && p.nu2 > -1.0 && p.nu2 < 0.5, "nu2", p.nu2, "in (-1, 0.5)");
  positive("R1", p.R1);
  positive("R2", p.R2);
  positive("q", p.q);
  need(std::isfinite(p.restitution) && p.restitution > 0.0 && p.restitution <= 1.0, "restitution", p.restitution,
       "in (0, 1]");
  if (p.damping) {
    non_negative("damping", *p.damping);
    if (p.law == ContactLawKind::hertz && *p.damping != 0.0)
      errors.push_back("damping = " + std::to_string(*p.damping) + ": needs a dissipative contact law, not hertz");
  }
  non_negative("F0", p.F0);
  positive("omega", p.omega);
  non_negative("lambda", p.lambda);
  finite("phi0", p.phi0);
  if (p.initial) {
    for (int i = 0; i < 4; ++i) finite("initial state", (*p.initial)[i]);
  }
  if (errors.empty())
    if (std::string e = frequency_ratio_error(p); !e.empty()) errors.push_back(std::move(e));
  return errors;
}

}  // namespace vibromap
