// A motion that never reaches contact, decided in closed form (issue 42): FreeFlight::never_enters
// is a bound the exact motion never breaks (checked against the largest z of the independent
// closed form, test::LinearOscillator, over many periods), and where solve_point takes it the
// answer is brute force's: the (1,0) no-contact orbit, its Floquet multipliers, its point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "problems/linear_oscillator.hpp"
#include "support/paper_points.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/integrate/free_flight.hpp"

using namespace vibromap;

namespace {

// Table 2's system, its clearance D (m) and its force amplitude F0 (N) given, from rest.
Parameters table2(double D, double F0) {
  Parameters p = test::table2();
  p.D = D;
  p.F0 = F0;
  return p;
}

// The largest z of the exact motion from u0 over [0, t1]: a dense scan (the motion's fastest
// oscillation is sampled about 60 times a cycle) refined by golden section around the best sample.
double max_z(const test::LinearOscillator& ref, const State& u0, double t1) {
  const int samples = 20000;
  auto z = [&](double t) { return ref.solution(u0, t)[1]; };
  double best_t = 0.0, best = z(0.0);
  for (int i = 1; i <= samples; ++i) {
    const double t = t1 * i / samples;
    if (const double zi = z(t); zi > best) best = zi, best_t = t;
  }
  double a = std::max(0.0, best_t - t1 / samples), b = std::min(t1, best_t + t1 / samples);
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int i = 0; i < 80; ++i) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    (z(c) > z(d) ? b : a) = (z(c) > z(d) ? d : c);
  }
  return std::max(best, z(0.5 * (a + b)));
}

}  // namespace

TEST(NoContact, NeverEntersOnlyWhereTheExactMotionStaysClear) {
  // Forced motion (F0 = 500 N) from initial states of growing size, at clearances from one that
  // the motion crosses to one it stays far from; 40 periods of the slowest decay cover the
  // transient's largest excursions.
  int certified = 0, refused_but_clear = 0;
  for (const double D : {0.01, 0.05, 0.15, 0.2, 0.3, 1.0}) {
    for (const double kick : {0.0, 0.3, 1.0, 3.0}) {
      Parameters p = table2(D, 500.0);
      p.initial = Eigen::Vector4d(0.01 * kick, D, -0.05 * kick, 0.1 * kick);
      const Model model(p);
      const FreeFlight flight(model);
      ASSERT_TRUE(flight.valid());
      const State u0 = Model::to_internal(p.initial_state());
      const double zmax = max_z(test::LinearOscillator(model), u0, 40.0 * model.period());
      if (flight.never_enters(0.0, u0)) {
        ++certified;
        EXPECT_LT(zmax, 0.0) << "D " << D << ", kick " << kick << ": certified clear, but z reaches " << zmax;
      } else if (zmax < 0.0) {
        ++refused_but_clear;  // a bound: it may leave a clear motion to the integrator
      }
      if (zmax >= 0.0) {
        EXPECT_FALSE(flight.never_enters(0.0, u0)) << "D " << D << ", kick " << kick;
      }
    }
  }
  // Not vacuous: of the 14 clear motions the bound certifies 10 (it leaves the 4 that pass within
  // 5 cm, a third of the motion's size, to the integrator); the other 10 motions reach contact.
  EXPECT_GE(certified, 10);
  EXPECT_LE(refused_but_clear, 4);
}

TEST(NoContact, TheClosedFormCellIsBruteForcesAnswer) {
  // At rest without forcing (a sweep's trivial cell), and forced far from contact.
  for (const auto& [D, F0] : {std::pair{0.05, 0.0}, std::pair{1.0, 500.0}}) {
    const Parameters p = table2(D, F0);
    const PointSummary closed = solve_point(p, PointOptions{});
    PointOptions brute_options;
    brute_options.analysis.steady = SteadyMethod::integrate;
    const PointSummary brute = solve_point(p, brute_options);
    const std::string what = "D " + std::to_string(D) + ", F0 " + std::to_string(F0);
    ASSERT_EQ(closed.status, SolveStatus::ok) << what;
    ASSERT_EQ(brute.status, SolveStatus::ok) << what;
    EXPECT_EQ(closed.periods, 0) << what << ": the closed form integrates nothing";
    EXPECT_GE(brute.periods, 2) << what;
    EXPECT_EQ(closed.regime.kind, RegimeKind::no_contact) << what;
    EXPECT_EQ(brute.regime.kind, RegimeKind::no_contact) << what;
    EXPECT_EQ(closed.regime.n, 1);
    EXPECT_EQ(brute.regime.n, 1);
    EXPECT_EQ(closed.regime.k, 0);
    EXPECT_EQ(closed.stable, 1);
    EXPECT_EQ(brute.stable, 1);
    EXPECT_FALSE(closed.soft);
    EXPECT_EQ(closed.T_con, 0.0);
    EXPECT_EQ(closed.k_con, 0.0);
    EXPECT_LT(closed.steady_residual, 1e-12) << what;
    // The orbit's point at the period start: the exact particular solution.
    const Model model(p);
    const Eigen::Vector4d exact = Model::to_physical(test::LinearOscillator(model).particular(0.0));
    const double scale = 1e-3 + exact.cwiseAbs().maxCoeff();
    EXPECT_LT((closed.final_state - exact).cwiseAbs().maxCoeff(), 1e-12 * scale) << what;
    EXPECT_LT((brute.final_state - exact).cwiseAbs().maxCoeff(), 1e-6 * scale) << what;
    // Floquet multipliers: e^{lambda_j T}, against the eigenvalues of the exact e^{A T} and brute
    // force's Newton monodromy.
    const Eigen::Matrix4d M = (test::LinearOscillator(model).matrix() * model.period()).exp();
    const Eigen::EigenSolver<Eigen::Matrix4d> es(M, false);
    ASSERT_EQ(closed.floquet.size(), 4u);
    ASSERT_EQ(brute.floquet.size(), 4u);
    for (std::size_t j = 0; j < 4; ++j) {
      double nearest = 1.0;
      for (int i = 0; i < 4; ++i) nearest = std::min(nearest, std::abs(closed.floquet[j] - es.eigenvalues()[i]));
      EXPECT_LT(nearest, 1e-12) << what << ", multiplier " << j;
      EXPECT_LT(std::abs(closed.floquet[j] - brute.floquet[j]), 1e-8) << what << ", multiplier " << j;
    }
  }
}

TEST(NoContact, AMotionThatReachesContactIsFollowedAsBefore) {
  // Table 2 itself: the motion from rest impacts, so nothing is decided in closed form.
  const PointSummary s = solve_point(table2(0.05, 500.0), PointOptions{});
  EXPECT_GT(s.periods, 0);
  EXPECT_EQ(s.regime.kind, RegimeKind::periodic);
  EXPECT_GT(s.k_con, 0.0);
}
