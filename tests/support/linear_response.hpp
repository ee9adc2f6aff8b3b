#pragma once
// The closed-form response of the contact-free system (shared by the continuation tests).
// Without contact (a clearance larger than any motion) the system is linear: in (x1, w = x2 - D)
//   M q'' + C q' + K q = (lambda F0 cos(omega t + phi0), 0),
// whose periodic response is q(t) = Re(H(omega) f e^(i omega t)), H = (K - omega^2 M + i omega C)^-1,
// f = (lambda F0 e^(i phi0), 0); its Floquet multipliers over T = 2 pi / omega are exp(s_k T),
// s_k the eigenvalues of the first-order system matrix.

#include <complex>
#include <vector>

#include <Eigen/Dense>

#include "vibromap/core/model/parameters.hpp"

namespace vibromap::test {

using cd = std::complex<double>;

struct Linear {
  Eigen::Matrix2d M, C, K;
  explicit Linear(const Parameters& p) {
    const double k1 = p.spring1.stiffness(p.m1), k2 = p.spring2.stiffness(p.m2);
    const double c1 = p.damper1.coefficient(p.m1, k1), c2 = p.damper2.coefficient(p.m2, k2);
    M << p.m1, 0, 0, p.m2;
    C << c1 + c2, -c2, -c2, c2;
    K << k1 + k2, -k2, -k2, k2;
  }
  // (x1, x2, v1, v2) at a period start of the periodic response at p.omega.
  Eigen::Vector4d orbit(const Parameters& p) const {
    const double w = p.omega;
    Eigen::Matrix2cd Z = K.cast<cd>() - w * w * M.cast<cd>() + cd(0, w) * C.cast<cd>();
    Eigen::Vector2cd f(p.lambda * p.F0 * std::exp(cd(0, p.phi0)), 0.0);
    const Eigen::Vector2cd Q = Z.lu().solve(f);
    return {Q[0].real(), Q[1].real() + p.D, (cd(0, w) * Q[0]).real(), (cd(0, w) * Q[1]).real()};
  }
  // The complex amplitudes (Q1, Q2) of x1 and x2 - D at p.omega.
  Eigen::Vector2cd amplitudes(const Parameters& p) const {
    const double w = p.omega;
    Eigen::Matrix2cd Z = K.cast<cd>() - w * w * M.cast<cd>() + cd(0, w) * C.cast<cd>();
    return Z.lu().solve(Eigen::Vector2cd(p.lambda * p.F0 * std::exp(cd(0, p.phi0)), 0.0));
  }
  std::vector<cd> multipliers(double T) const {
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    A.topRightCorner<2, 2>() = Eigen::Matrix2d::Identity();
    A.bottomLeftCorner<2, 2>() = -M.inverse() * K;
    A.bottomRightCorner<2, 2>() = -M.inverse() * C;
    const Eigen::EigenSolver<Eigen::Matrix4d> es(A, false);
    std::vector<cd> mu;
    for (int i = 0; i < 4; ++i) mu.push_back(std::exp(es.eigenvalues()[i] * T));
    return mu;
  }
};

}  // namespace vibromap::test
