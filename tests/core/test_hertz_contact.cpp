#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "problems/free_spheres.hpp"
#include "vibromap/core/model/keys.hpp"
#include "vibromap/core/model/hertz_contact.hpp"
#include "vibromap/core/model/system.hpp"

using namespace vibromap;

TEST(HertzContact, StiffnessMatchesSpecCheckValue) {
  // docs/model.md: E1 = E2 = 2.099e11 Pa, nu = 0.3, R1 = R2 = 2 m give K = 1.541e11 N/m^1.5.
  const HertzContact c(2.099e11, 2.099e11, 0.3, 0.3, 2.0, 2.0, 0.319);
  EXPECT_NEAR(c.stiffness(), 1.541e11, 0.0005e11);
  EXPECT_DOUBLE_EQ(c.effective_radius(), 1.0);
}

TEST(HertzContact, ForceIsDerivativeOfEnergyAndZeroOutsideContact) {
  const HertzContact c(1e9, 2e9, 0.25, 0.3, 0.5, 1.5, 0.319);
  EXPECT_EQ(c.force(-1e-3), 0.0);
  EXPECT_EQ(c.energy(-1e-3), 0.0);
  for (double z : {1e-6, 1e-4, 1e-2}) {
    const double h = z * 1e-5;
    const double dE = (c.energy(z + h) - c.energy(z - h)) / (2 * h);
    EXPECT_NEAR(dE / c.force(z), 1.0, 1e-8);
    const double dF = (c.force(z + h) - c.force(z - h)) / (2 * h);
    EXPECT_NEAR(dF / c.force_derivative(z), 1.0, 1e-8);
  }
}

TEST(HertzContact, DurationConstantMatchesSpec) {
  EXPECT_NEAR(test::hertz_duration_constant(), 3.2180655, 1e-7);
}

TEST(Model, PairsGivenEitherWayGiveTheSameCoefficients) {
  Parameters a;  // omega and xi form (defaults)
  Parameters b = a;
  b.spring1 = {Spring::Form::stiffness, a.m1 * 6.283 * 6.283};
  b.spring2 = {Spring::Form::stiffness, a.m2 * 5.646 * 5.646};
  const Model ma(a);
  b.damper1 = {Damper::Form::coefficient, ma.c1()};
  b.damper2 = {Damper::Form::coefficient, ma.c2()};
  const Model mb(b);
  EXPECT_NEAR(mb.k1(), ma.k1(), 1e-9 * ma.k1());
  EXPECT_NEAR(mb.k2(), ma.k2(), 1e-9 * ma.k2());
  EXPECT_NEAR(ma.c1(), 2 * 0.01 * a.m1 * 6.283, 1e-9);
  EXPECT_NEAR(Key::at("xi2").value(b), 0.01, 1e-12);
  EXPECT_NEAR(Key::at("k2").value(a), 100 * 5.646 * 5.646, 1e-9);
}

TEST(Model, NewtonThirdLawCouplingIsMassRatioM2OverM1) {
  // A static approach z with no motion: the spring and contact forces on the two bodies
  // are equal and opposite, so m1 a1 + m2 a2 = F(t) - k1 x1 (momentum balance).
  Parameters p;
  const Model m(p);
  const State u(0.01, 2e-4, 0.0, 0.0);  // x1, z, v1, w
  State du;
  m.rhs(0.3, u, ContactMode::contact, du);
  const double a1 = du[2], a2 = du[2] - du[3];
  EXPECT_NEAR(p.m1 * a1 + p.m2 * a2, m.forcing(0.3) - m.k1() * u[0], 1e-9);
}

// forcing_at (a dopri5 step's stages) against the closed form F0 lambda cos(omega t + phi0):
// a short step turns one sine and cosine by Taylor series, a long one takes a cosine per stage.
TEST(Model, StageForcingEqualsTheClosedForm) {
  vibromap::Parameters p;
  p.omega = 7.23;
  p.phi0 = 0.4;
  const vibromap::Model m(p);
  const std::array<double, 5> c{0.2, 0.3, 0.8, 8.0 / 9.0, 1.0};
  for (double h : {1e-6, 1e-3, 0.05 / 7.23, 0.3}) {  // the last is beyond the Taylor range
    for (double tau : {0.0, 0.31, 0.8}) {
      std::array<double, 5> F{};
      m.forcing_at(tau, h, c, F);
      for (std::size_t i = 0; i < c.size(); ++i) {
        const double exact = p.lambda * p.F0 * std::cos(p.omega * (tau + c[i] * h) + p.phi0);
        EXPECT_NEAR(F[i], exact, 4e-16 * p.lambda * p.F0) << "h " << h << " tau " << tau << " stage " << i;
      }
    }
  }
}
