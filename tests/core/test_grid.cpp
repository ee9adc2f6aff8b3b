// Sweep grids: axis points, flat index <-> per-axis index, cells as parameter points, and
// the fixed-size cell record.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "vibromap/core/quantities.hpp"
#include "vibromap/core/grid.hpp"

using namespace vibromap;

TEST(Grid, AxisPointsHitTheEndsExactlyWithConstantSpacing) {
  const auto lin = axis_points(100.0, 310.0, 8, AxisScale::lin);
  ASSERT_EQ(lin.size(), 8u);
  EXPECT_EQ(lin.front(), 100.0);
  EXPECT_EQ(lin.back(), 310.0);
  for (std::size_t i = 1; i < lin.size(); ++i) EXPECT_NEAR(lin[i] - lin[i - 1], 30.0, 1e-12);
  const auto log = axis_points(2e4, 2.1e11, 23, AxisScale::log);
  EXPECT_EQ(log.front(), 2e4);
  EXPECT_EQ(log.back(), 2.1e11);
  const double ratio = std::pow(2.1e11 / 2e4, 1.0 / 22.0);
  for (std::size_t i = 1; i < log.size(); ++i) EXPECT_NEAR(log[i] / log[i - 1], ratio, 1e-12);
  EXPECT_EQ(axis_points(5.0, 9.0, 1, AxisScale::lin), std::vector<double>{5.0});
}

TEST(Grid, FlatIndexRoundTripsRowMajorFirstAxisSlowest) {
  const Grid g({{"E1", {1, 2, 3}, AxisScale::lin}, {"R1", {0.1, 0.2}, AxisScale::lin}, {"m2", {100, 200, 300, 400}, AxisScale::lin}});
  EXPECT_EQ(g.size(), 24u);
  EXPECT_EQ(g.shape(), (std::vector<std::size_t>{3, 2, 4}));
  EXPECT_EQ(g.unravel(0), (std::vector<std::size_t>{0, 0, 0}));
  EXPECT_EQ(g.unravel(1), (std::vector<std::size_t>{0, 0, 1}));
  EXPECT_EQ(g.unravel(4), (std::vector<std::size_t>{0, 1, 0}));
  EXPECT_EQ(g.unravel(23), (std::vector<std::size_t>{2, 1, 3}));
  for (std::size_t i = 0; i < g.size(); ++i) EXPECT_EQ(g.ravel(g.unravel(i)), i);
}

TEST(Grid, CellsSetTheSweptParametersAndKeepTheRest) {
  Parameters base;
  base.E2 = 7e9;
  const Grid g({{"E1", {1e5, 1e9}, AxisScale::log}, {"omega2", {3.606, 5.646}, AxisScale::lin}});
  const Parameters p = g.cell(base, 3);  // E1 index 1, omega2 index 1
  EXPECT_EQ(p.E1, 1e9);
  EXPECT_EQ(get_parameter(p, "omega2"), 5.646);
  EXPECT_EQ(p.E2, 7e9);
  EXPECT_NEAR(get_parameter(p, "xi2"), 0.01, 1e-15);  // the ratio form is kept
  const Grid gk({{"k2", {4031.0}, AxisScale::lin}});
  EXPECT_EQ(get_parameter(gk.cell(base, 0), "k2"), 4031.0);
}

TEST(Grid, BadAxesAreRefusedWithAReason) {
  EXPECT_NE(validate_axis({"E3", {1.0}, AxisScale::lin}).find("unknown axis 'E3'"), std::string::npos);
  EXPECT_NE(validate_axis({"E1", {}, AxisScale::lin}).find("no values"), std::string::npos);
  EXPECT_NE(validate_axis({"E1", {0.0, 1.0}, AxisScale::log}).find("> 0"), std::string::npos);
  EXPECT_NE(validate_axis({"E1", {1.0, 1.0}, AxisScale::lin}).find("repeats"), std::string::npos);
  EXPECT_NE(validate_axis({"E1", {NAN}, AxisScale::lin}).find("non-finite"), std::string::npos);
  EXPECT_THROW(Grid({{"E1", {}, AxisScale::lin}}), std::invalid_argument);
}

TEST(CellResult, SummarizesTheLongestImpact) {
  PointSummary s;
  s.status = SolveStatus::ok;
  s.regime = {RegimeKind::periodic, 2, 2};
  Impact a, b;
  a.T_con = 1e-3;
  a.v_in = 0.5;
  a.impulse = 10.0;
  b.T_con = 2e-3;
  b.v_in = 0.3;
  b.impulse = 7.0;
  s.impacts = {a, b};
  s.T_con = 2e-3;
  s.k_con = 400.0;
  const CellResult c = summarize(s);
  EXPECT_EQ(c.regime, regime_code(RegimeKind::periodic));
  EXPECT_EQ(c.n, 2);
  EXPECT_EQ(c.k, 2);
  EXPECT_EQ(c.v_in, 0.3);
  EXPECT_EQ(c.impulse, 7.0);
  EXPECT_EQ(c.value(Quantity::k_con), 400.0);
  for (Quantity q : all_quantities()) EXPECT_EQ(parse_quantity(to_string(q)), q);
  EXPECT_EQ(regime_code(RegimeKind::failed), 8);
  EXPECT_EQ(status_code(SolveStatus::invalid_input), 3);
}

