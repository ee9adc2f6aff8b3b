#include "vibromap/core/integrate/event_locator.hpp"

#include <array>

#include "vibromap/core/integrate/root_finding.hpp"

namespace vibromap {

namespace {
constexpr int kSamples = 8;

struct GPoint {
  double tau, g, dg;
};
}  // namespace

std::optional<LocatedEvent> locate_contact_event(const DenseOutput& dense, double tau0, double tau1,
                                                 ContactMode mode, double tau_tol) {
  const double s = mode == ContactMode::free ? 1.0 : -1.0;
  auto sample = [&](double tau) {
    const State u = dense.eval(tau);
    return GPoint{tau, s * u[1], s * u[3]};
  };
  auto g_of = [&](double tau) { return s * dense.eval(tau)[1]; };
  auto dg_of = [&](double tau) { return s * dense.eval(tau)[3]; };

  GPoint prev = sample(tau0);
  // An event exactly at the start (g = 0, moving outward) is reported at tau0.
  if (prev.g > 0.0 || (prev.g == 0.0 && prev.dg > 0.0)) return LocatedEvent{tau0};

  for (int i = 1; i <= kSamples; ++i) {
    const double tau = i == kSamples ? tau1 : tau0 + (tau1 - tau0) * i / kSamples;
    const GPoint cur = sample(tau);
    if (cur.g > 0.0) {
      return LocatedEvent{illinois(g_of, prev.tau, cur.tau, prev.g, cur.g, tau_tol).x};
    }
    if (prev.dg > 0.0 && cur.dg < 0.0) {
      // Interior maximum of g: find where g' = 0 (g' goes + to -, so look for -g' > 0).
      auto minus_dg = [&](double t) { return -dg_of(t); };
      const double t_peak = illinois(minus_dg, prev.tau, cur.tau, -prev.dg, -cur.dg, tau_tol).x;
      const double g_peak = g_of(t_peak);
      if (g_peak > 0.0) {
        return LocatedEvent{illinois(g_of, prev.tau, t_peak, prev.g, g_peak, tau_tol).x};
      }
    }
    prev = cur;
  }
  return std::nullopt;
}

}  // namespace vibromap
