// The contact event locator (event_locator.hpp) on trajectories whose crossing of z = 0 is known
// in closed form: lines, parabolas (a free flight under constant acceleration), a grazing touch
// between the locator's samples, a sine with two crossings, and the two-body free flight of the
// model itself (linear, closed form in tests/problems/linear_oscillator.hpp). The located time
// must lie past the crossing by no more than the tolerance asked (the root finder returns the
// right end of its final bracket).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "problems/linear_oscillator.hpp"
#include "vibromap/core/integrate/event_locator.hpp"
#include "vibromap/core/integrate/integrator.hpp"

using namespace vibromap;

namespace {

constexpr double kTol = 1e-14;       // s: the time tolerance asked of the locator
constexpr double kRounding = 1e-15;  // s per s of the crossing time: a few ulps

// A dense output whose z (and w = z') are given functions of time; x1 and v1 are 0.
class AnalyticZ final : public DenseOutput {
 public:
  AnalyticZ(std::function<double(double)> z, std::function<double(double)> w) : z_(std::move(z)), w_(std::move(w)) {}
  State eval(double tau) const override { return {0.0, z_(tau), 0.0, w_(tau)}; }

 private:
  std::function<double(double)> z_, w_;
};

// Checks that the event found in [tau0, tau1] lies in [exact, exact + tol].
void expect_event_at(const DenseOutput& dense, double tau0, double tau1, ContactMode mode, double exact,
                     double tol = kTol) {
  const auto found = locate_contact_event(dense, tau0, tau1, mode, tol);
  ASSERT_TRUE(found.has_value()) << "expected " << exact;
  // The exact root and z near it are known to a few ulps (kRounding), not better.
  const double rounding = kRounding * std::max(1.0, std::abs(exact));
  EXPECT_GE(found->tau, exact - rounding);
  EXPECT_LE(found->tau - exact, tol + rounding);
}

}  // namespace

TEST(EventLocator, LinearApproachCrossesWhereTheLineDoes) {
  const AnalyticZ line([](double t) { return -0.3 + 0.5 * t; }, [](double) { return 0.5; });
  expect_event_at(line, 0.0, 1.0, ContactMode::free, 0.6);
  // The same motion in a step that starts later in the period.
  expect_event_at(line, 0.55, 0.65, ContactMode::free, 0.6);
}

TEST(EventLocator, FreeFlightParabolaEntersAtItsFirstRoot) {
  // z = -1e-3 + 0.02 t - 0.05 t^2: roots (0.02 -+ sqrt(2e-4)) / 0.1, peak +1e-3 at t = 0.2.
  const AnalyticZ flight([](double t) { return -1e-3 + 0.02 * t - 0.05 * t * t; },
                         [](double t) { return 0.02 - 0.1 * t; });
  const double first = (0.02 - std::sqrt(2e-4)) / 0.1;
  expect_event_at(flight, 0.0, 1.0, ContactMode::free, first);
}

TEST(EventLocator, ContactExitIsTheFirstTimeZFallsBelowZero) {
  const AnalyticZ leaving([](double t) { return 0.2 - t; }, [](double) { return -1.0; });
  expect_event_at(leaving, 0.0, 1.0, ContactMode::contact, 0.2);
  // In free mode the same motion has no entry (z only falls).
  const AnalyticZ falling([](double t) { return -0.2 - t; }, [](double) { return -1.0; });
  EXPECT_FALSE(locate_contact_event(falling, 0.0, 1.0, ContactMode::free, kTol).has_value());
}

TEST(EventLocator, GrazingTouchBetweenSamplesIsFound) {
  // z = 1e-4 - (t - 0.53)^2: negative at every sample t = i/8 of [0, 1], positive only on
  // (0.52, 0.54); the interior maximum between 0.5 and 0.625 is where the locator must look.
  const AnalyticZ touch([](double t) { return 1e-4 - (t - 0.53) * (t - 0.53); },
                        [](double t) { return -2.0 * (t - 0.53); });
  for (int i = 0; i <= 8; ++i) ASSERT_LT(touch.eval(i / 8.0)[1], 0.0);
  expect_event_at(touch, 0.0, 1.0, ContactMode::free, 0.52);
}

TEST(EventLocator, NearMissBetweenSamplesIsNoEvent) {
  const AnalyticZ miss([](double t) { return -1e-4 - (t - 0.53) * (t - 0.53); },
                       [](double t) { return -2.0 * (t - 0.53); });
  EXPECT_FALSE(locate_contact_event(miss, 0.0, 1.0, ContactMode::free, kTol).has_value());
}

