#pragma once
// One impact: a maximal time interval with approach z > 0 (docs/model.md), and the observer that
// measures impacts from an integrator's steps and events.
//
// Peak penetration is found where w = z' changes sign inside a contact step (a root of w on
// the dense output), the impulse by 4-point Gauss-Legendre quadrature of Fc(z(t)) on each
// contact step's dense output. With a dissipative contact law the same quadrature gives the
// energy the contact dissipates, the integral of the damping force (Fc minus its elastic
// part K z^(3/2)) times the approach rate w; the effective restitution is |w_out / w_in|.

#include <cstddef>
#include <deque>
#include <optional>

#include "vibromap/core/integrate/observer.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap {

struct Impact {
  long period_in = 0;    // forcing period (0-based) of contact entry
  double tau_in = 0.0;   // entry time since the start of that period, s
  long period_out = 0;   // forcing period of contact exit
  double tau_out = 0.0;  // exit time since the start of that period, s
  double T_con = 0.0;    // contact duration, s
  double F_max = 0.0;    // peak contact force (a damped law: the largest sampled on the steps' quadrature nodes), N
  double z_max = 0.0;    // peak penetration (approach), m
  double z_ratio = 0.0;  // z_max / R*: Hertz validity needs it small, -
  double v_in = 0.0;     // relative approach velocity at entry, m/s
  double impulse = 0.0;  // integral of the contact force over the impact, N s
  double v_out = 0.0;    // relative approach velocity at exit (< 0 when the bodies separate), m/s
  double e_effective = 0.0;        // effective restitution |v_out / v_in|, -
  double energy_dissipated = 0.0;  // integral of (Fc - K z^(3/2)) w over the impact, J
  bool clipped = false;  // the damped force was clipped at 0 (it would have pulled) somewhere

  // Entry and exit as times since t = 0 (for output only: durations use the per-period times).
  double t_in(double T) const { return static_cast<double>(period_in) * T + tau_in; }
  double t_out(double T) const { return static_cast<double>(period_out) * T + tau_out; }
};

// Collects the impacts completed in the last `keep_periods` forcing periods (older ones are
// dropped so long runs use bounded memory), and the one in progress. At most kMaxKept are
// kept (the oldest dropped first): a motion with that many impacts in a few periods (near-
// undamped grazing contact) is chatter by every count that is made of them (chatter_impacts
// is at most kMaxChatterImpacts, and kMaxChatterImpacts * kMaxN < kMaxKept), and its memory
// stays bounded (about 130 MB) instead of growing with the step budget.
class ImpactRecorder final : public Observer {
 public:
  static constexpr std::size_t kMaxKept = std::size_t{1} << 20;
  static constexpr int kMaxChatterImpacts = 10'000;

  ImpactRecorder(const Model& model, long keep_periods);

  void on_step(const StepView& step) override;
  void on_event(const ContactEvent& event) override;
  bool on_period_end(long period, const State& u) override;

  // Forgets the impacts kept and the one in progress (a new motion starts).
  void clear() {
    impacts_.clear();
    open_.reset();
  }
  // With measuring off, impacts keep their times and speeds only (no peak, impulse, force or
  // dissipation: the per-step quadrature is skipped), for a follower that needs no more.
  void set_measuring(bool on) { measuring_ = on; }
  const std::deque<Impact>& impacts() const { return impacts_; }
  const std::optional<Impact>& open_impact() const { return open_; }
  long total_impacts() const { return total_; }

 private:
  void track_peak(const StepView& step);
  double law_entry_speed_ = 0.0;  // the open impact's v_in as the contact law uses it
  const Model& model_;
  long keep_periods_;
  std::deque<Impact> impacts_;
  std::optional<Impact> open_;
  long total_ = 0;
  bool measuring_ = true;
};

}  // namespace vibromap
