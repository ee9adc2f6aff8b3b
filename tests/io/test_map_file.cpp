// Tests of the regime-map writer and reader (io/map_file.hpp) and of the parts of the HDF5
// layer they added (int8/uint8 datasets, array attributes, fill values, dimension scales):
// exact round trips, the on-disk layout (NaN fill, flags, coordinates as dimension scales),
// atomic writing and the one-line IoError of a bad file.
//
// Reference map: every field of cell i is a simple formula in i (sample_cell), so each number
// read back is known independently of the solver (which this test does not use). The Python
// test postprocess/tests/test_map_xarray.py checks the same formulas on the sample file.

#include <gtest/gtest.h>

#include <array>
#include <map>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <unistd.h>
#include <vector>

#include "attribute_seal.hpp"
#include "support/temp_dir.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/map_file.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Seals a map changed in place again, as the writer seals a map it makes: the reader's own checks
// of what was changed are what a test sees then, not the seal's (any change unsealed is damage).
void reseal(Hdf5File& f) { detail::seal_attributes(f, kMapFormat, {"cells_done", "complete", "ranks"}); }

// A map's dataset replaced by `values` of `shape`, stored as the writer stores it (one chunk,
// allocated when made): the reader's own checks of the values are what a test sees then.
template <class T>
void replace_dataset(Hdf5File& f, const std::string& name, const std::vector<T>& values, const Shape& shape) {
  f.remove(name);
  DatasetOptions o;
  o.chunk = shape;
  o.fletcher32 = true;
  o.allocate_early = true;
  f.write_dataset(name, values, shape, o);
}

// The cell formulas (keep equal to postprocess/tests/test_map_xarray.py): cell i is done
// unless i % 5 == 3, and each field is an exact function of i.
bool sample_done(std::size_t i) { return i % 5 != 3; }

// Every quantity first gets a value of its own from its place j in the table (so a quantity the
// writer or reader drops or mixes up shows, whatever its name); the formulas below then set
// those the Python test checks.
CellResult sample_cell(std::size_t i) {
  const auto n = static_cast<double>(i);
  CellResult c;
  const std::vector<Quantity>& all = all_quantities();
  for (std::size_t j = 0; j < all.size(); ++j) {
    const Quantity q = all[j];
    const std::int64_t top = quantity_is_integer(q) ? std::min<std::int64_t>(quantity_max(q), 999) : 0;
    if (quantity_is_integer(q))
      set_quantity_int(c, q, static_cast<std::int64_t>(i + j) % (top + 1));
    else
      set_quantity(c, q, 0.5 * static_cast<double>(j + 1) + n / 64.0);
  }
  c.status = static_cast<std::int8_t>(i % 4);
  c.regime = static_cast<std::int8_t>(i % 9);
  c.n = static_cast<std::int32_t>(1 + i % 3);
  c.k = static_cast<std::int32_t>(1 + i % 2);
  c.hertz_valid = static_cast<std::int8_t>(i % 2);
  c.periods = 100 + 10 * static_cast<std::int64_t>(i);
  c.rhs_evals = (std::int64_t{1} << 40) + static_cast<std::int64_t>(i);  // beyond int32, exact in int64
  c.wall_s = 0.25 * (n + 1.0);
  c.steady_residual = 1e-9 * (n + 1.0);
  c.T_con = 1e-3 * (n + 1.0);
  c.k_con = 1000.0 / (n + 1.0);
  c.F_max = 1e5 * (n + 1.0);
  c.z_max = 1e-6 * (n + 1.0);
  c.z_ratio = 1e-3 / (n + 1.0);
  c.v_in = -0.1 * (n + 1.0);
  c.impulse = 7.0 * (n + 1.0);
  // Stability: unknown, unstable, stable in turn; the multiplier NaN where unknown (not
  // computed) and > 1 where unstable; the Lyapunov exponent computed in odd cells only.
  // Exact products and one division: no fused multiply-add can make numpy differ.
  c.stable = static_cast<std::int8_t>(static_cast<int>(i % 3) - 1);
  c.max_multiplier = i % 3 == 0 ? kNaN : i % 3 == 1 ? 1.0 + 0.25 * (n + 1.0) : 1.0 / (n + 2.0);
  c.lyapunov = i % 2 == 0 ? kNaN : (n + 1.0) / 64.0 - 0.0625;
  return c;
}

SweepMap sample_map(std::vector<Axis> axes, std::vector<Quantity> stored) {
  SweepMap map;
  map.grid = Grid(std::move(axes));
  map.stored = std::move(stored);
  for (std::size_t i = 0; i < map.grid.size(); ++i) {
    map.done.push_back(sample_done(i) ? 1 : 0);
    map.cells.push_back(sample_done(i) ? sample_cell(i) : CellResult{});
  }
  map.scene_text = "[sweep]\naxes = [\"E1\", \"R1\"]\nnote = \"UTF-8: \xce\xbb\"\n";
  map.ranks = 3;
  return map;
}

// 3 x 4 over E1 (log) and R1 (lin): the map the Python test reads.
SweepMap sample_map_2d() {
  return sample_map({{"contact.E1", "E1", "Pa", "Young's modulus of body 1", {2e4, 1e7, 2.1e11}, AxisScale::log},
                     {"contact.R1", "R1", "m", "radius of curvature of body 1", {0.09, 0.5, 1.0, 2.0}, AxisScale::lin}},
                    {Quantity::T_con, Quantity::k_con, Quantity::hertz_valid, Quantity::periods,
                     Quantity::max_multiplier, Quantity::lyapunov});
}

