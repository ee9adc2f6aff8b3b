#include "vibromap/core/analysis/point/shooting.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace vibromap {

StateScale::StateScale(const Model& model) {
  length_ = motion_length(model.parameters());
  speed_ = motion_speed(model.parameters());
}

int least_period(const Model& model, const IntegratorOptions& integration, const State& y, int n, double tol,
                 IntegrationCounters& counters) {
  const StateScale scale(model);
  for (int d = 1; d < n; ++d) {
    if (n % d != 0) continue;
    const auto integ = make_integrator(model, integration);
    State u = y;
    integ->reset(u);
    Observer none;
    bool ok = true;
    for (int i = 0; i < d && ok; ++i) ok = integ->advance_period(u, none) == IntegrationStatus::ok;
    counters += integ->counters();
    if (ok && scale.distance(u, y) <= tol) return d;
  }
  return n;
}

double StateScale::distance(const State& a, const State& b) const {
  double d = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double base = i < 2 ? length_ : speed_;
    d = std::max(d, std::abs(a[i] - b[i]) / (base + std::max(std::abs(a[i]), std::abs(b[i]))));
  }
  return d;
}

State extrapolate_fixed_point(const std::vector<State>& iterates, const StateScale& scale) {
  const std::size_t k = iterates.size();
  if (k < 3) return iterates.empty() ? State::Zero() : iterates.back();
  const Eigen::Array4d unit = scale.unit();
  Eigen::MatrixXd U(4, static_cast<Eigen::Index>(k - 1));  // scaled differences
  for (std::size_t j = 0; j + 1 < k; ++j)
    U.col(static_cast<Eigen::Index>(j)) = ((iterates[j + 1] - iterates[j]).array() / unit).matrix();
  // min |U g| with sum g = 1: g = G^{-1} 1 / (1' G^{-1} 1), G = U'U (+ a tiny ridge, since
  // with more iterates than dimensions G is singular).
  Eigen::MatrixXd G = U.transpose() * U;
  G.diagonal().array() += 1e-14 * (G.trace() + 1e-300);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(G.rows());
  const Eigen::VectorXd w = G.ldlt().solve(ones);
  const double total = w.sum();
  if (!std::isfinite(total) || total == 0.0) return iterates.back();
  State x = State::Zero();
  for (std::size_t j = 0; j + 1 < k; ++j) x += (w[static_cast<Eigen::Index>(j)] / total) * iterates[j];
  return x.allFinite() ? x : iterates.back();
}

namespace {

constexpr int kMaxHalvings = 4;
// Give up early when, after kStallEvaluations map evaluations, the best residual is still
// above kStallFactor times the first: Newton is outside its basin.
constexpr int kStallEvaluations = 8;
constexpr double kStallFactor = 0.1;

// Inexact Newton: far from the orbit the map need not be integrated to the final
// tolerance. After a residual r Newton's next residual is ~r^2, so an evaluation uses
// rtol = kInexactFactor * r^2 (its error stays below what the next step can reach), no
// looser than kLoosestRtol (the contact must stay resolved) and no tighter than the
// requested rtol. A residual within tol is only accepted from an evaluation at the
// requested rtol, and residuals are only compared between evaluations at one rtol.
constexpr double kInexactFactor = 1e-2;
constexpr double kLoosestRtol = 1e-4;

IntegratorOptions evaluation_options(const IntegratorOptions& integration, double last_residual) {
  IntegratorOptions o = integration;
  o.rtol = std::clamp(kInexactFactor * last_residual * last_residual, integration.rtol,
                      std::max(kLoosestRtol, integration.rtol));
  return o;
}

// P^n(y) and its Jacobian with a fresh variational integrator (so no step-size history
// carries over between Newton iterates).
IntegrationStatus map_n(const Model& model, const IntegratorOptions& opt, const State& y, int n, State& out,
                        Eigen::Matrix4d& jac, IntegrationCounters& counters) {
  auto integ = make_variational_integrator(model, opt);
  out = y;
  integ->reset(out);
  integ->reset_jacobian();
  Observer none;
  IntegrationStatus status = IntegrationStatus::ok;
  for (int i = 0; i < n && status == IntegrationStatus::ok; ++i) status = integ->advance_period(out, none);
  counters += integ->counters();
  jac = integ->jacobian();
  if (status == IntegrationStatus::ok && !(out.allFinite() && jac.allFinite())) status = IntegrationStatus::non_finite;
  return status;
}

std::vector<std::complex<double>> eigenvalues_by_size(const Eigen::Matrix4d& m) {
  const Eigen::EigenSolver<Eigen::Matrix4d> es(m, false);
  std::vector<std::complex<double>> mu(es.eigenvalues().data(), es.eigenvalues().data() + 4);
  std::sort(mu.begin(), mu.end(), [](auto a, auto b) { return std::abs(a) > std::abs(b); });
  return mu;
}

// At convergence the Newton step from the last evaluation is still worth taking: its
// linear model is exact to O(residual^2), so it brings the orbit point from within tol to
// the integration's own accuracy (the quantities measured on the orbit follow) at no
// integration cost. The residual reported stays the one measured.
void polish(ShootingResult& r, const State& image) {
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(r.monodromy - Eigen::Matrix4d::Identity());
  if (!lu.isInvertible()) return;
  const State dy = lu.solve(r.y - image);
  if (dy.allFinite()) r.y += dy;
}

}  // namespace

