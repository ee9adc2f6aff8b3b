#pragma once
// Internal: the concrete integrators behind make_integrator().

#include <array>
#include <memory>

#include "dp5_engine.hpp"
#include "vibromap/core/integrate/free_flight.hpp"
#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap::detail {

// dopri5 over whole periods, both contact modes, events located and stepped to.
class DormandPrince final : public Integrator {
 public:
  DormandPrince(const Model& model, const IntegratorOptions& options);
  IntegrationStatus advance_period(State& u, Observer& obs) override;
  void set_rtol(double rtol) override { engine_.set_rtol(rtol); }
  void set_max_steps(long max_steps) override { engine_.set_max_steps(max_steps); }

 private:
  void restart(const State& u) override;
  Dp5Engine<1> engine_;
  double T_;
};

// dopri5 over whole periods with the variational equations alongside.
class DormandPrinceVariational final : public VariationalIntegrator {
 public:
  DormandPrinceVariational(const Model& model, const IntegratorOptions& options);
  IntegrationStatus advance_period(State& u, Observer& obs) override;
  void set_rtol(double rtol) override { engine_.set_rtol(rtol); }
  void set_max_steps(long max_steps) override { engine_.set_max_steps(max_steps); }
  const Eigen::Matrix4d& jacobian() const override { return phi_; }
  void reset_jacobian() override {
    phi_.setIdentity();
    engine_.restart();
    engine_.reset_entry_sensitivity();
  }

 private:
  void restart(const State& u) override;
  Dp5Engine<5> engine_;
  double T_;
  Eigen::Matrix4d phi_ = Eigen::Matrix4d::Identity();
};

// hybrid: closed-form free flight (FreeFlight), dopri5 only in contact. Cols = 1: the state
// alone; Cols = 5: with the variational solution (VariationalIntegrator).
template <int Cols>
class Hybrid final : public VariationalIntegrator {
 public:
  Hybrid(const Model& model, const IntegratorOptions& options, std::shared_ptr<const FreeFlight> flight);
  IntegrationStatus advance_period(State& u, Observer& obs) override;
  void set_rtol(double rtol) override { engine_.set_rtol(rtol); }
  void set_max_steps(long max_steps) override {
    opt_.max_steps = max_steps;
    engine_.set_max_steps(max_steps);
  }
  const Eigen::Matrix4d& jacobian() const override { return phi_; }
  void reset_jacobian() override {
    phi_.setIdentity();
    engine_.reset_entry_sensitivity();
  }

 private:
  void restart(const State& u) override;
  IntegrationStatus free_phase(State& u, double& tau, Observer& obs);
  IntegrationStatus contact_phase(State& u, double& tau, Observer& obs);
  std::shared_ptr<const FreeFlight> flight_;  // shared by every integrator of the model
  Dp5Engine<Cols> engine_;
  IntegratorOptions opt_;
  double T_;
  Eigen::Matrix4d phi_ = Eigen::Matrix4d::Identity();
};

// Cubic Hermite interpolant of a step from its end values and derivatives.
class HermiteDense final : public DenseOutput {
 public:
  void prepare(double tau0, double h, const State& y0, const State& f0, const State& y1, const State& f1);
  State eval(double tau) const override;

 private:
  double tau0_ = 0.0, h_ = 1.0;
  State y0_, f0_, y1_, f1_;
};

// The source paper's fixed-step classical RK4, contact force always in the right-hand side.
class ClassicalRk4 final : public Integrator {
 public:
  ClassicalRk4(const Model& model, const IntegratorOptions& options);
  IntegrationStatus advance_period(State& u, Observer& obs) override;
  void set_max_steps(long max_steps) override { opt_.max_steps = max_steps; }

 private:
  void restart(const State& u) override {
    f_valid_ = false;
    v_in_ = model_.entry_speed(u);
  }
  void rhs(double tau, const State& u, State& dudt);
  void report_step(double tau0, double tau1, Observer& obs);

  const Model& model_;
  IntegratorOptions opt_;
  double T_;
  bool f_valid_ = false;
  double v_in_ = 0.0;  // approach rate at the current contact's entry (dissipative laws), m/s
  State f_;  // f(tau, u) at the current point
  HermiteDense dense_;
};

}  // namespace vibromap::detail
