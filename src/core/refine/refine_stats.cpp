#include "vibromap/core/refine/refine_stats.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vibromap {

namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// The continued fraction of I_x(a, b) (modified Lentz), good for x < (a + 1) / (a + b + 2).
double beta_fraction(double x, double a, double b) {
  constexpr double tiny = 1e-300, eps = 1e-16;
  const double qab = a + b, qap = a + 1.0, qam = a - 1.0;
  double c = 1.0, d = 1.0 - qab * x / qap;
  if (std::fabs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 1000000; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
    d = 1.0 + aa * d;
    if (std::fabs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
    d = 1.0 + aa * d;
    if (std::fabs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::fabs(del - 1.0) < eps) return h;
  }
  return h;  // not reached for the a, b of a binomial with n < 2^53
}

}  // namespace

double audit_uniform(std::uint64_t seed, std::uint64_t index) {
  const std::uint64_t x = splitmix64(splitmix64(seed) ^ index);
  return static_cast<double>(x >> 11) * 0x1.0p-53;
}

bool audit_selects(std::uint64_t seed, std::uint64_t index, double fraction) {
  return audit_uniform(seed, index) < fraction;
}

double regularized_beta(double x, double a, double b) {
  if (!(x > 0.0)) return 0.0;
  if (!(x < 1.0)) return 1.0;
  const double ln_front = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  const double front = std::exp(ln_front);
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_fraction(x, a, b) / a;
  return 1.0 - front * beta_fraction(1.0 - x, b, a) / b;
}

double binomial_cdf(std::uint64_t k, std::uint64_t n, double p) {
  if (k >= n) return 1.0;
  return regularized_beta(1.0 - p, static_cast<double>(n - k), static_cast<double>(k) + 1.0);
}

double mismatch_upper_bound(std::uint64_t k, std::uint64_t n, double confidence) {
  if (k > n)
    throw std::invalid_argument("mismatch_upper_bound: " + std::to_string(k) + " mismatches in " +
                                std::to_string(n) + " audits");
  if (!(confidence > 0.0 && confidence < 1.0))
    throw std::invalid_argument("mismatch_upper_bound: confidence must be in (0, 1)");
  if (n == 0 || k == n) return 1.0;
  const double alpha = 1.0 - confidence;
  if (k == 0) return -std::expm1(std::log(alpha) / static_cast<double>(n));
  // binomial_cdf(k, n, p) falls from 1 to 0 as p goes from 0 to 1: bisect for alpha.
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200 && hi - lo > 0.0; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (binomial_cdf(k, n, mid) > alpha ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace vibromap
