// Regime names and the steady-state detector on synthetic stroboscopic sequences with known
// answers.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vibromap/core/analysis/point/regime.hpp"
#include "vibromap/core/analysis/point/steady_state.hpp"

using namespace vibromap;

TEST(Regime, LabelsAndParsingRoundTrip) {
  EXPECT_EQ((Regime{RegimeKind::periodic, 2, 1}.label()), "(2,1)");
  EXPECT_EQ((Regime{RegimeKind::no_contact, 1, 0}.label()), "no-contact");
  EXPECT_EQ(parse_regime("(1,1)"), (Regime{RegimeKind::periodic, 1, 1}));
  for (auto k : {RegimeKind::chatter, RegimeKind::no_contact, RegimeKind::permanent_contact,
                 RegimeKind::quasi_periodic, RegimeKind::chaotic, RegimeKind::non_periodic, RegimeKind::unresolved,
                 RegimeKind::failed})
    EXPECT_EQ(parse_regime_kind(to_string(k)), k);
  EXPECT_THROW(parse_regime("(0,1)"), std::invalid_argument);
  EXPECT_THROW(parse_regime("(1,x)"), std::invalid_argument);
  EXPECT_THROW(parse_regime("sticky"), std::invalid_argument);
}

namespace {
const Model& unit_model() {
  static const Model m([] {
    Parameters p;
    p.D = 1.0;
    return p;
  }());
  return m;
}

// Feeds y_j = base_j + r^j * rotation(theta j) * (1e-2, 0): a transient spiralling into the
// periodic sequence base_j with contraction r and rotation theta per period.
int detect(int n_max, double tol, int true_n, double r, double theta, long* at) {
  SteadyStateDetector d(unit_model(), n_max, tol);
  for (long j = 0; j < 3000; ++j) {
    State y(0.1 * static_cast<double>((j % true_n) + 1), 0.0, 0.0, 0.0);
    const double jd = static_cast<double>(j);
    const double a = std::pow(r, jd);
    y[0] += 1e-2 * a * std::cos(theta * jd);
    y[1] += 1e-2 * a * std::sin(theta * jd);
    if (d.on_period_end(j, y)) {
      *at = j;
      return d.period_n();
    }
  }
  return 0;
}
}  // namespace

TEST(SteadyState, FindsTheLeastPeriod) {
  long at = 0;
  EXPECT_EQ(detect(8, 1e-8, 1, 0.9, 0.0, &at), 1);
  // Found as soon as the transient's step |y_j - y_{j-1}| = 1e-2 * 0.9^j / 9 over the scale
  // D + |x| = 1.1 falls below 1e-8: 0.9^j <= 9.9e-6, j >= 109.4.
  EXPECT_EQ(at, 110);
  EXPECT_EQ(detect(8, 1e-8, 2, 0.9, 0.0, &at), 2);
  EXPECT_EQ(detect(8, 1e-8, 3, 0.9, 0.0, &at), 3);
}

TEST(SteadyState, SpiralTransientIsNotMistakenForALongerPeriod) {
  // Rotation 2 pi / 5 per period: y_j - y_{j-5} is far smaller than y_j - y_{j-1} while the
  // transient decays; the detector must still report period 1.
  long at = 0;
  EXPECT_EQ(detect(8, 1e-8, 1, 0.97, 2.0 * std::numbers::pi / 5.0 + 1e-4, &at), 1);
}

TEST(SteadyState, PeriodAboveNmaxIsNotFound) {
  long at = 0;
  EXPECT_EQ(detect(4, 1e-8, 5, 0.9, 0.0, &at), 0);
}

TEST(SteadyState, ConvergingAndWanderingSequencesAreToldApart) {
  SteadyStateDetector slow(unit_model(), 2, 1e-14), wander(unit_model(), 2, 1e-14);
  for (long j = 0; j < 300; ++j) {
    const double jd = static_cast<double>(j);
    slow.on_period_end(j, State(0.1 + 1e-2 * std::pow(0.99, jd), 0, 0, 0));
    // quasi-periodic: an irrational rotation on a circle never repeats and never settles
    wander.on_period_end(j, State(0.1 * std::cos(jd * std::numbers::sqrt2), 0.1 * std::sin(jd * std::numbers::sqrt2), 0, 0));
  }
  EXPECT_TRUE(slow.still_converging());
  EXPECT_FALSE(wander.still_converging());
}

// The one definition of soft (regime.hpp): every condition is needed, and the threshold is inclusive.
TEST(Soft, NeedsPeriodicImpactsStabilityHertzValidityAndSmallKcon) {
  const Regime one_one{RegimeKind::periodic, 1, 1};
  EXPECT_TRUE(is_soft(one_one, 1, true, 8.9, 10.0));
  EXPECT_TRUE(is_soft(one_one, 1, true, 10.0, 10.0));
  EXPECT_FALSE(is_soft(one_one, 1, true, 10.0001, 10.0));               // rigid enough
  EXPECT_FALSE(is_soft(one_one, 0, true, 2.0, 10.0));                   // unstable
  EXPECT_FALSE(is_soft(one_one, -1, true, 2.0, 10.0));                  // stability unknown
  EXPECT_FALSE(is_soft(one_one, 1, false, 2.0, 10.0));                  // beyond the Hertz limit
  EXPECT_FALSE(is_soft({RegimeKind::periodic, 1, 0}, 1, true, 0.0, 10.0));  // no impact
  EXPECT_FALSE(is_soft({RegimeKind::chatter, 1, 7}, 1, true, 2.0, 10.0));
  EXPECT_FALSE(is_soft({RegimeKind::non_periodic, 0, 0}, -1, true, 2.0, 10.0));
  EXPECT_TRUE(is_soft({RegimeKind::periodic, 3, 3}, 1, true, 24.9, 30.0));
}
