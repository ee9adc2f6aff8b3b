// The extended system of a curve in two parameters: see curve_problem.hpp.

#include "curve_problem.hpp"

#include <cmath>

#include "continuation_problem.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap::curve_detail {

double fold_test(const Eigen::Matrix4d& M) { return (M - Eigen::Matrix4d::Identity()).determinant(); }
double pd_test(const Eigen::Matrix4d& M) { return (M + Eigen::Matrix4d::Identity()).determinant(); }

int ns_count(const Eigen::Matrix4d& M) {
  int outside = 0;
  for (const auto& mu : floquet_multipliers(M))
    if (std::abs(mu.imag()) > 1e-9 * std::abs(mu) && std::abs(mu) > 1.0) ++outside;
  return outside;
}

std::optional<double> ns_condition(const Eigen::Matrix4d& M) {
  std::optional<double> best;
  for (const auto& mu : floquet_multipliers(M)) {
    if (!(std::abs(mu.imag()) > 1e-9 * std::abs(mu))) continue;
    const double c = std::norm(mu) - 1.0;
    if (!best || std::abs(c) < std::abs(*best)) best = c;
  }
  return best;
}

CurveProblem::CurveProblem(const PointAt2& at, const CurveBox& box, const CurveSpec& spec, int n, const CurveOptions& o)
    : at_(at), box_(box), spec_(spec), n_(n), o_(o) {
  const auto [p, opt] = at_(box.from, box.from2);
  const StateScale scale{Model(p)};
  unit_ = Eigen::Array4d(scale.length(), scale.length(), scale.speed(), scale.speed());
  if (spec.kind == CurveKind::level && spec.value != 0.0) level_scale_ = std::abs(spec.value);
}

Vector6d CurveProblem::scaled(const State& y, double P, double Q) const {
  Vector6d z;
  z.head<4>() = (y.array() / unit_).matrix();
  z[4] = u_of(P);
  z[5] = v_of(Q);
  return z;
}

bool CurveProblem::needs_monodromy() const {
  return spec_.kind == CurveKind::fold || spec_.kind == CurveKind::period_doubling ||
         spec_.kind == CurveKind::neimark_sacker;
}

std::optional<MapAt> CurveProblem::map_at(const Vector6d& z) {
  const auto [p, opt] = at_(P(z[4]), Q(z[5]));
  MapAt m;
  if (period_map(Model(p), opt.integrator, state(z), n_, m.image, m.M, counters) != IntegrationStatus::ok)
    return std::nullopt;
  return m;
}

std::optional<double> CurveProblem::condition(const Vector6d& z, const Eigen::Matrix4d& M) {
  switch (spec_.kind) {
    case CurveKind::fold: return fold_test(M);
    case CurveKind::period_doubling: return pd_test(M);
    case CurveKind::neimark_sacker: return ns_condition(M);
    case CurveKind::grazing: {
      const auto [p, opt] = at_(P(z[4]), Q(z[5]));
      const OrbitExtent x = orbit_extent(Model(p), opt.integrator, state(z), n_, counters);
      const Approach* a = x.ok ? tracked(x) : nullptr;
      if (!a) return std::nullopt;
      return a->clearance / unit_[0];
    }
    case CurveKind::level: break;
  }
  const auto [p, opt] = at_(P(z[4]), Q(z[5]));
  const PointSummary s = measure_orbit(p, opt, Model::to_physical(state(z)), n_);
  counters += s.counters;
  if (s.status != SolveStatus::ok) return std::nullopt;
  return (level_value(spec_.quantity, s) - spec_.value) / level_scale_;
}

bool CurveProblem::track_touching(const Vector6d& z) {
  const auto [p, opt] = at_(P(z[4]), Q(z[5]));
  const OrbitExtent x = orbit_extent(Model(p), opt.integrator, state(z), n_, counters);
  const Approach* a = x.ok ? touching_approach(x) : nullptr;
  if (a) phase_ = a->phase;
  return a != nullptr;
}

