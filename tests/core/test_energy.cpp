// Undamped, unforced, with contact: the Hertz force is conservative, so the total energy
// (kinetic + springs + (2/5) K z^(5/2)) stays constant over many impacts, to tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "vibromap/core/analysis/point/impact.hpp"
#include "vibromap/core/integrate/integrator.hpp"

using namespace vibromap;

namespace {
struct Drift : Observer {
  const Model* model;
  double e0 = 0.0, worst = 0.0;
  void on_event(const ContactEvent& e) override { check(e.u); }
  bool on_period_end(long, const State& u) override {
    check(u);
    return false;
  }
  void check(const State& u) { worst = std::max(worst, std::abs(model->energy(u) - e0) / e0); }
};

double energy_drift(double E, Method method, double rtol, long* impacts) {
  Parameters p;
  p.damper1 = {Damper::Form::coefficient, 0.0};
  p.damper2 = {Damper::Form::coefficient, 0.0};
  p.F0 = 0.0;
  p.E1 = p.E2 = E;
  p.initial = Eigen::Vector4d(0.0, p.D, 0.6, 0.0);
  const Model model(p);
  IntegratorOptions o;
  o.method = method;
  o.rtol = rtol;
  o.rk4_steps = 1 << 15;
  auto integ = make_integrator(model, o);
  State u = Model::to_internal(p.initial_state());
  integ->reset(u);
  ImpactRecorder rec(model, 1000);
  Drift drift;
  drift.model = &model;
  drift.e0 = model.energy(u);
  ObserverList obs{&rec, &drift};
  EXPECT_EQ(integrate_periods(*integ, u, 40, obs).status, IntegrationStatus::ok);
  *impacts = rec.total_impacts();
  return drift.worst;
}
}  // namespace

TEST(Energy, ConservedOverManyRigidImpacts) {
  long impacts = 0;
  const double drift = energy_drift(2.099e11, Method::dopri5, 1e-10, &impacts);
  EXPECT_GE(impacts, 20);
  EXPECT_LT(drift, 1e-7);
}

TEST(Energy, ConservedOverManySoftImpacts) {
  long impacts = 0;
  const double drift = energy_drift(1e6, Method::dopri5, 1e-10, &impacts);
  EXPECT_GE(impacts, 20);
  EXPECT_LT(drift, 1e-7);
}

TEST(Energy, DriftFallsWithTolerance) {
  long impacts = 0;
  const double loose = energy_drift(2.099e11, Method::dopri5, 1e-6, &impacts);
  const double tight = energy_drift(2.099e11, Method::dopri5, 1e-10, &impacts);
  EXPECT_LT(tight, loose / 100.0);
}
