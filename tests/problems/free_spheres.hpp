#pragma once
// Analytic reference: two free elastic bodies (no springs, no dampers, no forcing) meeting
// at relative speed v with Hertz law F = K z^(3/2). Energy balance (1/2) m* v^2 = (2/5) K z^(5/2)
// gives the peak approach and, integrating dt = dz / z', the duration
//   z_max = (5 m* v^2 / (4 K))^(2/5),
//   T_con = 2 (z_max / v) * integral_0^1 ds / sqrt(1 - s^(5/2)) = 3.2180655 (m*^2 / (K^2 v))^(1/5),
// with m* = m1 m2 / (m1 + m2). The bodies separate with relative speed -v, and the impulse
// exchanged is 2 m* v.

#include <cmath>

namespace vibromap::test {

// 2 (5/4)^(2/5) * integral_0^1 ds / sqrt(1 - s^(5/2)); the integral is (2/5) B(2/5, 1/2).
inline double hertz_duration_constant() {
  const double integral = 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  return 2.0 * std::pow(1.25, 0.4) * integral;  // = 3.2180655 (docs/numerics.md)
}
inline double hertz_duration(double m_star, double K, double v) {
  return hertz_duration_constant() * std::pow(m_star * m_star / (K * K * v), 0.2);
}
inline double hertz_compression(double m_star, double K, double v) {
  return std::pow(5.0 * m_star * v * v / (4.0 * K), 0.4);
}

}  // namespace vibromap::test
