// The steady-state detector (steady_state.hpp) on synthetic stroboscopic sequences whose period is
// known: exact cycles of period 1, 2, 3 and 5, cycles approached geometrically, a quasi-periodic
// rotation and a chaotic (logistic map) sequence that never repeat.
//
// Scale (StateScale): for Table 1, L = max(D, lambda F0 / k1) = max(0.05, 500 / (1000 6.283^2))
// = 0.05 m and the speed unit omega L; a difference dx between positions near x counts as
// dx / (L + |x|). The sequences below move positions by centimetres (scaled ~0.1), far above tol.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "vibromap/core/analysis/point/steady_state.hpp"

using namespace vibromap;

namespace {

constexpr double kTol = 1e-6;  // the detector's tolerance on the scaled distance
constexpr int kNMax = 8;

// The j-th point of a cycle of period n: distinct, centimetres apart.
State cycle_point(int j, int n) {
  const double a = 2.0 * std::numbers::pi * (j % n) / n;
  return {0.02 * std::cos(a), -0.05 + 0.01 * std::sin(a), 0.1 * std::sin(a), 0.05 * std::cos(a)};
}

struct Fed {
  long stopped_at = -1;  // the period at whose end on_period_end said stop, -1 if never
};

// Feeds `count` samples y(j) to the detector, stopping when it asks to.
template <class Sequence>
Fed feed(SteadyStateDetector& d, long count, Sequence y) {
  for (long j = 0; j < count; ++j)
    if (d.on_period_end(j, y(j))) return {j};
  return {};
}

}  // namespace

TEST(SteadyState, ExactCyclesAreFoundWithTheirPeriodAfterTwoCycles) {
  const Model model{Parameters{}};
  for (int n : {1, 2, 3, 5}) {
    SteadyStateDetector d(model, kNMax, kTol);
    const Fed fed = feed(d, 100, [n](long j) { return cycle_point(static_cast<int>(j), n); });
    // The whole cycle must repeat: samples 0 .. 2n-1 are the first that show it.
    EXPECT_EQ(fed.stopped_at, 2 * n - 1) << "n = " << n;
    EXPECT_EQ(d.period_n(), n);
    EXPECT_EQ(d.detected_at(), 2 * n - 1);
    EXPECT_EQ(d.residual(), 0.0);
  }
}

TEST(SteadyState, ACycleLongerThanNMaxIsNotFound) {
  const Model model{Parameters{}};
  SteadyStateDetector d(model, 4, kTol);
  const Fed fed = feed(d, 100, [](long j) { return cycle_point(static_cast<int>(j), 5); });
  EXPECT_EQ(fed.stopped_at, -1);
  EXPECT_EQ(d.period_n(), 0);
  EXPECT_EQ(d.detected_at(), -1);
}

TEST(SteadyState, CandidatePeriodsOfACycleStartWithItsPeriod) {
  const Model model{Parameters{}};
  SteadyStateDetector d(model, kNMax, kTol);
  // Samples 0..4 of a 3-cycle: one short of detection (which needs samples 0..5).
  for (long j = 0; j < 5; ++j) ASSERT_FALSE(d.on_period_end(j, cycle_point(static_cast<int>(j), 3)));
  // ||y_4 - y_{4-n}|| is 0 for n = 3 and large otherwise (n = 6 needs 7 samples).
  const std::vector<int> c = d.candidate_periods(2);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0], 3);
}

// y_j = c_j + r^j e: a cycle of period n approached geometrically. The gap ||y_i - y_{i-n}|| is
// r^(i-n) (1 - r^n) |e| (scaled), largest at the oldest of the last n samples, i = J - n + 1 for
// the newest index J: detection at the first J with r^(J - 2n + 1) (1 - r^n) s <= tol, s the
// scaled size of e.
TEST(SteadyState, GeometricApproachIsDetectedWhenTheLastCycleIsWithinTol) {
  const Model model{Parameters{}};
  const double r = 0.5;
  // e moves only v1, by 1e-3 m/s, at a cycle point whose v1 is 0.1 sin(a): the scaled size
  // depends on that point, so the test uses n = 1 (v1 = 0 at a = 0) where s = 1e-3 / (omega L).
  const double s = 1e-3 / (Parameters{}.omega * 0.05);
  SteadyStateDetector d(model, kNMax, kTol);
  const Fed fed = feed(d, 200, [r](long j) {
    State y = cycle_point(0, 1);
    y[2] += std::pow(r, static_cast<double>(j)) * 1e-3;
    return y;
  });
  // n = 1: r^(J-1) (1 - r) s <= tol  <=>  J >= 1 + log(tol / ((1 - r) s)) / log(r).
  const long expected = static_cast<long>(std::ceil(1.0 + std::log(kTol / ((1.0 - r) * s)) / std::log(r)));
  EXPECT_EQ(fed.stopped_at, expected);
  EXPECT_EQ(d.period_n(), 1);
  EXPECT_LE(d.residual(), kTol);
  EXPECT_GT(d.residual(), r * kTol);  // one period earlier it was not yet within tol
}