SweepMap sample_map_3d() {
  return sample_map({{"system.m2", "m2", "kg", "attached body mass", {100.0, 205.0, 310.0}, AxisScale::lin},
                     {"contact.E2", "E2", "Pa", "Young's modulus of body 2", axis_points(2e4, 2.1e11, 5, AxisScale::log),
                      AxisScale::log},
                     {"system.omega2", "omega2", "rad/s", "coupling spring frequency", {3.606, 5.646}, AxisScale::lin}},
                    all_quantities());
}

// Every field of every cell, compared exactly (NaN equal to NaN).
void expect_same_cells(const SweepMap& expected, const SweepMap& actual) {
  ASSERT_EQ(actual.cells.size(), expected.cells.size());
  const auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  for (std::size_t i = 0; i < expected.cells.size(); ++i) {
    const CellResult& e = expected.cells[i];
    const CellResult& a = actual.cells[i];
    SCOPED_TRACE("cell " + std::to_string(i));
    EXPECT_EQ(a.status, e.status);
    EXPECT_EQ(a.regime, e.regime);
    EXPECT_EQ(a.hertz_valid, e.hertz_valid);
    EXPECT_EQ(a.stable, e.stable);
    EXPECT_EQ(a.n, e.n);
    EXPECT_EQ(a.k, e.k);
    for (const auto member : {&CellResult::wall_s, &CellResult::steady_residual})
      EXPECT_TRUE(same(a.*member, e.*member)) << a.*member << " != " << e.*member;
    for (const Quantity q : all_quantities()) {
      if (quantity_is_integer(q))
        EXPECT_EQ(quantity_int(a, q), quantity_int(e, q)) << to_string(q);
      else
        EXPECT_TRUE(same(a.value(q), e.value(q))) << to_string(q) << ": " << a.value(q) << " != " << e.value(q);
    }
  }
}

void expect_same_grid(const Grid& expected, const Grid& actual) {
  ASSERT_EQ(actual.axes().size(), expected.axes().size());
  for (std::size_t d = 0; d < expected.axes().size(); ++d) {
    EXPECT_EQ(actual.axes()[d].name, expected.axes()[d].name);
    EXPECT_EQ(actual.axes()[d].values, expected.axes()[d].values);
    EXPECT_EQ(actual.axes()[d].scale, expected.axes()[d].scale);
    EXPECT_EQ(actual.axes()[d].categories, expected.axes()[d].categories);
  }
}

// What read_map gives back for `map`: the quantities not stored read as in a default record
// (0, NaN for max_multiplier and lyapunov).
SweepMap as_stored(SweepMap map) {
  const CellResult fresh;
  const auto stored = [&](Quantity q) { return std::find(map.stored.begin(), map.stored.end(), q) != map.stored.end(); };
  for (CellResult& c : map.cells)
    for (const Quantity q : all_quantities()) {
      if (stored(q)) continue;
      if (quantity_is_integer(q))
        set_quantity_int(c, q, quantity_int(fresh, q));
      else
        set_quantity(c, q, fresh.value(q));
    }
  return map;
}

void expect_round_trip(const SweepMap& map, const std::string& path) {
  write_map(path, map);
  const SweepMap back = read_map(path);
  expect_same_grid(map.grid, back.grid);
  EXPECT_EQ(back.stored, map.stored);
  EXPECT_EQ(back.done, map.done);
  expect_same_cells(as_stored(map), back);
  EXPECT_EQ(back.scene_text, map.scene_text);
  EXPECT_EQ(back.ranks, map.ranks);
}

// ---- round trips ------------------------------------------------------------------------

using MapFile = TempDir;

TEST_F(MapFile, RoundTripsA2dMapWithCellsNotDone) {
  const SweepMap map = sample_map_2d();
  ASSERT_EQ(map.grid.size(), 12u);
  ASSERT_EQ(std::count(map.done.begin(), map.done.end(), 0), 2);  // cells 3 and 8
  expect_round_trip(map, file("map2d.h5"));
  const SweepMap back = read_map(file("map2d.h5"));
  EXPECT_EQ(back.cells[3].status, kNotComputed);
  EXPECT_EQ(back.cells[3].regime, kNotComputed);
  EXPECT_EQ(back.cells[8].T_con, 0.0);  // a cell not done reads as a default record
  EXPECT_EQ(back.cells[5].F_max, 0.0);  // a quantity not stored reads as 0
  EXPECT_EQ(back.cells[8].stable, -1);
  EXPECT_TRUE(std::isnan(back.cells[8].max_multiplier));
}

