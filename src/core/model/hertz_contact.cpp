#include "vibromap/core/model/hertz_contact.hpp"

#include <numbers>

namespace vibromap {

HertzContact::HertzContact(double E1, double E2, double nu1, double nu2, double R1, double R2, double q,
                           double chi)
    : chi_(chi) {
  const double delta1 = (1.0 - nu1 * nu1) / (std::numbers::pi * E1);
  const double delta2 = (1.0 - nu2 * nu2) / (std::numbers::pi * E2);
  // Spherical surfaces: A = B = 1/(2 R1) + 1/(2 R2), so A + B = 1/R1 + 1/R2.
  const double A_plus_B = 1.0 / R1 + 1.0 / R2;
  K_ = (4.0 / 3.0) * q / ((delta1 + delta2) * std::sqrt(A_plus_B));
  R_star_ = R1 * R2 / (R1 + R2);
}

}  // namespace vibromap
