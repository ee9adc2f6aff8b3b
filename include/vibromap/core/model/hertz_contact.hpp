#pragma once
// Hertz contact law between two elastic bodies with curved surfaces (docs/model.md), with the
// optional nonlinear damping of the dissipative laws (contact_law.hpp):
//   Fc(z) = K z^(3/2) for approach z > 0, else 0                          (elastic, chi = 0)
//   Fc(z, w; v_in) = max(0, K z^(3/2) (1 + chi w / v_in)) for z > 0, else 0  (damped)
//   K = (4/3) q / ((delta1 + delta2) sqrt(A + B)),  delta_i = (1 - nu_i^2) / (pi E_i),
//   A = B = 1/(2 R1) + 1/(2 R2).
// w = z' is the approach rate, v_in > 0 the approach rate at the contact's entry. The clip
// at 0 keeps the contact from pulling the bodies together while they separate fast
// (w < -v_in / chi). With chi = 0 the damped form returns the elastic force exactly (the
// same floating-point operations), so elastic scenes do not move by a bit.
// Units: E in Pa, R in m, z in m, w and v_in in m/s, K in N/m^1.5, force in N.

#include <cmath>

namespace vibromap {

class HertzContact {
 public:
  HertzContact() = default;
  HertzContact(double E1, double E2, double nu1, double nu2, double R1, double R2, double q, double chi = 0.0);

  double stiffness() const { return K_; }                 // K, N/m^1.5
  double effective_radius() const { return R_star_; }     // R* = R1 R2 / (R1 + R2), m
  double damping() const { return chi_; }                 // chi, -
  bool dissipative() const { return chi_ != 0.0; }
  // The elastic part K z^(3/2), N.
  double force(double z) const { return z > 0.0 ? K_ * z * std::sqrt(z) : 0.0; }
  // The whole contact force with damping (clipped at 0), N.
  double force(double z, double w, double v_in) const {
    if (chi_ == 0.0) return force(z);
    const double f = force(z) * (1.0 + chi_ * w / v_in);
    return f > 0.0 ? f : 0.0;
  }
  // Whether the damped force is clipped at (z, w): z > 0 and 1 + chi w / v_in < 0.
  bool clipped(double z, double w, double v_in) const { return z > 0.0 && chi_ * w < -v_in; }
  // Elastic energy stored at approach z: (2/5) K z^(5/2), J.
  double energy(double z) const { return z > 0.0 ? 0.4 * K_ * z * z * std::sqrt(z) : 0.0; }
  // dFc/dz of the elastic force, (3/2) K sqrt(z), N/m.
  double force_derivative(double z) const { return z > 0.0 ? 1.5 * K_ * std::sqrt(z) : 0.0; }

  // Partial derivatives of the damped force (0 where it is clipped or z <= 0).
  struct Partials {
    double dz = 0.0;     // dFc/dz, N/m
    double dw = 0.0;     // dFc/dw, N s/m
    double dv_in = 0.0;  // dFc/dv_in, N s/m
  };
  Partials partials(double z, double w, double v_in) const {
    if (chi_ == 0.0) return {force_derivative(z), 0.0, 0.0};
    if (z <= 0.0 || clipped(z, w, v_in)) return {};
    const double f = force(z), r = chi_ / v_in;
    return {force_derivative(z) * (1.0 + r * w), f * r, -f * r * w / v_in};
  }

 private:
  double K_ = 0.0;
  double R_star_ = 0.0;
  double chi_ = 0.0;
};

}  // namespace vibromap
