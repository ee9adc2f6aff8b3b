// The paper's fixed-step RK4 on the smooth (contact-free) problem: 4th order, so the error
// after one period falls by 2^4 = 16 when the step halves.
#include <gtest/gtest.h>

#include <cmath>

#include "problems/linear_oscillator.hpp"
#include "vibromap/core/integrate/integrator.hpp"

using namespace vibromap;

TEST(Rk4, ErrorFallsSixteenfoldWhenStepHalves) {
  Parameters p;
  p.D = 10.0;
  p.initial = Eigen::Vector4d(0.02, 10.0, -0.05, 0.1);
  const Model model(p);
  const test::LinearOscillator exact(model);
  const State u0 = Model::to_internal(p.initial_state());
  const Eigen::Vector4d ref = exact.solution(u0, model.period());
  std::vector<double> errors;
  for (int steps : {32, 64, 128, 256}) {
    IntegratorOptions o;
    o.method = Method::rk4;
    o.rk4_steps = steps;
    auto integ = make_integrator(model, o);
    State u = u0;
    integ->reset(u);
    Observer none;
    ASSERT_EQ(integ->advance_period(u, none), IntegrationStatus::ok);
    EXPECT_EQ(integ->counters().rhs_evals, 4L * steps + 1);
    errors.push_back((u - ref).norm());
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double ratio = errors[i - 1] / errors[i];
    EXPECT_NEAR(ratio, 16.0, 1.5) << "steps " << (32 << i);
  }
}
