// The source paper's method: classical RK4 with a fixed step h = T / rk4_steps and the
// Hertz force K max(z, 0)^(3/2) always in the right-hand side. Contact entries and exits
// are located after each step on a cubic Hermite interpolant (end values and slopes), only
// for measurement: the steps themselves run through the kink of z^(3/2), which is why the
// method's order collapses at contact (docs/numerics.md).

#include <cmath>

#include "steppers.hpp"
#include "vibromap/core/integrate/cancel.hpp"
#include "vibromap/core/integrate/event_locator.hpp"

namespace vibromap::detail {

State HermiteDense::eval(double tau) const {
  const double s = (tau - tau0_) / h_;
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  return h00 * y0_ + (h10 * h_) * f0_ + h01 * y1_ + (h11 * h_) * f1_;
}

void HermiteDense::prepare(double tau0, double h, const State& y0, const State& f0, const State& y1,
                           const State& f1) {
  tau0_ = tau0;
  h_ = h;
  y0_ = y0;
  f0_ = f0;
  y1_ = y1;
  f1_ = f1;
}

ClassicalRk4::ClassicalRk4(const Model& model, const IntegratorOptions& options)
    : model_(model), opt_(options), T_(model.period()) {}

void ClassicalRk4::rhs(double tau, const State& u, State& dudt) {
  model_.rhs(tau, u, ContactMode::contact, v_in_, dudt);
  ++counters_.rhs_evals;
}

IntegrationStatus ClassicalRk4::advance_period(State& u, Observer& obs) {
  const long n = opt_.rk4_steps;
  const double h = T_ / static_cast<double>(n);
  if (v_in_ <= 0.0) v_in_ = model_.entry_speed(u);  // never reset(): no entry known
  if (!f_valid_) {
    rhs(0.0, u, f_);
    f_valid_ = true;
  }
  State k2, k3, k4, u_new, f_new;
  for (long i = 0; i < n; ++i) {
    if (counters_.steps >= opt_.max_steps) return IntegrationStatus::step_limit;
    poll_cancel(counters_.steps);
    // tau from the step index, not by accumulation, so rounding does not drift.
    const double tau = T_ * static_cast<double>(i) / static_cast<double>(n);
    const double tau1 = i + 1 == n ? T_ : T_ * static_cast<double>(i + 1) / static_cast<double>(n);
    // A dissipative law's v_in: the approach rate at the last step start before the contact
    // (first order in h, like the method's accuracy at contact).
    if (u[1] <= 0.0 || v_in_ <= 0.0) v_in_ = model_.entry_speed(u);
    rhs(tau + 0.5 * h, u + 0.5 * h * f_, k2);
    rhs(tau + 0.5 * h, u + 0.5 * h * k2, k3);
    rhs(tau1, u + h * k3, k4);
    u_new = u + (h / 6.0) * (f_ + 2.0 * k2 + 2.0 * k3 + k4);
    if (!u_new.allFinite()) return IntegrationStatus::non_finite;
    rhs(tau1, u_new, f_new);
    dense_.prepare(tau, tau1 - tau, u, f_, u_new, f_new);
    report_step(tau, tau1, obs);
    u = u_new;
    f_ = f_new;
    ++counters_.steps;
  }
  ++period_;
  return IntegrationStatus::ok;
}

// Reports [tau0, tau1] to the observer, split at every contact entry or exit found on the
// Hermite interpolant, with the mode tracking the sign of z.
void ClassicalRk4::report_step(double tau0, double tau1, Observer& obs) {
  double start = tau0;
  for (int guard = 0; guard < 8; ++guard) {
    const auto event = locate_contact_event(dense_, start, tau1, mode_, 4e-16 * T_);
    if (!event || event->tau >= tau1) break;
    if (event->tau > start) obs.on_step({period_, start, event->tau, mode_, &dense_});
    const bool entering = mode_ == ContactMode::free;
    mode_ = entering ? ContactMode::contact : ContactMode::free;
    ++counters_.events;
    obs.on_event({entering ? ContactEvent::Kind::entry : ContactEvent::Kind::exit, period_, event->tau,
                  dense_.eval(event->tau)});
    start = event->tau;
  }
  obs.on_step({period_, start, tau1, mode_, &dense_});
}

}  // namespace vibromap::detail
