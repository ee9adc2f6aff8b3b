// Cancelling an integration from outside (core/integrate/cancel.hpp): inside a CancelScope whose flag is
// set, every method's step loop throws Cancelled within kCancelPollSteps steps; outside a
// scope, or with the flag clear, the run is the same as without the hook.
#include <gtest/gtest.h>

#include <atomic>

#include "vibromap/core/integrate/cancel.hpp"
#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap {
namespace {

// Sets `flag` once the integrator has taken `after` steps.
class SetFlagAfter final : public Observer {
 public:
  SetFlagAfter(const Integrator& integ, std::atomic<int>& flag, long after) : integ_(integ), flag_(flag), after_(after) {}
  void on_step(const StepView&) override {
    if (integ_.counters().steps + integ_.counters().rejected >= after_) flag_.store(15);
  }

 private:
  const Integrator& integ_;
  std::atomic<int>& flag_;
  long after_;
};

// Table 1 with dopri5 at a tight tolerance and a step budget far beyond what the test runs:
// only a cancellation ends it early.
IntegratorOptions long_run(Method method) {
  IntegratorOptions o;
  o.method = method;
  o.rtol = 1e-12;
  o.rk4_steps = 4096;
  o.max_steps = 1'000'000'000;
  return o;
}

constexpr long kSetAt = 1000;   // steps before the flag is set
constexpr long kPeriods = 400;  // periods of the run (some 10^5 steps or more)

long periods_before_cancel(Method method, std::atomic<int>& flag, long& steps) {
  const Parameters p;
  const Model model(p);
  auto integ = make_integrator(model, long_run(method));
  State u = Model::to_internal(p.initial_state());
  integ->reset(u);
  SetFlagAfter observer(*integ, flag, kSetAt);
  long periods = 0;
  try {
    for (; periods < kPeriods; ++periods) EXPECT_EQ(integ->advance_period(u, observer), IntegrationStatus::ok);
  } catch (const Cancelled&) {
    steps = integ->counters().steps + integ->counters().rejected;
    throw;
  }
  steps = integ->counters().steps + integ->counters().rejected;
  return periods;
}

TEST(Cancel, EveryMethodStopsWithinAPollIntervalOfTheFlag) {
  for (const Method method : {Method::hybrid, Method::dopri5, Method::rk4}) {
    std::atomic<int> flag{0};
    const CancelScope scope(&flag);
    long steps = 0;
    EXPECT_THROW(periods_before_cancel(method, flag, steps), Cancelled) << to_string(method);
    EXPECT_GE(steps, kSetAt) << to_string(method);
    EXPECT_LE(steps, kSetAt + 2 * kCancelPollSteps) << to_string(method);
  }
}

TEST(Cancel, OutsideAScopeTheFlagIsNotSeen) {
  std::atomic<int> flag{0};
  long steps = 0;
  EXPECT_EQ(periods_before_cancel(Method::dopri5, flag, steps), kPeriods);
  EXPECT_EQ(flag.load(), 15) << "the flag was set, and nobody looked";
  EXPECT_GT(steps, 10 * kSetAt);
  EXPECT_FALSE(cancel_requested());
}

TEST(Cancel, ScopesNestAndRestore) {
  std::atomic<int> outer{0}, inner{1};
  EXPECT_FALSE(cancel_requested());
  {
    const CancelScope a(&outer);
    EXPECT_FALSE(cancel_requested());
    {
      const CancelScope b(&inner);
      EXPECT_TRUE(cancel_requested());
      EXPECT_THROW(check_cancel(), Cancelled);
      const CancelScope off(nullptr);
      EXPECT_FALSE(cancel_requested());
    }
    EXPECT_FALSE(cancel_requested());
    outer.store(2);
    EXPECT_TRUE(cancel_requested());
  }
  EXPECT_FALSE(cancel_requested());
  EXPECT_NO_THROW(check_cancel());
}

}  // namespace
}  // namespace vibromap
