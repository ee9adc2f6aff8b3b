#pragma once
// Shared by the shooting and contact-law tests: the state after a transient from rest, the
// n-period map by plain integration, and the monodromy by central differences of that map,
// the independent check of the variational monodromy and its Floquet multipliers.

#include <algorithm>
#include <complex>
#include <vector>

#include <Eigen/Eigenvalues>

#include "vibromap/core/analysis/point/shooting.hpp"
#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap::test {

inline constexpr double kFdStep = 1e-5;  // finite-difference step, in units of the motion's scale

inline State map_n(const Model& m, const State& y, int n, const IntegratorOptions& o) {
  auto integ = make_integrator(m, o);
  State u = y;
  integ->reset(u);
  Observer none;
  for (int i = 0; i < n; ++i) integ->advance_period(u, none);
  return u;
}

// The state after `periods` forcing periods from the scene's initial state.
inline State after_transient(const Model& m, int periods) {
  return map_n(m, Model::to_internal(m.parameters().initial_state()), periods, IntegratorOptions{});
}

// d P^n / d y at y by central differences, one column per state component.
inline Eigen::Matrix4d fd_monodromy(const Model& m, const State& y, int n, const IntegratorOptions& o) {
  Eigen::Matrix4d fd;
  const StateScale scale(m);
  const Eigen::Vector4d unit(scale.length(), scale.length(), scale.speed(), scale.speed());
  for (int j = 0; j < 4; ++j) {
    State e = State::Zero();
    e[j] = kFdStep * unit[j];
    fd.col(j) = (map_n(m, y + e, n, o) - map_n(m, y - e, n, o)) / (2 * e[j]);
  }
  return fd;
}

// |mu| of each multiplier, ascending.
inline std::vector<double> moduli(const std::vector<std::complex<double>>& mu) {
  std::vector<double> out;
  for (auto x : mu) out.push_back(std::abs(x));
  std::sort(out.begin(), out.end());
  return out;
}

inline std::vector<double> eigenvalue_moduli(const Eigen::Matrix4d& m) {
  const Eigen::EigenSolver<Eigen::Matrix4d> es(m, false);
  return moduli({es.eigenvalues().data(), es.eigenvalues().data() + 4});
}

}  // namespace vibromap::test