const Approach* CurveProblem::tracked(const OrbitExtent& x) const {
  return phase_ ? nearest_approach(x, *phase_) : touching_approach(x);
}

std::optional<CurveEval> CurveProblem::eval(const Vector6d& z) {
  const std::optional<MapAt> base = map_at(z);
  if (!base) return std::nullopt;
  CurveEval e;
  e.M = base->M;
  const State y = state(z);
  e.F = ((base->image - y).array() / unit_).matrix();
  const std::optional<double> g = condition(z, e.M);
  if (!g) return std::nullopt;
  e.g = *g;
  const Eigen::Matrix4d D = unit_.matrix().asDiagonal();
  const Eigen::Matrix4d Dinv = unit_.inverse().matrix().asDiagonal();
  e.J.topLeftCorner<4, 4>() = Dinv * (e.M - Eigen::Matrix4d::Identity()) * D;
  for (int k = 0; k < 6; ++k) {
    Vector6d zk = z;
    zk[k] += kDz;
    std::optional<MapAt> mk;
    if (k >= 4 || needs_monodromy()) {
      mk = map_at(zk);
      if (!mk) return std::nullopt;
    }
    if (k >= 4) e.J.block<4, 1>(0, k) = ((mk->image - base->image).array() / unit_).matrix() / kDz;
    const std::optional<double> gk = condition(zk, mk ? mk->M : e.M);
    if (!gk) return std::nullopt;
    e.J(4, k) = (*gk - e.g) / kDz;
  }
  return e;
}

namespace {
void curve_rows(const CurveEval& e, Matrix6d& A, Vector6d& r) {
  A.topRows<5>() = e.J;
  r.head<4>() = e.F;
  r[4] = e.g;
}
}  // namespace

std::optional<std::pair<Vector6d, CurveEval>> CurveProblem::correct(const Vector6d& z_pred, const Vector6d& t,
                                                                    int* iterations) {
  return continuation_detail::arclength_correct<6, CurveEval>(
      [this](const Vector6d& z) { return eval(z); },
      [this](const CurveEval& e) {
        return e.F.cwiseAbs().maxCoeff() <= o_.base.tol && std::abs(e.g) <= o_.condition_tol;
      },
      curve_rows, z_pred, t, o_.base.max_corrections, iterations);
}

Vector6d CurveProblem::tangent(const CurveEval& e, const Vector6d& previous) {
  Matrix6d A;
  Vector6d unused;
  curve_rows(e, A, unused);
  return continuation_detail::arclength_tangent<6>(A, previous);
}

Vector6d CurveProblem::null_vector(const CurveEval& e) {
  const Eigen::FullPivLU<Eigen::Matrix<double, 5, 6>> lu(e.J);
  Eigen::MatrixXd k = lu.kernel();
  Vector6d t = k.col(0);
  return t / t.norm();
}

CurvePoint CurveProblem::point(const Vector6d& z_corrected, const CurveEval& e) {
  Vector6d z = z_corrected;
  z.head<4>() = continuation_detail::polished(z.head<4>(), e.F, e.J.topLeftCorner<4, 4>());
  CurvePoint c;
  c.param = P(z[4]);
  c.param2 = Q(z[5]);
  c.y = Model::to_physical(state(z));
  c.multipliers = floquet_multipliers(e.M);
  c.stable = std::abs(c.multipliers.front()) < 1.0;
  c.residual = std::abs(e.g);
  c.orbit_residual = e.F.cwiseAbs().maxCoeff();
  const auto [p, opt] = at_(c.param, c.param2);
  const OrbitExtent x = orbit_extent(Model(p), opt.integrator, state(z), n_, counters);
  c.contacts = x.contacts;
  c.clearance_min = x.clearance_min;
  if (spec_.kind != CurveKind::grazing) return c;
  if (const Approach* a = tracked(x)) {
    c.phase = a->phase;
    c.approach = a->clearance;
    for (const Approach& b : x.approaches) c.other_contacts += &b != a && b.clearance < 0.0 ? 1 : 0;
  }
  return c;
}

}  // namespace vibromap::curve_detail