TEST(EventLocator, TheFirstOfTwoCrossingsIsReported) {
  // sin t = 1/2 at pi/6 and 5 pi/6, both in [0, 3].
  const AnalyticZ wave([](double t) { return std::sin(t) - 0.5; }, [](double t) { return std::cos(t); });
  expect_event_at(wave, 0.0, 3.0, ContactMode::free, std::numbers::pi / 6);
  // In contact mode (z > 0 at the start) the exit is the second one.
  expect_event_at(wave, 1.0, 3.0, ContactMode::contact, 5 * std::numbers::pi / 6);
}

TEST(EventLocator, OnTheSurfaceAtTheStart) {
  // z = 0 moving outward: the event is the step's start itself.
  const AnalyticZ rising([](double t) { return t - 0.25; }, [](double) { return 1.0; });
  const auto at_start = locate_contact_event(rising, 0.25, 1.0, ContactMode::free, kTol);
  ASSERT_TRUE(at_start.has_value());
  EXPECT_EQ(at_start->tau, 0.25);
  // z = 0 moving away from contact: no entry.
  const AnalyticZ receding([](double t) { return 0.25 - t; }, [](double) { return -1.0; });
  EXPECT_FALSE(locate_contact_event(receding, 0.25, 1.0, ContactMode::free, kTol).has_value());
}

TEST(EventLocator, CoarseToleranceIsHonoured) {
  const AnalyticZ line([](double t) { return t - 1.0 / 3.0; }, [](double) { return 1.0; });
  for (double tol : {1e-2, 1e-6, 1e-10}) expect_event_at(line, 0.0, 1.0, ContactMode::free, 1.0 / 3.0, tol);
}

namespace {

// The two bodies approaching at 0.6 m/s from rest positions (Table 1, forced): z(t) on the
// closed form, and its first crossing of 0 found by bisection on that closed form alone.
Parameters approaching() {
  Parameters p;
  p.initial = Eigen::Vector4d(0.0, p.D, 0.6, 0.0);  // x1, x2, v1, v2: z0 = -D, w0 = 0.6 m/s
  return p;
}

double exact_entry(const test::LinearOscillator& ref, const State& u0) {
  auto z = [&](double t) { return ref.solution(u0, t)[1]; };
  double a = 0.0, b = 1e-3;
  while (z(b) <= 0.0) a = b, b += 1e-3;
  for (int i = 0; i < 200 && b - a > 1e-16; ++i) (z(0.5 * (a + b)) > 0.0 ? b : a) = 0.5 * (a + b);
  return b;
}

class FirstEntry final : public Observer {
 public:
  void on_event(const ContactEvent& e) override {
    if (e.kind == ContactEvent::Kind::entry && tau < 0.0) tau = e.tau;
  }
  double tau = -1.0;
};

// The model's free flight on its closed form as a dense output.
class ClosedFormFlight final : public DenseOutput {
 public:
  ClosedFormFlight(const test::LinearOscillator& ref, const State& u0) : ref_(ref), u0_(u0) {}
  State eval(double tau) const override { return ref_.solution(u0_, tau); }

 private:
  const test::LinearOscillator& ref_;
  State u0_;
};

}  // namespace

TEST(EventLocator, ModelFreeFlightEntryOnItsClosedForm) {
  const Model model(approaching());
  const test::LinearOscillator ref(model);
  const State u0 = Model::to_internal(approaching().initial_state());
  const double entry = exact_entry(ref, u0);
  // x1 swings out with amplitude w0 / omega1 = 0.095 m > D: about asin(D / 0.095) / omega1 = 0.09 s.
  ASSERT_GT(entry, 0.05);
  ASSERT_LT(entry, 0.2);
  // A step around the entry, as an integrator would show it.
  expect_event_at(ClosedFormFlight(ref, u0), entry - 0.02, entry + 0.01, ContactMode::free, entry, 1e-13);
}

TEST(EventLocator, IntegratorsReportTheEntryOfTheClosedForm) {
  // dopri5 locates the entry on its dense output; hybrid on the closed-form free flight. At
  // rtol 1e-12 the state is good to ~1e-13 m, and with w ~ 0.5 m/s the entry time to ~1e-12 s.
  const Model model(approaching());
  const test::LinearOscillator ref(model);
  const State u0 = Model::to_internal(approaching().initial_state());
  const double entry = exact_entry(ref, u0);
  for (Method method : {Method::dopri5, Method::hybrid}) {
    IntegratorOptions o;
    o.method = method;
    o.rtol = 1e-12;
    auto integ = make_integrator(model, o);
    State u = u0;
    integ->reset(u);
    FirstEntry first;
    ASSERT_EQ(integ->advance_period(u, first), IntegrationStatus::ok);
    EXPECT_NEAR(first.tau, entry, 1e-10) << to_string(method);
  }
}
