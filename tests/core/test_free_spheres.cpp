// Hertz impact of two free bodies: closed-form duration, compression, rebound and impulse
// (tests/problems/free_spheres.hpp), on a rigid and a soft contact.
#include <gtest/gtest.h>

#include <cmath>

#include "problems/free_spheres.hpp"
#include "vibromap/core/analysis/point/restitution.hpp"

using namespace vibromap;

namespace {
constexpr double kTight = 1e-6;  // required relative error at rtol = 1e-12

struct Case {
  double E, v;
};

std::ostream& operator<<(std::ostream& os, const Case& c) { return os << "E " << c.E << ", v " << c.v; }

class FreeSpheres : public ::testing::TestWithParam<Case> {};
}  // namespace

TEST_P(FreeSpheres, DurationCompressionReboundAndImpulseMatchHertz) {
  Parameters base;
  base.E1 = base.E2 = GetParam().E;
  const Parameters p = free_bodies(base, GetParam().v);
  const Model model(p);
  Impact im;
  ASSERT_EQ(free_impact(p, RestitutionOptions{1e-12, 1e-16}, im), IntegrationStatus::ok);
  const double m_star = model.reduced_mass(), K = model.contact().stiffness(), v = GetParam().v;

  EXPECT_NEAR(im.T_con / test::hertz_duration(m_star, K, v), 1.0, kTight);
  EXPECT_NEAR(im.z_max / test::hertz_compression(m_star, K, v), 1.0, kTight);
  EXPECT_NEAR(im.v_in / v, 1.0, kTight);
  EXPECT_NEAR(im.v_out / -v, 1.0, kTight);  // elastic: relative velocity reverses
  EXPECT_NEAR(im.impulse / (2.0 * m_star * v), 1.0, kTight);
  EXPECT_NEAR(im.tau_in, p.D / v, 1e-12);  // free approach at constant speed
}

INSTANTIATE_TEST_SUITE_P(RigidAndSoft, FreeSpheres,
                         ::testing::Values(Case{2.099e11, 0.4}, Case{2.099e11, 0.05}, Case{1e6, 0.4}));
