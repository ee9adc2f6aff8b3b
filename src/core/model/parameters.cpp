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

double force_amplitude(const Parameters& p) { return p.lambda * p.F0; }

double motion_length(const Parameters& p) {
  const double k1 = p.spring1.stiffness(p.m1);
  return std::max({p.D, k1 > 0.0 ? p.lambda * p.F0 / k1 : 0.0, 1e-9});
}

double motion_speed(const Parameters& p) { return p.omega * motion_length(p); }

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

}  // namespace vibromap
