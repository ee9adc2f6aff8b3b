// hybrid: closed-form free flight between impacts, dopri5 in contact. See integrator.hpp
// and free_flight.hpp.

#include "steppers.hpp"
#include "vibromap/core/integrate/cancel.hpp"

namespace vibromap::detail {

namespace {
// The free flight's continuous extension is the closed form itself, from the flight's modal
// amplitudes (FreeFlight::fly computed them).
class FreeFlightDense final : public DenseOutput {
 public:
  FreeFlightDense(const FreeFlight& flight, double tau0, const FreeFlight::Modes& alpha)
      : flight_(flight), tau0_(tau0), alpha_(alpha) {}
  State eval(double tau) const override { return flight_.propagate(alpha_, tau0_, tau); }

 private:
  const FreeFlight& flight_;
  double tau0_;
  const FreeFlight::Modes& alpha_;
};
}  // namespace

template <int Cols>
Hybrid<Cols>::Hybrid(const Model& model, const IntegratorOptions& options, std::shared_ptr<const FreeFlight> flight)
    : flight_(std::move(flight)), engine_(model, options, counters_), opt_(options), T_(model.period()) {}

template <int Cols>
void Hybrid<Cols>::restart(const State& u) { engine_.begin(u, mode_); }

template <int Cols>
IntegrationStatus Hybrid<Cols>::advance_period(State& u, Observer& obs) {
  double tau = 0.0;
  while (tau < T_) {
    const long taken = counters_.steps + counters_.rejected;
    if (taken >= opt_.max_steps) return IntegrationStatus::step_limit;
    poll_cancel(taken);
    const IntegrationStatus status =
        mode_ == ContactMode::free ? free_phase(u, tau, obs) : contact_phase(u, tau, obs);
    if (status != IntegrationStatus::ok) return status;
  }
  ++period_;
  return IntegrationStatus::ok;
}

// From tau to the next contact entry or the period's end, in closed form.
template <int Cols>
IntegrationStatus Hybrid<Cols>::free_phase(State& u, double& tau, Observer& obs) {
  const FreeFlight::Flight flight = flight_->fly(tau, u, T_);
  const std::optional<double>& entry = flight.entry;
  const double tau1 = entry ? *entry : T_;
  const FreeFlightDense dense(*flight_, tau, flight.alpha);
  obs.on_step({period_, tau, tau1, ContactMode::free, &dense});
  const State& u1 = flight.u;
  if (!u1.allFinite()) return IntegrationStatus::non_finite;
  if constexpr (Cols > 1) phi_ = flight_->transition(tau1 - tau) * phi_;
  u = u1;
  tau = tau1;
  ++counters_.steps;
  if (entry) {
    u[1] = 0.0;
    mode_ = ContactMode::contact;
    ++counters_.events;
    obs.on_event({ContactEvent::Kind::entry, period_, tau, u});
    Augmented<Cols> y;
    y.col(0) = u;
    if constexpr (Cols > 1) y.template rightCols<4>() = phi_;
    engine_.enter_contact(tau, y);
  }
  return IntegrationStatus::ok;
}

// From tau to the contact's exit or the period's end, by dopri5.
template <int Cols>
IntegrationStatus Hybrid<Cols>::contact_phase(State& u, double& tau, Observer& obs) {
  Augmented<Cols> y;
  y.col(0) = u;
  if constexpr (Cols > 1) y.template rightCols<4>() = phi_;
  bool exited = false;
  const IntegrationStatus status = engine_.advance(y, tau, T_, period_, obs, true, &exited);
  if (status != IntegrationStatus::ok) return status;
  u = y.col(0);
  if constexpr (Cols > 1) phi_ = y.template rightCols<4>();
  if (exited) mode_ = ContactMode::free;
  return IntegrationStatus::ok;
}

template class Hybrid<1>;
template class Hybrid<5>;

}  // namespace vibromap::detail
