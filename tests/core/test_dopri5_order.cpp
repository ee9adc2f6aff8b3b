// The dopri5 integrator's measured order of convergence on the smooth problem: the two bodies far
// apart (no contact) are a linear oscillator with harmonic forcing, whose exact solution is
// tests/problems/linear_oscillator.hpp.
//
// Fixed steps: with rtol near its upper bound and a huge atol every trial step passes the error
// test, so the step is always the largest allowed, max_step * T, and the engine is the plain
// Dormand-Prince 5(4) pair stepped at h = T / N (the counters prove it: N accepted steps, none
// rejected, 6 N + 1 right-hand sides with FSAL). The global error of a 5th-order method falls
// like h^5, so log2(err(h) / err(h/2)) -> 5; Shampine's continuous extension is 4th order
// (local error O(h^5)). On the linear autonomous variational equations Phi' = A Phi a step is
// exactly Phi <- R(hA) Phi with the method's stability polynomial R (Hairer & Wanner, "Solving
// ODEs II", IV.2: R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24 + z^5/120 + z^6/600 for DOPRI5).
// N >= 64: from T / 64 on, the first step (min(max_step, 1/64) T) is as long as the others.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "problems/linear_oscillator.hpp"
#include "vibromap/core/integrate/integrator.hpp"

using namespace vibromap;

namespace {

// Each order measured between two step counts must lie within this of the method's order.
constexpr double kOrderSlack = 0.5;

Parameters far_apart() {
  Parameters p;
  p.D = 10.0;  // z stays near -10 m: never a contact
  p.phi0 = 0.4;
  p.initial = Eigen::Vector4d(0.02, 10.0, -0.05, 0.1);
  return p;
}

// Options under which every step of dopri5 is exactly T / steps.
IntegratorOptions fixed_steps(int steps) {
  IntegratorOptions o;
  o.method = Method::dopri5;
  o.rtol = 0.099;  // the largest valid (validate(): rtol < 0.1)
  o.atol = 1e6;    // m: the error estimate is always far below 1
  o.max_step = 1.0 / steps;
  return o;
}

// The largest error of a component, in m and m/s (relative errors would swell where a component
// passes through 0 and hide the order).
double scaled_error(const State& u, const State& exact) { return (u - exact).cwiseAbs().maxCoeff(); }

std::vector<double> measured_orders(const std::vector<int>& steps, const std::vector<double>& errors) {
  std::vector<double> orders;
  for (std::size_t i = 1; i < errors.size(); ++i)
    orders.push_back(std::log(errors[i - 1] / errors[i]) / std::log(double(steps[i]) / steps[i - 1]));
  return orders;
}

// Keeps the largest error of the dense output at the middle of every step (period 0: tau = t).
class MidStepError final : public Observer {
 public:
  MidStepError(const test::LinearOscillator& exact, const State& u0) : exact_(exact), u0_(u0) {}
  void on_step(const StepView& step) override {
    const double mid = 0.5 * (step.tau0 + step.tau1);
    worst_ = std::max(worst_, scaled_error(step.eval(mid), exact_.solution(u0_, mid)));
  }
  double worst() const { return worst_; }

 private:
  const test::LinearOscillator& exact_;
  State u0_;
  double worst_ = 0.0;
};

const std::vector<int> kSteps = {64, 128, 256};

}  // namespace

TEST(Dopri5Order, FixedStepOptionsGiveExactlyNStepsPerPeriod) {
  const Model model(far_apart());
  for (int steps : kSteps) {
    auto integ = make_integrator(model, fixed_steps(steps));
    State u = Model::to_internal(far_apart().initial_state());
    integ->reset(u);
    Observer none;
    ASSERT_EQ(integ->advance_period(u, none), IntegrationStatus::ok);
    EXPECT_EQ(integ->counters().steps, steps);
    EXPECT_EQ(integ->counters().rejected, 0);
    EXPECT_EQ(integ->counters().rhs_evals, 6L * steps + 1);  // FSAL: one start, then 6 per step
    EXPECT_EQ(integ->counters().events, 0);
  }
}

TEST(Dopri5Order, GlobalErrorFallsLikeHToTheFifth) {
  const Model model(far_apart());
  const test::LinearOscillator exact(model);
  const State u0 = Model::to_internal(far_apart().initial_state());
  const State ref = exact.solution(u0, model.period());
  std::vector<double> errors;
  for (int steps : kSteps) {
    auto integ = make_integrator(model, fixed_steps(steps));
    State u = u0;
    integ->reset(u);
    Observer none;
    ASSERT_EQ(integ->advance_period(u, none), IntegrationStatus::ok);
    errors.push_back(scaled_error(u, ref));
  }
  // Round-off (1e-16 per step) must not reach the finest error, or the order would be meaningless.
  ASSERT_GT(errors.back(), 1e-12);
  const std::vector<double> orders = measured_orders(kSteps, errors);
  for (std::size_t i = 0; i < orders.size(); ++i) {
    EXPECT_NEAR(orders[i], 5.0, kOrderSlack) << "steps " << kSteps[i] << " -> " << kSteps[i + 1] << ": errors "
                                             << errors[i] << ", " << errors[i + 1];
    std::printf("dopri5 global order, %d -> %d steps: %.3f (errors %.3e -> %.3e)\n", kSteps[i], kSteps[i + 1],
                orders[i], errors[i], errors[i + 1]);
  }
}

