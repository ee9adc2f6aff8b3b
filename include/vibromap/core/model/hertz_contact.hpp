#pragma once
// Hertz contact law between two elastic bodies with curved surfaces (SPEC.md):
//   Fc(z) = K z^(3/2) for approach z > 0, else 0,
//   K = (4/3) q / ((delta1 + delta2) sqrt(A + B)),  delta_i = (1 - nu_i^2) / (pi E_i),
//   A = B = 1/(2 R1) + 1/(2 R2).
// Units: E in Pa, R in m, z in m, K in N/m^1.5, force in N.

#include <cmath>

namespace vibromap {

class HertzContact {
 public:
  HertzContact() = default;
  HertzContact(double E1, double E2, double nu1, double nu2, double R1, double R2, double q);

  double stiffness() const { return K_; }                 // K, N/m^1.5
  double effective_radius() const { return R_star_; }     // R* = R1 R2 / (R1 + R2), m
  double force(double z) const { return z > 0.0 ? K_ * z * std::sqrt(z) : 0.0; }
  // Elastic energy stored at approach z: (2/5) K z^(5/2), J.
  double energy(double z) const { return z > 0.0 ? 0.4 * K_ * z * z * std::sqrt(z) : 0.0; }
  // dFc/dz = (3/2) K sqrt(z), N/m.
  double force_derivative(double z) const { return z > 0.0 ? 1.5 * K_ * std::sqrt(z) : 0.0; }

 private:
  double K_ = 0.0;
  double R_star_ = 0.0;
};

}  // namespace vibromap