ShootingResult shoot(const Model& model, const IntegratorOptions& integration, const State& y0,
                     const ShootingOptions& options, IntegrationCounters& counters, const KnownOrbit& known) {
  const StateScale scale(model);
  ShootingResult r;
  r.y = y0;
  State image;
  // Backtracking: when a Newton step raises the residual, retry half of it from the previous
  // iterate (Armijo-style damping without the slope test), at most kMaxHalvings times.
  State y_prev = y0, step_prev = State::Zero();
  double res_prev = std::numeric_limits<double>::infinity();
  double first_residual = 0.0, best_residual = std::numeric_limits<double>::infinity();
  int halvings = 0;
  double last_residual = std::numeric_limits<double>::infinity(), rtol_prev = 0.0;
  const long steps_before = counters.steps + counters.rejected;
  for (int evaluations = 0; evaluations <= options.max_iterations; ++evaluations) {
    if (known && known(r.y)) {
      r.known = true;
      r.message = "at an orbit already found";
      return r;
    }
    IntegratorOptions evaluation = evaluation_options(integration, last_residual);
    // integration.max_steps budgets all the evaluations together.
    evaluation.max_steps = integration.max_steps - (counters.steps + counters.rejected - steps_before);
    if (evaluation.max_steps < 1) {
      r.message = "step budget (solver.max_steps) exhausted during Newton";
      return r;
    }
    const IntegrationStatus status = map_n(model, evaluation, r.y, options.n, image, r.monodromy, counters);
    if (status != IntegrationStatus::ok) {
      r.message = "integration failed during Newton: " + to_string(status);
      return r;
    }
    r.residual = scale.distance(image, r.y);
    r.iterations = evaluations;
    if (evaluations == 0) first_residual = r.residual;
    best_residual = std::min(best_residual, r.residual);
    last_residual = r.residual;
    if (r.residual <= options.tol && evaluation.rtol <= integration.rtol) {
      r.converged = true;
      r.multipliers = eigenvalues_by_size(r.monodromy);
      polish(r, image);
      return r;
    }
    if (evaluations >= kStallEvaluations && best_residual > kStallFactor * first_residual) {
      r.message = "Newton is not converging (residual " + std::to_string(best_residual) + " after " +
                  std::to_string(evaluations) + " evaluations)";
      return r;
    }
    if (evaluation.rtol != rtol_prev) res_prev = std::numeric_limits<double>::infinity();
    rtol_prev = evaluation.rtol;
    if (r.residual > res_prev && halvings < kMaxHalvings) {
      ++halvings;
      step_prev *= 0.5;
      r.y = y_prev + step_prev;
      continue;
    }
    halvings = 0;
    const Eigen::FullPivLU<Eigen::Matrix4d> lu(r.monodromy - Eigen::Matrix4d::Identity());
    if (!lu.isInvertible()) {
      r.message = "singular Newton matrix (a Floquet multiplier at 1)";
      return r;
    }
    State dy = lu.solve(r.y - image);
    // Limit the step: a Newton step longer than the motion's scale leaves the basin.
    const double length = scale.size(dy);
    if (length > options.max_step) dy *= options.max_step / length;
    y_prev = r.y;
    res_prev = r.residual;
    step_prev = dy;
    r.y += dy;
  }
  r.message = "Newton did not converge in " + std::to_string(options.max_iterations) + " evaluations (residual " +
              std::to_string(r.residual) + ")";
  return r;
}

IntegrationStatus period_map(const Model& model, const IntegratorOptions& integration, const State& y, int n,
                             State& image, Eigen::Matrix4d& jac, IntegrationCounters& counters) {
  return map_n(model, integration, y, n, image, jac, counters);
}

std::vector<std::complex<double>> floquet_multipliers(const Eigen::Matrix4d& monodromy) {
  return eigenvalues_by_size(monodromy);
}

}  // namespace vibromap