TEST_F(MapFile, StabilityAndQuantitiesNotComputedRoundTripInCellsDone) {
  const SweepMap map = sample_map_2d();
  write_map(file("map.h5"), map);
  const SweepMap back = read_map(file("map.h5"));
  // Cell 0 is done, of unknown stability, with neither multiplier nor Lyapunov exponent.
  ASSERT_EQ(back.done[0], 1);
  EXPECT_EQ(back.cells[0].stable, -1);
  EXPECT_TRUE(std::isnan(back.cells[0].max_multiplier));
  EXPECT_TRUE(std::isnan(back.cells[0].lyapunov));
  EXPECT_EQ(back.cells[1].stable, 0);                  // unstable: |mu| = 1 + 0.25 * 2
  EXPECT_EQ(back.cells[1].max_multiplier, 1.5);
  EXPECT_EQ(back.cells[1].lyapunov, -0.03125);         // 2 / 64 - 1 / 16
  EXPECT_EQ(back.cells[2].stable, 1);                  // stable: |mu| = 1 / 4
  EXPECT_EQ(back.cells[2].max_multiplier, 0.25);
  EXPECT_TRUE(std::isnan(back.cells[2].lyapunov));
  EXPECT_EQ(back.cells[11].lyapunov, 0.125);  // 12 / 64 - 1 / 16
  const Hdf5File f(file("map.h5"));
  const auto stable = f.open_dataset("stable").read_int();
  const auto multiplier = f.open_dataset("max_multiplier").read_double();
  EXPECT_EQ(stable, (std::vector<std::int64_t>{-1, 0, 1, -1, 0, 1, -1, 0, -1, -1, 0, 1}));  // 3, 8 not done
  EXPECT_TRUE(std::isnan(multiplier[0]) && std::isnan(multiplier[3]));  // not computed, not done
  EXPECT_EQ(f.open_dataset("done").read_int()[0], 1);                  // which /done tells apart
  EXPECT_EQ(f.open_dataset("done").read_int()[3], 0);
}

TEST_F(MapFile, RoundTripsA3dMapWithEveryQuantity) {
  const SweepMap map = sample_map_3d();
  ASSERT_EQ(map.grid.size(), 30u);
  expect_round_trip(map, file("map3d.h5"));
  EXPECT_EQ(read_map(file("map3d.h5")).cells[29].rhs_evals, (std::int64_t{1} << 40) + 29);
}

TEST_F(MapFile, RoundTripsACompleteMapAndAMapWithNothingDone) {
  SweepMap map = sample_map_2d();
  for (std::size_t i = 0; i < map.grid.size(); ++i) {
    map.done[i] = 1;
    map.cells[i] = sample_cell(i);
  }
  expect_round_trip(map, file("complete.h5"));
  EXPECT_EQ(Hdf5File(file("complete.h5")).read_int_attribute("complete"), 1);
  map.done.assign(map.grid.size(), 0);
  map.cells.assign(map.grid.size(), CellResult{});
  expect_round_trip(map, file("empty.h5"));
  EXPECT_EQ(Hdf5File(file("empty.h5")).read_int_attribute("cells_done"), 0);
}

// A census map (issue #11): cell i lists i % 4 attractors (0 to 3, of a dimension of 3), each
// field of attractor a an exact formula in (i, a).
SweepMap sample_census_map() {
  SweepMap map = sample_map_2d();
  map.attractors = 3;
  for (std::size_t i = 0; i < map.grid.size(); ++i) {
    if (!map.done[i]) continue;
    CellResult& c = map.cells[i];
    const auto n = static_cast<double>(i);
    c.soft_fraction = 0.125 * static_cast<double>(i % 8);
    c.unresolved_fraction = i % 2 == 0 ? 0.0 : 0.0625;
    c.unlisted_fraction = 1.0 / (n + 1.0);
    c.budget_fraction = i % 3 == 0 ? 0.0 : 0.03125 * static_cast<double>(i % 5);
    c.basin_entropy = 0.0078125 * static_cast<double>(i % 89);
    for (std::size_t a = 0; a < i % 4; ++a) {
      Attractor r;
      const auto x = static_cast<double>(a);
      r.regime = Regime{static_cast<RegimeKind>((i + a) % 9), static_cast<int>(1 + a), static_cast<int>(1 + i % 3)};
      r.stable = static_cast<int>((i + a) % 3) - 1;
      r.hertz_valid = a % 2 == 1;
      r.from_rest = a == 0;
      r.soft = (i + a) % 2 == 1;
      r.transient = (i + a) % 3 == 0;
      r.T_con = 1e-3 * (n + x + 1.0);
      r.k_con = 100.0 / (n + x + 1.0);
      r.F_max = 1e5 * (x + 1.0);
      r.z_ratio = 1e-4 * (x + 1.0);
      r.max_floquet = a == 2 ? kNaN : 0.5 + 0.125 * x;
      r.fraction = 0.25 * (x + 1.0) / 2.0;
      r.fraction_stderr = 0.01 * (x + 1.0);
      if (a != 1) r.strobe = {Eigen::Vector4d(-0.01 * x, 0.05 + n, 0.5 * x, -0.25 * n)};  // none for attractor 1
      c.census.push_back(r);
    }
  }
  return map;
}

