// The [sweep] section of a scene (io/scene/): axes, order, store, intervals, overrides,
// one-line errors, provenance, the reference scene's example and the sweep jobs in jobs/.

#include <cmath>
#include <cstddef>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "support/scene_testing.hpp"
#include "vibromap/io/scene/docs.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/io/scene/cell_maker.hpp"
#include "vibromap/core/grid.hpp"

namespace vibromap {
namespace {

using test::concat;
using test::error_of;
using test::kFile;
using test::parse;
using test::read_text;
using test::source_path;
constexpr double kLogRatioTol = 1e-12;  // relative spread of v[i+1]/v[i] on a log axis

// The sweep of a scene that must have one.
SweepOptions sweep_of(const std::string& text, const std::vector<std::string>& sets = {}) {
  const Scene s = parse(text, sets);
  if (!s.sweep) {
    ADD_FAILURE() << "no sweep in:\n" << text;
    return {};
  }
  return *s.sweep;
}

std::vector<std::string> axis_names(const SweepOptions& s) {
  std::vector<std::string> names;
  for (const Axis& a : s.axes) names.push_back(a.name);
  return names;
}

void expect_same_sweep(const SweepOptions& a, const SweepOptions& b) {
  ASSERT_EQ(a.axes.size(), b.axes.size());
  for (std::size_t i = 0; i < a.axes.size(); ++i) {
    EXPECT_EQ(a.axes[i].key, b.axes[i].key);
    EXPECT_EQ(a.axes[i].name, b.axes[i].name);
    EXPECT_EQ(a.axes[i].units, b.axes[i].units);
    EXPECT_EQ(a.axes[i].long_name, b.axes[i].long_name);
    EXPECT_EQ(a.axes[i].values, b.axes[i].values) << a.axes[i].name;  // exact: the text round-trips
    EXPECT_EQ(a.axes[i].scale, b.axes[i].scale) << a.axes[i].name;
  }
  EXPECT_EQ(a.store, b.store);
  EXPECT_EQ(a.checkpoint_interval, b.checkpoint_interval);
  EXPECT_EQ(a.progress_interval, b.progress_interval);
}

// Largest relative deviation of the ratios of successive points from the first ratio.
double log_ratio_spread(const std::vector<double>& v) {
  const double r0 = v[1] / v[0];
  double spread = 0.0;
  for (std::size_t i = 1; i + 1 < v.size(); ++i) spread = std::max(spread, std::abs(v[i + 1] / v[i] / r0 - 1.0));
  return spread;
}

// ---------------------------------------------------------------------------------------
// Reading a valid section

TEST(SweepScene, SceneWithoutSweepHasNone) {
  EXPECT_FALSE(parse("").sweep.has_value());
  EXPECT_FALSE(parse("[contact]\nE1 = 1e9\n").sweep.has_value());
  EXPECT_FALSE(load_scene(source_path("jobs/paper/table2.toml")).sweep.has_value());
}

TEST(SweepScene, LogAxisHasExactEndsAndConstantRatio) {
  const SweepOptions s = sweep_of("[sweep]\nE1 = { from = 2e4, to = 2.1e11, n = 23, scale = \"log\" }\n");
  ASSERT_EQ(s.axes.size(), 1u);
  const Axis& a = s.axes[0];
  EXPECT_EQ(a.name, "E1");
  EXPECT_EQ(a.scale, AxisScale::log);
  ASSERT_EQ(a.values.size(), 23u);
  EXPECT_EQ(a.values.front(), 2e4);
  EXPECT_EQ(a.values.back(), 2.1e11);
  EXPECT_LT(log_ratio_spread(a.values), kLogRatioTol);
  EXPECT_NEAR(a.values[1] / a.values[0], std::pow(2.1e11 / 2e4, 1.0 / 22.0), 1e-12);
}

TEST(SweepScene, LinAxisIsTheDefaultScaleWithEvenSteps) {
  const SweepOptions s = sweep_of("[sweep]\nR1 = { from = 0.09, to = 2, n = 5 }\n");
  const Axis& a = s.axes.at(0);
  EXPECT_EQ(a.scale, AxisScale::lin);
  ASSERT_EQ(a.values.size(), 5u);
  EXPECT_EQ(a.values.front(), 0.09);
  EXPECT_EQ(a.values.back(), 2.0);
  for (std::size_t i = 1; i < a.values.size(); ++i) EXPECT_NEAR(a.values[i] - a.values[i - 1], (2.0 - 0.09) / 4.0, 1e-14);
}

TEST(SweepScene, ExplicitValuesAreKeptAsGiven) {
  const SweepOptions s =
      sweep_of("[sweep]\nE2 = { values = [2.1e11, 2e4, 1000000] }\nm2 = { values = [310], scale = \"log\" }\n");
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_EQ(s.axes[0].values, (std::vector<double>{2.1e11, 2e4, 1e6}));
  EXPECT_EQ(s.axes[0].scale, AxisScale::lin);
  EXPECT_EQ(s.axes[1].values, (std::vector<double>{310.0}));
  EXPECT_EQ(s.axes[1].scale, AxisScale::log);
}

TEST(SweepScene, OnePointAndWholeFloatCount) {
  const SweepOptions s = sweep_of("[sweep]\nomega2 = { from = 4.0, to = 4.0, n = 1 }\nm2 = { from = 100, to = 310, n = 3.0 }\n");
  EXPECT_EQ(s.axes.at(0).values, (std::vector<double>{100.0, 205.0, 310.0}));
  EXPECT_EQ(s.axes.at(1).values, (std::vector<double>{4.0}));
}

TEST(SweepScene, DefaultOrderIsCanonicalWhateverTheFileOrder) {
  const SweepOptions s = sweep_of(
      "[sweep]\nomega2 = { values = [4.0] }\nm2 = { values = [200] }\nE2 = { values = [1e6] }\n"
      "R1 = { values = [1] }\nE1 = { values = [1e9] }\n");
  EXPECT_EQ(axis_names(s), (std::vector<std::string>{"E1", "E2", "R1", "m2", "omega2"}));
}

TEST(SweepScene, OrderSetsTheAxisOrder) {
  const SweepOptions s = sweep_of(
      "[sweep]\nE1 = { values = [1e9, 2e9] }\nE2 = { values = [1e6, 2e6, 3e6] }\nk2 = { values = [3000] }\n"
      "order = [\"k2\", \"E2\", \"E1\"]\n");
  EXPECT_EQ(axis_names(s), (std::vector<std::string>{"k2", "E2", "E1"}));
  EXPECT_EQ(s.axes[1].values.size(), 3u);  // values travel with their axis
  const Grid grid(s.axes);
  EXPECT_EQ(grid.size(), 6u);
  EXPECT_EQ(grid.shape(), (std::vector<std::size_t>{1, 3, 2}));
}

TEST(SweepScene, StoreAndIntervals) {
  const SweepOptions d = sweep_of("[sweep]\nE1 = { values = [1e9] }\n");
  const SweepOptions defaults;
  EXPECT_EQ(d.store, defaults.store);
  EXPECT_EQ(d.checkpoint_interval, defaults.checkpoint_interval);
  EXPECT_EQ(d.progress_interval, defaults.progress_interval);

  const SweepOptions s = sweep_of(
      "[sweep]\nE1 = { values = [1e9] }\nstore = [\"v_in\", \"T_con\", \"hertz_valid\", \"rhs_evals\"]\n"
      "checkpoint_interval = 5\nprogress_interval = 0.5\n");
  EXPECT_EQ(s.store, (std::vector<Quantity>{Quantity::v_in, Quantity::T_con, Quantity::hertz_valid, Quantity::rhs_evals}));
  EXPECT_EQ(s.checkpoint_interval, 5.0);
  EXPECT_EQ(s.progress_interval, 0.5);
  // Every map stores hertz_valid (its pictures mark where the Hertz law fails): added when not listed.
  EXPECT_EQ(sweep_of("[sweep]\nE1 = { values = [1e9] }\nstore = []\n").store, std::vector<Quantity>{Quantity::hertz_valid});
}

TEST(SweepScene, SubtableFormIsAnAxisToo) {
  const SweepOptions s = sweep_of("[sweep.E1]\nfrom = 1e5\nto = 1e9\nn = 5\nscale = \"log\"\n");
  EXPECT_EQ(s.axes.at(0).values.size(), 5u);
  EXPECT_NEAR(s.axes[0].values[1], 1e6, 1e-6);
}

TEST(SweepScene, SweptSpringReplacesTheBaseSpringPerCell) {
  const Scene s = parse("[system]\nm2 = 310.0\nomega2 = 3.606\n[sweep]\nk2 = { values = [1000, 4000] }\n");
  ASSERT_TRUE(s.sweep.has_value());
  EXPECT_EQ(s.params.spring2.form, Spring::Form::frequency);  // the base keeps its own value
  EXPECT_EQ(s.params.spring2.value, 3.606);
  const CellPoint cell = CellMaker(s, Grid(s.sweep->axes))(1);
  EXPECT_EQ(cell.params.spring2.form, Spring::Form::stiffness);
  EXPECT_EQ(cell.params.spring2.value, 4000.0);
}

// ---------------------------------------------------------------------------------------
// Any numeric key as an axis

const std::string kOmegaAxis = "{ from = 5.0, to = 9.0, n = 41 }";
const std::string kF0Axis = "{ values = [0, 250, 500] }";

TEST(SweepScene, AnyNumericKeyIsAnAxisByItsFullOrShortName) {
  const SweepOptions quoted =
      sweep_of(concat({"[sweep]\n\"forcing.omega\" = ", kOmegaAxis, "\n\"forcing.F0\" = ", kF0Axis, "\n"}));
  const SweepOptions dotted = sweep_of(concat({"[sweep]\nforcing.omega = ", kOmegaAxis, "\nforcing.F0 = ", kF0Axis, "\n"}));
  const SweepOptions section = sweep_of(concat({"[sweep.forcing]\nomega = ", kOmegaAxis, "\nF0 = ", kF0Axis, "\n"}));
  const SweepOptions short_names = sweep_of(concat({"[sweep]\nomega = ", kOmegaAxis, "\nF0 = ", kF0Axis, "\n"}));
  expect_same_sweep(quoted, dotted);
  expect_same_sweep(quoted, section);
  expect_same_sweep(quoted, short_names);
  ASSERT_EQ(quoted.axes.size(), 2u);
  const Axis& f0 = quoted.axes[0];  // default order: the schema's, F0 before omega in [forcing]
  EXPECT_EQ(f0.key, "forcing.F0");
  EXPECT_EQ(f0.name, "F0");
  EXPECT_EQ(f0.units, "N");
  EXPECT_EQ(f0.long_name, "force amplitude");
  EXPECT_EQ(f0.values, (std::vector<double>{0.0, 250.0, 500.0}));
  const Axis& omega = quoted.axes[1];
  EXPECT_EQ(omega.key, "forcing.omega");
  EXPECT_EQ(omega.name, "omega");
  EXPECT_EQ(omega.units, "rad/s");
  EXPECT_EQ(omega.long_name, "forcing frequency (period T = 2 pi/omega)");
  ASSERT_EQ(omega.values.size(), 41u);
  EXPECT_EQ(omega.values.front(), 5.0);
  EXPECT_EQ(omega.values.back(), 9.0);
  EXPECT_NEAR(omega.values[20], 7.0, 1e-15);
}

TEST(SweepScene, FirstAxesComeFirstThenTheSchemaOrder) {
  const SweepOptions s = sweep_of(
      "[sweep]\nomega = { values = [7.0] }\nxi2 = { values = [0.01] }\nm2 = { values = [310] }\n"
      "E1 = { values = [1e9] }\n\"initial.v1\" = { values = [0.0] }\n");
  EXPECT_EQ(axis_names(s), (std::vector<std::string>{"E1", "m2", "xi2", "omega", "v1"}));
  EXPECT_EQ(s.axes[2].units, "1");  // a dimensionless key's unit ("-" in the catalogue)
  EXPECT_EQ(s.axes[4].units, "m/s");
  const SweepOptions ordered = sweep_of(
      "[sweep]\nomega = { values = [7.0] }\nE1 = { values = [1e9] }\nF0 = { values = [500] }\n"
      "order = [\"forcing.omega\", \"F0\", \"contact.E1\"]\n");
  EXPECT_EQ(axis_names(ordered), (std::vector<std::string>{"omega", "F0", "E1"}));
}

TEST(SweepScene, IntegerKeyAxisTakesWholeValues) {
  const SweepOptions s = sweep_of("[sweep]\n\"analysis.n_max\" = { from = 4, to = 16, n = 4 }\nrk4_steps = { values = [2048.0] }\n");
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_EQ(s.axes[0].key, "solver.rk4_steps");
  EXPECT_EQ(s.axes[0].values, (std::vector<double>{2048.0}));
  EXPECT_EQ(s.axes[1].key, "analysis.n_max");
  EXPECT_EQ(s.axes[1].values, (std::vector<double>{4.0, 8.0, 12.0, 16.0}));
  EXPECT_EQ(s.axes[1].units, "1");
}

TEST(SweepScene, EightAxesAreAllowed) {
  const SweepOptions s = sweep_of(
      "[sweep]\nE1 = { values = [1e9] }\nE2 = { values = [1e9] }\nR1 = { values = [1] }\nR2 = { values = [1] }\n"
      "m2 = { values = [100] }\nk2 = { values = [3000] }\nF0 = { values = [500] }\nomega = { values = [7] }\n");
  EXPECT_EQ(s.axes.size(), kMaxSweepAxes);
}

TEST(SweepScene, SetOfAnAxisReplacesEverySpellingOfItsKey) {
  const std::string dotted = concat({"[sweep]\nforcing.omega = ", kOmegaAxis, "\nF0 = ", kF0Axis, "\n"});
  for (const char* set : {"sweep.forcing.omega={values=[6, 7]}", "sweep.omega={values=[6, 7]}"}) {
    const SweepOptions s = sweep_of(dotted, {set});
    ASSERT_EQ(s.axes.size(), 2u) << set;
    EXPECT_EQ(s.axes[1].key, "forcing.omega") << set;
    EXPECT_EQ(s.axes[1].values, (std::vector<double>{6.0, 7.0})) << set;
  }
  const SweepOptions quoted = sweep_of("[sweep]\n\"system.xi2\" = { values = [0.01] }\n", {"sweep.c2={values=[10]}"});
  EXPECT_EQ(axis_names(quoted), (std::vector<std::string>{"c2"}));  // the pair partner goes too
}

TEST(SweepScene, TextOfAnyKeyAxesReadsBack) {
  const Scene s = parse(concat({"[sweep]\nforcing.omega = ", kOmegaAxis, "\n\"forcing.F0\" = ", kF0Axis,
                                "\nn_max = { values = [8, 16] }\norder = [\"omega\", \"F0\", \"n_max\"]\n"}));
  EXPECT_NE(s.text.find("\nforcing.omega = { from = 5.0, to = 9.0, n = 41 }\n"), std::string::npos) << s.text;
  EXPECT_NE(s.text.find("\n\"forcing.F0\" = { values = [0, 250, 500] }\n"), std::string::npos) << s.text;
  const Scene again = parse_scene(s.text, s.path);
  ASSERT_TRUE(again.sweep.has_value());
  expect_same_sweep(*again.sweep, *s.sweep);
  EXPECT_EQ(axis_names(*again.sweep), (std::vector<std::string>{"omega", "F0", "n_max"}));
}

// A megabyte of user input (a key, a value, a name in a list) reaches a message clipped.
TEST(SweepScene, AMegabyteKeyOrValueNeverReachesAMessageWhole) {
  const std::string big(std::size_t{1} << 20, 'x');
  const std::vector<std::pair<std::string, std::vector<std::string>>> inputs = {
      {concat({"[sweep]\n\"", big, "\" = { values = [1.0] }\n"}), {}},
      {concat({"[sweep]\n", big, " = { values = [1.0] }\n"}), {}},
      {concat({"[sweep]\nforcing.", big, " = { values = [1.0] }\n"}), {}},
      {concat({"[sweep]\nE1 = { values = [1.0] }\norder = [\"", big, "\"]\n"}), {}},
      {concat({"[sweep]\nE1 = { values = [1.0, \"", big, "\"] }\n"}), {}},
      {concat({"[sweep]\nE1 = { values = [1.0], ", big, " = 2 }\n"}), {}},
      {concat({"[sweep]\nE1 = { values = [1.0] }\nstore = [\"", big, "\"]\n"}), {}},
      {concat({"[", big, "]\n"}), {}},
      {concat({"[system]\n", big, " = 1\n"}), {}},
      {"", {concat({"sweep.", big, "={values=[1]}"})}},
      {"", {concat({"system.", big, "=1"})}},
      {"", {concat({"system.m2=", big})}},
  };
  for (const auto& [text, sets] : inputs) {
    const std::string message = error_of(text, sets);
    EXPECT_FALSE(message.empty());
    EXPECT_LT(message.size(), 1000u) << message.substr(0, 300);
    EXPECT_NE(message.find("... (104"), std::string::npos) << message.substr(0, 300);  // "... (1048576 characters)"
  }
}

// ---------------------------------------------------------------------------------------
// Overrides

TEST(SweepScene, SetChangesAnIntervalAndAnAxis) {
  const std::string text = "[sweep]\nE1 = { from = 2e4, to = 2.1e11, n = 23, scale = \"log\" }\n";
  EXPECT_EQ(sweep_of(text, {"sweep.checkpoint_interval=5"}).checkpoint_interval, 5.0);
  const SweepOptions s = sweep_of(text, {"sweep.E1={from=1e5,to=1e9,n=5,scale=\"log\"}"});
  EXPECT_EQ(s.axes.at(0).values.size(), 5u);
  EXPECT_EQ(s.axes[0].values.front(), 1e5);
  EXPECT_EQ(s.axes[0].values.back(), 1e9);
  EXPECT_EQ(sweep_of(text, {"sweep.store=[\"k_con\"]"}).store,
            (std::vector<Quantity>{Quantity::k_con, Quantity::hertz_valid}));
  // A scene without [sweep] becomes a sweep by --set.
  EXPECT_EQ(sweep_of("", {"sweep.R2={values=[0.5, 1]}"}).axes.at(0).name, "R2");
}

TEST(SweepScene, SetOfOneSpringAxisReplacesTheOther) {
  const SweepOptions s = sweep_of("[sweep]\nomega2 = { values = [4.0, 5.0] }\n", {"sweep.k2={values=[3000]}"});
  EXPECT_EQ(axis_names(s), (std::vector<std::string>{"k2"}));
}

// ---------------------------------------------------------------------------------------
// Errors: one line naming the file, the line, [sweep] KEY and what is allowed.

struct BadSweep {
  std::string name;
  std::string text;
  std::vector<std::string> sets;
  std::vector<std::string> expected;  // substrings of the message
};

const std::string kAxisForms = "{ from, to, n[, scale] } or { values[, scale] }";

const std::vector<BadSweep>& bad_sweeps() {
  static const std::vector<BadSweep> cases = {
      {"unknown axis", "[sweep]\nE3 = { values = [1.0] }\n", {},
       {"jobs/x.toml:2: unknown key 'E3' in [sweep] (did you mean 'E1'?)",
        "; an axis is any real or integer key of [system], [contact], [forcing], [solver], [analysis], [initial], "
        "as section.key or by the key alone when only one section has it; the options are order, store, "
        "checkpoint_interval, progress_interval"}},
      {"choice key as axis", "[sweep]\nmethod = { values = [1.0] }\n", {},
       {"jobs/x.toml:2: [sweep] solver.method cannot be an axis: it is one of "
        "\"hybrid\", \"dopri5\", \"rk4\", not a number; run one sweep per value"}},
      {"unknown key", "[sweep]\nE1 = { values = [1e9] }\nchekpoint_interval = 5.0\n", {},
       {"jobs/x.toml:3: unknown key 'chekpoint_interval' in [sweep]", "did you mean 'checkpoint_interval'?"}},
      {"sweep key elsewhere", "[system]\norder = [\"E1\"]\n", {},
       {"unknown key 'order' in [system] (it belongs in [sweep])"}},
      {"sweep key outside any section", "store = [\"T_con\"]\n", {},
       {"jobs/x.toml:1: key 'store' is outside any section: put it under [sweep]"}},
      {"axis not a table", "[sweep]\nE1 = [1e5, 1e6]\n", {},
       {"jobs/x.toml:2: [sweep] E1 = [1e+05, 1e+06]", concat({"axis E1 must be an inline table ", kAxisForms})}},
      {"unknown axis field", "[sweep]\nE1 = { form = 1e5, to = 1e9, n = 5 }\n", {},
       {"jobs/x.toml:2: [sweep] E1 = { to = 1e+09, n = 5, form = 1e+05 }", "unknown field 'form' in axis E1",
        "did you mean 'from'?", kAxisForms}},
      {"both forms", "[sweep]\nE1 = { from = 1e5, to = 1e9, n = 5, values = [1e5] }\n", {},
       {"jobs/x.toml:2: [sweep] E1 = ", "axis E1 gives both values and from/to/n", kAxisForms}},
      {"missing to", "[sweep]\nE1 = { from = 1e5, n = 5 }\n", {},
       {"jobs/x.toml:2: [sweep] E1 = { from = 1e+05, n = 5 }", "axis E1 lacks 'to'", kAxisForms}},
      {"missing n", "[sweep]\nR1 = { from = 0.1, to = 1 }\n", {}, {"[sweep] R1 = ", "axis R1 lacks 'n'"}},
      {"empty axis", "[sweep]\nR1 = {}\n", {}, {"jobs/x.toml:2: [sweep] R1 = {}", "axis R1 lacks 'from'"}},
      {"n zero", "[sweep]\nE1 = { from = 1e5, to = 1e9, n = 0 }\n", {},
       {"jobs/x.toml:2: [sweep] E1 = ", "n must be an integer in [1, 1000000]"}},
      {"n not whole", "[sweep]\nE1 = { from = 1e5, to = 1e9, n = 2.5 }\n", {}, {"n must be an integer in [1, 1000000]"}},
      {"n a string", "[sweep]\nE1 = { from = 1e5, to = 1e9, n = \"5\" }\n", {}, {"n must be an integer in [1, 1000000]"}},
      {"n too big", "[sweep]\nE1 = { from = 1e5, to = 1e9, n = 1e9 }\n", {}, {"n must be an integer in [1, 1000000]"}},
      {"log from zero", "[sweep]\nomega2 = { from = 0, to = 5, n = 3, scale = \"log\" }\n", {},
       {"jobs/x.toml:2: [sweep] omega2 = ", "a log axis needs from > 0 and to > 0"}},
      {"log to negative", "[sweep]\nR1 = { from = 1, to = -1, n = 3, scale = \"log\" }\n", {},
       {"[sweep] R1 = ", "a log axis needs from > 0 and to > 0"}},
      {"log values zero", "[sweep]\nk2 = { values = [0, 10], scale = \"log\" }\n", {},
       {"[sweep] k2 = ", "a log axis needs values > 0"}},
      {"unknown scale", "[sweep]\nE1 = { from = 1e5, to = 1e9, n = 5, scale = \"lgo\" }\n", {},
       {"jobs/x.toml:2: [sweep] E1 = ", "scale must be one of \"lin\", \"log\"", "did you mean \"log\"?"}},
      {"scale not a string", "[sweep]\nE1 = { values = [1e5], scale = 10 }\n", {}, {"scale must be one of \"lin\", \"log\""}},
      {"empty values", "[sweep]\nE2 = { values = [] }\n", {},
       {"jobs/x.toml:2: [sweep] E2 = { values = [] }", "values is empty: give at least one point"}},
      {"values not an array", "[sweep]\nE2 = { values = 1e6 }\n", {}, {"values must be an array of finite numbers"}},
      {"infinite value", "[sweep]\nE2 = { values = [1e6, inf] }\n", {},
       {"[sweep] E2 = { values = [1e+06, inf] }", "the axis reaches [contact] E2 = inf: must be a finite number > 0 (Pa)"}},
      {"string value", "[sweep]\nE2 = { values = [1e6, \"2e6\"] }\n", {}, {"values must be numbers, not \"2e6\""}},
      {"nan end", "[sweep]\nE2 = { from = nan, to = 1e6, n = 3 }\n", {}, {"[sweep] E2 = ", "from must be a finite number"}},
      {"duplicate values", "[sweep]\nR2 = { values = [0.5, 1.0, 0.5] }\n", {},
       {"jobs/x.toml:2: [sweep] R2 = ", "values repeat 0.5: give each point once"}},
      {"equal ends", "[sweep]\nR2 = { from = 0.5, to = 0.5, n = 3 }\n", {}, {"[sweep] R2 = ", "from = to with n = 3 repeats a point"}},
      {"axis reaches zero", "[sweep]\nE1 = { from = 0, to = 2.1e11, n = 4 }\n", {},
       {"jobs/x.toml:2: [sweep] E1 = { from = 0, to = 2.1e+11, n = 4 }",
        "the axis reaches [contact] E1 = 0: must be > 0 (Pa)"}},
      {"axis below range", "[sweep]\nomega2 = { values = [3.6, -1] }\n", {},
       {"the axis reaches [system] omega2 = -1: must be >= 0 (rad/s)"}},
      {"both spring axes", "[sweep]\nk2 = { values = [3000] }\nomega2 = { values = [4.0] }\n", {},
       {"jobs/x.toml:3: [sweep] both k2 and omega2 given as axes", "(k2 in N/m, or omega2 in rad/s)"}},
      {"order names no axis", "[sweep]\nE1 = { values = [1e9] }\nE2 = { values = [1e6] }\norder = [\"E1\", \"R1\"]\n", {},
       {"jobs/x.toml:4: [sweep] order = [\"E1\", \"R1\"]", "'R1' is not an axis of this sweep", "; axes: E1, E2"}},
      {"order typo", "[sweep]\nE1 = { values = [1e9] }\nE2 = { values = [1e6] }\norder = [\"E1\", \"E3\"]\n", {},
       {"'E3' is not an axis of this sweep (did you mean 'E1'?); axes: E1, E2"}},
      {"order lacks an axis", "[sweep]\nE1 = { values = [1e9] }\nE2 = { values = [1e6] }\norder = [\"E2\"]\n", {},
       {"jobs/x.toml:4: [sweep] order = [\"E2\"]", "axis E1 is missing: order must list every axis once (E1, E2)"}},
      {"order repeats", "[sweep]\nE1 = { values = [1e9] }\norder = [\"E1\", \"E1\"]\n", {}, {"axis E1 is listed twice"}},
      {"order not strings", "[sweep]\nE1 = { values = [1e9] }\norder = [1]\n", {},
       {"[sweep] order = [1]", "must be an array of strings (the axes: E1)"}},
      {"unknown quantity", "[sweep]\nE1 = { values = [1e9] }\nstore = [\"T_cn\"]\n", {},
       {"jobs/x.toml:3: [sweep] store = [\"T_cn\"]", "unknown quantity 'T_cn' (did you mean 'T_con'?)",
        "allowed: T_con, k_con, F_max, z_max, z_ratio, v_in, impulse, hertz_valid, periods, rhs_evals"}},
      {"duplicate quantity", "[sweep]\nE1 = { values = [1e9] }\nstore = [\"T_con\", \"z_max\", \"T_con\"]\n", {},
       {"[sweep] store = ", "quantity T_con is listed twice"}},
      {"store not an array", "[sweep]\nE1 = { values = [1e9] }\nstore = \"T_con\"\n", {},
       {"must be an array of strings (quantities: T_con, k_con"}},
      {"zero axes", "[sweep]\ncheckpoint_interval = 5.0\n", {},
       {"jobs/x.toml:1: [sweep] has no axes: give at least one real or integer key (E1, \"forcing.omega\", ...) as "
        "KEY = ", kAxisForms}},
      {"empty section", "[sweep]\n", {}, {"jobs/x.toml:1: [sweep] has no axes"}},
      {"checkpoint zero", "[sweep]\nE1 = { values = [1e9] }\ncheckpoint_interval = 0\n", {},
       {"jobs/x.toml:3: [sweep] checkpoint_interval = 0: must be > 0 (s)"}},
      {"progress negative", "[sweep]\nE1 = { values = [1e9] }\nprogress_interval = -1.0\n", {},
       {"[sweep] progress_interval = -1: must be > 0 (s)"}},
      {"progress a string", "[sweep]\nE1 = { values = [1e9] }\nprogress_interval = \"often\"\n", {},
       {"[sweep] progress_interval = \"often\": must be a finite number > 0 (s)"}},
      {"grid too big",
       "[sweep]\nE1 = { from = 1, to = 2, n = 1000000 }\nE2 = { from = 1, to = 2, n = 1000000 }\nR1 = { values = [1, 2] }\n",
       {},
       {"jobs/x.toml: [sweep] the grid has 2e+12 cells: at most 1e+12"}},
      {"set bad interval", "[sweep]\nE1 = { values = [1e9] }\n", {"sweep.checkpoint_interval=0"},
       {"jobs/x.toml: --set sweep.checkpoint_interval=0: [sweep] checkpoint_interval = 0: must be > 0 (s)"}},
      {"set axis to zero", "", {"sweep.E1={from=0,to=1,n=2}"},
       {"jobs/x.toml: --set sweep.E1={from=0,to=1,n=2}: [sweep] E1 = { from = 0, to = 1, n = 2 }: the axis reaches [contact] E1 = 0", "must be > 0 (Pa)"}},
      {"set unknown key", "", {"sweep.E3=5"}, {"jobs/x.toml: --set sweep.E3=5: unknown key 'E3' in [sweep]"}},
      {"boolean key as axis", "[sweep]\nlyapunov = { values = [0, 1] }\n", {},
       {"jobs/x.toml:2: [sweep] analysis.lyapunov cannot be an axis: it is true or false, not a number"}},
      {"choice key as dotted axis", "[sweep]\nsolver.method = { values = [1] }\n", {},
       {"[sweep] solver.method cannot be an axis: it is one of \"hybrid\""}},
      {"unknown full key", "[sweep]\n\"forcing.omgea\" = { values = [6.0] }\n", {},
       {"jobs/x.toml:2: unknown key 'forcing.omgea' in [sweep] (did you mean 'forcing.omega'?)"}},
      {"unknown dotted key", "[sweep]\nforcing.omgea = { values = [6.0] }\n", {},
       {"jobs/x.toml:2: unknown key 'forcing.omgea' in [sweep] (did you mean 'forcing.omega'?)"}},
      {"key of another section", "[sweep]\n\"system.E1\" = { values = [1e9] }\n", {},
       {"unknown key 'system.E1' in [sweep]", "an axis is any real or integer key of [system]"}},
      {"integer axis not whole", "[sweep]\n\"analysis.n_max\" = { from = 1, to = 8, n = 3 }\n", {},
       {"jobs/x.toml:2: [sweep] analysis.n_max = { from = 1, to = 8, n = 3 }: the axis reaches [analysis] n_max = 4.5: must be an integer in [1, 64]"}},
      {"integer axis out of range", "[sweep]\nn_max = { values = [8, 65] }\n", {},
       {"the axis reaches [analysis] n_max = 65: must be an integer in [1, 64]"}},
      {"new axis below range", "[sweep]\n\"forcing.omega\" = { values = [0, 1] }\n", {},
       {"the axis reaches [forcing] omega = 0: must be > 0 (rad/s)"}},
      {"one key twice", "[sweep]\nomega = { values = [6.0] }\n\"forcing.omega\" = { values = [7.0] }\n", {},
       {"jobs/x.toml:2: [sweep] forcing.omega is given twice (as forcing.omega and omega): give each axis once"}},
      {"dotted and quoted twice", "[sweep]\nforcing.omega = { values = [6.0] }\n\"forcing.omega\" = { values = [7.0] }\n", {},
       {"[sweep] forcing.omega is given twice (as forcing.omega and forcing.omega)"}},
      {"damper pair", "[sweep]\nxi1 = { values = [0.01] }\n\"system.c1\" = { values = [100] }\n", {},
       {"jobs/x.toml:2: [sweep] both c1 and xi1 given as axes: sweep only one (c1 in N s/m, or xi1 dimensionless)"}},
      {"nine axes",
       "[sweep]\nE1 = { values = [1e9] }\nE2 = { values = [1e9] }\nR1 = { values = [1] }\nR2 = { values = [1] }\n"
       "m2 = { values = [100] }\nk2 = { values = [3000] }\nF0 = { values = [500] }\nomega = { values = [7] }\n"
       "D = { values = [0.05] }\n",
       {},
       {"jobs/x.toml:1: [sweep] has 9 axes: at most 8"}},
      {"order by an unknown full name", "[sweep]\nomega = { values = [6.0] }\norder = [\"forcing.omegaa\"]\n", {},
       {"'forcing.omegaa' is not an axis of this sweep; axes: omega"}},
      {"set a choice axis", "", {"sweep.solver.method={values=[1]}"},
       {"jobs/x.toml: --set sweep.solver.method={values=[1]}: [sweep] solver.method cannot be an axis"}},
      {"set sweep without axes", "", {"sweep.checkpoint_interval=5"}, {"jobs/x.toml: [sweep] has no axes"}},
      {"unknown section lists sweep", "[swep]\n", {},
       {"unknown section [swep] (did you mean [sweep]?)", "sections: system, contact, forcing, solver, analysis, initial, sweep"}},
  };
  return cases;
}

// The forcing against the natural frequencies (parameters.hpp) holds at every cell: checked at
// the grid's corners, where an axis of any key it reads is at its least or largest value.
TEST(SweepScene, TheFrequencyRuleIsCheckedAtTheGridsCorners) {
  // Table 1: omega_n = 6.98 rad/s, so forcing.omega must lie in [6.98e-4, 6.98e4] rad/s.
  EXPECT_EQ(parse("[sweep]\nomega = { from = 0.001, to = 60000.0, n = 3 }\n").sweep->axes.size(), 1u);
  const std::string low = error_of("[sweep]\nomega = { from = 1e-9, to = 7.0, n = 3 }\nm2 = { values = [50.0, 100.0] }\n");
  EXPECT_NE(low.find("jobs/x.toml: [sweep]: at the cell system.m2 = 50, forcing.omega = 1e-09: "), std::string::npos) << low;
  EXPECT_NE(low.find("forcing.omega = 1e-09 rad/s is "), std::string::npos) << low;
  EXPECT_NE(low.find("omega/omega_n must be in [0.0001, 1e+04]"), std::string::npos) << low;
  // The corner that breaks the rule need not be an omega end: a stiff main spring.
  const std::string stiff = error_of("[sweep]\nomega1 = { values = [6.0, 2147483647.0] }\n");
  EXPECT_NE(stiff.find("at the cell system.omega1 = 2147483647: forcing.omega = 7.23 rad/s is 3.37e-09 times"),
            std::string::npos) << stiff;
  // A base point that breaks the rule is fine when an axis replaces the key that broke it.
  EXPECT_NO_THROW(parse("[forcing]\nomega = 1e-9\n[sweep]\nomega = { values = [5.0, 9.0] }\n"));
  // Set as an axis (continue and orbit-diagram do so), the message names the --set.
  const std::string set = error_of("", {"sweep.forcing.omega={values=[1e-300,1e308]}"});
  EXPECT_NE(set.find("jobs/x.toml: --set sweep.forcing.omega={values=[1e-300,1e308]}: at the cell forcing.omega = 1e-300: "),
            std::string::npos) << set;
}

TEST(SweepScene, EachBadInputGivesOneLineNamingFileKeyAndAllowed) {
  for (const BadSweep& c : bad_sweeps()) {
    const std::string message = error_of(c.text, c.sets);
    EXPECT_EQ(message.find('\n'), std::string::npos) << c.name << ": " << message;
    for (const std::string& part : c.expected) {
      EXPECT_NE(message.find(part), std::string::npos) << c.name << ": '" << part << "' not in: " << message;
    }
  }
}

TEST(SweepScene, ErrorNamesTheLineOfTheAxis) {
  const std::string message = error_of("[system]\nm2 = 310.0\n\n[sweep]\nE1 = { values = [1e9] }\nR2 = { values = [0] }\n");
  EXPECT_EQ(message.rfind("jobs/x.toml:6: [sweep] R2 = { values = [0] }: the axis reaches [contact] R2 = 0", 0), 0u) << message;
}

TEST(SweepScene, LongValueIsClippedInTheMessage) {
  std::string values;
  for (int i = 1; i <= 200; ++i) values += concat({i > 1 ? ", " : "", std::to_string(i)});
  const std::string message = error_of(concat({"[sweep]\nm2 = { values = [", values, ", 1] }\n"}));
  EXPECT_NE(message.find("values repeat 1"), std::string::npos) << message;
  EXPECT_LT(message.size(), 200u) << message;
}

// ---------------------------------------------------------------------------------------
// Provenance

TEST(SweepScene, TextReadsBackToTheSameSweep) {
  const Scene s = parse(
      "[system]\nm2 = 310.0\n[sweep]\n"
      "E1 = { scale = \"log\", n = 3, to = 2.1e11, from = 2e4 }\n"
      "E2 = { values = [2e4, 1e6, 2.1e11] }\n"
      "omega2 = { from = 3.606, to = 5.646, n = 4 }\n"
      "order = [\"E2\", \"omega2\", \"E1\"]\n"
      "store = [\"z_ratio\", \"T_con\"]\n"
      "progress_interval = 2.5\n",
      {"sweep.checkpoint_interval=30", "sweep.E1={ scale=\"log\", n=23, to=2.1e11, from=2e4 }"});
  ASSERT_TRUE(s.sweep.has_value());
  EXPECT_NE(s.text.find("\n[sweep]\n"), std::string::npos) << s.text;
  EXPECT_NE(s.text.find("E1 = { from = 20000.0, to = 2.1e+11, n = 23, scale = \"log\" }"), std::string::npos) << s.text;
  EXPECT_NE(s.text.find("order = [\"E2\", \"omega2\", \"E1\"]"), std::string::npos) << s.text;
  EXPECT_NE(s.text.find("checkpoint_interval = 30"), std::string::npos) << s.text;
  EXPECT_NE(s.text.find("# overrides: --set sweep.checkpoint_interval=30 --set sweep.E1="), std::string::npos);
  const Scene again = parse_scene(s.text, s.path);
  ASSERT_TRUE(again.sweep.has_value());
  expect_same_sweep(*again.sweep, *s.sweep);
  EXPECT_EQ(axis_names(*again.sweep), (std::vector<std::string>{"E2", "omega2", "E1"}));
  EXPECT_EQ(again.params.m2, 310.0);
  EXPECT_EQ(again.sweep->axes.at(2).values.size(), 23u);
  EXPECT_EQ(again.text.substr(again.text.find("\n[")), s.text.substr(s.text.find("\n[")));  // a fixed point
}

TEST(SweepScene, TextOfAPointSceneHasNoSweep) {
  EXPECT_EQ(parse("[system]\nm2 = 310.0\n").text.find("[sweep]"), std::string::npos);
}

// ---------------------------------------------------------------------------------------
// Documentation: keys listing, --help summary, reference scene

TEST(SweepScene, KeysListingDocumentsTheSweepKeys) {
  std::ostringstream os;
  write_scene_keys(os);
  const std::string text = os.str();
  for (const char* key : {"sweep.KEY ", "sweep.order ", "sweep.store ", "sweep.checkpoint_interval ",
                          "sweep.progress_interval "}) {
    EXPECT_NE(text.find(key), std::string::npos) << key;
  }
  EXPECT_NE(text.find("[\"T_con\", \"k_con\", \"F_max\", \"z_max\", \"hertz_valid\"]"), std::string::npos);  // store's default
  EXPECT_NE(text.find("grid axis over any real or integer key above"), std::string::npos);
  EXPECT_NE(text.find("at most 8 axes, not both keys of a pair"), std::string::npos);
  EXPECT_NE(text.find("(E1, E2, R1, R2, m2, k2, omega2, then key table order)"), std::string::npos);  // order's default
}

TEST(SweepScene, HelpSummaryListsTheSweepKeys) {
  std::ostringstream os;
  write_scene_key_summary(os);
  EXPECT_NE(os.str().find("  [sweep]     KEY (an axis: any real or integer key above) order store checkpoint_interval "
                          "progress_interval refine refine_on refine_audit refine_speckle\n"),
            std::string::npos)
      << os.str();
}

TEST(SweepScene, SweepKeysStayOutOfTheScalarSchema) {
  for (const Key k : Key::all()) EXPECT_NE(k.info().section, "sweep") << k.full_name();
  EXPECT_EQ(scene_sections().back(), "sweep");
}

// The example [sweep] of the reference scene, uncommented, parses to the documented grid.
TEST(SweepScene, ReferenceExampleParses) {
  std::ostringstream os;
  write_reference_scene(os);
  const std::string ref = os.str();
  const auto start = ref.find("# [sweep]\n");
  ASSERT_NE(start, std::string::npos) << ref;
  std::istringstream lines(ref.substr(start));
  std::string example, line;
  while (std::getline(lines, line)) {
    ASSERT_EQ(line.rfind("# ", 0), 0u) << line;
    example += concat({line.substr(2), "\n"});
  }
  const SweepOptions s = sweep_of(example);
  EXPECT_EQ(axis_names(s), (std::vector<std::string>{"E1", "E2"}));
  EXPECT_EQ(s.axes[0].values.size(), 23u);
  EXPECT_EQ(s.axes[1].values, (std::vector<double>{2e4, 1e6, 2.1e11}));
  EXPECT_EQ(s.store, SweepOptions{}.store);
  EXPECT_EQ(s.checkpoint_interval, SweepOptions{}.checkpoint_interval);
}

// When this fails, regenerate it: `vibromap keys --toml > jobs/reference.toml`.
TEST(SweepScene, ReferenceFileIsTheWriterOutput) {
  std::ostringstream os;
  write_reference_scene(os);
  EXPECT_EQ(read_text(source_path("jobs/reference.toml")), os.str());
  EXPECT_FALSE(load_scene(source_path("jobs/reference.toml")).sweep.has_value());
}

// ---------------------------------------------------------------------------------------
// The sweep jobs

TEST(SweepScene, DemoE1E2IsTheTable2BaseOverThePaperBox) {
  const Scene s = load_scene(source_path("jobs/demo/e1_e2.toml"));
  ASSERT_TRUE(s.sweep.has_value());
  EXPECT_EQ(s.params.m2, 310.0);
  EXPECT_EQ(Key::at("omega2").value(s.params), 3.606);
  EXPECT_EQ(s.params.R1, 2.0);
  EXPECT_EQ(s.params.R2, 2.0);
  const SweepOptions& w = *s.sweep;
  EXPECT_EQ(axis_names(w), (std::vector<std::string>{"E1", "E2"}));
  for (const Axis& a : w.axes) {
    EXPECT_EQ(a.scale, AxisScale::log);
    EXPECT_EQ(a.values.front(), 2e4);
    EXPECT_EQ(a.values.back(), 2.1e11);
    EXPECT_LT(log_ratio_spread(a.values), kLogRatioTol);
  }
  EXPECT_EQ(Grid(w.axes).size(), 23u * 22u);
  EXPECT_EQ(w.store, (std::vector<Quantity>{Quantity::T_con, Quantity::k_con, Quantity::F_max, Quantity::z_max,
                                            Quantity::z_ratio, Quantity::v_in, Quantity::hertz_valid}));
  EXPECT_EQ(w.checkpoint_interval, 10.0);
}

TEST(SweepScene, ClusterPaperBoxSpansSixParameters) {
  const Scene s = load_scene(source_path("jobs/cluster/paper_box_6d.toml"));
  ASSERT_TRUE(s.sweep.has_value());
  const SweepOptions& w = *s.sweep;
  EXPECT_EQ(axis_names(w), (std::vector<std::string>{"E1", "E2", "R1", "R2", "m2", "omega2"}));
  struct Box {
    double lo, hi;
  };
  const std::vector<Box> box = {{2e4, 2.1e11}, {2e4, 2.1e11}, {0.09, 2.0}, {0.09, 2.0}, {100.0, 310.0}, {3.606, 5.646}};
  for (std::size_t d = 0; d < box.size(); ++d) {
    EXPECT_EQ(w.axes[d].values.front(), box[d].lo) << w.axes[d].name;
    EXPECT_EQ(w.axes[d].values.back(), box[d].hi) << w.axes[d].name;
  }
  const std::size_t cells = Grid(w.axes).size();
  EXPECT_EQ(cells, 15u * 15u * 6u * 6u * 6u * 6u);
  EXPECT_GE(cells, 100000u);
  EXPECT_LE(cells, 1000000u);
  EXPECT_EQ(w.checkpoint_interval, 300.0);
}

}  // namespace
}  // namespace vibromap