TEST(Dopri5Order, DenseOutputErrorFallsAtLeastLikeHToTheFourth) {
  const Model model(far_apart());
  const test::LinearOscillator exact(model);
  const State u0 = Model::to_internal(far_apart().initial_state());
  std::vector<double> errors;
  for (int steps : kSteps) {
    auto integ = make_integrator(model, fixed_steps(steps));
    State u = u0;
    integ->reset(u);
    MidStepError mid(exact, u0);
    ASSERT_EQ(integ->advance_period(u, mid), IntegrationStatus::ok);
    errors.push_back(mid.worst());
  }
  ASSERT_GT(errors.back(), 1e-12);
  const std::vector<double> orders = measured_orders(kSteps, errors);
  for (std::size_t i = 0; i < orders.size(); ++i) {
    // A 4th-order interpolant: local error O(h^5), never worse than h^4 globally.
    EXPECT_GE(orders[i], 4.0 - kOrderSlack) << "steps " << kSteps[i];
    EXPECT_LE(orders[i], 5.0 + kOrderSlack) << "steps " << kSteps[i];
    std::printf("dopri5 dense output order, %d -> %d steps: %.3f (errors %.3e -> %.3e)\n", kSteps[i],
                kSteps[i + 1], orders[i], errors[i], errors[i + 1]);
  }
}

// DOPRI5's stability polynomial R(z) at a matrix.
Eigen::Matrix4d stability_polynomial(const Eigen::Matrix4d& Z) {
  const double c[] = {1.0, 1.0, 1.0 / 2, 1.0 / 6, 1.0 / 24, 1.0 / 120, 1.0 / 600};
  Eigen::Matrix4d R = c[6] * Eigen::Matrix4d::Identity();
  for (int k = 5; k >= 0; --k) R = R * Z + c[k] * Eigen::Matrix4d::Identity();  // Horner
  return R;
}

// The variational solution Phi = du(T)/du0 of the linear system after N fixed steps is R(hA)^N,
// to rounding, and e^{AT} to the method's order (the reference's columns are differences of
// exact solutions: the flow is affine in u0).
TEST(Dopri5Order, VariationalSolutionIsTheStabilityPolynomialToThePowerN) {
  const Model model(far_apart());
  const test::LinearOscillator exact(model);
  const double T = model.period();
  Eigen::Matrix4d flow;
  for (int j = 0; j < 4; ++j) flow.col(j) = exact.solution(State::Unit(j), T) - exact.solution(State::Zero(), T);
  for (int steps : kSteps) {
    auto integ = make_variational_integrator(model, fixed_steps(steps));
    State u = Model::to_internal(far_apart().initial_state());
    integ->reset(u);
    integ->reset_jacobian();
    Observer none;
    ASSERT_EQ(integ->advance_period(u, none), IntegrationStatus::ok);
    ASSERT_EQ(integ->counters().steps, steps);
    ASSERT_EQ(integ->counters().rejected, 0);
    Eigen::Matrix4d R_N = Eigen::Matrix4d::Identity();
    const Eigen::Matrix4d R = stability_polynomial(exact.matrix() * (T / steps));
    for (int i = 0; i < steps; ++i) R_N = R * R_N;
    const double size = flow.cwiseAbs().maxCoeff();
    const double vs_polynomial = (integ->jacobian() - R_N).cwiseAbs().maxCoeff() / size;
    const double vs_flow = (integ->jacobian() - flow).cwiseAbs().maxCoeff() / size;
    EXPECT_LT(vs_polynomial, 1e-13) << steps << " steps";
    // ... and R(hA)^N differs from e^{AT} by the method's error, above that rounding (measured:
    // 5e-9, 1e-10, 4e-12 against 1e-14 .. 3e-14 at 64, 128, 256 steps).
    EXPECT_GT(vs_flow, 30.0 * vs_polynomial) << steps << " steps";
    std::printf("dopri5 variational, %d steps: |Phi - R(hA)^N| %.2e, |Phi - e^(AT)| %.2e (relative)\n", steps,
                vs_polynomial, vs_flow);
  }
}
