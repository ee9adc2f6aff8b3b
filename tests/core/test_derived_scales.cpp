// The scales the model derives from the keys (parameters.hpp: derived_scale_error) and the
// census box (census.hpp: census_box_error): keys each in their range whose products overflow
// are refused naming the key, with the bound it must keep, found against the closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/model/keys.hpp"
#include "vibromap/core/model/parameters.hpp"

namespace vibromap {
namespace {

constexpr double kMax = std::numeric_limits<double>::max();

// The bound a refusal states ("... must be at most 3.595e+305", "... at least 7.1e-163 (rad/s)").
double stated_bound(const std::string& refusal) {
  const std::string from = refusal.substr(refusal.rfind("at ") + 3);
  return std::strtod(from.substr(from.find(' ') + 1).c_str(), nullptr);  // strtod: subnormals too
}

TEST(DerivedScales, TheDefaultPointAndTheShippedExtremesPass) {
  EXPECT_EQ(derived_scale_error(Parameters{}), "");
  Parameters p;
  p.lambda = 1e300;  // lambda F0 = 5e302 N: finite
  EXPECT_EQ(derived_scale_error(p), "");
}

TEST(DerivedScales, AnOverflowingForceAmplitudeNamesLambdaAndItsBound) {
  Parameters p;
  p.lambda = kMax;
  const std::string r = derived_scale_error(p);
  EXPECT_EQ(r.rfind("[forcing] lambda = 1.7976931348623157e+308: makes the force amplitude lambda F0 (N) not finite; "
                    "with the other keys as given it must be at most ", 0), 0U) << r;
  // lambda F0 <= DBL_MAX: the bound is DBL_MAX / 500 in the fewest digits that stay below it.
  const double bound = stated_bound(r);
  EXPECT_LE(bound, kMax / 500.0);
  EXPECT_GT(bound, 0.999 * kMax / 500.0);
  EXPECT_EQ(r.substr(r.rfind(' ') + 1), "3.595e+305");  // lambda is dimensionless: no unit after it
  EXPECT_EQ(validate(p).front(), r);  // validate() gives it, before the frequency rule
}

TEST(DerivedScales, AStiffnessThatUnderflowsToZeroNamesTheFrequencyWithALowerBound) {
  Parameters p;
  p.spring1 = {Spring::Form::frequency, 1e-200};  // k1 = 1000 * 1e-400 = 0
  const std::string r = derived_scale_error(p);
  EXPECT_EQ(r.rfind("[system] omega1 = 1e-200: makes the main spring's stiffness k1 = m1 omega1^2 (N/m) zero or not "
                    "finite; with the other keys as given it must be at least ", 0), 0U) << r;
  // k1 = (m1 omega1) omega1 > 0 needs 1000 omega1^2 of at least half the least subnormal
  // (4.9e-324): omega1 of order 5e-164, and k1 = 0 just below it.
  const double bound = stated_bound(r);
  EXPECT_GT(1000.0 * bound * bound, 0.0);
  EXPECT_EQ(1000.0 * (0.99 * bound) * (0.99 * bound), 0.0);
  EXPECT_EQ(r.substr(r.rfind("least ")), "least 4.97024e-164 (rad/s)");
}

TEST(DerivedScales, FloresChiAtATinyRestitutionNamesRestitution) {
  Parameters p;
  p.law = ContactLawKind::flores;
  p.restitution = 5e-324;  // chi = 1.6 (1 - e) / e = inf
  const std::string r = derived_scale_error(p);
  EXPECT_EQ(r.rfind("[contact] restitution = 5e-324: makes the contact's damping factor chi (-) not finite; "
                    "with the other keys as given it must be at least ", 0), 0U) << r;
  EXPECT_TRUE(std::isfinite(1.6 * (1.0 - stated_bound(r)) / stated_bound(r)));
}

TEST(DerivedScales, AContactStiffnessOverflowIsRefused) {
  Parameters p;
  p.E1 = p.E2 = kMax;
  p.nu1 = p.nu2 = -0.9999999999999999;  // 1 - nu^2 = 2.2e-16: delta underflows, K = inf
  const std::string r = derived_scale_error(p);
  EXPECT_NE(r.find("makes the contact stiffness K (N/m^1.5) not finite"), std::string::npos) << r;
}

TEST(DerivedScales, TheCensusBoxOverflowsBeforeTheMotionScales) {
  // L = lambda F0 / k1 = 1.5e308 m is finite, the box's width 2 L is not.
  Parameters p;
  p.spring1 = {Spring::Form::stiffness, 1.0};
  p.m1 = 1.0;
  p.F0 = 1.5e308;
  p.omega = 0.5;
  EXPECT_EQ(derived_scale_error(p), "");
  const std::string r = census_box_error(p, CensusOptions{});
  EXPECT_EQ(r.rfind("[forcing] F0 = 1.5e+308: makes the census box, the rest state +- L in positions and +- omega L "
                    "in velocities (m, m/s), not finite; with the other keys as given it must be at most ", 0), 0U)
      << r;
  EXPECT_LE(2.0 * stated_bound(r), kMax);
  // A box the scene gives on every side is the scene's: nothing derived to overflow.
  CensusOptions given;
  given.x1 = given.x2 = given.v1 = given.v2 = std::array<double, 2>{-1.0, 1.0};
  EXPECT_EQ(census_box_error(p, given), "");
}

}  // namespace
}  // namespace vibromap
