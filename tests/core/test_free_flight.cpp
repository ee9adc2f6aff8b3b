// Free flight: with the clearance too large for contact, the system is linear and the
// adaptive integrator must match the closed-form solution (tests/problems/linear_oscillator.hpp).
#include <gtest/gtest.h>

#include "problems/linear_oscillator.hpp"
#include "vibromap/core/integrate/integrator.hpp"

using namespace vibromap;

namespace {
Parameters no_contact_point() {
  Parameters p;
  p.D = 10.0;  // far beyond the ~0.1 m amplitude
  p.phi0 = 0.4;
  p.initial = Eigen::Vector4d(0.02, 10.0, -0.05, 0.1);
  return p;
}

double max_relative_error(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  return ((a - b).array().abs() / (b.array().abs() + 1e-3)).maxCoeff();
}
}  // namespace

TEST(FreeFlight, AdaptiveMatchesClosedFormOverTenPeriods) {
  const Parameters p = no_contact_point();
  const Model model(p);
  const test::LinearOscillator exact(model);
  IntegratorOptions o;
  o.method = Method::dopri5;
  o.rtol = 1e-12;
  auto integ = make_integrator(model, o);
  State u = Model::to_internal(p.initial_state());
  const State u0 = u;
  integ->reset(u);
  Observer none;
  for (int j = 1; j <= 10; ++j) {
    ASSERT_EQ(integ->advance_period(u, none), IntegrationStatus::ok);
    EXPECT_LT(max_relative_error(u, exact.solution(u0, j * model.period())), 1e-9) << "period " << j;
  }
  EXPECT_EQ(integ->counters().events, 0);
}

TEST(FreeFlight, ErrorFollowsToleranceAndDenseOutputIsAccurate) {
  const Parameters p = no_contact_point();
  const Model model(p);
  const test::LinearOscillator exact(model);
  // Dense output inside steps: compare every step midpoint with the closed form.
  struct Midpoints : Observer {
    const test::LinearOscillator* exact;
    State u0;
    double worst = 0.0;
    void on_step(const StepView& s) override {
      const double tau = 0.5 * (s.tau0 + s.tau1);
      const Eigen::Vector4d ref = exact->solution(u0, tau);
      worst = std::max(worst, ((s.eval(tau) - ref).array().abs() / (ref.array().abs() + 1e-3)).maxCoeff());
    }
  };
  double previous = 1.0;
  for (double rtol : {1e-6, 1e-8, 1e-10}) {
    IntegratorOptions o;
    o.method = Method::dopri5;
    o.rtol = rtol;
    auto integ = make_integrator(model, o);
    State u = Model::to_internal(p.initial_state());
    Midpoints mid;
    mid.exact = &exact;
    mid.u0 = u;
    integ->reset(u);
    ASSERT_EQ(integ->advance_period(u, mid), IntegrationStatus::ok);
    const double err = max_relative_error(u, exact.solution(mid.u0, model.period()));
    EXPECT_LT(err, 100 * rtol) << "rtol " << rtol;
    EXPECT_LT(mid.worst, 1000 * rtol) << "dense output, rtol " << rtol;
    EXPECT_LT(err, previous);
    previous = err;
  }
}

// Hybrid integrators of one model share its free-flight decomposition; integrators of
// models made one after another (a sweep's cells) must each follow their own closed form.
TEST(FreeFlight, HybridIntegratorsOfAlternatingModelsFollowTheirOwnClosedForm) {
  Parameters pa = no_contact_point(), pb = no_contact_point();
  pb.m2 = 250.0;
  pb.D = 12.0;
  const Model ma(pa), mb(pb);
  const test::LinearOscillator exact_a(ma), exact_b(mb);
  IntegratorOptions o;  // hybrid
  Observer none;
  for (int round = 0; round < 2; ++round) {
    for (const auto* m : {&ma, &mb}) {
      const Parameters& p = m->parameters();
      auto integ = make_integrator(*m, o);
      State u = Model::to_internal(p.initial_state());
      const State u0 = u;
      integ->reset(u);
      ASSERT_EQ(integ->advance_period(u, none), IntegrationStatus::ok);
      const auto& exact = m == &ma ? exact_a : exact_b;
      EXPECT_LT(max_relative_error(u, exact.solution(u0, m->period())), 1e-12) << "round " << round << ", m2 " << p.m2;
    }
  }
}
