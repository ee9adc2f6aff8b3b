#include "vibromap/core/analysis/point/impact.hpp"

#include <array>
#include <cmath>

#include "vibromap/core/analysis/point/steady_state.hpp"
#include "vibromap/core/integrate/root_finding.hpp"

namespace vibromap {

// Chatter is decided on counts of at most kMaxChatterImpacts * n_max impacts, all of them kept.
static_assert(std::size_t{ImpactRecorder::kMaxChatterImpacts} * SteadyStateDetector::kMaxN < ImpactRecorder::kMaxKept);

namespace {
// 4-point Gauss-Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun 25.4.30).
constexpr std::array<double, 4> kGaussNodes = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                               0.8611363115940526};
constexpr std::array<double, 4> kGaussWeights = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                                 0.3478548451374538};
}  // namespace

ImpactRecorder::ImpactRecorder(const Model& model, long keep_periods)
    : model_(model), keep_periods_(keep_periods) {}

void ImpactRecorder::on_step(const StepView& step) {
  if (!open_ || !measuring_ || step.tau1 <= step.tau0) return;
  const HertzContact& contact = model_.contact();
  const double half = 0.5 * (step.tau1 - step.tau0), mid = 0.5 * (step.tau1 + step.tau0);
  double impulse = 0.0, dissipated = 0.0;
  for (std::size_t i = 0; i < kGaussNodes.size(); ++i) {
    const State u = step.eval(mid + half * kGaussNodes[i]);
    const double f = contact.force(u[1], u[3], law_entry_speed_);
    impulse += kGaussWeights[i] * f;
    if (!contact.dissipative()) continue;
    dissipated += kGaussWeights[i] * (f - contact.force(u[1])) * u[3];
    open_->F_max = std::max(open_->F_max, f);
    open_->clipped = open_->clipped || contact.clipped(u[1], u[3], law_entry_speed_);
  }
  open_->impulse += half * impulse;
  open_->energy_dissipated += half * dissipated;
  if (contact.dissipative()) {
    const State end = step.eval(step.tau1);
    open_->clipped = open_->clipped || contact.clipped(end[1], end[3], law_entry_speed_);
  }
  track_peak(step);
}

// The peak of z within a contact step is either at an end or where w = z' changes sign
// from + to -; the latter is located as a root of w on the dense output.
void ImpactRecorder::track_peak(const StepView& step) {
  const State u0 = step.eval(step.tau0), u1 = step.eval(step.tau1);
  double z_peak = std::max(u0[1], u1[1]);
  if (u0[3] > 0.0 && u1[3] < 0.0) {
    auto minus_w = [&](double t) { return -step.eval(t)[3]; };
    const double tol = 1e-15 * (std::abs(step.tau1) + 1.0);
    const double t_peak = illinois(minus_w, step.tau0, step.tau1, -u0[3], -u1[3], tol).x;
    z_peak = std::max(z_peak, step.eval(t_peak)[1]);
  }
  open_->z_max = std::max(open_->z_max, z_peak);
}

void ImpactRecorder::on_event(const ContactEvent& event) {
  if (event.kind == ContactEvent::Kind::entry) {
    open_ = Impact{};
    open_->period_in = event.period;
    open_->tau_in = event.tau;
    open_->v_in = event.u[3];
    law_entry_speed_ = model_.entry_speed(event.u);
    return;
  }
  if (!open_) return;  // exit of a contact that began before recording started
  Impact& im = *open_;
  im.period_out = event.period;
  im.tau_out = event.tau;
  im.v_out = event.u[3];
  im.e_effective = im.v_in != 0.0 ? std::abs(im.v_out / im.v_in) : 0.0;
  // Durations from per-period times: (whole periods) T + (difference of local times).
  im.T_con = static_cast<double>(im.period_out - im.period_in) * model_.period() + (im.tau_out - im.tau_in);
  // At z_max the approach rate is 0, so a damped force equals the elastic one there; it peaks
  // earlier, while w > 0, and F_max keeps the largest of that and the quadrature nodes' forces.
  im.F_max = std::max(im.F_max, model_.contact().force(im.z_max));
  im.z_ratio = im.z_max / model_.contact().effective_radius();
  impacts_.push_back(im);
  if (impacts_.size() > kMaxKept) impacts_.pop_front();
  open_.reset();
  ++total_;
}

bool ImpactRecorder::on_period_end(long period, const State& /*u*/) {
  while (!impacts_.empty() && impacts_.front().period_in < period + 1 - keep_periods_) impacts_.pop_front();
  return false;
}

}  // namespace vibromap
