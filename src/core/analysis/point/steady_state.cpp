#include "vibromap/core/analysis/point/steady_state.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vibromap {

namespace {
constexpr double kNearFactor = 1e3;
constexpr double kCandidateFactor = 10.0;
// Fewer samples than this cannot tell a slow approach from a non-periodic motion (a shooting
// transient is 10 periods, integrated loosely).
constexpr long kMinTrendPeriods = 20;
}  // namespace

SteadyStateDetector::SteadyStateDetector(const Model& model, int n_max, double tol)
    : n_max_(n_max), tol_(tol), scale_(model) {
  if (n_max < 1 || n_max > kMaxN) throw std::invalid_argument("SteadyStateDetector: n_max must be in [1, " + std::to_string(kMaxN) + "]");
}

double SteadyStateDetector::distance(const State& a, const State& b) const { return scale_.distance(a, b); }

bool SteadyStateDetector::on_period_end(long period, const State& u) {
  samples_.push_back(u);
  if (samples_.size() > static_cast<std::size_t>(2 * n_max_)) {
    samples_.pop_front();
    gaps_.pop_front();
  }
  const int count = static_cast<int>(samples_.size());
  const int last = count - 1;
  auto& gap = gaps_.emplace_back();
  gap.fill(std::numeric_limits<double>::infinity());
  double best = std::numeric_limits<double>::infinity();  // the nearest earlier sample
  for (int n = 1; n <= n_max_ && n <= last; ++n) {
    gap[static_cast<std::size_t>(n)] = distance(samples_[last], samples_[last - n]);
    best = std::min(best, gap[static_cast<std::size_t>(n)]);
  }
  if (std::isfinite(best)) best_log10_.push_back(std::log10(std::max(best, 1e-300)));
  residual_ = best;

  // worst[n]: largest ||y_i - y_{i-n}|| over the last n samples (infinite when too few).
  std::vector<double>& worst = worst_;  // kept between periods: no allocation per period
  worst.assign(static_cast<std::size_t>(n_max_) + 1, std::numeric_limits<double>::infinity());
  for (int n = 1; n <= n_max_ && 2 * n <= count; ++n) {
    double w = 0.0;
    for (int i = last; i > last - n; --i) w = std::max(w, gaps_[static_cast<std::size_t>(i)][static_cast<std::size_t>(n)]);
    worst[static_cast<std::size_t>(n)] = w;
  }
  for (int n = 1; n <= n_max_; ++n) {
    if (!(worst[static_cast<std::size_t>(n)] <= tol_)) continue;
    // A transient that spirals into an m-periodic orbit with a rotation of ~2 pi m/n per
    // period comes back near itself after n periods before it settles: while some m < n
    // is within kNearFactor * tol, wait for m rather than report n.
    bool nearly_shorter = false;
    for (int m = 1; m < n; ++m) nearly_shorter = nearly_shorter || worst[static_cast<std::size_t>(m)] <= kNearFactor * tol_;
    if (nearly_shorter) break;
    n_found_ = n;
    detected_at_ = period;
    residual_ = worst[static_cast<std::size_t>(n)];
    return true;
  }
  return false;
}

std::vector<int> SteadyStateDetector::candidate_periods(int count) const {
  // A transient spiralling in with a rotation near 2 pi m / n per period comes back near
  // itself after n periods, so the smallest residual can point at a multiple of the true
  // period. Shorter periods whose residual is within kCandidateFactor of the smallest are
  // tried first, then the rest by residual.
  const int last = static_cast<int>(samples_.size()) - 1;
  std::vector<std::pair<double, int>> by_distance;
  for (int n = 1; n <= n_max_ && n <= last; ++n) by_distance.emplace_back(gaps_.back()[static_cast<std::size_t>(n)], n);
  if (by_distance.empty()) return {1};
  const double best = std::min_element(by_distance.begin(), by_distance.end())->first;
  std::stable_sort(by_distance.begin(), by_distance.end(), [best](const auto& a, const auto& b) {
    const bool a_near = a.first <= kCandidateFactor * best, b_near = b.first <= kCandidateFactor * best;
    if (a_near != b_near) return a_near;
    return a_near ? a.second < b.second : a.first < b.first;
  });
  std::vector<int> out;
  for (std::size_t i = 0; i < by_distance.size() && static_cast<int>(i) < count; ++i) out.push_back(by_distance[i].second);
  return out;
}

bool SteadyStateDetector::still_converging() const {
  const auto total = static_cast<long>(best_log10_.size());
  const long w = std::min<long>(total, std::max<long>(20, 2 * total / 3));
  if (w < kMinTrendPeriods) return true;  // too few periods to tell: the budget was the limit
  // Least-squares slope of log10(residual) against the period index over the last w samples.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (long i = 0; i < w; ++i) {
    const double x = static_cast<double>(i), y = best_log10_[static_cast<std::size_t>(total - w + i)];
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double n = static_cast<double>(w);
  const double denom = n * sxx - sx * sx;
  const double slope = (n * sxy - sx * sy) / denom;
  const double intercept = (sy - slope * sx) / n;
  double sse = 0;
  for (long i = 0; i < w; ++i) {
    const double r = best_log10_[static_cast<std::size_t>(total - w + i)] - (intercept + slope * static_cast<double>(i));
    sse += r * r;
  }
  const double stderr_slope = std::sqrt(sse / std::max(1.0, n - 2) * n / denom);
  return slope < -std::max(1e-5, 3.0 * stderr_slope);
}

}  // namespace vibromap