TEST_F(MapFile, RoundTripsACensusMapWithItsAttractorDimension) {
  const SweepMap map = sample_census_map();
  expect_round_trip(map, file("census.h5"));
  const SweepMap back = read_map(file("census.h5"));
  EXPECT_EQ(back.attractors, 3u);
  const auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  for (std::size_t i = 0; i < map.grid.size(); ++i) {
    SCOPED_TRACE("cell " + std::to_string(i));
    const CellResult& e = map.cells[i];
    const CellResult& a = back.cells[i];
    ASSERT_EQ(a.census.size(), e.census.size());
    for (const auto member : {&CellResult::soft_fraction, &CellResult::unresolved_fraction, &CellResult::unlisted_fraction,
                              &CellResult::budget_fraction, &CellResult::basin_entropy})
      EXPECT_TRUE(same(a.*member, e.*member));
    for (std::size_t k = 0; k < e.census.size(); ++k) {
      const Attractor& x = e.census[k];
      const Attractor& y = a.census[k];
      EXPECT_EQ(y.regime, x.regime);
      EXPECT_EQ(std::vector<int>({y.stable, y.hertz_valid, y.from_rest, y.soft, y.transient}),
                std::vector<int>({x.stable, x.hertz_valid, x.from_rest, x.soft, x.transient}));
      for (const auto member : {&Attractor::T_con, &Attractor::k_con, &Attractor::F_max, &Attractor::z_ratio,
                                &Attractor::max_floquet, &Attractor::fraction, &Attractor::fraction_stderr})
        EXPECT_TRUE(same(y.*member, x.*member));
      // The first stroboscopic state; none is read back as one of NaN.
      ASSERT_EQ(y.strobe.size(), 1u);
      for (int d = 0; d < 4; ++d) EXPECT_TRUE(same(y.strobe[0][d], x.strobe.empty() ? kNaN : x.strobe[0][d]));
    }
  }
  // On disk: (E1, R1, attractor), slots beyond a cell's attractors hold the fill values.
  const Hdf5File f(file("census.h5"));
  EXPECT_EQ(f.read_int_attribute("census_attractors"), 3);
  const Dataset fraction = f.open_dataset("attractor_fraction");
  EXPECT_EQ(fraction.shape(), (Shape{3, 4, 3}));
  EXPECT_EQ(fraction.attached_scales(2), std::vector<std::string>{"/attractor"});
  const auto values = fraction.read_double();
  EXPECT_EQ(values[2 * 3 + 1], 0.25);                                  // cell 2, attractor 1
  EXPECT_TRUE(std::isnan(values[2 * 3 + 2]));                           // cell 2 lists 2
  EXPECT_EQ(f.open_dataset("attractor_regime").read_int()[2 * 3 + 2], -1);
  EXPECT_EQ(f.open_dataset("attractors").read_int()[7], 3);
  EXPECT_EQ(f.open_dataset("attractor").read_int(), (std::vector<std::int64_t>{0, 1, 2}));
}

TEST_F(MapFile, ADamagedCensusDatasetIsNamed) {
  write_map(file("census.h5"), sample_census_map());
  {
    Hdf5File f(file("census.h5"), FileMode::read_write);
    replace_dataset(f, "attractors", std::vector<int>(12, 4), {3, 4});
    reseal(f);
  }
  try {
    read_map(file("census.h5"));
    FAIL() << "a census map listing 4 attractors in a dimension of 3 was read";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()),
              file("census.h5") + ": not a valid vibromap map: dataset '/attractors' holds 4, outside 0..3");
  }
}

TEST_F(MapFile, AListedAttractorWithoutARegimeOrFlagIsRefused) {
  // -1 (not listed) fills the slots beyond a cell's attractors; a listed one holding it is malformed.
  for (const std::string name : {"attractor_regime", "attractor_soft"}) {
    SCOPED_TRACE(name);
    write_map(file("census.h5"), sample_census_map());
    {
      Hdf5File f(file("census.h5"), FileMode::read_write);
      std::vector<std::int64_t> codes = f.open_dataset(name).read_int();
      codes[7 * 3 + 2] = -1;  // cell 7 lists 3 attractors
      replace_dataset(f, name, std::vector<std::int8_t>(codes.begin(), codes.end()), {3, 4, 3});
      reseal(f);
    }
    try {
      read_map(file("census.h5"));
      FAIL() << "a listed attractor with " << name << " -1 was read";
    } catch (const IoError& e) {
      EXPECT_EQ(std::string(e.what()), file("census.h5") + ": not a valid vibromap map: dataset '/" + name +
                                           "' holds -1 (not listed) for a listed attractor");
    }
  }
}

// ---- the layout on disk -----------------------------------------------------------------

TEST_F(MapFile, CellsNotDoneHoldTheFillValuesOnDisk) {
  const SweepMap map = sample_map_2d();
  write_map(file("map.h5"), map);
  const Hdf5File f(file("map.h5"));
  const auto done = f.open_dataset("done").read_int();
  const auto regime = f.open_dataset("regime").read_int();
  const auto status = f.open_dataset("status").read_int();
  const auto stable = f.open_dataset("stable").read_int();
  const auto n = f.open_dataset("n").read_int();
  const auto periods = f.open_dataset("periods").read_int();
  const auto T_con = f.open_dataset("T_con").read_double();
  const auto wall_s = f.open_dataset("wall_s").read_double();
  for (std::size_t i = 0; i < map.grid.size(); ++i) {
    SCOPED_TRACE("cell " + std::to_string(i));
    EXPECT_EQ(done[i], sample_done(i) ? 1 : 0);
    if (sample_done(i)) {
      EXPECT_EQ(regime[i], sample_cell(i).regime);
      EXPECT_EQ(T_con[i], sample_cell(i).T_con);
      continue;
    }
    EXPECT_EQ(regime[i], -1);
    EXPECT_EQ(status[i], -1);
    EXPECT_EQ(stable[i], -1);
    EXPECT_EQ(n[i], 0);
    EXPECT_EQ(periods[i], 0);
    EXPECT_TRUE(std::isnan(T_con[i]));
    EXPECT_TRUE(std::isnan(wall_s[i]));
  }
  for (const char* name : {"T_con", "k_con", "max_multiplier", "lyapunov", "wall_s", "steady_residual"})
    EXPECT_TRUE(std::isnan(f.open_dataset(name).read_double_attribute("_FillValue"))) << name;
  for (const char* name : {"done", "regime", "status", "stable", "n", "k", "periods", "hertz_valid"})
    EXPECT_FALSE(f.open_dataset(name).has_attribute("_FillValue")) << name;
}

