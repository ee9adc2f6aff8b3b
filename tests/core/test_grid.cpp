// Sweep grids: axis points, flat index <-> per-axis index, a cell's coordinates, and the
// fixed-size cell record.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
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

namespace {

// An axis by its coordinate name alone (the Grid needs no key, unit or meaning).
Axis axis(std::string name, std::vector<double> values, AxisScale scale = AxisScale::lin) {
  return {"", std::move(name), "", "", std::move(values), scale};
}

}  // namespace

TEST(Grid, FlatIndexRoundTripsRowMajorFirstAxisSlowest) {
  const Grid g({axis("E1", {1, 2, 3}), axis("R1", {0.1, 0.2}), axis("m2", {100, 200, 300, 400})});
  EXPECT_EQ(g.size(), 24u);
  EXPECT_EQ(g.shape(), (std::vector<std::size_t>{3, 2, 4}));
  EXPECT_EQ(g.unravel(0), (std::vector<std::size_t>{0, 0, 0}));
  EXPECT_EQ(g.unravel(1), (std::vector<std::size_t>{0, 0, 1}));
  EXPECT_EQ(g.unravel(4), (std::vector<std::size_t>{0, 1, 0}));
  EXPECT_EQ(g.unravel(23), (std::vector<std::size_t>{2, 1, 3}));
  for (std::size_t i = 0; i < g.size(); ++i) EXPECT_EQ(g.ravel(g.unravel(i)), i);
}

TEST(Grid, CoordinatesAreTheCellsValueOnEachAxis) {
  const Grid g({axis("E1", {1e5, 1e9}, AxisScale::log), axis("omega", {5.0, 7.0, 9.0}), axis("n_max", {8, 16})});
  std::array<double, 3> x{};
  g.coordinates(0, x);
  EXPECT_EQ(x, (std::array<double, 3>{1e5, 5.0, 8}));
  g.coordinates(9, x);  // (1, 1, 1): row-major, first axis slowest
  EXPECT_EQ(x, (std::array<double, 3>{1e9, 7.0, 16}));
  for (std::size_t i = 0; i < g.size(); ++i) {
    g.coordinates(i, x);
    const auto index = g.unravel(i);
    for (std::size_t d = 0; d < 3; ++d) EXPECT_EQ(x[d], g.axes()[d].values[index[d]]) << i << " " << d;
  }
  std::array<double, 2> short_out{};
  EXPECT_THROW(g.coordinates(0, short_out), std::invalid_argument);
}

TEST(Grid, MoreCellsThanAFlatIndexCountsAreRefused) {
  std::vector<double> v(8192);  // 2^13 points: five such axes make 2^65 cells
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<double>(i);
  std::vector<Axis> axes;
  for (const char* name : {"a", "b", "c", "d"}) axes.push_back(axis(name, v));
  EXPECT_EQ(Grid(axes).size(), std::size_t{1} << 52);
  axes.push_back(axis("e", v));
  EXPECT_THROW(Grid{axes}, std::invalid_argument);
}

TEST(Grid, BadAxesAreRefusedWithAReason) {
  EXPECT_NE(validate_axis(axis("", {1.0})).find("no name"), std::string::npos);
  EXPECT_EQ(validate_axis(axis("anything", {1.0})), "");  // the Grid does not know scene keys
  EXPECT_NE(validate_axis(axis("E1", {})).find("no values"), std::string::npos);
  EXPECT_NE(validate_axis(axis("E1", {0.0, 1.0}, AxisScale::log)).find("> 0"), std::string::npos);
  EXPECT_NE(validate_axis(axis("E1", {1.0, 1.0})).find("repeats"), std::string::npos);
  EXPECT_NE(validate_axis(axis("E1", {NAN})).find("non-finite"), std::string::npos);
  EXPECT_THROW(Grid({axis("E1", {})}), std::invalid_argument);
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

// Every quantity reads back through value() what set_quantity wrote, each a value of its own
// (so two table rows on one member show: the later overwrites the earlier), leaving the fields
// that are not quantities alone; integers keep all 64 bits.
TEST(CellResult, EveryQuantityIsSetAndReadThroughItsTableRow) {
  const std::vector<Quantity>& all = all_quantities();
  // Row j: j + 0.5, or for an integer j + 2 up to its largest (hertz_valid: 1).
  const auto written = [](std::size_t j, Quantity q) {
    const auto at = static_cast<std::int64_t>(j);
    return quantity_is_integer(q) ? static_cast<double>(std::min(quantity_max(q), at + 2)) : static_cast<double>(j) + 0.5;
  };
  CellResult c;
  for (std::size_t j = 0; j < all.size(); ++j) set_quantity(c, all[j], written(j, all[j]));
  for (std::size_t j = 0; j < all.size(); ++j) EXPECT_EQ(c.value(all[j]), written(j, all[j])) << to_string(all[j]);
  const CellResult fresh;
  EXPECT_EQ(c.status, fresh.status);
  EXPECT_EQ(c.regime, fresh.regime);
  EXPECT_EQ(c.n, fresh.n);
  EXPECT_EQ(c.wall_s, fresh.wall_s);
  EXPECT_EQ(c.steady_residual, fresh.steady_residual);
  EXPECT_TRUE(std::isnan(c.soft_fraction));
  // A few members by name: the rows point where the names say.
  EXPECT_EQ(c.T_con, 0.5);
  EXPECT_EQ(c.hertz_valid, 1);
  EXPECT_EQ(c.lyapunov, written(static_cast<std::size_t>(Quantity::lyapunov), Quantity::lyapunov));
  EXPECT_EQ(c.clipped_impacts, written(static_cast<std::size_t>(Quantity::clipped_impacts), Quantity::clipped_impacts));
  const std::int64_t big = (std::int64_t{1} << 62) + 1;  // not a double: needs the int64 path
  set_quantity_int(c, Quantity::rhs_evals, big);
  EXPECT_EQ(quantity_int(c, Quantity::rhs_evals), big);
  EXPECT_EQ(c.rhs_evals, big);
  EXPECT_THROW(quantity_int(c, Quantity::T_con), std::logic_error);
  EXPECT_THROW(set_quantity(c, Quantity::hertz_valid, 2.0), std::invalid_argument);
  EXPECT_THROW(set_quantity(c, Quantity::periods, std::nan("")), std::invalid_argument);
}

// A map's long_name says "(NaN where not computed)" exactly for the quantities a default record
// holds as NaN: the Python readers take NaN there as "not computed" (vibromap_map.py) from it.
TEST(CellResult, TheDescriptionSaysNaNWhereNotComputedExactlyWhereTheDefaultIsNaN) {
  const CellResult fresh;
  for (const Quantity q : all_quantities())
    EXPECT_EQ(quantity_description(q).ends_with("(NaN where not computed)"), std::isnan(fresh.value(q))) << to_string(q);
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
