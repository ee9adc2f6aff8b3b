// The audit of an adaptive map: the deterministic sample and the exact (Clopper-Pearson)
// one-sided 95 % upper bound on the mismatch rate, against closed forms and against
// scipy.stats.beta.ppf(0.95, k + 1, n - k) (scipy 1.10, checked with mpmath at 40 digits).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "vibromap/core/refine/refine_stats.hpp"

using namespace vibromap;

TEST(RefineStats, RegularizedBetaMatchesClosedForms) {
  for (double x : {0.01, 0.3, 0.5, 0.77, 0.999}) {
    EXPECT_NEAR(regularized_beta(x, 1.0, 1.0), x, 1e-15);
    EXPECT_NEAR(regularized_beta(x, 3.0, 1.0), x * x * x, 1e-14);
    EXPECT_NEAR(regularized_beta(x, 1.0, 4.0), 1.0 - std::pow(1.0 - x, 4.0), 1e-14);
  }
  EXPECT_NEAR(regularized_beta(0.5, 37.0, 37.0), 0.5, 1e-13);
  EXPECT_EQ(regularized_beta(0.0, 2.0, 3.0), 0.0);
  EXPECT_EQ(regularized_beta(1.0, 2.0, 3.0), 1.0);
  // P(X <= 2) for binomial(10, 0.3): 0.3827827864 (sum of three terms).
  const double p = 0.3, q = 0.7;
  const double exact = std::pow(q, 10) + 10 * p * std::pow(q, 9) + 45 * p * p * std::pow(q, 8);
  EXPECT_NEAR(binomial_cdf(2, 10, p), exact, 1e-14);
  EXPECT_EQ(binomial_cdf(10, 10, p), 1.0);
}

TEST(RefineStats, NoMismatchGivesOneMinusAlphaToTheOneOverN) {
  for (std::uint64_t n : {1ull, 10ull, 100ull}) {
    const double expected = 1.0 - std::pow(0.05, 1.0 / static_cast<double>(n));
    EXPECT_NEAR(mismatch_upper_bound(0, n) / expected, 1.0, 1e-12) << n;
  }
  EXPECT_NEAR(mismatch_upper_bound(0, 10), 0.2588655508930522, 1e-15);
  EXPECT_NEAR(mismatch_upper_bound(0, 1), 0.95, 1e-15);
  // n = 1e6 (1 - pow loses digits there; the value from mpmath at 30 digits).
  EXPECT_NEAR(mismatch_upper_bound(0, 1000000) / 2.9957277863525444e-6, 1.0, 1e-12);
  EXPECT_NEAR(mismatch_upper_bound(0, 300), 3.0 / 300.0, 3e-4);  // the rule of three
}

TEST(RefineStats, ClopperPearsonUpperBoundsMatchScipy) {
  struct Case {
    std::uint64_t k, n;
    double upper;
  };
  const Case cases[] = {{1, 10, 0.39416330243650466},   {5, 20, 0.4555824040017489},
                        {3, 100, 0.07571079374983004},  {10, 1000, 0.016903175120562504},
                        {9, 10, 0.9948838031081763},    {50, 100000, 0.0006328286928247058}};
  for (const Case& c : cases) {
    const double u = mismatch_upper_bound(c.k, c.n);
    EXPECT_NEAR(u / c.upper, 1.0, 1e-9) << c.k << " of " << c.n;
    EXPECT_NEAR(binomial_cdf(c.k, c.n, u), 0.05, 1e-9) << c.k << " of " << c.n;
  }
  EXPECT_EQ(mismatch_upper_bound(7, 7), 1.0);
  EXPECT_EQ(mismatch_upper_bound(0, 0), 1.0);
  EXPECT_LT(mismatch_upper_bound(3, 100, 0.9), mismatch_upper_bound(3, 100, 0.95));
  EXPECT_THROW(mismatch_upper_bound(4, 3), std::invalid_argument);
  EXPECT_THROW(mismatch_upper_bound(1, 3, 1.0), std::invalid_argument);
}

TEST(RefineStats, TheAuditSampleIsAFunctionOfSeedAndIndex) {
  std::uint64_t picked = 0, again = 0, other_seed = 0, both = 0;
  const std::uint64_t n = 100000;
  for (std::uint64_t i = 0; i < n; ++i) {
    const bool a = audit_selects(42, i, 0.01);
    picked += a;
    again += audit_selects(42, i, 0.01) == a;
    const bool b = audit_selects(43, i, 0.01);
    other_seed += b;
    both += a && b;
    const double u = audit_uniform(42, i);
    ASSERT_TRUE(u >= 0.0 && u < 1.0);
    ASSERT_FALSE(audit_selects(42, i, 0.0));
    ASSERT_TRUE(audit_selects(42, i, 1.0));
  }
  EXPECT_EQ(again, n);
  // Binomial(1e5, 0.01): mean 1000, standard deviation 31.5; the two seeds draw independently
  // (expected overlap 10).
  EXPECT_NEAR(static_cast<double>(picked), 1000.0, 5 * 31.5);
  EXPECT_NEAR(static_cast<double>(other_seed), 1000.0, 5 * 31.5);
  EXPECT_LT(both, 40u);
  EXPECT_EQ(audit_uniform(42, 12345), audit_uniform(42, 12345));
}
