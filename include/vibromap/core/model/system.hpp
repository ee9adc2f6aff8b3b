#pragma once
// The equations of motion of SPEC.md as a vector field, in relative coordinates.
//
// Physical state (x1, x2, v1, v2). Internally the integrators use
//   u = (x1, z, v1, w),  z = x1 - x2 (approach), w = v1 - v2 (approach rate),
// so that the contact condition z > 0 is a coordinate of its own: the error control then
// sees z with its own relative tolerance (z is ~1e-4 m in a rigid contact while x1 is
// ~0.1 m), and the contact boundary z = 0 can be set exactly after an event.
//
//   m1 v1' = -c1 v1 - k1 x1 - c2 w - k2 (z + D) + F(t) - Fc(z)
//   m2 v2' =  c2 w + k2 (z + D) + Fc(z)
//   F(t) = lambda F0 cos(omega t + phi0)
//
// SPEC.md notes that the source paper prints the attached spring's coupling factor in the
// main body's equation as chi = m1/m2; Newton's third law requires m2/m1 in its
// dimensionless form, which is what the physical equations above contain.
//
// Time: the forcing is T-periodic, so callers pass the time since the start of the
// current forcing period (this keeps digits: see SPEC.md "Numerics that matter").

#include <cmath>

#include <Eigen/Core>

#include "vibromap/core/model/hertz_contact.hpp"
#include "vibromap/core/model/parameters.hpp"

namespace vibromap {

using State = Eigen::Vector4d;  // (x1, z, v1, w) in m, m, m/s, m/s

// Whether the contact force is switched on in the right-hand side. The integrators keep
// the mode fixed over a step and switch it only at a located event, so the right-hand side
// they see is smooth within every step.
enum class ContactMode { free, contact };

class Model {
 public:
  explicit Model(const Parameters& p);

  const Parameters& parameters() const { return p_; }
  const HertzContact& contact() const { return contact_; }
  double period() const { return T_; }
  double k1() const { return k1_; }
  double k2() const { return k2_; }
  double c1() const { return c1_; }
  double c2() const { return c2_; }
  double reduced_mass() const { return p_.m1 * p_.m2 / (p_.m1 + p_.m2); }

  double forcing(double tau) const { return F_amp_ * std::cos(p_.omega * tau + p_.phi0); }

  // du/dt at time tau (since the start of the forcing period) in the given mode.
  void rhs(double tau, const State& u, ContactMode mode, State& dudt) const { rhs_forced(forcing(tau), u, mode, dudt); }
  // The same with the external force F = forcing(tau) given (integrators evaluate several
  // stages at one time and spare the cosine).
  void rhs_forced(double F, const State& u, ContactMode mode, State& dudt) const {
    const double fc = mode == ContactMode::contact ? contact_.force(u[1]) : 0.0;
    const double spring = k2_ * (u[1] + p_.D) + c2_ * u[3];
    const double a1 = (-c1_ * u[2] - k1_ * u[0] - spring + F - fc) * inv_m1_;
    const double a2 = (spring + fc) * inv_m2_;
    dudt << u[2], u[3], a1, a1 - a2;
  }

  // Jacobian d(du/dt)/du in the given mode (the forcing does not depend on u). The Hertz
  // term dFc/dz = (3/2) K sqrt(z) is continuous and vanishes at z = 0.
  Eigen::Matrix4d jacobian(const State& u, ContactMode mode) const {
    const double dfc = mode == ContactMode::contact ? contact_.force_derivative(u[1]) : 0.0;
    const double da1_dz = -(k2_ + dfc) * inv_m1_, da2_dz = (k2_ + dfc) * inv_m2_;
    const double da1_dw = -c2_ * inv_m1_, da2_dw = c2_ * inv_m2_;
    const double da1_dx1 = -k1_ * inv_m1_, da1_dv1 = -c1_ * inv_m1_;
    Eigen::Matrix4d J;
    J << 0, 0, 1, 0,                                      //
        0, 0, 0, 1,                                       //
        da1_dx1, da1_dz, da1_dv1, da1_dw,                 //
        da1_dx1, da1_dz - da2_dz, da1_dv1, da1_dw - da2_dw;
    return J;
  }

  // Total mechanical energy (kinetic + springs + Hertz), J: conserved when c1 = c2 = 0
  // and F0 = 0.
  double energy(const State& u) const;

  // Conversions between the physical (x1, x2, v1, v2) and internal (x1, z, v1, w) states.
  static State to_internal(const Eigen::Vector4d& x) { return {x[0], x[0] - x[1], x[2], x[2] - x[3]}; }
  static Eigen::Vector4d to_physical(const State& u) { return {u[0], u[0] - u[1], u[2], u[2] - u[3]}; }

 private:
  Parameters p_;
  HertzContact contact_;
  double k1_, k2_, c1_, c2_, T_, F_amp_, inv_m1_, inv_m2_;
};

}  // namespace vibromap
