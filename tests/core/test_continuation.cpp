// Tests of periodic-orbit continuation (core/analysis/continuation/continuation.hpp) against closed forms.
//
// Without contact (a clearance larger than any motion) the system is linear: in (x1, w = x2 - D)
//   M q'' + C q' + K q = (lambda F0 cos(omega t + phi0), 0),
// whose periodic response is q(t) = Re(H(omega) f e^(i omega t)), H = (K - omega^2 M + i omega C)^-1,
// f = (lambda F0 e^(i phi0), 0); its Floquet multipliers over T = 2 pi / omega are exp(s_k T),
// s_k the eigenvalues of the first-order system matrix.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include <Eigen/Dense>

#include "vibromap/core/analysis/continuation/continuation.hpp"
#include "vibromap/core/analysis/continuation/orbit_diagram.hpp"
#include "vibromap/core/analysis/continuation/orbit_extent.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"
#include "support/linear_response.hpp"

namespace vibromap {
namespace {

using test::cd;
using test::Linear;

// The points of base with the forcing frequency omega.
PointAt omega_path(const Parameters& base, const PointOptions& options) {
  return [base, options](double omega) {
    Parameters p = base;
    p.omega = omega;
    return std::make_pair(p, options);
  };
}

// y at x on the polyline through (x, y) pairs of increasing x (the last y beyond it).
double interpolate(const std::vector<std::pair<double, double>>& xy, double x) {
  for (std::size_t i = 1; i < xy.size(); ++i)
    if (xy[i].first >= x) {
      const double f = (x - xy[i - 1].first) / (xy[i].first - xy[i - 1].first);
      return xy[i - 1].second + f * (xy[i].second - xy[i - 1].second);
    }
  return xy.back().second;
}

// The extremes of the linear response x1 = Re(Q1 e^(i w t)), x2 = D + Re(Q2 e^(i w t)) over a cycle:
// x1_max = |Q1|, x2_max = D + |Q2|, clearance_min = min(x2 - x1) = D - |Q2 - Q1|. Returns the worst
// error of each of a branch's points, relative to the amplitude |Q1|, |Q2|, |Q2 - Q1|.
Eigen::Vector3d worst_extremes(const Branch& b, const Parameters& base, const Linear& linear) {
  Eigen::Vector3d worst = Eigen::Vector3d::Zero();
  for (const BranchPoint& q : b.points) {
    Parameters p = base;
    p.omega = q.param;
    const Eigen::Vector2cd Q = linear.amplitudes(p);
    const double a1 = std::abs(Q[0]), a2 = std::abs(Q[1]), a12 = std::abs(Q[1] - Q[0]);
    worst = worst.cwiseMax(Eigen::Vector3d(std::abs(q.x1_max - a1) / a1, std::abs(q.x2_max - (p.D + a2)) / a2,
                                           std::abs(q.clearance_min - (p.D - a12)) / a12));
  }
  return worst;
}

// A point's state against the linear response at its omega, relative to the amplitudes of
// displacement and velocity.
double state_error(const BranchPoint& q, const Parameters& p, const Linear& linear) {
  const Eigen::Vector4d ref = linear.orbit(p);
  const double scale_x = std::max(std::abs(ref[0]), std::abs(ref[1] - p.D));
  const double scale_v = std::max(std::abs(ref[2]), std::abs(ref[3]));
  const Eigen::Vector4d err = q.y - ref;
  return std::max({std::abs(err[0]) / scale_x, std::abs(err[1]) / scale_x, std::abs(err[2]) / scale_v,
                   std::abs(err[3]) / scale_v});
}

TEST(Continuation, WithoutContactTheBranchIsTheLinearFrequencyResponse) {
  Parameters base;
  base.D = 10.0;  // m: far beyond the motion (at most ~0.6 m at resonance)
  PointOptions options;
  options.integrator.rtol = 1e-12;
  options.integrator.atol = 1e-15;
  const PointAt at = omega_path(base, options);
  ContinuationOptions o;
  o.tol = 1e-13;
  const Linear linear(base);
  Parameters start = base;
  start.omega = 2.0;
  const Branch b = continue_orbit(at, 2.0, 12.0, start.initial_state(), o);
  ASSERT_GT(b.points.size(), 20u) << b.stop;
  EXPECT_EQ(b.stop, "reached the end of the interval");
  EXPECT_DOUBLE_EQ(b.points.back().param, 12.0);
  EXPECT_TRUE(b.bifurcations.empty());
  double worst = 0.0, worst_mu = 0.0;
  for (const BranchPoint& q : b.points) {
    Parameters p = base;
    p.omega = q.param;
    worst = std::max(worst, state_error(q, p, linear));
    std::vector<cd> mu = linear.multipliers(p.period());
    for (const cd& m : q.multipliers) {
      double nearest = 1e300;
      for (const cd& r : mu) nearest = std::min(nearest, std::abs(m - r) / std::abs(r));
      worst_mu = std::max(worst_mu, nearest);
    }
    EXPECT_TRUE(q.stable);
  }
  EXPECT_LT(worst, 1e-8) << "state, relative to the amplitude";
  EXPECT_LT(worst_mu, 1e-8) << "Floquet multipliers, relative";
  const Eigen::Vector3d extremes = worst_extremes(b, base, linear);
  EXPECT_LT(extremes.maxCoeff(), 1e-8) << "x1_max, x2_max, clearance_min, relative to their amplitudes";
  std::printf("%zu points from omega = 2 to %.3f rad/s; worst relative error: state %.2e, multipliers %.2e, "
              "extremes %.2e\n",
              b.points.size(), b.points.back().param, worst, worst_mu, extremes.maxCoeff());
}

// Issue #31, item 5: at the default tolerances (the corrector stops at a residual of 1e-9,
// which leaves a lightly damped orbit's state up to ~1e-7 of its amplitude off), every reported
// point takes one more Newton step at its own omega: the state and its extremes are then the
// closed form to the integration's accuracy (exact in free flight), not to the corrector's.
TEST(Continuation, AtTheDefaultTolerancesEveryPointIsTheLinearOrbitTo1e8) {
  Parameters base;
  base.D = 10.0;
  const PointOptions options;
  const Linear linear(base);
  Parameters start = base;
  start.omega = 2.0;
  const Branch b = continue_orbit(omega_path(base, options), 2.0, 12.0, start.initial_state(), ContinuationOptions{});
  ASSERT_GT(b.points.size(), 20u) << b.stop;
  EXPECT_EQ(b.stop, "reached the end of the interval");
  double worst = 0.0;
  for (const BranchPoint& q : b.points) {
    Parameters p = base;
    p.omega = q.param;
    worst = std::max(worst, state_error(q, p, linear));
  }
  const Eigen::Vector3d extremes = worst_extremes(b, base, linear);
  EXPECT_LT(worst, 1e-8) << "state, relative to the amplitude";
  EXPECT_LT(extremes.maxCoeff(), 1e-8) << "x1_max, x2_max, clearance_min, relative to their amplitudes";
  std::printf("defaults: %zu points; worst relative error: state %.2e, extremes %.2e\n", b.points.size(), worst,
              extremes.maxCoeff());
}

// Issue #31: the extremes of every point of a branch are located, not sampled: Table 2's system
// without contact (D = 10 m) over omega in [2, 12] rad/s, every point's x1_max, x2_max and
// clearance_min against the closed form. Sampled at 64 points per step and refined only when the
// best sample was inside a step, they were off by up to 1.2e-3 of the amplitude (a maximum next
// to a step's end: 1 - cos(pi / 64)); located as roots of the velocity they are as exact as the
// orbit (state to ~1e-11 here).
TEST(Continuation, WithoutContactTheExtremesOfEveryPointAreTheClosedForm) {
  Parameters base;
  base.m2 = 310.0;
  base.spring2 = {Spring::Form::frequency, 3.606};
  base.E1 = 1.4e10;
  base.E2 = 1.0e6;
  base.D = 10.0;
  PointOptions options;
  options.integrator.rtol = 1e-12;
  options.integrator.atol = 1e-15;
  ContinuationOptions o;
  o.tol = 1e-13;
  const Linear linear(base);
  Parameters start = base;
  start.omega = 2.0;
  const Branch b = continue_orbit(omega_path(base, options), 2.0, 12.0, start.initial_state(), o);
  ASSERT_GT(b.points.size(), 50u) << b.stop;
  EXPECT_EQ(b.stop, "reached the end of the interval");
  EXPECT_EQ(b.points.back().contacts, 0);
  const Eigen::Vector3d worst = worst_extremes(b, base, linear);
  EXPECT_LT(worst[0], 1e-8) << "x1_max, relative to |Q1|";
  EXPECT_LT(worst[1], 1e-8) << "x2_max, relative to |Q2|";
  EXPECT_LT(worst[2], 1e-8) << "clearance_min, relative to |Q2 - Q1|";
  std::printf("%zu points; worst relative error: x1_max %.2e, x2_max %.2e, clearance_min %.2e\n", b.points.size(),
              worst[0], worst[1], worst[2]);
}

// orbit_extent on a transient whose free oscillation is fast: Table 1's system with a stiff
// attached spring (omega2 = 400 rad/s) without contact, from rest at omega = 2 rad/s, over one
// period taken in steps of up to a whole period (max_step = 1): the relative motion rings at
// ~430 rad/s, some 200 oscillations in a step, which 64 samples per step would alias. The
// extremes against the exact solution, X_p(t) + V e^(L t) V^-1 (X(0) - X_p(0)) of the first-order
// system, maximised over 2e5 samples each refined by golden section.
TEST(OrbitExtent, AFastFreeOscillationWithinLongStepsIsResolved) {
  Parameters p;
  p.spring2 = {Spring::Form::frequency, 400.0};
  p.D = 10.0;
  p.omega = 2.0;
  const Linear linear(p);
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  A.topRightCorner<2, 2>() = Eigen::Matrix2d::Identity();
  A.bottomLeftCorner<2, 2>() = -linear.M.inverse() * linear.K;
  A.bottomRightCorner<2, 2>() = -linear.M.inverse() * linear.C;
  const Eigen::Vector2cd Q = linear.amplitudes(p);
  const Eigen::Vector4cd P(Q[0], Q[1], cd(0, p.omega) * Q[0], cd(0, p.omega) * Q[1]);  // X_p = Re(P e^(i w t))
  const Eigen::EigenSolver<Eigen::Matrix4d> es(A);
  const Eigen::Vector4cd c = es.eigenvectors().lu().solve((Eigen::Vector4d::Zero() - P.real()).cast<cd>());
  const auto X = [&](double t) -> Eigen::Vector3d {  // (x1, x2, x1 - x2)
    Eigen::Vector4cd e = es.eigenvectors() * (es.eigenvalues().array() * t).exp().matrix().cwiseProduct(c);
    const Eigen::Vector4d x = (P * std::exp(cd(0, p.omega * t))).real() + e.real();
    return {x[0], x[1] + p.D, x[0] - x[1] - p.D};
  };
  const double T = p.period();
  const int n = 200000;
  Eigen::Vector3d best = Eigen::Vector3d::Constant(-1e300);
  std::vector<Eigen::Vector3d> v(n + 1);
  for (int i = 0; i <= n; ++i) v[static_cast<std::size_t>(i)] = X(T * i / n);
  for (int k = 0; k < 3; ++k)
    for (int i = 1; i < n; ++i) {
      const auto at = [&](int j) { return v[static_cast<std::size_t>(j)][k]; };
      best[k] = std::max({best[k], at(0), at(n)});
      if (!(at(i) >= at(i - 1) && at(i) >= at(i + 1))) continue;
      double a = T * (i - 1) / n, b = T * (i + 1) / n;  // golden section on the bracket
      for (int it = 0; it < 80; ++it) {
        const double m1 = b - 0.618033988749895 * (b - a), m2 = a + 0.618033988749895 * (b - a);
        (X(m1)[k] >= X(m2)[k] ? b : a) = X(m1)[k] >= X(m2)[k] ? m2 : m1;
      }
      best[k] = std::max(best[k], X(0.5 * (a + b))[k]);
    }
  IntegratorOptions io;
  io.max_step = 1.0;
  IntegrationCounters counters;
  const OrbitExtent e = orbit_extent(Model(p), io, Model::to_internal(p.initial_state()), 1, counters);
  ASSERT_TRUE(e.ok);
  const double ring = best[2] - (-p.D);  // the amplitude of x1 - x2 about its rest value
  EXPECT_NEAR(e.x1_max, best[0], 1e-8 * std::abs(best[0]));
  EXPECT_NEAR(e.x2_max, best[1], 1e-8 * std::abs(best[1] - p.D));
  EXPECT_NEAR(e.clearance_min, -best[2], 1e-8 * ring);
  std::printf("x1_max %.12e (exact %.12e), clearance_min %.12e (exact %.12e)\n", e.x1_max, best[0],
              e.clearance_min, -best[2]);
}

TEST(Continuation, BadOptionsAndAStartWithoutOrbitAreSaid) {
  ContinuationOptions o;
  o.ds = 2.0;
  const PointAt at = [](double) { return std::make_pair(Parameters{}, PointOptions{}); };
  EXPECT_EQ(continue_orbit(at, 2.0, 3.0, Parameters{}.initial_state(), o).stop,
            "steps must satisfy 0 < ds_min <= ds <= ds_max <= 1");
  EXPECT_EQ(continue_orbit(at, 2.0, 2.0, Parameters{}.initial_state(), ContinuationOptions{}).stop,
            "the interval is empty (from = to)");
}

// Table 2 (m2 310 kg, omega2 3.606 rad/s, E1 1.4e10 Pa, E2 1e6 Pa): the soft (1,1) orbit followed
// up in omega from 7.23 rad/s turns back at a fold. The orbit diagram swept up with a step of
// 0.02 rad/s follows the branch (to 1e-3 m) at every step below the fold and has left it at the
// first step above: the fold brackets the up-sweep's jump within one diagram step. Likewise the
// second fold, where the branch turns up again, and the sweep down along its lower part.
TEST(Continuation, TheFoldsBracketTheJumpsOfTheUpAndDownSweeps) {
  Parameters base;
  base.m2 = 310.0;
  base.spring2 = {Spring::Form::frequency, 3.606};
  base.E1 = 1.4e10;
  base.E2 = 1.0e6;
  const PointOptions options;
  const PointAt at = omega_path(base, options);
  Parameters start = base;
  start.omega = 7.23;
  const PointSummary s = solve_point(start, options);
  ASSERT_EQ(s.regime.label(), "(1,1)");
  ContinuationOptions o;
  o.max_points = 3000;
  const Branch b = continue_orbit(at, 7.23, 8.6, s.final_state, o);
  ASSERT_FALSE(b.bifurcations.empty()) << b.stop;
  const Bifurcation& fold = b.bifurcations.front();
  ASSERT_EQ(fold.type, BifurcationType::fold);
  // The multiplier through +1 at the fold.
  double nearest_one = 1e300;
  for (const auto& mu : fold.at.multipliers) nearest_one = std::min(nearest_one, std::abs(mu - 1.0));
  EXPECT_LT(nearest_one, 1e-4);
  // x1 at period starts along the stable part, below the fold (param increasing there).
  std::vector<std::pair<double, double>> stable;
  for (const BranchPoint& q : b.points) {
    if (q.param > fold.at.param || (!stable.empty() && q.param < stable.back().first)) break;
    stable.emplace_back(q.param, q.y[0]);
  }
  const auto branch_x1 = [&](double w) { return interpolate(stable, w); };
  // The sweep starts on the branch: at its first point at or above 7.9 rad/s, from its state.
  const auto on = std::find_if(b.points.begin(), b.points.end(), [](const BranchPoint& q) { return q.param >= 7.9; });
  ASSERT_NE(on, b.points.end());
  std::vector<std::pair<Parameters, PointOptions>> path;
  std::vector<double> omegas;
  for (double w = on->param; w <= 8.5 + 1e-9; w += 0.02) {
    omegas.push_back(w);
    path.push_back(at(w));
  }
  OrbitDiagramOptions d;
  d.transient = 600;
  d.keep = 2;
  const auto steps = orbit_diagram(path, on->y, d);
  std::size_t above = 0;
  while (above < omegas.size() && omegas[above] < fold.at.param) ++above;
  ASSERT_GT(above, 1u);
  ASSERT_LT(above, omegas.size());
  for (std::size_t k = 0; k < above; ++k)
    EXPECT_NEAR(steps[k].strobe.back()[0], branch_x1(omegas[k]), 1e-3) << "omega " << omegas[k];
  EXPECT_GT(std::abs(steps[above].strobe.back()[0] - fold.at.y[0]), 1e-2) << "omega " << omegas[above];
  std::printf("fold at omega = %.9f rad/s; the up-sweep follows the branch at %.2f and has left it at %.2f\n",
              fold.at.param, omegas[above - 1], omegas[above]);

  // The down-sweep: the branch turns back at a second fold below the first, and its lower part
  // (after that fold, the key increasing again) is the motion a sweep down from 8.5 rad/s
  // follows; the sweep leaves it within one step of that fold.
  const auto second = std::find_if(b.bifurcations.begin() + 1, b.bifurcations.end(),
                                   [](const Bifurcation& x) { return x.type == BifurcationType::fold; });
  ASSERT_NE(second, b.bifurcations.end()) << b.stop;
  ASSERT_LT(second->at.param, fold.at.param - 0.3);
  // The points after the second fold: from where the key, having decreased, increases again.
  auto turn = b.points.begin();
  while (turn + 1 != b.points.end() && (turn + 1)->param >= turn->param) ++turn;  // up to the first fold
  while (turn + 1 != b.points.end() && (turn + 1)->param <= turn->param) ++turn;  // down to the second
  std::vector<std::pair<double, double>> lower;
  for (auto q = turn; q != b.points.end(); ++q)
    if (lower.empty() || q->param > lower.back().first) lower.emplace_back(q->param, q->y[0]);
  EXPECT_NEAR(turn->param, second->at.param, 0.01);
  ASSERT_GT(lower.size(), 10u);
  ASSERT_GT(lower.back().first, 8.5);
  const auto lower_x1 = [&](double w) { return interpolate(lower, w); };
  const auto top = std::find_if(b.points.rbegin(), b.points.rend(), [](const BranchPoint& q) { return q.param <= 8.5; });
  ASSERT_NE(top, b.points.rend());
  std::vector<std::pair<Parameters, PointOptions>> down;
  std::vector<double> down_omegas;
  for (double w = top->param; w >= 7.3 - 1e-9; w -= 0.02) {
    down_omegas.push_back(w);
    down.push_back(at(w));
  }
  const auto down_steps = orbit_diagram(down, top->y, d);
  std::size_t left = 0;
  while (left < down_omegas.size() && down_omegas[left] >= second->at.param &&
         std::abs(down_steps[left].strobe.back()[0] - lower_x1(down_omegas[left])) <= 1e-3)
    ++left;
  ASSERT_GT(left, 5u);
  ASSERT_LT(left, down_omegas.size());
  // On the lower branch down to its fold, off it within one step of the fold.
  EXPECT_LE(down_omegas[left], second->at.param + 0.02 + 1e-9) << "the down-sweep leaves the branch early";
  EXPECT_GE(down_omegas[left], second->at.param - 0.02 - 1e-9);
  std::printf("second fold at omega = %.9f rad/s; the down-sweep follows the lower branch down to %.2f and has left "
              "it at %.2f\n",
              second->at.param, down_omegas[left - 1], down_omegas[left]);
}

// Grazing: Table 1's system (D = 0.05 m) followed up in omega from 2 rad/s, where its motion is
// the contact-free linear response, reaches contact where the closed-form relative amplitude
// |Q2 - Q1| equals D (its closest approach D - |Q2 - Q1| crosses zero). The continuation locates
// that omega to 1e-6 relative against the closed form's own root (bisection to 1e-14), and goes on
// across it with one contact per cycle.
TEST(Continuation, GrazingIsLocatedWhereTheClosedFormApproachReachesContact) {
  const Parameters base;  // Table 1
  const Linear linear(base);
  const auto approach = [&](double w) {
    Parameters p = base;
    p.omega = w;
    const Eigen::Vector4d q = linear.orbit(p);
    // x2 - x1 = D + Re((Q2 - Q1) e^(i w t)): its least value is D - |Q2 - Q1|.
    const double re = (q[1] - p.D) - q[0], im = (q[3] - q[2]) / w;
    return p.D - std::hypot(re, im);
  };
  double lo = 2.0, hi = 6.2;
  ASSERT_GT(approach(lo), 0.0);
  ASSERT_LT(approach(hi), 0.0);
  while (hi - lo > 1e-14 * hi) {
    const double mid = 0.5 * (lo + hi);
    (approach(mid) > 0.0 ? lo : hi) = mid;
  }
  const double reference = 0.5 * (lo + hi);
  PointOptions options;
  const PointAt at = omega_path(base, options);
  Parameters start = base;
  start.omega = 2.0;
  const Branch b = continue_orbit(at, 2.0, 6.2, linear.orbit(start), ContinuationOptions{});
  const auto grazing = std::find_if(b.bifurcations.begin(), b.bifurcations.end(),
                                    [](const Bifurcation& x) { return x.type == BifurcationType::grazing; });
  ASSERT_NE(grazing, b.bifurcations.end()) << b.stop;
  EXPECT_NEAR(grazing->at.param, reference, 1e-6 * reference);
  EXPECT_NEAR(grazing->at.clearance_min, 0.0, 1e-6 * base.D);
  // The branch goes on across the grazing with one impact per cycle, to the end of the interval.
  EXPECT_EQ(b.stop, "reached the end of the interval");
  const auto beyond = std::find_if(b.points.begin(), b.points.end(),
                                   [&](const BranchPoint& q) { return q.param > grazing->at.param + 0.01; });
  ASSERT_NE(beyond, b.points.end());
  EXPECT_EQ(beyond->contacts, 1);
  EXPECT_LT(beyond->clearance_min, 0.0);
  EXPECT_EQ(b.points.front().contacts, 0);
  std::printf("grazing at omega = %.10f rad/s (closed form %.10f, relative %.1e); clearance there %.2e m; "
              "the branch then: %zu points, %s\n",
              grazing->at.param, reference, std::abs(grazing->at.param - reference) / reference,
              grazing->at.clearance_min, b.points.size(), b.stop.c_str());
}

// Period doubling and the switch onto the doubled branch: Table 1's (1,1) orbit followed down in
// omega from 7.23 rad/s loses stability at a period doubling near 6.46 rad/s. The orbit diagram
// swept down in steps of 0.01 rad/s (3000 transient periods) has one stroboscopic x1 above it and
// two below: the period doubling lies within the step where the points split. The branch
// switched onto there, corrected at the diagram's points below the doubling (Newton at the
// parameter fixed, from the branch's nearest point), is the 2T orbit the diagram shows: its two
// stroboscopic x1 equal the diagram's two values to 1e-6 m, and it is stable.
TEST(Continuation, PeriodDoublingSwitchesOntoTheTwoPeriodOrbitOfTheDiagram) {
  const Parameters base;  // Table 1
  const PointOptions options;
  const PointAt at = omega_path(base, options);
  Parameters start = base;
  const PointSummary s = solve_point(start, options);
  ASSERT_EQ(s.regime.label(), "(1,1)");
  ContinuationOptions o;
  o.pd_depth = 1;
  o.max_points = 2000;
  const std::vector<Branch> branches = continue_branches(at, 7.23, 6.3, s.final_state, o);
  ASSERT_GE(branches.size(), 2u) << branches.front().stop;
  const auto pd = std::find_if(branches[0].bifurcations.begin(), branches[0].bifurcations.end(),
                               [](const Bifurcation& x) { return x.type == BifurcationType::period_doubling; });
  ASSERT_NE(pd, branches[0].bifurcations.end());
  double nearest_minus_one = 1e300;
  for (const auto& mu : pd->at.multipliers) nearest_minus_one = std::min(nearest_minus_one, std::abs(mu + 1.0));
  EXPECT_LT(nearest_minus_one, 1e-4);
  const Branch& doubled = branches[1];
  EXPECT_EQ(doubled.n, 2);
  EXPECT_EQ(doubled.parent, 0);
  ASSERT_GE(doubled.points.size(), 3u) << doubled.stop;
  EXPECT_NEAR(doubled.points.front().param, pd->at.param, 1e-12);

  // The orbit diagram down from 6.52 rad/s, starting on the period-1 orbit there.
  std::vector<std::pair<Parameters, PointOptions>> path;
  std::vector<double> omegas;
  for (int k = 0; k <= 10; ++k) {
    omegas.push_back(6.52 - 0.01 * k);
    path.push_back(at(omegas.back()));
  }
  OrbitDiagramOptions d;
  d.transient = 3000;
  d.keep = 8;
  const auto steps = orbit_diagram(path, branches[0].points.front().y, d);
  const auto spread = [&](std::size_t k) {
    double lo = 1e300, hi = -1e300;
    for (const auto& x : steps[k].strobe) lo = std::min(lo, x[0]), hi = std::max(hi, x[0]);
    return hi - lo;
  };
  std::size_t split = 0;
  while (split < steps.size() && spread(split) < 1e-4) ++split;
  ASSERT_GT(split, 0u);
  ASSERT_LT(split + 1, steps.size());
  EXPECT_LT(spread(split - 1), 1e-6) << "omega " << omegas[split - 1] << ": the period-1 orbit";
  EXPECT_LE(omegas[split], pd->at.param);
  EXPECT_GE(omegas[split - 1], pd->at.param);
  // The doubled branch at the two diagram points below the split.
  for (std::size_t k : {split, split + 1}) {
    const double w = omegas[k];
    const auto near = std::min_element(doubled.points.begin(), doubled.points.end(), [&](const auto& a, const auto& b) {
      return std::abs(a.param - w) < std::abs(b.param - w);
    });
    ASSERT_LT(std::abs(near->param - w), 0.01) << "the doubled branch does not reach omega " << w;
    const auto [p, po] = at(w);
    const Model model(p);
    ShootingOptions so;
    so.n = 2;
    IntegrationCounters counters;
    const ShootingResult sh = shoot(model, po.integrator, Model::to_internal(near->y), so, counters);
    ASSERT_TRUE(sh.converged) << sh.message;
    EXPECT_TRUE(sh.stable()) << "omega " << w;
    const OrbitExtent x = orbit_extent(model, po.integrator, sh.y, 2, counters);
    ASSERT_EQ(x.strobe.size(), 2u);
    std::vector<double> branch_x1{x.strobe[0][0], x.strobe[1][0]}, diagram_x1{steps[k].strobe[0][0], steps[k].strobe[1][0]};
    std::sort(branch_x1.begin(), branch_x1.end());
    std::sort(diagram_x1.begin(), diagram_x1.end());
    EXPECT_GT(branch_x1[1] - branch_x1[0], 1e-4);
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(branch_x1[i], diagram_x1[i], 1e-6) << "omega " << w;
    std::printf("omega %.2f: doubled branch x1 = %.7f, %.7f; diagram %.7f, %.7f\n", w, branch_x1[0], branch_x1[1],
                diagram_x1[0], diagram_x1[1]);
  }
  std::printf("period doubling at omega = %.9f rad/s (a multiplier %.1e from -1); the diagram splits between %.2f and "
              "%.2f; doubled branch: %zu points, %s\n",
              pd->at.param, nearest_minus_one, omegas[split - 1], omegas[split], doubled.points.size(), doubled.stop.c_str());
}

}  // namespace
}  // namespace vibromap