TEST_F(MapFile, StoresOnlyTheRequestedQuantities) {
  SweepMap map = sample_map_2d();
  map.stored = {Quantity::z_ratio, Quantity::rhs_evals};
  write_map(file("map.h5"), map);
  {
    const Hdf5File f(file("map.h5"));
    EXPECT_EQ(f.read_string_attribute("stored"), "z_ratio rhs_evals");
    for (const Quantity q : all_quantities()) {
      const bool wanted = q == Quantity::z_ratio || q == Quantity::rhs_evals;
      EXPECT_EQ(f.exists(to_string(q)), wanted) << to_string(q);
    }
    for (const char* always :
         {"E1", "R1", "done", "status", "regime", "stable", "n", "k", "wall_s", "steady_residual"})
      EXPECT_TRUE(f.exists(always)) << always;
  }
  const SweepMap back = read_map(file("map.h5"));
  EXPECT_EQ(back.stored, map.stored);
  EXPECT_EQ(back.cells[1].z_ratio, sample_cell(1).z_ratio);
  EXPECT_EQ(back.cells[1].rhs_evals, sample_cell(1).rhs_evals);
  EXPECT_EQ(back.cells[1].T_con, 0.0);
  EXPECT_EQ(back.cells[1].periods, 0);
  EXPECT_EQ(back.cells[1].stable, 0);  // always kept
  EXPECT_TRUE(std::isnan(back.cells[1].max_multiplier));  // not stored: NaN, as in a default record

  map.stored.clear();
  expect_round_trip(map, file("none.h5"));
  EXPECT_EQ(Hdf5File(file("none.h5")).read_string_attribute("stored"), "");
}

TEST_F(MapFile, ACategoricalAxisKeepsItsIndicesAndNamesThem) {
  Axis law{"contact.law", "law", "1", "contact law", {3.0, 1.0}, AxisScale::lin,
           {"hertz", "hunt-crossley", "lankarani-nikravesh", "flores", "gonthier"}};
  const SweepMap map = sample_map(
      {law, {"contact.restitution", "restitution", "1", "restitution", {0.1, 0.5, 0.9}, AxisScale::lin}},
      {Quantity::k_con, Quantity::e_effective, Quantity::energy_dissipated, Quantity::clipped_impacts});
  write_map(file("law.h5"), map);
  {
    const Hdf5File f(file("law.h5"));
    const Dataset coordinate = f.open_dataset("law");
    EXPECT_EQ(coordinate.read_double(), (std::vector<double>{3.0, 1.0}));
    EXPECT_EQ(coordinate.read_string_attribute("flag_meanings"),
              "hertz hunt-crossley lankarani-nikravesh flores gonthier");
    EXPECT_FALSE(f.open_dataset("restitution").has_attribute("flag_meanings"));
  }
  const SweepMap back = read_map(file("law.h5"));
  expect_same_grid(map.grid, back.grid);
  EXPECT_EQ(back.grid.axes()[0].categories.at(3), "flores");
  EXPECT_TRUE(back.grid.axes()[1].categories.empty());
}

