#pragma once
// Internal to solve_point (point_solver.cpp): the observer that records a trajectory
// (analysis.trajectory_periods, `vibromap run --trajectory`).

#include <cmath>
#include <vector>

#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/integrate/observer.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap::detail {

// Keeps uniform samples of each period plus extra samples inside contact steps (a rigid
// contact lasts ~1e-3 T and would fall between uniform samples) and the event points.
class TrajectoryRecorder final : public Observer {
 public:
  TrajectoryRecorder(const Model& model, long first_period, int samples_per_period,
                     std::vector<TrajectorySample>& out)
      : model_(model), first_(first_period), dt_(model.period() / samples_per_period), out_(out) {}

  void on_step(const StepView& step) override {
    const double offset = static_cast<double>(step.period - first_) * model_.period();
    // Uniform grid points in (tau0, tau1].
    for (double tau = std::floor(step.tau0 / dt_ + 1.0) * dt_; tau <= step.tau1; tau += dt_) {
      if (step.mode == ContactMode::contact) break;  // contact steps are sampled densely below
      add(offset + tau, step.eval(tau), tau);
    }
    if (step.mode == ContactMode::contact) {
      constexpr int kPerStep = 8;
      for (int i = 1; i <= kPerStep; ++i) {
        const double tau = step.tau0 + (step.tau1 - step.tau0) * i / kPerStep;
        add(offset + tau, step.eval(tau), tau);
      }
    }
  }
  void on_event(const ContactEvent& e) override {
    if (e.kind == ContactEvent::Kind::entry) v_in_ = model_.entry_speed(e.u);
    add(static_cast<double>(e.period - first_) * model_.period() + e.tau, e.u, e.tau);
  }

 private:
  void add(double t, const State& u, double tau) {
    if (!out_.empty() && t <= out_.back().t) return;
    const Eigen::Vector4d x = Model::to_physical(u);
    if (v_in_ <= 0.0) v_in_ = model_.entry_speed(u);  // the window opened inside a contact
    out_.push_back({t, x[0], x[1], x[2], x[3], model_.contact().force(u[1], u[3], v_in_), model_.forcing(tau)});
  }
  double v_in_ = 0.0;  // the current contact's entry speed (a dissipative law's force reads it)
  const Model& model_;
  long first_;
  double dt_;
  std::vector<TrajectorySample>& out_;
};

}  // namespace vibromap::detail
