#pragma once
// The audit of an adaptive map: which inherited points are solved again to check
// the inference, and what the mismatches found say about the mismatch rate of all inherited
// points.
//
// The sample is a function of (seed, fine flat index) alone, so every rank and every resume
// draws the same points; the number drawn is binomial(inherited, fraction). The bound is the
// exact one-sided Clopper-Pearson upper limit: the rate p at which seeing at most k mismatches
// in n audits has probability 1 - confidence (k = 0 gives 1 - (1 - confidence)^(1/n)).

#include <cstddef>
#include <cstdint>

namespace vibromap {

// A uniform number in [0, 1) from (seed, index): SplitMix64 of both, 53 bits.
double audit_uniform(std::uint64_t seed, std::uint64_t index);
// The point is audited: audit_uniform(seed, index) < fraction (fraction 0: none, 1: all).
bool audit_selects(std::uint64_t seed, std::uint64_t index, double fraction);

// The regularized incomplete beta function I_x(a, b), a, b > 0, x in [0, 1] (continued
// fraction; absolute accuracy about 1e-13, less for a + b of 1e8 and more, where the
// rounding of lgamma shows).
double regularized_beta(double x, double a, double b);
// P(X <= k) for X ~ binomial(n, p): I_{1-p}(n - k, k + 1); 1 when k >= n.
double binomial_cdf(std::uint64_t k, std::uint64_t n, double p);
// The one-sided upper confidence limit of a binomial rate after k successes in n trials
// (Clopper-Pearson, exact): 1 when n == 0 or k == n. Throws std::invalid_argument when k > n
// or confidence is not in (0, 1).
double mismatch_upper_bound(std::uint64_t k, std::uint64_t n, double confidence = 0.95);

}  // namespace vibromap