TEST_F(MapFile, CoordinatesAreDimensionScalesAttachedInAxisOrder) {
  const SweepMap map = sample_map_3d();
  write_map(file("map.h5"), map);
  const Hdf5File f(file("map.h5"));
  const std::vector<std::string> axes = {"m2", "E2", "omega2"};
  const std::vector<std::string> units = {"kg", "Pa", "rad/s"};
  for (std::size_t d = 0; d < axes.size(); ++d) {
    const Dataset coordinate = f.open_dataset(axes[d]);
    EXPECT_TRUE(coordinate.is_dimension_scale());
    EXPECT_EQ(coordinate.dimension_scale_name(), axes[d]);
    EXPECT_EQ(coordinate.read_double(), map.grid.axes()[d].values);
    EXPECT_EQ(coordinate.read_string_attribute("units"), units[d]);
    EXPECT_FALSE(coordinate.read_string_attribute("long_name").empty());
    EXPECT_EQ(coordinate.read_string_attribute("scale"), d == 1 ? "log" : "lin");
  }
  std::vector<std::string> fields = {"done", "status", "regime", "stable", "n", "k", "wall_s", "steady_residual"};
  for (const Quantity q : all_quantities()) fields.push_back(to_string(q));
  for (const std::string& name : fields) {
    const Dataset dataset = f.open_dataset(name);
    EXPECT_FALSE(dataset.is_dimension_scale()) << name;
    EXPECT_EQ(dataset.dimension_scale_name(), "") << name;
    EXPECT_EQ(dataset.shape(), (Shape{3, 5, 2})) << name;
    EXPECT_FALSE(dataset.read_string_attribute("long_name").empty()) << name;
    for (std::size_t d = 0; d < axes.size(); ++d)
      EXPECT_EQ(dataset.attached_scales(d), std::vector<std::string>{"/" + axes[d]}) << name << " dim " << d;
  }
  EXPECT_EQ(f.open_dataset("T_con").read_string_attribute("units"), "s");
  EXPECT_EQ(f.open_dataset("impulse").read_string_attribute("units"), "N s");
  EXPECT_EQ(f.open_dataset("lyapunov").read_string_attribute("units"), "1/s");
  EXPECT_EQ(f.open_dataset("max_multiplier").read_string_attribute("units"), "1");
  for (const Quantity q : all_quantities()) {  // each as the quantity table describes it
    const Dataset dataset = f.open_dataset(to_string(q));
    EXPECT_EQ(dataset.read_string_attribute("long_name"), quantity_description(q));
    EXPECT_EQ(dataset.read_string_attribute("units"), quantity_units(q)) << to_string(q);
    EXPECT_EQ(dataset.element_type_text(), quantity_is_integer(q) ? "<i8" : "<f8") << to_string(q);
  }
  EXPECT_EQ(f.open_dataset("lyapunov").read_string_attribute("long_name"),
            "largest Lyapunov exponent (NaN where not computed)");
  EXPECT_EQ(f.open_dataset("rhs_evals").read_string_attribute("long_name"), "right-hand side evaluations");
  EXPECT_THROW(f.open_dataset("done").attached_scales(3), IoError);
}

