// Tests of the impact recorder's memory bound (core/analysis/point/impact.hpp): it keeps the
// impacts of its last periods, and at most ImpactRecorder::kMaxKept of them, the oldest dropped
// first, however many impacts a period holds; every impact is still counted.

#include <gtest/gtest.h>

#include <cstddef>

#include "vibromap/core/analysis/point/impact.hpp"

namespace vibromap {
namespace {

// One impact of period `period`, entering at tau and leaving 1e-9 s later.
void impact(ImpactRecorder& rec, long period, double tau) {
  rec.on_event({ContactEvent::Kind::entry, period, tau, State(0.0, 0.0, 0.0, -1.0)});
  rec.on_event({ContactEvent::Kind::exit, period, tau + 1e-9, State(0.0, 0.0, 0.0, 0.5)});
}

TEST(ImpactRecorder, KeepsTheLastPeriodsImpacts) {
  const Model model{Parameters{}};
  ImpactRecorder rec(model, 2);
  for (long period = 0; period < 5; ++period) {
    impact(rec, period, 0.1);
    impact(rec, period, 0.2);
    rec.on_period_end(period, State::Zero());
  }
  ASSERT_EQ(rec.impacts().size(), 4u);  // periods 3 and 4
  EXPECT_EQ(rec.impacts().front().period_in, 3);
  EXPECT_EQ(rec.total_impacts(), 10);
  EXPECT_DOUBLE_EQ(rec.impacts().front().e_effective, 0.5);
}

TEST(ImpactRecorder, KeepsAtMostItsBoundInOnePeriodDroppingTheOldestFirst) {
  const Model model{Parameters{}};
  ImpactRecorder rec(model, 4);
  const std::size_t extra = 3;
  const std::size_t n = ImpactRecorder::kMaxKept + extra;
  for (std::size_t i = 0; i < n; ++i) impact(rec, 0, 1e-7 * static_cast<double>(i));
  ASSERT_EQ(rec.impacts().size(), ImpactRecorder::kMaxKept);
  EXPECT_EQ(rec.impacts().front().tau_in, 1e-7 * static_cast<double>(extra));
  EXPECT_EQ(rec.impacts().back().tau_in, 1e-7 * static_cast<double>(n - 1));
  EXPECT_EQ(rec.total_impacts(), static_cast<long>(n));
}

}  // namespace
}  // namespace vibromap
