#pragma once
// Analytic reference: the two-body system without contact is linear with harmonic forcing,
//   u' = A u + b cos(omega t + phi0) + c,
// in the internal coordinates u = (x1, z, v1, w) of system.hpp. Its exact solution is
//   u(t) = e^{A t} (u0 - u_p(0)) + u_p(t),
//   u_p(t) = Re[(i omega I - A)^{-1} b e^{i (omega t + phi0)}] - A^{-1} c,
// with e^{A t} from Eigen's MatrixFunctions (Pade approximation with scaling and squaring),
// independent of anything in the library under test.

#include <complex>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include "vibromap/core/model/system.hpp"

namespace vibromap::test {

class LinearOscillator {
 public:
  explicit LinearOscillator(const Model& m) : omega_(m.parameters().omega), phi0_(m.parameters().phi0) {
    const Parameters& p = m.parameters();
    const double m1 = p.m1, m2 = p.m2, k1 = m.k1(), k2 = m.k2(), c1 = m.c1(), c2 = m.c2();
    // rows: x1' = v1; z' = w; v1' = a1; w' = a1 - a2 (see system.hpp)
    A_.setZero();
    A_(0, 2) = 1.0;
    A_(1, 3) = 1.0;
    // a1 = (-c1 v1 - k1 x1 - c2 w - k2 z - k2 D + F - 0) / m1 ; a2 = (c2 w + k2 z + k2 D) / m2
    A_(2, 0) = -k1 / m1;
    A_(2, 1) = -k2 / m1;
    A_(2, 2) = -c1 / m1;
    A_(2, 3) = -c2 / m1;
    A_(3, 0) = A_(2, 0);
    A_(3, 1) = -k2 / m1 - k2 / m2;
    A_(3, 2) = A_(2, 2);
    A_(3, 3) = -c2 / m1 - c2 / m2;
    b_ << 0, 0, p.lambda * p.F0 / m1, p.lambda * p.F0 / m1;
    c_ << 0, 0, -k2 * p.D / m1, -k2 * p.D / m1 - k2 * p.D / m2;
    const Eigen::Matrix4cd M = std::complex<double>(0, omega_) * Eigen::Matrix4cd::Identity() - A_.cast<std::complex<double>>();
    amp_ = M.partialPivLu().solve(b_.cast<std::complex<double>>());
    constant_ = -A_.partialPivLu().solve(c_);
  }

  Eigen::Vector4d particular(double t) const {
    const std::complex<double> e = std::exp(std::complex<double>(0, omega_ * t + phi0_));
    return (amp_ * e).real() + constant_;
  }

  // The system matrix A of u' = A u + ... (the free vector field's Jacobian).
  const Eigen::Matrix4d& matrix() const { return A_; }

  Eigen::Vector4d solution(const Eigen::Vector4d& u0, double t) const {
    const Eigen::Matrix4d E = (A_ * t).exp();
    return E * (u0 - particular(0.0)) + particular(t);
  }

 private:
  double omega_, phi0_;
  Eigen::Matrix4d A_;
  Eigen::Vector4d b_, c_, constant_;
  Eigen::Vector4cd amp_;
};

}  // namespace vibromap::test
