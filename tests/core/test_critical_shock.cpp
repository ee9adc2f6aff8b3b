// The minimal critical shock (critical_shock.hpp) against known answers:
//  - one ray's bisection brackets a constructed boundary to the tolerance;
//  - the whole search on constructed basins: a half-space a.z >= c has its nearest point at
//    distance c / |a| along a (restricted to the coordinates the shock moves: c / |a_on|, the
//    others exactly 0); an overlap limit (z1 - z2 <= slack) moves it to the corner of the two;
//    a basin that is never left gives none;
//  - at Table 2 (a soft (1,1) and a (3,3) coexist), the soft (1,1)'s shock leads to another
//    attractor (listed or not) when followed by a fresh follower, and the same vector scaled by
//    (1 - 10 tol) leads back to the (1,1); a velocity kick leaves x1 and x2 exactly alone.

#include <gtest/gtest.h>

#include <cmath>

#include "vibromap/core/analysis/census/critical_shock.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"
#include "support/paper_points.hpp"

namespace vibromap {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

ShockLeads half_space(const Eigen::Vector4d& a, double c) {
  return [a, c](const Eigen::Vector4d& z) { return a.dot(z) >= c ? ShockVerdict::elsewhere : ShockVerdict::stays; };
}

TEST(ShockRay, BisectionBracketsTheBoundaryToTheTolerance) {
  ShockOptions o;
  o.tolerance = 1e-4;
  ShockSearch counts;
  const Eigen::Vector4d u = Eigen::Vector4d(1.0, -1.0, 2.0, 0.5).normalized();
  const auto leads = [](const Eigen::Vector4d& z) { return z.norm() >= 0.8 ? ShockVerdict::elsewhere : ShockVerdict::stays; };
  const std::optional<RayBoundary> b = ray_boundary(leads, u, o.max_radius, o, counts);
  ASSERT_TRUE(b);
  EXPECT_LT(b->r_in, 0.8);
  EXPECT_GE(b->r_out, 0.8);
  EXPECT_LE(b->r_out - b->r_in, o.tolerance * b->r_out);
  // Below the limit the ray leads nowhere else.
  EXPECT_FALSE(ray_boundary(leads, u, 0.79, o, counts));
}

TEST(ShockSearch, HalfSpaceNearestPointIsFoundToTheTolerance) {
  ShockOptions o;  // 32 directions, tolerance 1e-3
  const Eigen::Vector4d a(0.3, -0.5, 0.8, 0.1);
  const double c = 0.4;
  const ShockSearch s = search_shock(half_space(a, c), kInf, o, kInf);
  ASSERT_TRUE(s.found);
  const double exact = c / a.norm();
  EXPECT_NEAR(s.size, exact, 2e-3 * exact);
  EXPECT_GE(a.dot(s.z), c);  // the point reported leads elsewhere
  EXPECT_GT(s.z.normalized().dot(a.normalized()), std::cos(0.05));
  EXPECT_LE(s.size, s.random_size);
}

TEST(ShockSearch, RestrictedCoordinatesStayExactlyZero) {
  ShockOptions o;
  o.on = {false, false, true, true};
  const Eigen::Vector4d a(0.3, -0.5, 0.8, 0.1);
  const ShockSearch s = search_shock(half_space(a, 0.4), kInf, o, kInf);
  ASSERT_TRUE(s.found);
  const double exact = 0.4 / std::hypot(a[2], a[3]);
  EXPECT_NEAR(s.size, exact, 2e-3 * exact);
  EXPECT_EQ(s.z[0], 0.0);
  EXPECT_EQ(s.z[1], 0.0);
  // One coordinate: the two directions along it.
  o.on = {false, false, true, false};
  const ShockSearch one = search_shock(half_space(a, 0.4), kInf, o, kInf);
  ASSERT_TRUE(one.found);
  EXPECT_NEAR(one.size, 0.5, 1e-3 * 0.5);
  EXPECT_EQ(one.z[0], 0.0);
  EXPECT_EQ(one.z[1], 0.0);
  EXPECT_EQ(one.z[3], 0.0);
}

TEST(ShockSearch, OverlapLimitMovesTheShockToTheCorner) {
  // Elsewhere where z1 >= 0.5, with z1 - z2 <= 0.3 allowed: the nearest allowed point is
  // (0.5, 0.2, 0, 0), at sqrt(0.29).
  ShockOptions o;
  o.on = {true, true, false, false};
  const ShockSearch s = search_shock(half_space(Eigen::Vector4d::Unit(0), 0.5), 0.3, o, kInf);
  ASSERT_TRUE(s.found);
  EXPECT_NEAR(s.size, std::sqrt(0.29), 5e-3 * std::sqrt(0.29));
  EXPECT_LE(s.z[0] - s.z[1], 0.3 + 1e-12);
}

TEST(ShockSearch, NoneWithinTheLargestRadius) {
  ShockOptions o;
  o.max_radius = 0.5;
  const ShockSearch s = search_shock(half_space(Eigen::Vector4d::Unit(2), 0.6), kInf, o, kInf);
  EXPECT_FALSE(s.found);
  EXPECT_EQ(s.unresolved, 0);
  EXPECT_GT(s.follows, 0);
}

// Where x0 leads for a fresh follower: the index of the census attractor it lands on, -2 a
// decided attractor the census does not list, -1 none.
int lands_on(const Parameters& p, const PointOptions& po, const CensusOptions& c, const CensusSummary& s,
             const Eigen::Vector4d& x0) {
  CensusFollower fresh(p, po, c);
  const CensusFollower::Outcome f = fresh.follow(x0);
  if (f.label < 0) return -1;
  for (std::size_t i = 0; i < s.attractors.size(); ++i)
    if (same_attractor(p, po, s.attractors[i], fresh.attractor(static_cast<std::size_t>(f.label)))) return static_cast<int>(i);
  return kShockToUnlisted;
}

CensusOptions table2_census() {
  CensusOptions c;
  c.initial_conditions = 12;
  c.shock_directions = 8;
  c.shock_tolerance = 1e-3;
  return c;
}

// The census of Table 2 (without shocks) and the index of its soft (1,1).
std::size_t soft_index(const CensusSummary& s) {
  for (std::size_t i = 0; i < s.attractors.size(); ++i)
    if (s.attractors[i].soft && s.attractors[i].regime.label() == "(1,1)") return i;
  return s.attractors.size();
}

// The soft (1,1)'s shock (the (3,3)'s needs a radius past the default 2: docs/guide-census-and-basins.md).
TEST(CriticalShock, Table2SoftShockLeadsElsewhereAndJustBelowBack) {
  const Parameters p = test::table2();
  const PointOptions po;
  CensusOptions c = table2_census();
  const CensusSummary s = census_point(p, po, c);
  ASSERT_EQ(s.status, SolveStatus::ok) << s.message;
  const std::size_t i = soft_index(s);
  ASSERT_LT(i, s.attractors.size());
  c.shock = true;
  CensusFollower follower(p, po, c);
  const CriticalShock k = critical_shock(p, po, c, s, i, follower);
  ASSERT_EQ(k.status, ShockStatus::found);
  EXPECT_TRUE(k.verified);
  EXPECT_NE(k.to, static_cast<int>(i));
  EXPECT_NE(k.to, -1);
  EXPECT_EQ(k.x_star, s.attractors[i].strobe[static_cast<std::size_t>(k.strobe_index)]);
  EXPECT_EQ(lands_on(p, po, c, s, k.x_star + k.dx), k.to);  // another attractor, listed or not
  EXPECT_EQ(lands_on(p, po, c, s, k.x_star + (1.0 - 10.0 * c.shock_tolerance) * k.dx), static_cast<int>(i));
  EXPECT_GT(k.size, 0.0);
  EXPECT_LE(k.size, c.shock_max_radius);
  EXPECT_LE(k.size, k.random_size);
  // Its size in motion scales is the vector's.
  const StateScale scale{Model(p)};
  const Eigen::Vector4d unit(scale.length(), scale.length(), scale.speed(), scale.speed());
  EXPECT_NEAR((k.dx.array() / unit.array()).matrix().norm(), k.size, 1e-12 * k.size);
}

TEST(CriticalShock, VelocityKickMovesOnlyTheVelocities) {
  const Parameters p = test::table2();
  CensusOptions c = table2_census();
  const CensusSummary s = census_point(p, PointOptions{}, c);
  ASSERT_EQ(s.status, SolveStatus::ok) << s.message;
  const std::size_t i = soft_index(s);
  ASSERT_LT(i, s.attractors.size());
  c.shock = true;
  c.shock_on = {false, false, true, true};
  CensusFollower follower(p, PointOptions{}, c);
  const CriticalShock k = critical_shock(p, PointOptions{}, c, s, i, follower);
  ASSERT_EQ(k.status, ShockStatus::found);
  EXPECT_EQ(k.dx[0], 0.0);
  EXPECT_EQ(k.dx[1], 0.0);
  EXPECT_TRUE(k.verified);
  EXPECT_EQ(lands_on(p, PointOptions{}, c, s, k.x_star + k.dx), k.to);
}

TEST(CriticalShock, OffByDefaultAndBadOptionsRefused) {
  CensusOptions off;
  off.initial_conditions = 4;
  const CensusSummary s = census_point(test::table2(), PointOptions{}, off);
  for (const Attractor& a : s.attractors) EXPECT_EQ(a.shock.status, ShockStatus::not_computed);
  CensusOptions bad;
  bad.shock_on = {false, false, false, false};
  EXPECT_NE(validate(bad).find("shock_on"), std::string::npos);
  bad = CensusOptions{};
  bad.shock_tolerance = 0.5;
  EXPECT_EQ(validate(bad), "[census] shock_tolerance = 0.5: must be in [1e-08, 0.1]");
  bad = CensusOptions{};
  bad.shock_max_radius = 0.0;
  EXPECT_NE(validate(bad).find("shock_max_radius"), std::string::npos);
}

}  // namespace
}  // namespace vibromap
