// The hybrid integrator's closed-form free flight: propagation and transition matrix against
// Eigen's matrix exponential, contact entry against a root found independently, grazing
// contacts that must and must not be found, and the whole hybrid method against dopri5.
#include <gtest/gtest.h>

#include <cmath>

#include "problems/linear_oscillator.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/integrate/free_flight.hpp"

using namespace vibromap;

namespace {
Parameters far_apart() {
  Parameters p;
  p.D = 10.0;
  p.phi0 = 0.4;
  p.initial = Eigen::Vector4d(0.02, 10.0, -0.05, 0.1);
  return p;
}

double max_rel(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  return ((a - b).array().abs() / (b.array().abs() + 1e-3)).maxCoeff();
}

// z on the reference closed form, and the time of its largest value in [t0, t1] (golden
// section on a dense scan's best bracket): independent of FreeFlight.
struct ZMax {
  double t, z;
};
ZMax max_of_z(const test::LinearOscillator& ref, const State& u0, double t0, double t1) {
  auto z = [&](double t) { return ref.solution(u0, t)[1]; };
  double best_t = t0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = t0 + (t1 - t0) * i / 2000.0;
    if (z(t) > z(best_t)) best_t = t;
  }
  double a = std::max(t0, best_t - (t1 - t0) / 2000.0), b = std::min(t1, best_t + (t1 - t0) / 2000.0);
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int i = 0; i < 80; ++i) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    (z(c) > z(d) ? b : a) = (z(c) > z(d) ? d : c);
  }
  return {0.5 * (a + b), z(0.5 * (a + b))};
}

// far_apart() with the clearance shifted so that the largest z of its free motion over [0, 3]
// is +eps or -eps: D -> D + (z* - eps) moves z by -(z* - eps) for the same x1, x2 - D. Also
// the unshifted peak.
struct Peaking {
  Parameters p;
  ZMax peak;
};
Peaking peaking_at(double eps) {
  const Parameters base = far_apart();
  const test::LinearOscillator ref0{Model(base)};
  const ZMax peak = max_of_z(ref0, Model::to_internal(base.initial_state()), 0.0, 3.0);
  Parameters p = base;
  const double shift = peak.z - eps;
  p.D = base.D + shift;
  p.initial = Eigen::Vector4d(0.02, 10.0 + shift, -0.05, 0.1);
  return {p, peak};
}
}  // namespace

TEST(FreeFlightClosedForm, PropagationAndTransitionMatchTheMatrixExponential) {
  const Model model(far_apart());
  const FreeFlight flight(model);
  ASSERT_TRUE(flight.valid());
  const test::LinearOscillator ref(model);
  const State u0 = Model::to_internal(far_apart().initial_state());
  for (double t : {0.01, 0.3, 0.869, 5.0, 40.0}) {
    EXPECT_LT(max_rel(flight.propagate(0.0, u0, t), ref.solution(u0, t)), 1e-11) << t;
    const Eigen::Matrix4d exact = (flight.matrix() * t).exp();
    EXPECT_LT((flight.transition(t) - exact).cwiseAbs().maxCoeff(), 1e-11 * (1.0 + exact.cwiseAbs().maxCoeff())) << t;
  }
  // Starting mid-period (forcing phase) is the same motion.
  const State mid = flight.propagate(0.0, u0, 0.4);
  EXPECT_LT(max_rel(flight.propagate(0.4, mid, 1.3), ref.solution(u0, 1.3)), 1e-11);
}

TEST(FreeFlightClosedForm, EntryIsTheFirstRootAndGrazesAreDecidedByTheirSign) {
  for (double eps : {1e-6, 1e-10, -1e-10, -1e-6}) {
    const auto [p, peak] = peaking_at(eps);
    const Model model(p);
    const FreeFlight flight(model);
    const auto entry = flight.find_entry(0.0, Model::to_internal(p.initial_state()), 3.0);
    if (eps > 0) {
      ASSERT_TRUE(entry.has_value()) << "eps " << eps;
      // The crossing lies before the peak, within the time z needs to fall eps from it.
      EXPECT_LT(*entry, peak.t);
      EXPECT_GT(*entry, peak.t - 1e-2);
      const State at = flight.propagate(0.0, Model::to_internal(p.initial_state()), *entry);
      EXPECT_NEAR(at[1], 0.0, 1e-13);
    } else {
      EXPECT_FALSE(entry.has_value()) << "eps " << eps;
    }
  }
}

TEST(FreeFlightClosedForm, FlyIsFindEntryThenPropagateBitForBit) {
  // fly() reuses the entry search's last exponentials: its state must be propagate()'s to the
  // last bit, at entries (the grazing set-up above, several phases) and at the interval's end.
  int entries = 0, ends = 0;
  for (double eps : {1e-3, 1e-6, -1e-6}) {
    const Parameters p = peaking_at(eps).p;
    const Model model(p);
    const FreeFlight flight(model);
    const State start = Model::to_internal(p.initial_state());
    for (double tau0 : {0.0, 0.1, 0.37}) {
      const State u = flight.propagate(0.0, start, tau0);
      for (double tau1 : {0.5, 1.7, 3.0}) {
        const FreeFlight::Flight f = flight.fly(tau0, u, tau1);
        const auto entry = flight.find_entry(tau0, u, tau1);
        ASSERT_EQ(f.entry.has_value(), entry.has_value());
        if (entry) {
          EXPECT_EQ(*f.entry, *entry);
        }
        const State exact = flight.propagate(tau0, u, entry ? *entry : tau1);
        for (int i = 0; i < 4; ++i) EXPECT_EQ(f.u[i], exact[i]) << "eps " << eps << " tau0 " << tau0 << " tau1 " << tau1;
        (entry ? entries : ends) += 1;
      }
    }
  }
  EXPECT_GT(entries, 0);
  EXPECT_GT(ends, 0);
}

TEST(FreeFlightClosedForm, HybridAgreesWithDopri5ToSteadyState) {
  Parameters table2;  // the paper's Table 2 (docs/model.md)
  table2.m2 = 310.0;
  table2.spring2 = {Spring::Form::frequency, 3.606};
  table2.E1 = 1.4e10;
  table2.E2 = 1.0e6;
  for (const Parameters& p : {Parameters{}, table2}) {
    PointOptions hybrid, dopri5;
    hybrid.analysis.steady = dopri5.analysis.steady = SteadyMethod::integrate;
    dopri5.integrator.method = Method::dopri5;
    const PointSummary a = solve_point(p, hybrid), b = solve_point(p, dopri5);
    ASSERT_EQ(a.regime.label(), "(1,1)");
    ASSERT_EQ(a.regime, b.regime);
    EXPECT_NEAR(a.T_con / b.T_con, 1.0, 1e-8);
    EXPECT_LT(a.counters.rhs_evals, b.counters.rhs_evals);  // free flight costs no RHS evaluations
  }
}

TEST(FreeFlightClosedForm, DefectiveSystemFallsBackToDopri5) {
  Parameters p;  // two free bodies: k1 = k2 = 0, no dampers: A has a Jordan block
  p.spring1 = {Spring::Form::stiffness, 0.0};
  p.spring2 = {Spring::Form::stiffness, 0.0};
  p.damper1 = {Damper::Form::coefficient, 0.0};
  p.damper2 = {Damper::Form::coefficient, 0.0};
  EXPECT_FALSE(FreeFlight(Model(p)).valid());
}
