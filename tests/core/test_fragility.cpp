// Fragility of a point's answer (fragility.hpp) against constructed cases:
//  - the rest state of the paper's Table 2 lies well inside the basin of the soft (1,1): every
//    perturbation of size 1e-3 motion scales settles onto the same orbit, the point is not
//    fragile, and its own answer is the one solve_point gives without fragility, bit for bit;
//  - an initial state on the boundary between the (1,1)'s basin and the (3,3)'s, located by
//    bisection on the segment from rest to a (3,3) orbit point (to 6e-12 of its length, about 3e-11
//    motion scales): perturbations of 1e-6 motion scales end on both attractors, so the point
//    is fragile, and the perturbed states that end elsewhere reach the (3,3);
//  - the directions are unit vectors, and the comparison rule (same_steady_state) on ends made up
//    for it.

#include <gtest/gtest.h>

#include <cmath>

#include "vibromap/core/analysis/point/fragility.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/model/keys.hpp"
#include "support/paper_points.hpp"

namespace vibromap {
namespace {

using test::table2;  // tests/support/paper_points.hpp

// The two sides of the (1,1) | (3,3) basin boundary on the segment from rest (0, D, 0, 0) to the
// (3,3) orbit's stroboscopic state (0.0553099, 0.144713, 0.909958, 1.22891) of Table 2, found by
// bisection with `vibromap run jobs/paper/table2.toml --set initial.*` (the default follow) to
// t in [0.10025584485265426, 0.10025584485847502] of the segment.
const Eigen::Vector4d kBoundaryOneOne(0.0055451369935364545, 0.05949549058538896, 0.09122858920242753,
                                      0.12320572975636745);
const Eigen::Vector4d kBoundaryThreeThree(0.0055451369938584, 0.05949549058594026, 0.09122858920772418,
                                          0.12320572976352066);

PointOptions with_fragility(double size) {
  PointOptions o;
  o.analysis.fragility = size;
  return o;
}

TEST(FragilityDirections, UnitVectorsInMotionScalesInPlusMinusPairs) {
  for (int i = 0; i < kMaxFragilityStates; ++i) {
    EXPECT_DOUBLE_EQ(fragility_direction(i).norm(), 1.0) << i;
    if (i % 2 == 1) {
      EXPECT_EQ(fragility_direction(i), -fragility_direction(i - 1)) << i;
    }
    for (int j = 0; j < i / 2 * 2; j += 2) EXPECT_DOUBLE_EQ(fragility_direction(i).dot(fragility_direction(j)), 0.0);
  }
}

TEST(FragilitySameSteadyState, PeriodicByOrbitNonPeriodicByKindUnresolvedApart) {
  const Parameters p = table2();
  const PointOptions o;
  SteadyEnd a, b;
  a.settled = b.settled = true;
  a.regime = b.regime = {RegimeKind::periodic, 2, 2};
  a.strobe = {Eigen::Vector4d(0.01, 0.05, 0.1, 0.2), Eigen::Vector4d(0.02, 0.06, -0.1, 0.3)};
  b.strobe = {a.strobe[1], a.strobe[0]};  // the same cycle, shifted
  EXPECT_TRUE(same_steady_state(p, o, a, b));
  b.strobe[0][0] += 1e-3;  // another orbit of the same label
  EXPECT_FALSE(same_steady_state(p, o, a, b));
  b.strobe[0][0] -= 1e-3;
  b.strobe[0][0] += 1e-9;  // within the orbit tolerance (1e-6 scaled)
  EXPECT_TRUE(same_steady_state(p, o, a, b));
  SteadyEnd chaos, chaos2, unresolved, unresolved2;
  chaos.regime = chaos2.regime = {RegimeKind::non_periodic, 0, 0};
  unresolved.regime = unresolved2.regime = {RegimeKind::unresolved, 0, 0};
  EXPECT_TRUE(same_steady_state(p, o, chaos, chaos2));
  EXPECT_TRUE(same_steady_state(p, o, unresolved, unresolved2));
  EXPECT_FALSE(same_steady_state(p, o, chaos, unresolved));
  EXPECT_FALSE(same_steady_state(p, o, a, chaos));
}

TEST(Fragility, Table2RestIsInsideTheSoftBasinAndNotFragile) {
  const Parameters p = table2();
  const PointSummary off = solve_point(p, PointOptions{});
  const PointSummary s = solve_point(p, with_fragility(1e-3));
  ASSERT_EQ(s.status, SolveStatus::ok) << s.message;
  EXPECT_EQ(s.regime.label(), "(1,1)");
  // Fragility adds a flag: the point's own answer is unchanged.
  EXPECT_EQ(s.k_con, off.k_con);
  EXPECT_EQ(s.final_state, off.final_state);
  EXPECT_EQ(s.counters.steps, off.counters.steps);
  EXPECT_EQ(off.fragility.size, 0.0);
  EXPECT_EQ(s.fragility.size, 1e-3);
  EXPECT_FALSE(s.fragility.fragile);
  ASSERT_EQ(s.fragility.perturbed.size(), 4u);
  ASSERT_EQ(s.fragility.own.strobe.size(), 1u);
  for (const SteadyEnd& e : s.fragility.perturbed) {
    EXPECT_EQ(e.regime.label(), "(1,1)");
    EXPECT_TRUE(e.same);
    ASSERT_EQ(e.strobe.size(), 1u);
    // The same orbit: the refined cycles agree far below the orbit tolerance.
    EXPECT_LT((e.strobe[0] - s.fragility.own.strobe[0]).cwiseAbs().maxCoeff(), 1e-7);
  }
  // The perturbed state moves each coordinate by half the size, in its scale (L = D = 0.05 m).
  EXPECT_NEAR(s.fragility.perturbed[0].x0[0], 0.5e-3 * 0.05, 1e-15);
  EXPECT_NEAR(s.fragility.perturbed[0].x0[2], 0.5e-3 * 0.05 * 7.23, 1e-15);
}

// The pair +h1, -h1 straddles the boundary (1e-6 motion scales against the 3e-11 the states lie
// from it): +h1 reaches the (3,3), -h1 the (1,1), from either side.
TEST(Fragility, AStateOnTheBasinBoundaryIsFragile) {
  for (const auto& [x0, own] : {std::pair{kBoundaryOneOne, "(1,1)"}, std::pair{kBoundaryThreeThree, "(3,3)"}}) {
    Parameters p = table2();
    p.initial = x0;
    PointOptions o = with_fragility(1e-6);
    o.analysis.fragility_states = 2;
    const PointSummary s = solve_point(p, o);
    ASSERT_EQ(s.status, SolveStatus::ok) << s.message;
    EXPECT_EQ(s.regime.label(), own);
    EXPECT_TRUE(s.fragility.fragile) << own;
    ASSERT_EQ(s.fragility.perturbed.size(), 2u);
    EXPECT_EQ(s.fragility.perturbed[0].regime.label(), "(3,3)");
    EXPECT_EQ(s.fragility.perturbed[1].regime.label(), "(1,1)");
    for (const SteadyEnd& e : s.fragility.perturbed) EXPECT_EQ(e.same, e.regime.label() == own) << own;
  }
}

TEST(FragilityKeys, BoundsAreTheKeyTable) {
  EXPECT_EQ(Key::at("analysis.fragility").check(0.2), "[analysis] fragility = 0.2: must be in [0, 0.1]");
  EXPECT_EQ(Key::at("analysis.fragility_states").check(9), "[analysis] fragility_states = 9: must be an integer in [1, 8]");
  PointOptions o;
  o.analysis.fragility = -1.0;
  EXPECT_NE(validate(o.analysis).find("fragility"), std::string::npos);
}

}  // namespace
}  // namespace vibromap