TEST(SteadyState, GeometricApproachToATwoCycleFindsPeriodTwo) {
  const Model model{Parameters{}};
  SteadyStateDetector d(model, kNMax, kTol);
  const Fed fed = feed(d, 400, [](long j) {
    State y = cycle_point(static_cast<int>(j), 2);
    y[0] += std::pow(0.8, static_cast<double>(j)) * 1e-3;  // x1 moves 1 mm at first
    return y;
  });
  // ||y_i - y_{i-2}|| = 0.8^(i-2) (1 - 0.8^2) 1 mm over L + |x1| = 0.05 + 0.02 m, largest at
  // i = J - 1: within tol from 0.8^(J-3) <= 1e-6 0.07 / 0.36e-3, J - 3 >= 38.27, so J = 42.
  EXPECT_EQ(fed.stopped_at, 42);
  EXPECT_EQ(d.period_n(), 2);
  EXPECT_LE(d.residual(), kTol);
}

TEST(SteadyState, QuasiPeriodicRotationIsNeverPeriodicNorConverging) {
  // A rotation by the golden angle: y_j never comes back near y_{j-n} for any n <= n_max.
  const Model model{Parameters{}};
  SteadyStateDetector d(model, kNMax, kTol);
  const double angle = 2.0 * std::numbers::pi * (std::sqrt(5.0) - 1.0) / 2.0;
  const Fed fed = feed(d, 300, [angle](long j) {
    const double a = angle * static_cast<double>(j);
    return State{0.02 * std::cos(a), -0.05 + 0.01 * std::sin(a), 0.1 * std::sin(a), 0.05 * std::cos(a)};
  });
  EXPECT_EQ(fed.stopped_at, -1);
  EXPECT_EQ(d.period_n(), 0);
  EXPECT_GT(d.residual(), 1e-3);  // the nearest return (n = 5 or 8) is still far
  EXPECT_FALSE(d.still_converging());
}

TEST(SteadyState, ChaoticLogisticSequenceIsNeverPeriodicNorConverging) {
  const Model model{Parameters{}};
  SteadyStateDetector d(model, kNMax, kTol);
  std::vector<double> x{0.123456789};
  for (int j = 1; j < 300; ++j) x.push_back(4.0 * x.back() * (1.0 - x.back()));
  const Fed fed = feed(d, 300, [&x](long j) {
    const double s = x[static_cast<std::size_t>(j)];
    return State{0.02 * s, -0.05 + 0.01 * s, 0.1 * (1.0 - s), 0.05 * s};
  });
  EXPECT_EQ(fed.stopped_at, -1);
  EXPECT_EQ(d.period_n(), 0);
  EXPECT_FALSE(d.still_converging());
}

TEST(SteadyState, SlowApproachOutOfBudgetIsStillConverging) {
  // r = 0.95: the gap falls by log10(0.95) per period, detection would need some 250 periods.
  const Model model{Parameters{}};
  SteadyStateDetector d(model, kNMax, kTol);
  const Fed fed = feed(d, 60, [](long j) {
    State y = cycle_point(static_cast<int>(j), 3);
    y[1] += std::pow(0.95, static_cast<double>(j)) * 1e-2;
    return y;
  });
  EXPECT_EQ(fed.stopped_at, -1);
  EXPECT_EQ(d.period_n(), 0);
  EXPECT_TRUE(d.still_converging());
}

TEST(SteadyState, NMaxOutsideItsRangeIsRefused) {
  const Model model{Parameters{}};
  EXPECT_THROW(SteadyStateDetector(model, 0, kTol), std::invalid_argument);
  EXPECT_THROW(SteadyStateDetector(model, SteadyStateDetector::kMaxN + 1, kTol), std::invalid_argument);
}
