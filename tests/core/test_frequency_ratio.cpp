// The forcing against the natural frequencies (parameters.hpp): omega_n against closed forms,
// and the rule omega / omega_n in [1e-4, 1e4] that validate() applies.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vibromap/core/model/parameters.hpp"

namespace vibromap {
namespace {

constexpr double kTol = 1e-12;  // relative: closed forms against the quadratic's root

Parameters springs(double m1, double k1, double m2, double k2) {
  Parameters p;
  p.m1 = m1;
  p.m2 = m2;
  p.spring1 = {Spring::Form::stiffness, k1};
  p.spring2 = {Spring::Form::stiffness, k2};
  return p;
}

TEST(FrequencyRatio, FastestNaturalFrequencyMatchesClosedForms) {
  // No coupling spring: body 1 alone on k1, sqrt(k1/m1).
  EXPECT_NEAR(fastest_natural_frequency(springs(1000.0, 39476.0, 100.0, 0.0)), std::sqrt(39.476), kTol * 7.0);
  // Equal masses and springs: K/m = [[2, -1], [-1, 1]] k/m, eigenvalues (3 +- sqrt 5)/2 k/m, so
  // omega_n = phi sqrt(k/m), phi the golden ratio.
  const double w = fastest_natural_frequency(springs(2.0, 50.0, 2.0, 50.0));
  EXPECT_NEAR(w / (std::numbers::phi * 5.0), 1.0, kTol);
  // A stiff coupling of a light body: omega_n -> sqrt(k2 (1/m1 + 1/m2)), the two bodies on k2.
  const double stiff = fastest_natural_frequency(springs(1000.0, 1.0, 1.0, 1e12));
  EXPECT_NEAR(stiff / std::sqrt(1e12 * (1.0 / 1000.0 + 1.0)), 1.0, 1e-9);
  // Units do not matter: masses and stiffnesses both x 1e6 leave it.
  EXPECT_NEAR(fastest_natural_frequency(springs(2e6, 5e7, 2e6, 5e7)) / w, 1.0, kTol);
}

TEST(FrequencyRatio, ValidateRefusesForcingOutsideTheRangeAndNamesIt) {
  Parameters p = springs(2.0, 50.0, 2.0, 50.0);  // omega_n = 8.09 rad/s
  const double wn = fastest_natural_frequency(p);
  for (const double ratio : {1e-4 * 1.001, 1.0, 1e4 * 0.999}) {
    p.omega = ratio * wn;
    EXPECT_TRUE(validate(p).empty()) << ratio;
  }
  for (const double ratio : {1e-4 * 0.999, 1e-300, 1e4 * 1.001, 1e300}) {
    p.omega = ratio * wn;
    const auto errors = validate(p);
    ASSERT_EQ(errors.size(), 1u) << ratio;
    EXPECT_EQ(errors.front(), frequency_ratio_error(p));
    EXPECT_NE(errors.front().find("omega_n = 8.09 rad/s"), std::string::npos) << errors.front();
    EXPECT_NE(errors.front().find("forcing.omega in [0.000809, 8.09e+04] rad/s"), std::string::npos) << errors.front();
  }
  // Another error comes first: the rule is not judged on a point that is invalid already.
  p.m1 = -1.0;
  const auto errors = validate(p);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors.front(), "[system] m1 = -1: must be > 0 (kg)");
}

TEST(FrequencyRatio, FastestDampingRateMatchesClosedForms) {
  Parameters p = springs(2.0, 50.0, 2.0, 50.0);
  // No coupling damper: body 1 alone, c1/m1.
  p.damper1 = {Damper::Form::coefficient, 6.0};
  p.damper2 = {Damper::Form::coefficient, 0.0};
  EXPECT_NEAR(fastest_damping_rate(p), 3.0, 3.0 * kTol);
  // Equal masses and dampers: C/m = [[2, -1], [-1, 1]] c/m, largest eigenvalue phi^2 c/m.
  p.damper2 = {Damper::Form::coefficient, 6.0};
  EXPECT_NEAR(fastest_damping_rate(p) / (std::numbers::phi * std::numbers::phi * 3.0), 1.0, kTol);
  // A ratio xi is c / (2 sqrt(k m)): xi1 = 1, no coupling: 2 sqrt(k1/m1) = 10 1/s.
  p.damper1 = {Damper::Form::ratio, 1.0};
  p.damper2 = {Damper::Form::ratio, 0.0};
  EXPECT_NEAR(fastest_damping_rate(p), 10.0, 10.0 * kTol);
}

TEST(FrequencyRatio, ValidateRefusesDampingFasterThan1e4TimesTheForcing) {
  Parameters p;  // Table 1: the dampers' rate is about 0.02 omega
  EXPECT_LT(fastest_damping_rate(p) / p.omega, 0.05);
  EXPECT_TRUE(validate(p).empty());
  p.damper1 = {Damper::Form::coefficient, 0.999e4 * p.omega * p.m1};  // c1/m1 just under the bound
  p.damper2 = {Damper::Form::coefficient, 0.0};
  EXPECT_TRUE(validate(p).empty()) << validate(p).front();
  p.damper1 = {Damper::Form::coefficient, 1.001e4 * p.omega * p.m1};
  auto errors = validate(p);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors.front().find("times forcing.omega = 7.23 rad/s: at most 1e+04 times"), std::string::npos)
      << errors.front();
  p.damper1 = {Damper::Form::ratio, 1e12};  // the fuzzer's xi1 = 1e12, which spent minutes
  errors = validate(p);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors.front(), frequency_ratio_error(p));
}

}  // namespace
}  // namespace vibromap
