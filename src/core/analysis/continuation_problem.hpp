#pragma once
// Internal to continuation.cpp: the continuation problem of periodic orbits of period n, in
// scaled variables z = (y scaled by the motion's length and speed, l) with the parameter
// lambda = from + l span: G(z) = (P^n(y) - y) / unit, its Jacobian, Newton's corrector on the
// pseudo-arclength system and the tangent.

#include <optional>
#include <utility>

#include <Eigen/Dense>

#include "vibromap/core/analysis/continuation.hpp"
#include "vibromap/core/analysis/orbit_extent.hpp"
#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap::continuation_detail {

using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;

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
