#pragma once
// Closed-form free flight: between impacts the system is linear with harmonic forcing,
//   u' = A u + b cos(omega tau + phi0) + c      (internal coordinates, system.hpp),
// so u(tau) = V e^{Lambda (tau - tau0)} V^{-1} (u(tau0) - u_p(tau0)) + u_p(tau), with
// A = V Lambda V^{-1} decomposed once per parameter point and the particular solution
//   u_p(tau) = Re[(i omega I - A)^{-1} b e^{i (omega tau + phi0)}] - A^{-1} c.
//
// Contact entry is the first root of z on this closed form, found with steps that cannot
// pass a root: with M >= |z''| over the whole free flight (a bound from the modal
// amplitudes, since every mode decays: Re(lambda) <= 0), z(tau + h) <= z + w h + M h^2 / 2,
// and the step h is the positive root of that quadratic, so z stays negative up to tau + h.
// The steps shrink quadratically towards a crossing and are refined by Newton's method on
// the closed form; a graze that stays below 0 is stepped past.
//
// valid() is false when the decomposition is ill-conditioned (nearly defective A, e.g. a
// free attached body with k2 = c2 = 0) or the forcing is resonant with an undamped mode;
// make_integrator() then uses dopri5 for the whole motion.

#include <array>
#include <complex>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/model/system.hpp"

namespace vibromap {

class FreeFlight {
 public:
  explicit FreeFlight(const Model& model);

  bool valid() const { return valid_; }
  const Eigen::Matrix4d& matrix() const { return sys_.A; }

  // The state at tau1 of the contact-free motion through (tau0, u0).
  State propagate(double tau0, const State& u0, double tau1) const;
  // The same in two parts, for many tau1 from one (tau0, u0) (a step's dense output): the
  // motion's modal amplitudes, then the state at tau1 from them (propagate's values).
  using Modes = Eigen::Matrix<std::complex<double>, 4, 1>;
  Modes modes(double tau0, const State& u0) const;
  State propagate(const Modes& alpha, double tau0, double tau1) const;
  // e^{A dt}: the derivative of propagate() with respect to u0.
  Eigen::Matrix4d transition(double dt) const;
  // First contact entry (z rising through 0) in (tau0, tau1], or nullopt.
  std::optional<double> find_entry(double tau0, const State& u0, double tau1) const;
  // The free flight from (tau0, u0) to its first contact entry in (tau0, tau1], or to tau1
  // when there is none: find_entry() and then propagate() to where it ends, the same values
  // bit for bit, with the modal amplitudes and the last exponentials of the entry search
  // reused (a third of a free flight's sines, cosines and exponentials).
  struct Flight {
    std::optional<double> entry;
    State u;      // the state at *entry (z is then 0 to the entry tolerance) or at tau1
    Modes alpha;  // modes(tau0, u0): what propagate(alpha, tau0, tau) needs for any tau of the flight
  };
  Flight fly(double tau0, const State& u0, double tau1) const;
  // Whether the contact-free motion through (tau0, u0) stays clear of contact for ever after:
  // z never comes within the entry tolerance of 0. A bound, not a search: z's largest value is
  // at most its constant part plus its forced part's amplitude plus every mode's amplitude
  // (|e^{lambda s}| <= 1), so false only says that the bound does not decide.
  bool never_enters(double tau0, const State& u0) const;
  // The T-periodic motion the contact-free motion tends to (the particular solution), at tau.
  State orbit(double tau) const { return particular(tau); }
  // Its Floquet multipliers e^{lambda_j T} (T = 2 pi / omega), largest |mu| first and, of a
  // complex pair, the one with the positive imaginary part first (as the eigenvalues of e^{A T}
  // come); computed with the decomposition.
  const std::vector<std::complex<double>>& multipliers() const { return multipliers_; }

  // Whether this is the free flight of `model`: the same linear part, forcing and entry
  // tolerance (so it can be shared by every integrator of that model).
  bool describes(const Model& model) const;

 private:
  using Vec4c = Modes;
  // What the decomposition is computed from: u' = A u + b cos(omega tau + phi0) + c.
  struct System {
    Eigen::Matrix4d A;
    State b, c;
    double omega, phi0, z_tol;
    explicit System(const Model& model);
    bool operator==(const System& o) const {
      return A == o.A && b == o.b && c == o.c && omega == o.omega && phi0 == o.phi0 && z_tol == o.z_tol;
    }
  };
  State particular(double tau) const;
  State particular_at(std::complex<double> forcing) const;  // forcing: e^{i (omega tau + phi0)}
  // The state at tau1 from the modal amplitudes alpha at tau0, given modal_exp(tau1 - tau0) and
  // e^{i (omega tau1 + phi0)}.
  State state_at(const Modes& alpha, const Modes& exponentials, std::complex<double> forcing) const;
  // What the entry search evaluated last: the modal amplitudes at tau0 and, at its last
  // offset s, e^{lambda_j s} and e^{i (omega (tau0 + s) + phi0)}.
  struct Search {
    Vec4c alpha, modal;
    std::complex<double> forcing;
    double s = 0.0;
  };
  std::optional<double> search_entry(double tau0, const State& u0, double tau1, Search& last) const;
  // e^{lambda_j dt} for every mode; the second mode of a complex-conjugate pair takes the
  // conjugate of the first (half the complex exponentials of an underdamped system).
  Vec4c modal_exp(double dt) const;

  System sys_;
  Eigen::Matrix4cd V_, V_inv_;
  Vec4c lambda_;
  std::array<int, 4> conjugate_of_{-1, -1, -1, -1};  // the mode this one is the conjugate of, or -1
  Vec4c amp_;          // (i omega I - A)^{-1} b
  double forcing_z2_ = 0.0;  // omega^2 |amp_z|: the bound on the forced part of |z''|
  State constant_;     // -A^{-1} c
  std::vector<std::complex<double>> multipliers_;
  bool valid_ = false;
};

}  // namespace vibromap
