#pragma once
// The largest Lyapunov exponent of a motion, from the variational equations (Benettin et al.,
// Meccanica 15 (1980) 9-20): a tangent vector is carried period by period by the monodromy
// matrix of each forcing period and renormalised; the exponent is the mean log growth per
// unit time. Used to tell a non-periodic motion chaotic (exponent clearly > 0) from
// quasi-periodic (exponent ~ 0).

#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap {

struct LyapunovEstimate {
  bool ok = false;          // false when the integration failed
  double exponent = 0.0;    // largest Lyapunov exponent, 1/s
  double std_error = 0.0;   // standard error of the mean over the periods, 1/s
  // Chaotic: the exponent exceeds kChaosGrowth per period and three standard errors.
  bool chaotic() const;
  double period = 1.0;      // forcing period T, s
};

// Integrates `periods` forcing periods from u (advanced in place) and estimates the exponent.
LyapunovEstimate largest_lyapunov(const Model& model, const IntegratorOptions& options, State& u, int periods,
                                  IntegrationCounters& counters);

}  // namespace vibromap
