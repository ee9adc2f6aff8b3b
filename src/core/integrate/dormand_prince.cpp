// dopri5: Dormand-Prince 5(4) with located contact events over whole periods; see
// integrator.hpp for the contract and dp5_engine.hpp for the method.

#include "steppers.hpp"

namespace vibromap::detail {

DormandPrince::DormandPrince(const Model& model, const IntegratorOptions& options)
    : engine_(model, options, counters_), T_(model.period()) {}

void DormandPrince::restart(const State& u) { engine_.begin(u, mode_); }

IntegrationStatus DormandPrince::advance_period(State& u, Observer& obs) {
  double tau = 0.0;
  const IntegrationStatus status = engine_.advance(u, tau, T_, period_, obs, false, nullptr);
  mode_ = engine_.mode();
  if (status == IntegrationStatus::ok) ++period_;
  return status;
}

DormandPrinceVariational::DormandPrinceVariational(const Model& model, const IntegratorOptions& options)
    : engine_(model, options, counters_), T_(model.period()) {}

void DormandPrinceVariational::restart(const State& u) { engine_.begin(u, mode_); }

IntegrationStatus DormandPrinceVariational::advance_period(State& u, Observer& obs) {
  Augmented<5> y;
  y.col(0) = u;
  y.rightCols<4>() = phi_;
  double tau = 0.0;
  const IntegrationStatus status = engine_.advance(y, tau, T_, period_, obs, false, nullptr);
  mode_ = engine_.mode();
  if (status != IntegrationStatus::ok) return status;
  u = y.col(0);
  phi_ = y.rightCols<4>();
  ++period_;
  return status;
}

}  // namespace vibromap::detail
