#include "vibromap/core/analysis/point/lyapunov.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vibromap {

namespace {
// Growth per forcing period above which a motion counts as chaotic: e^{0.01} per period.
constexpr double kChaosGrowth = 0.01;
// Periods skipped before averaging while the tangent vector aligns with the leading
// direction: a quarter of the averaged ones, at least kMinAlignPeriods (a subdominant
// direction decaying by r per period biases the mean by ~ r^align / ((1 - r) periods)).
constexpr int kMinAlignPeriods = 10;
constexpr std::size_t kBatches = 10;  // batch means for the standard error
}  // namespace

bool LyapunovEstimate::chaotic() const {
  return ok && exponent * period > kChaosGrowth && exponent > 3.0 * std_error;
}

LyapunovEstimate largest_lyapunov(const Model& model, const IntegratorOptions& options, State& u, int periods,
                                  IntegrationCounters& counters) {
  LyapunovEstimate e;
  e.period = model.period();
  auto integ = make_variational_integrator(model, options);
  integ->reset(u);
  Observer none;
  Eigen::Vector4d v = Eigen::Vector4d::Ones().normalized();
  std::vector<double> growth;
  const int align = std::max(kMinAlignPeriods, periods / 4);
  for (int j = 0; j < align + periods; ++j) {
    integ->reset_jacobian();
    if (integ->advance_period(u, none) != IntegrationStatus::ok) break;
    v = integ->jacobian() * v;
    const double norm = v.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) break;
    v /= norm;
    if (j >= align) growth.push_back(std::log(norm));
  }
  counters += integ->counters();
  if (growth.size() < static_cast<std::size_t>(periods)) return e;
  // Standard error from batch means: the log growths of successive periods are correlated,
  // the means of kBatches long batches much less so.
  const std::size_t per_batch = growth.size() / kBatches;
  std::vector<double> batch(kBatches, 0.0);
  for (std::size_t b = 0; b < kBatches; ++b) {
    for (std::size_t i = 0; i < per_batch; ++i) batch[b] += growth[b * per_batch + i];
    batch[b] /= static_cast<double>(per_batch);
  }
  double mean = 0.0, var = 0.0;
  for (double g : batch) mean += g;
  mean /= static_cast<double>(kBatches);
  for (double g : batch) var += (g - mean) * (g - mean);
  var /= static_cast<double>(kBatches - 1);
  e.ok = true;
  e.exponent = mean / e.period;
  e.std_error = std::sqrt(var / static_cast<double>(kBatches)) / e.period;
  return e;
}

}  // namespace vibromap
