#pragma once
// The equations of motion of docs/model.md as a vector field, in relative coordinates.
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
// docs/model.md notes that the source paper prints the attached spring's coupling factor in the
// main body's equation as chi = m1/m2; Newton's third law requires m2/m1 in its
// dimensionless form, which is what the physical equations above contain.
//
// Time: the forcing is T-periodic, so callers pass the time since the start of the
// current forcing period (this keeps digits: see docs/numerics.md, "Time").

#include <array>
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
  // The forcing at tau + c[i] h (i < N, 0 < c[i] <= 1), as an integrator step's stages need
  // it. A short step (omega h <= 0.05) takes one sine and cosine at tau and turns them by
  // omega c h with Taylor series whose truncation is below 1e-19: the same values as
  // forcing() to rounding, at a fraction of the cost of N cosines.
  template <std::size_t N>
  void forcing_at(double tau, double h, const std::array<double, N>& c, std::array<double, N>& F) const {
    const double x = p_.omega * h;
    if (!(std::abs(x) <= 0.05)) {
      for (std::size_t i = 0; i < N; ++i) F[i] = forcing(tau + c[i] * h);
      return;
    }
    const double theta = p_.omega * tau + p_.phi0;
    const double C = std::cos(theta), S = std::sin(theta);
    for (std::size_t i = 0; i < N; ++i) {
      const double a = c[i] * x, a2 = a * a;
      const double cos_a = 1.0 - a2 * (1.0 / 2) * (1.0 - a2 * (1.0 / 12) * (1.0 - a2 * (1.0 / 30) * (1.0 - a2 * (1.0 / 56))));
      const double sin_a = a * (1.0 - a2 * (1.0 / 6) * (1.0 - a2 * (1.0 / 20) * (1.0 - a2 * (1.0 / 42) * (1.0 - a2 * (1.0 / 72)))));
      F[i] = F_amp_ * (C * cos_a - S * sin_a);
    }
  }

  // du/dt at time tau (since the start of the forcing period) in the given mode; v_in is the
  // approach rate at the current contact's entry (only a dissipative law reads it).
  void rhs(double tau, const State& u, ContactMode mode, double v_in, State& dudt) const {
    rhs_forced(forcing(tau), u, mode, v_in, dudt);
  }
  // The same for a state without a remembered entry: v_in = entry_speed(u), exact for
  // elastic Hertz (which ignores it).
  void rhs(double tau, const State& u, ContactMode mode, State& dudt) const {
    rhs_forced(forcing(tau), u, mode, entry_speed(u), dudt);
  }
  // The same with the external force F = forcing(tau) given (integrators evaluate several
  // stages at one time and spare the cosine).
  void rhs_forced(double F, const State& u, ContactMode mode, double v_in, State& dudt) const {
    const double fc = mode == ContactMode::contact ? contact_.force(u[1], u[3], v_in) : 0.0;
    const double spring = k2_ * (u[1] + p_.D) + c2_ * u[3];
    const double a1 = (-c1_ * u[2] - k1_ * u[0] - spring + F - fc) * inv_m1_;
    const double a2 = (spring + fc) * inv_m2_;
    dudt << u[2], u[3], a1, a1 - a2;
  }

  // Jacobian d(du/dt)/du in the given mode (the forcing does not depend on u), v_in held
  // fixed. The Hertz term dFc/dz = (3/2) K sqrt(z) (1 + chi w / v_in) is continuous and
  // vanishes at z = 0; a damped law adds dFc/dw = K z^(3/2) chi / v_in.
  Eigen::Matrix4d jacobian(const State& u, ContactMode mode, double v_in) const {
    const HertzContact::Partials d =
        mode == ContactMode::contact ? contact_.partials(u[1], u[3], v_in) : HertzContact::Partials{};
    const double da1_dz = -(k2_ + d.dz) * inv_m1_, da2_dz = (k2_ + d.dz) * inv_m2_;
    const double da1_dw = -(c2_ + d.dw) * inv_m1_, da2_dw = (c2_ + d.dw) * inv_m2_;
    const double da1_dx1 = -k1_ * inv_m1_, da1_dv1 = -c1_ * inv_m1_;
    Eigen::Matrix4d J;
    J << 0, 0, 1, 0,                                      //
        0, 0, 0, 1,                                       //
        da1_dx1, da1_dz, da1_dv1, da1_dw,                 //
        da1_dx1, da1_dz - da2_dz, da1_dv1, da1_dw - da2_dw;
    return J;
  }
  // d(du/dt)/d(v_in) in contact (zero for elastic Hertz): the variational equations carry
  // it times d(v_in)/d(u0), since v_in is a property of the entry state.
  State entry_speed_column(const State& u, ContactMode mode, double v_in) const {
    const double d = mode == ContactMode::contact ? contact_.partials(u[1], u[3], v_in).dv_in : 0.0;
    const double da1 = -d * inv_m1_, da2 = d * inv_m2_;
    return {0.0, 0.0, da1, da1 - da2};
  }

  // The entry speed assigned to a state that carries no memory of its contact's entry (an
  // initial state, a shooting iterate, a Poincare point inside a contact): the approach rate
  // an elastic impact of the free bodies needs to reach (z, w), sqrt(w^2 + 2 U(z) / mu), U the
  // Hertz energy; for z <= 0 it is w. Never below min_entry_speed().
  double entry_speed(const State& u) const {
    const double v2 = u[3] * u[3] + 2.0 * contact_.energy(u[1]) / reduced_mass();
    const double v = u[1] > 0.0 ? std::sqrt(v2) : u[3];
    return v > v_floor_ ? v : v_floor_;
  }
  // Its gradient d(entry_speed)/du (a row), zero where the floor holds.
  Eigen::RowVector4d entry_speed_gradient(const State& u) const {
    const double v = entry_speed(u);
    if (v <= v_floor_) return Eigen::RowVector4d::Zero();
    if (u[1] <= 0.0) return {0.0, 0.0, 0.0, 1.0};
    return {0.0, contact_.force(u[1]) / (reduced_mass() * v), 0.0, u[3] / v};
  }
  // The least entry speed a damped law uses, m/s: 1e-6 omega L, L = max(D, lambda F0 / k1, 1 nm).
  // A grazing entry (v_in -> 0) would make the damping chi w / v_in unbounded; below this
  // floor the damping is that of an entry at the floor speed.
  double min_entry_speed() const { return v_floor_; }

  // Total mechanical energy (kinetic + springs + Hertz), J: conserved when c1 = c2 = 0
  // and F0 = 0.
  double energy(const State& u) const;

  // Conversions between the physical (x1, x2, v1, v2) and internal (x1, z, v1, w) states.
  static State to_internal(const Eigen::Vector4d& x) { return {x[0], x[0] - x[1], x[2], x[2] - x[3]}; }
  static Eigen::Vector4d to_physical(const State& u) { return {u[0], u[0] - u[1], u[2], u[2] - u[3]}; }

 private:
  Parameters p_;
  HertzContact contact_;
  double k1_, k2_, c1_, c2_, T_, F_amp_, inv_m1_, inv_m2_, v_floor_;
};

}  // namespace vibromap
