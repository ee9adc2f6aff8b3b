#pragma once
// Internal to continuation.cpp: the continuation problem of periodic orbits of period n, in
// scaled variables z = (y scaled by the motion's length and speed, l) with the parameter
// lambda = from + l span: G(z) = (P^n(y) - y) / unit, its Jacobian, Newton's corrector on the
// pseudo-arclength system and the tangent.

#include <cmath>
#include <optional>
#include <utility>

#include <Eigen/Dense>

#include "vibromap/core/analysis/continuation/continuation.hpp"
#include "vibromap/core/analysis/continuation/orbit_extent.hpp"
#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap::continuation_detail {

using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;

// The largest turn of the tangent over one accepted step, rad (branches and curves alike).
inline constexpr double kMaxTurn = 0.3;
// A branch or curve whose step stays below kStallStep for kStallPoints accepted points in a row
// stops: Newton converges only on tiny steps (a nonsmooth stretch, e.g. a grazing of stiff contact).
inline constexpr double kStallStep = 1e-4;
inline constexpr int kStallPoints = 200;

// Newton's corrector of pseudo-arclength continuation, shared by the branch (N = 5: y, lambda)
// and the curves of two parameters (N = 6: y, P, Q; curve_problem.hpp): from z_pred, solves
// [R(z) = 0, t.(z - z_pred) = 0], R of N - 1 equations. eval(z) -> std::optional<E> (none: the
// integration failed); done(e): converged; rows(e, A, r) fills the first N - 1 rows of the
// Jacobian A and of the residual r. A step further than 0.5 (scaled) from the predictor fails
// (a smaller step is wanted).
template <int N, class E, class EvalF, class Done, class Rows>
std::optional<std::pair<Eigen::Matrix<double, N, 1>, E>> arclength_correct(EvalF&& eval, Done&& done, Rows&& rows,
                                                                           const Eigen::Matrix<double, N, 1>& z_pred,
                                                                           const Eigen::Matrix<double, N, 1>& t,
                                                                           int max_corrections, int* iterations) {
  Eigen::Matrix<double, N, 1> z = z_pred;
  for (int it = 0; it <= max_corrections; ++it) {
    const std::optional<E> e = eval(z);
    if (!e) return std::nullopt;
    if (done(*e)) {
      if (iterations) *iterations = it;
      return std::make_pair(z, *e);
    }
    Eigen::Matrix<double, N, N> A;
    Eigen::Matrix<double, N, 1> r;
    rows(*e, A, r);
    A.template bottomRows<1>() = t.transpose();
    r[N - 1] = t.dot(z - z_pred);
    const Eigen::Matrix<double, N, 1> dz = A.fullPivLu().solve(-r);
    if (!dz.allFinite() || dz.norm() > 0.5) return std::nullopt;  // far from the predictor: a smaller step
    z += dz;
  }
  return std::nullopt;
}

// The unit tangent of the solution curve of N - 1 equations whose Jacobian's rows A (the first
// N - 1 rows filled), oriented along `previous`.
template <int N>
Eigen::Matrix<double, N, 1> arclength_tangent(Eigen::Matrix<double, N, N> A, const Eigen::Matrix<double, N, 1>& previous) {
  A.template bottomRows<1>() = previous.transpose();
  Eigen::Matrix<double, N, 1> rhs = Eigen::Matrix<double, N, 1>::Zero();
  rhs[N - 1] = 1.0;
  Eigen::Matrix<double, N, 1> t = A.fullPivLu().solve(rhs);
  return t / t.norm();
}

// One more Newton step at the point's own parameters, from a corrected point: the
// orbit the corrector accepts has its residual F below the Newton tolerance, which leaves the
// state off the orbit by up to |F| / |1 - mu| (lightly damped orbits: hundreds of times |F|); the
// point's extremes (x1_max, clearance_min) measured there would carry that error. The step
// dy = -(M - I)^-1 F uses the Jacobian already evaluated (no integration), converges
// quadratically (exactly for a linear orbit) and is taken only where that holds: the step is
// below 1e-4 of the motion's scale and 1e-2 of M - I's least singular value sigma (Newton's
// error after the step is ~ |dy|^2 / sigma in these units, so it then shrinks the error by 100 or
// more). Near a fold (mu = 1, sigma -> 0) the corrected state is kept.
// y_scaled and F in the motion's scaled units; Jy = dF/dy_scaled.
inline Eigen::Vector4d polished(const Eigen::Vector4d& y_scaled, const Eigen::Vector4d& F, const Eigen::Matrix4d& Jy) {
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(Jy, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const double sigma = svd.singularValues()[3];
  if (!(sigma > 0.0)) return y_scaled;
  const Eigen::Vector4d dy = svd.solve(-F);
  const double step = dy.cwiseAbs().maxCoeff();
  if (!std::isfinite(step) || !(step <= 1e-4) || !(step <= 1e-2 * sigma)) return y_scaled;
  return y_scaled + dy;
}

// G and its Jacobian at one point z = (y scaled by the motion's scale, l): lambda = from + l span.
struct Eval {
  Eigen::Vector4d F = Eigen::Vector4d::Zero();   // (P^n(y) - y) / unit
  Eigen::Matrix4d Jy = Eigen::Matrix4d::Zero();  // dF/dy_scaled
  Eigen::Vector4d Jl = Eigen::Vector4d::Zero();  // dF/dl (forward difference)
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();  // monodromy dP^n/dy
};

class Problem {
 public:
  Problem(const PointAt& point_at, double from, double to, const ContinuationOptions& o);

  double lambda(double l) const { return from_ + l * span_; }
  State state(const Vector5d& z) const { return (z.head<4>().array() * unit_).matrix(); }
  Vector5d scaled(const State& y, double l) const {
    Vector5d z;
    z.head<4>() = (y.array() / unit_).matrix();
    z[4] = l;
    return z;
  }

  std::optional<Eval> eval(const Vector5d& z);
  // Newton on [G(z) = 0, t.(z - z_pred) = 0] from z_pred.
  std::optional<std::pair<Vector5d, Eval>> correct(const Vector5d& z_pred, const Vector5d& t, int* iterations = nullptr);
  // The unit tangent at a point, oriented along `previous`.
  static Vector5d tangent(const Eval& e, const Vector5d& previous);
  BranchPoint point(const Vector5d& z, const Eval& e);
  OrbitExtent extent(const Vector5d& z);

  double length_scale() const { return unit_[0]; }
  double from() const { return from_; }
  double span() const { return span_; }
  // A physical state difference in the scaled units.
  Eigen::Vector4d scaled_difference(const Eigen::Vector4d& d) const { return (d.array() / unit_).matrix(); }

  IntegrationCounters counters;

 private:
  static constexpr double kDl = 1e-7;  // finite-difference step in the scaled parameter
  PointAt point_at_;
  double from_, span_;
  ContinuationOptions o_;
  Eigen::Array4d unit_;
};

}  // namespace vibromap::continuation_detail