TEST_F(MapFile, FlagsAndRootAttributesFollowTheLayout) {
  const SweepMap map = sample_map_2d();
  write_map(file("map.h5"), map);
  const Hdf5File f(file("map.h5"));
  const Dataset regime = f.open_dataset("regime");
  EXPECT_EQ(regime.read_int_array_attribute("flag_values"), (std::vector<std::int64_t>{-1, 0, 1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(regime.read_string_attribute("flag_meanings"),
            "not_computed periodic chatter no_contact permanent_contact quasi_periodic chaotic non_periodic "
            "unresolved failed");
  const Dataset status = f.open_dataset("status");
  EXPECT_EQ(status.read_int_array_attribute("flag_values"), (std::vector<std::int64_t>{-1, 0, 1, 2, 3}));
  EXPECT_EQ(status.read_string_attribute("flag_meanings"), "not_computed ok budget failed invalid_input");
  const Dataset stable = f.open_dataset("stable");
  EXPECT_EQ(stable.read_int_array_attribute("flag_values"), (std::vector<std::int64_t>{-1, 0, 1}));
  EXPECT_EQ(stable.read_string_attribute("flag_meanings"), "unknown unstable stable");
  EXPECT_FALSE(stable.read_string_attribute("long_name").empty());
  EXPECT_EQ(f.read_string_attribute("title"), "vibromap regime map");
  EXPECT_EQ(f.read_string_attribute("Conventions"), "CF-1.8");
  EXPECT_EQ(f.read_string_attribute("vibromap_version"), VIBROMAP_VERSION);
  EXPECT_EQ(f.read_string_attribute("scene"), map.scene_text);
  EXPECT_EQ(f.read_int_attribute("ranks"), 3);
  EXPECT_EQ(f.read_int_attribute("cells_total"), 12);
  EXPECT_EQ(f.read_int_attribute("cells_done"), 10);
  EXPECT_EQ(f.read_int_attribute("complete"), 0);
  EXPECT_EQ(f.read_string_attribute("stored"), "T_con k_con hertz_valid periods max_multiplier lyapunov");
}

// ---- atomic writing and refusals --------------------------------------------------------

TEST_F(MapFile, UnwritableDirectoryThrowsIoErrorAndLeavesNoTmp) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  const fs::path locked = dir_ / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  const std::string path = (locked / "map.h5").string();
  EXPECT_THROW(write_map(path, sample_map_2d()), IoError);
  fs::permissions(locked, fs::perms::owner_all);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST_F(MapFile, ADirectoryInTheWayIsRefusedAndNothingIsLeftBesideIt) {
  // Before the write: refused at once. During it (the directory made while the map is being
  // written): the rename is refused, and the new file removed.
  const std::string path = file("occupied");
  fs::create_directories(fs::path(path) / "inside");
  const auto leftovers = [&] {
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(fs::path(path).parent_path()))
      n += e.path().extension() == ".tmp";
    return n;
  };
  EXPECT_THROW(write_map(path, sample_map_2d()), SceneError);
  EXPECT_EQ(leftovers(), 0u);
  fs::remove_all(path);
  {
    NewFile out(path);
    { MapWriter w = MapWriter::create_in(out, MapLayout{sample_map_2d().grid, {}, "", "", 0}, 1); }
    fs::create_directories(fs::path(path) / "inside");
    EXPECT_THROW(out.commit(), SceneError);
  }
  EXPECT_EQ(leftovers(), 0u);
  EXPECT_TRUE(fs::is_directory(fs::path(path) / "inside"));
}

TEST_F(MapFile, RewritingReplacesTheMapWhole) {
  SweepMap map = sample_map_2d();
  write_map(file("map.h5"), map);
  map.done.assign(map.grid.size(), 1);
  for (std::size_t i = 0; i < map.grid.size(); ++i) map.cells[i] = sample_cell(i);
  map.stored = {Quantity::v_in};
  write_map(file("map.h5"), map);  // a checkpoint replaced by the next one
  const SweepMap back = read_map(file("map.h5"));
  EXPECT_EQ(back.stored, map.stored);
  expect_same_cells(as_stored(map), back);
  EXPECT_FALSE(Hdf5File(file("map.h5")).exists("T_con"));
  EXPECT_FALSE(fs::exists(file("map.h5.tmp")));
}

TEST_F(MapFile, InconsistentMapIsRefusedBeforeAnyFileIsMade) {
  const std::string path = file("map.h5");
  const auto expect_refused = [&](const SweepMap& map, const std::string& why) {
    try {
      write_map(path, map);
      FAIL() << "expected IoError: " << why;
    } catch (const IoError& e) {
      EXPECT_EQ(std::string(e.what()), path + ": cannot write map: " + why);
    }
    EXPECT_FALSE(fs::exists(path));
    EXPECT_FALSE(fs::exists(path + ".tmp"));
  };
  SweepMap map = sample_map_2d();
  map.cells.pop_back();
  expect_refused(map, "11 cell records for 12 cells");
  map = sample_map_2d();
  map.done.push_back(0);
  expect_refused(map, "13 done flags for 12 cells");
  map = sample_map_2d();
  map.stored.push_back(Quantity::k_con);
  expect_refused(map, "quantity 'k_con' is stored twice");
  expect_refused(sample_map({{"contact.E1", "E1", "Pa", "", {1.0, 2.0}}, {"contact.E1", "E1", "Pa", "", {3.0}}}, {}),
                 "axis 'E1' appears twice");
  SweepMap no_axes;
  no_axes.cells.resize(1);
  no_axes.done.resize(1);
  expect_refused(no_axes, "the grid has no axes");
}

// ---- reading a bad file -----------------------------------------------------------------

// The message of the IoError that read_map(path) throws ("" if none).
std::string read_error(const std::string& path) {
  try {
    read_map(path);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST_F(MapFile, ReadingAMissingOrForeignFileThrowsIoErrorNamingIt) {
  const std::string missing = file("missing.h5");
  EXPECT_EQ(read_error(missing), missing + ": cannot open file for reading (No such file or directory)");
  const std::string text = file("text.h5");
  std::ofstream(text) << "not hdf5\n";
  EXPECT_EQ(read_error(text).rfind(text + ": cannot open file for reading", 0), 0u) << read_error(text);
  const std::string other = file("other.h5");
  {
    Hdf5File f(other, FileMode::truncate);
    f.write_dataset("t", std::vector<double>{0.0, 1.0});
  }
  EXPECT_EQ(read_error(other), other + ": not a vibromap regime map (no root attribute 'version')");
}

// Writes the 2-D sample map to `path`, then lets `damage` alter it in place and seals it again
// (resealed = true: the reader's own checks are what is tested then). Unsealed, any such change is
// refused first as damage (attribute_seal.hpp).
template <class Damage>
std::string damaged_map_error(const std::string& path, Damage damage, bool resealed = true) {
  write_map(path, sample_map_2d());
  {
    Hdf5File f(path, FileMode::read_write);
    damage(f);
    if (resealed) reseal(f);
  }
  return read_error(path);
}

TEST_F(MapFile, ReadingADamagedMapNamesTheFileAndTheDataset) {
  const std::string path = file("map.h5");
  const std::string prefix = path + ": not a valid vibromap map: ";
  EXPECT_EQ(damaged_map_error(path, [](Hdf5File& f) { f.remove("regime"); }), prefix + "no dataset '/regime'");
  const std::string damage = path + ": damaged: its attributes fail their checksum (attribute_checksum says crc32 ";
  EXPECT_EQ(damaged_map_error(path, [](Hdf5File& f) { f.remove("regime"); }, false).substr(0, damage.size()), damage);
  EXPECT_EQ(damaged_map_error(path, [](Hdf5File& f) { f.remove("k_con"); }), prefix + "no dataset '/k_con'");
  EXPECT_EQ(damaged_map_error(path, [](Hdf5File& f) { f.remove("done"); }), prefix + "no dataset '/done'");
  EXPECT_EQ(damaged_map_error(path, [](Hdf5File& f) { f.remove("stable"); }), prefix + "no dataset '/stable'");
  const auto replaced = [](std::string name, std::vector<int> values, Shape shape) {
    return [=](Hdf5File& f) { replace_dataset(f, name, values, shape); };
  };
  EXPECT_EQ(damaged_map_error(path, replaced("stable", std::vector<int>(12, 2), {3, 4})),
            prefix + "dataset '/stable' holds 2, outside -1..1");
  EXPECT_EQ(damaged_map_error(path, replaced("hertz_valid", std::vector<int>(12, 2), {3, 4})),
            prefix + "dataset '/hertz_valid' holds 2, outside 0..1");
  EXPECT_EQ(damaged_map_error(path, replaced("n", std::vector<int>(6, 1), {3, 2})),
            prefix + "dataset '/n' has shape 3x2, expected 3x4 (the axes' lengths)");
  EXPECT_EQ(damaged_map_error(path, replaced("regime", std::vector<int>(12, 9), {3, 4})),
            prefix + "dataset '/regime' holds 9, outside -1..8");
  EXPECT_EQ(damaged_map_error(path, [](Hdf5File& f) { f.set_attribute("stored", "T_con speed"); }),
            prefix + "root attribute 'stored' names an unknown quantity 'speed'");
  EXPECT_EQ(damaged_map_error(path, [](Hdf5File& f) { f.set_attribute("cells_total", 11); }),
            prefix + "root attribute 'cells_total' differs from the grid's 12 cells");
  for (const char* name : {"census_attractors", "steady", "hertz_limit", "soft_kcon"})  // every map has them
    EXPECT_EQ(damaged_map_error(path, [&](Hdf5File& f) { f.remove_attribute(name); }),
              prefix + "no root attribute '" + name + "'");
  EXPECT_EQ(damaged_map_error(path, [](Hdf5File& f) { f.open_dataset("R1").set_attribute("scale", "cubic"); }),
            prefix + "coordinate '/R1': unknown axis scale 'cubic' (allowed: lin, log)");
}

// ---- the HDF5 layer's additions ---------------------------------------------------------

using Hdf5Additions = TempDir;

TEST_F(Hdf5Additions, Int8AndUint8ArraysRoundTrip) {
  const std::string path = file("small.h5");
  const std::vector<std::int8_t> codes = {-128, -1, 0, 1, 8, 127};
  const std::vector<std::uint8_t> flags = {0, 1, 255, 7, 0, 1};
  {
    Hdf5File f(path, FileMode::truncate);
    f.write_dataset("codes", codes, {2, 3});
    f.write_dataset("flags", flags, {3, 2}, DatasetOptions{{1, 2}, 4});
  }
  const Hdf5File f(path);
  EXPECT_EQ(f.open_dataset("codes").shape(), (Shape{2, 3}));
  EXPECT_EQ(f.open_dataset("codes").read_int(), (std::vector<std::int64_t>{-128, -1, 0, 1, 8, 127}));
  EXPECT_EQ(f.open_dataset("flags").read_int(), (std::vector<std::int64_t>{0, 1, 255, 7, 0, 1}));
  EXPECT_EQ(f.open_dataset("flags").read_double(), (std::vector<double>{0, 1, 255, 7, 0, 1}));
}

TEST_F(Hdf5Additions, ArrayAttributesAndFillValuesRoundTrip) {
  const std::string path = file("attrs.h5");
  {
    Hdf5File f(path, FileMode::truncate);
    Dataset d = f.write_dataset("x", std::vector<double>{1.0, 2.0}, {}, DatasetOptions{{}, 0, -7.5});
    d.set_attribute("flag_values", std::vector<std::int8_t>{-1, 0, 5});
    d.set_attribute("valid_range", std::vector<double>{0.0, 1e300});
    d.set_attribute("valid_range", std::vector<double>{0.5, 2.5});  // replaced
    Dataset i = f.write_dataset("i", std::vector<int>{1, 2}, {}, DatasetOptions{{}, 0, -1.0});
    EXPECT_THROW(d.set_attribute("empty", std::vector<std::int8_t>{}), IoError);
  }
  const Hdf5File f(path);
  const Dataset d = f.open_dataset("x");
  EXPECT_EQ(d.read_int_array_attribute("flag_values"), (std::vector<std::int64_t>{-1, 0, 5}));
  EXPECT_EQ(d.read_double_array_attribute("flag_values"), (std::vector<double>{-1, 0, 5}));
  EXPECT_EQ(d.read_double_array_attribute("valid_range"), (std::vector<double>{0.5, 2.5}));
  EXPECT_EQ(d.read_double_attribute("_FillValue"), -7.5);
  EXPECT_EQ(d.read_double_array_attribute("_FillValue"), (std::vector<double>{-7.5}));  // a scalar is one element
  EXPECT_THROW(d.read_int_array_attribute("_FillValue"), IoError);  // a float is not an integer
  EXPECT_THROW(d.read_double_attribute("valid_range"), IoError);   // not a scalar
  EXPECT_EQ(f.open_dataset("i").read_int_attribute("_FillValue"), -1);  // of the dataset's own type
  EXPECT_THROW(d.read_int_array_attribute("missing"), IoError);
}

// ---- the sample for the Python tests ----------------------------------------------------

// Writes the 2-D sample map where VIBROMAP_SAMPLE_MAP says (ctest sets it for
// postprocess/tests/test_map_xarray.py, which checks it with h5py and xarray).
TEST(MapFileSample, WritesTheSampleForThePython) {
  const char* path = std::getenv("VIBROMAP_SAMPLE_MAP");
  if (path == nullptr) GTEST_SKIP() << "VIBROMAP_SAMPLE_MAP not set (set by ctest's postprocess tests)";
  write_map(path, sample_map_2d());
  EXPECT_EQ(read_map(path).grid.size(), 12u);
}

}  // namespace
}  // namespace vibromap
