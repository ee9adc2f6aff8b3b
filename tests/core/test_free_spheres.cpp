// Hertz impact of two free bodies: closed-form duration, compression, rebound and impulse
// (tests/problems/free_spheres.hpp), on a rigid and a soft contact.
#include <gtest/gtest.h>

#include <cmath>

#include "problems/free_spheres.hpp"
#include "vibromap/core/analysis/impact.hpp"
#include "vibromap/core/integrate/integrator.hpp"

using namespace vibromap;

namespace {
constexpr double kTight = 1e-6;  // required relative error at rtol = 1e-12

struct Case {
  double E, v;
};

std::ostream& operator<<(std::ostream& os, const Case& c) { return os << "E " << c.E << ", v " << c.v; }

Parameters free_bodies(const Case& c) {
  Parameters p;
  p.spring1 = {Spring::Form::stiffness, 0.0};
  p.spring2 = {Spring::Form::stiffness, 0.0};
  p.damper1 = {Damper::Form::coefficient, 0.0};
  p.damper2 = {Damper::Form::coefficient, 0.0};
  p.F0 = 0.0;
  p.E1 = p.E2 = c.E;
  p.D = 1e-3;
  p.initial = Eigen::Vector4d(0.0, p.D, c.v, 0.0);
  return p;
}

class FreeSpheres : public ::testing::TestWithParam<Case> {};
}  // namespace

TEST_P(FreeSpheres, DurationCompressionReboundAndImpulseMatchHertz) {
  const Parameters p = free_bodies(GetParam());
  const Model model(p);
  IntegratorOptions o;
  o.rtol = 1e-12;
  o.atol = 1e-16;
  auto integ = make_integrator(model, o);
  State u = Model::to_internal(p.initial_state());
  integ->reset(u);
  ImpactRecorder rec(model, 100);
  State at_exit = u;
  struct ExitState : Observer {
    State* out;
    void on_event(const ContactEvent& e) override {
      if (e.kind == ContactEvent::Kind::exit) *out = e.u;
    }
  } exit_state;
  exit_state.out = &at_exit;
  ObserverList both{&rec, &exit_state};
  // One forcing period (0.87 s) is far longer than the approach and the contact.
  ASSERT_EQ(integ->advance_period(u, both), IntegrationStatus::ok);
  ASSERT_EQ(rec.impacts().size(), 1u);
  const Impact& im = rec.impacts().front();
  const double m_star = model.reduced_mass(), K = model.contact().stiffness(), v = GetParam().v;

  EXPECT_NEAR(im.T_con / test::hertz_duration(m_star, K, v), 1.0, kTight);
  EXPECT_NEAR(im.z_max / test::hertz_compression(m_star, K, v), 1.0, kTight);
  EXPECT_NEAR(im.v_in / v, 1.0, kTight);
  EXPECT_NEAR(at_exit[3] / -v, 1.0, kTight);  // elastic: relative velocity reverses
  EXPECT_NEAR(im.impulse / (2.0 * m_star * v), 1.0, kTight);
  EXPECT_NEAR(im.tau_in, p.D / v, 1e-12);  // free approach at constant speed
}

INSTANTIATE_TEST_SUITE_P(RigidAndSoft, FreeSpheres,
                         ::testing::Values(Case{2.099e11, 0.4}, Case{2.099e11, 0.05}, Case{1e6, 0.4}));
