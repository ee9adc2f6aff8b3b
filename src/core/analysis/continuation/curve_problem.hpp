#pragma once
// Internal to curve_continuation.cpp: the extended system of a curve in two parameters (see
// curve_continuation.hpp) in scaled unknowns z = (y / unit, u, v), P = from + u (to - from),
// Q = from2 + v (to2 - from2): its value, Jacobian, corrector and tangent.

#include <optional>
#include <utility>

#include <Eigen/Dense>

#include "vibromap/core/analysis/continuation/curve_continuation.hpp"
#include "vibromap/core/analysis/continuation/orbit_extent.hpp"
#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap::curve_detail {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct CurveEval {
  Eigen::Vector4d F = Eigen::Vector4d::Zero();      // (P^n(y) - y) / unit
  double g = 0.0;                                   // the defining condition
  Eigen::Matrix<double, 5, 6> J = Eigen::Matrix<double, 5, 6>::Zero();  // d(F, g)/dz
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();  // monodromy
};

// The period map and monodromy at one z.
struct MapAt {
  State image;
  Eigen::Matrix4d M;
};

class CurveProblem {
 public:
  CurveProblem(const PointAt2& at, const CurveBox& box, const CurveSpec& spec, int n, const CurveOptions& o);

  double P(double u) const { return box_.from + u * (box_.to - box_.from); }
  double Q(double v) const { return box_.from2 + v * (box_.to2 - box_.from2); }
  double u_of(double P) const { return (P - box_.from) / (box_.to - box_.from); }
  double v_of(double Q) const { return (Q - box_.from2) / (box_.to2 - box_.from2); }
  State state(const Vector6d& z) const { return (z.head<4>().array() * unit_).matrix(); }
  Vector6d scaled(const State& y, double P, double Q) const;

  std::optional<CurveEval> eval(const Vector6d& z);
  // Newton on [G = 0, g = 0, t.(z - z_pred) = 0] from z_pred (arclength_correct).
  std::optional<std::pair<Vector6d, CurveEval>> correct(const Vector6d& z_pred, const Vector6d& t,
                                                        int* iterations = nullptr);
  static Vector6d tangent(const CurveEval& e, const Vector6d& previous);
  // The unit null vector of J (either orientation).
  static Vector6d null_vector(const CurveEval& e);
  CurvePoint point(const Vector6d& z, const CurveEval& e);

  // Grazing: the approach the condition tracks (OrbitExtent::approaches) is the one whose phase is
  // nearest `phase` (the previous point's), or with none set the one nearest touching.
  void track_phase(double phase) { phase_ = phase; }
  // Grazing: tracks the approach of the orbit at z nearest touching; false when it has none.
  bool track_touching(const Vector6d& z);
  const CurveOptions& options() const { return o_; }
  const CurveBox& box() const { return box_; }
  const CurveSpec& spec() const { return spec_; }
  IntegrationCounters counters;

 private:
  std::optional<MapAt> map_at(const Vector6d& z);
  // g at z (M: the monodromy at z); none when it cannot be evaluated.
  std::optional<double> condition(const Vector6d& z, const Eigen::Matrix4d& M);
  bool needs_monodromy() const;
  const Approach* tracked(const OrbitExtent& x) const;

  static constexpr double kDz = 1e-7;  // forward-difference step in the scaled unknowns
  PointAt2 at_;
  CurveBox box_;
  CurveSpec spec_;
  int n_;
  CurveOptions o_;
  Eigen::Array4d unit_;
  double level_scale_ = 1.0;
  std::optional<double> phase_;  // grazing: the tracked approach's phase
};

// The test functions along a curve (curve_continuation.hpp), each a sign or a count.
double fold_test(const Eigen::Matrix4d& M);
double pd_test(const Eigen::Matrix4d& M);
int ns_count(const Eigen::Matrix4d& M);
// |mu|^2 - 1 of the complex pair nearest the unit circle; none without a complex pair.
std::optional<double> ns_condition(const Eigen::Matrix4d& M);

}  // namespace vibromap::curve_detail
