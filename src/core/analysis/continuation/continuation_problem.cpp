// The continuation problem: see continuation_problem.hpp.

#include "continuation_problem.hpp"

#include <cmath>

#include "vibromap/core/analysis/point/shooting.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap::continuation_detail {

Problem::Problem(const PointAt& point_at, double from, double to, const ContinuationOptions& o)
    : point_at_(point_at), from_(from), span_(to - from), o_(o) {
  const auto [p, opt] = point_at_(from);
  const StateScale scale{Model(p)};
  unit_ = Eigen::Array4d(scale.length(), scale.length(), scale.speed(), scale.speed());
}

std::optional<Eval> Problem::eval(const Vector5d& z) {
  Eval e;
  const State y = state(z);
  State image;
  {
    const auto [p, opt] = point_at_(lambda(z[4]));
    if (period_map(Model(p), opt.integrator, y, o_.n, image, e.M, counters) != IntegrationStatus::ok) return std::nullopt;
  }
  const Eigen::Matrix4d D = unit_.matrix().asDiagonal();
  const Eigen::Matrix4d Dinv = unit_.inverse().matrix().asDiagonal();
  e.F = ((image - y).array() / unit_).matrix();
  e.Jy = Dinv * (e.M - Eigen::Matrix4d::Identity()) * D;
  const auto [p2, opt2] = point_at_(lambda(z[4] + kDl));
  const Model m2(p2);
  const auto integ = make_integrator(m2, opt2.integrator);
  State u = y;
  integ->reset(u);
  Observer none;
  for (int i = 0; i < o_.n; ++i)
    if (integ->advance_period(u, none) != IntegrationStatus::ok) return std::nullopt;
  counters += integ->counters();
  e.Jl = ((u - image).array() / unit_).matrix() / kDl;
  return e;
}

namespace {
void branch_rows(const Eval& e, Matrix5d& A, Vector5d& r) {
  A.topLeftCorner<4, 4>() = e.Jy;
  A.topRightCorner<4, 1>() = e.Jl;
  r.head<4>() = e.F;
}
}  // namespace

std::optional<std::pair<Vector5d, Eval>> Problem::correct(const Vector5d& z_pred, const Vector5d& t, int* iterations) {
  return arclength_correct<5, Eval>([this](const Vector5d& z) { return eval(z); },
                                    [this](const Eval& e) { return e.F.cwiseAbs().maxCoeff() <= o_.tol; }, branch_rows,
                                    z_pred, t, o_.max_corrections, iterations);
}

Vector5d Problem::tangent(const Eval& e, const Vector5d& previous) {
  Matrix5d A;
  Vector5d unused;
  branch_rows(e, A, unused);
  return arclength_tangent<5>(A, previous);
}

BranchPoint Problem::point(const Vector5d& z_corrected, const Eval& e) {
  Vector5d z = z_corrected;
  z.head<4>() = polished(z.head<4>(), e.F, e.Jy);
  BranchPoint b;
  b.param = lambda(z[4]);
  b.y = Model::to_physical(state(z));
  b.multipliers = floquet_multipliers(e.M);
  b.stable = std::abs(b.multipliers.front()) < 1.0;
  b.residual = e.F.cwiseAbs().maxCoeff();
  const OrbitExtent x = extent(z);
  b.x1_max = x.x1_max;
  b.x2_max = x.x2_max;
  b.clearance_min = x.clearance_min;
  b.strobe = x.strobe;
  b.contacts = x.contacts;
  b.graze_gap = x.graze_gap;
  return b;
}

OrbitExtent Problem::extent(const Vector5d& z) {
  const auto [p, opt] = point_at_(lambda(z[4]));
  return orbit_extent(Model(p), opt.integrator, state(z), o_.n, counters);
}

}  // namespace vibromap::continuation_detail