// Every quantity reads back through value() what set_quantity wrote, member by member (so a
// table row pointing at the wrong member shows), and integers keep all 64 bits.
TEST(CellResult, EveryQuantityIsSetAndReadThroughItsTableRow) {
  const std::vector<std::pair<Quantity, double>> written = {
      {Quantity::T_con, 1.5e-3}, {Quantity::k_con, 42.0},  {Quantity::F_max, 3e5},
      {Quantity::z_max, 2e-6},   {Quantity::z_ratio, 1e-4}, {Quantity::v_in, -0.25},
      {Quantity::impulse, 9.0},  {Quantity::hertz_valid, 1}, {Quantity::periods, 250},
      {Quantity::rhs_evals, 123456}, {Quantity::max_multiplier, 1.25}, {Quantity::lyapunov, -0.5}};
  ASSERT_EQ(written.size(), all_quantities().size());
  CellResult c;
  for (const auto& [q, v] : written) set_quantity(c, q, v);
  for (const auto& [q, v] : written) EXPECT_EQ(c.value(q), v) << to_string(q);
  EXPECT_EQ(c.T_con, 1.5e-3);
  EXPECT_EQ(c.hertz_valid, 1);
  EXPECT_EQ(c.periods, 250);
  EXPECT_EQ(c.rhs_evals, 123456);
  EXPECT_EQ(c.max_multiplier, 1.25);
  EXPECT_EQ(c.lyapunov, -0.5);
  const std::int64_t big = (std::int64_t{1} << 62) + 1;  // not a double: needs the int64 path
  set_quantity_int(c, Quantity::rhs_evals, big);
  EXPECT_EQ(quantity_int(c, Quantity::rhs_evals), big);
  EXPECT_EQ(c.rhs_evals, big);
  EXPECT_THROW(quantity_int(c, Quantity::T_con), std::logic_error);
  EXPECT_THROW(set_quantity(c, Quantity::hertz_valid, 2.0), std::invalid_argument);
  EXPECT_THROW(set_quantity(c, Quantity::periods, std::nan("")), std::invalid_argument);
}

TEST(CellResult, QuantitiesNotComputedAreNaNAndStabilityUnknownByDefault) {
  const CellResult c;
  EXPECT_EQ(c.stable, -1);
  EXPECT_TRUE(std::isnan(c.value(Quantity::max_multiplier)));
  EXPECT_TRUE(std::isnan(c.value(Quantity::lyapunov)));
  EXPECT_EQ(c.value(Quantity::T_con), 0.0);
}

TEST(CellResult, EveryQuantityHasUnitsAndADescription) {
  for (const Quantity q : all_quantities()) {
    EXPECT_FALSE(quantity_units(q).empty()) << to_string(q);
    EXPECT_FALSE(quantity_description(q).empty()) << to_string(q);
    if (quantity_is_integer(q)) {
      EXPECT_GE(quantity_max(q), 1) << to_string(q);
    }
  }
  EXPECT_EQ(quantity_units(Quantity::lyapunov), "1/s");
  EXPECT_EQ(quantity_units(Quantity::max_multiplier), "1");
  EXPECT_EQ(quantity_units(Quantity::impulse), "N s");
  EXPECT_EQ(quantity_max(Quantity::hertz_valid), 1);
  EXPECT_FALSE(quantity_is_integer(Quantity::max_multiplier));
  EXPECT_TRUE(quantity_is_integer(Quantity::rhs_evals));
  EXPECT_NE(quantity_description(Quantity::max_multiplier).find("NaN where not computed"), std::string_view::npos);
  EXPECT_NE(quantity_description(Quantity::lyapunov).find("NaN where not computed"), std::string_view::npos);
  EXPECT_THROW(quantity_max(Quantity::T_con), std::logic_error);
}

TEST(CellResult, SummarizesStabilityFromTheLargestMultiplier) {
  PointSummary s;
  s.status = SolveStatus::ok;
  s.regime = {RegimeKind::periodic, 1, 1};
  s.floquet = {{-3.0, 4.0}, {0.3, 0.0}};  // largest |mu| first, as shooting sorts them
  s.stable = 0;
  const CellResult c = summarize(s);
  EXPECT_EQ(c.stable, 0);
  EXPECT_EQ(c.max_multiplier, 5.0);  // |-3 + 4i|
  EXPECT_TRUE(std::isnan(c.lyapunov));
  PointSummary none;
  none.regime = {RegimeKind::chaotic, 0, 0};
  none.lyapunov = 0.75;
  const CellResult d = summarize(none);
  EXPECT_EQ(d.stable, -1);
  EXPECT_TRUE(std::isnan(d.max_multiplier));
  EXPECT_EQ(d.lyapunov, 0.75);
}
