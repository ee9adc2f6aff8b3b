// A sweep cell's parameter point (io/scene/cell_maker.hpp) and the setter of one key
// (Key::set, core/model/keys.hpp): a cell must equal the scene read with `--set KEY=value`
// for each of its axes, field by field.

#include <array>
#include <charconv>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "support/scene_testing.hpp"
#include "vibromap/io/scene/cell_maker.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {
namespace {

using test::concat;
using test::parse;

// The shortest text that reads back to v, as `--set` takes it.
std::string number(double v) {
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), res.ptr);
}

// Every field of two points, compared exactly (the forms of springs and dampers too).
void expect_same_point(const CellPoint& cell, const Scene& expected, const std::string& what) {
  const Parameters& p = cell.params;
  const Parameters& q = expected.params;
  const auto same_double = [&](double a, double b, const char* name) { EXPECT_EQ(a, b) << what << ": " << name; };
  for (const auto& [a, b, name] : {std::tuple{p.m1, q.m1, "m1"}, {p.m2, q.m2, "m2"}, {p.D, q.D, "D"}, {p.E1, q.E1, "E1"},
                                   {p.E2, q.E2, "E2"}, {p.nu1, q.nu1, "nu1"}, {p.nu2, q.nu2, "nu2"}, {p.R1, q.R1, "R1"},
                                   {p.R2, q.R2, "R2"}, {p.q, q.q, "q"}, {p.F0, q.F0, "F0"}, {p.omega, q.omega, "omega"},
                                   {p.lambda, q.lambda, "lambda"}, {p.phi0, q.phi0, "phi0"},
                                   {p.spring1.value, q.spring1.value, "spring1"}, {p.spring2.value, q.spring2.value, "spring2"},
                                   {p.damper1.value, q.damper1.value, "damper1"}, {p.damper2.value, q.damper2.value, "damper2"}})
    same_double(a, b, name);
  EXPECT_EQ(p.spring1.form, q.spring1.form) << what;
  EXPECT_EQ(p.spring2.form, q.spring2.form) << what;
  EXPECT_EQ(p.damper1.form, q.damper1.form) << what;
  EXPECT_EQ(p.damper2.form, q.damper2.form) << what;
  ASSERT_EQ(p.initial.has_value(), q.initial.has_value()) << what;
  if (p.initial) {
    EXPECT_EQ(*p.initial, *q.initial) << what;
  }
  const IntegratorOptions& i = cell.options.integrator;
  const IntegratorOptions& j = expected.options.integrator;
  EXPECT_EQ(i.method, j.method) << what;
  for (const auto& [a, b, name] : {std::tuple{i.rtol, j.rtol, "rtol"}, {i.atol, j.atol, "atol"},
                                   {i.max_step, j.max_step, "max_step"}})
    same_double(a, b, name);
  EXPECT_EQ(i.rk4_steps, j.rk4_steps) << what;
  EXPECT_EQ(i.max_steps, j.max_steps) << what;
  const AnalysisOptions& a = cell.options.analysis;
  const AnalysisOptions& b = expected.options.analysis;
  EXPECT_EQ(a.steady, b.steady) << what;
  EXPECT_EQ(a.lyapunov, b.lyapunov) << what;
  for (const auto& [x, y, name] : {std::tuple{a.newton_tol, b.newton_tol, "newton_tol"},
                                   {a.steady_tol, b.steady_tol, "steady_tol"}, {a.hertz_limit, b.hertz_limit, "hertz_limit"}})
    same_double(x, y, name);
  for (const auto& [x, y, name] : {std::tuple<long, long, const char*>{a.transient_periods, b.transient_periods, "transient_periods"},
                                   {a.newton_max_iterations, b.newton_max_iterations, "newton_max_iterations"},
                                   {a.lyapunov_periods, b.lyapunov_periods, "lyapunov_periods"}, {a.n_max, b.n_max, "n_max"},
                                   {a.max_periods, b.max_periods, "max_periods"},
                                   {a.chatter_impacts, b.chatter_impacts, "chatter_impacts"},
                                   {a.trajectory_periods, b.trajectory_periods, "trajectory_periods"},
                                   {a.trajectory_samples, b.trajectory_samples, "trajectory_samples"}})
    EXPECT_EQ(x, y) << what << ": " << name;
}

// Axes of every kind: a new key by its full name, the other form of a pair the scene gives
// (k2 for omega2), an integer key, D (which the [initial] keys not given follow), an [initial]
// key, a solver option.
const std::string kScene =
    "[system]\nm2 = 310.0\nomega2 = 3.606\nxi2 = 0.02\n[initial]\nx1 = 0.01\n[sweep]\n"
    "\"forcing.omega\" = { from = 5.0, to = 9.0, n = 3 }\nk2 = { values = [1000, 4000] }\n"
    "analysis.n_max = { values = [8, 16] }\nD = { values = [0.04, 0.06] }\n\"initial.v2\" = { values = [0, 0.1] }\n"
    "solver.rtol = { values = [1e-8, 1e-10] }\norder = [\"initial.v2\", \"omega\", \"k2\", \"n_max\", \"D\", \"rtol\"]\n";

TEST(CellMaker, EveryCellIsTheSceneWithItsAxesSetByOverrides) {
  const Scene scene = parse(kScene);
  ASSERT_TRUE(scene.sweep.has_value());
  const Grid grid(scene.sweep->axes);
  ASSERT_EQ(grid.size(), 96u);
  const CellMaker make_cell(scene, grid);
  std::vector<double> x(grid.axes().size());
  for (std::size_t i = 0; i < grid.size(); ++i) {
    grid.coordinates(i, x);
    std::vector<std::string> sets;
    for (std::size_t d = 0; d < x.size(); ++d) sets.push_back(concat({grid.axes()[d].key, "=", number(x[d])}));
    expect_same_point(make_cell(i), parse(kScene, sets), concat({"cell ", std::to_string(i)}));
  }
}

TEST(CellMaker, ACellKeepsTheFormsTheSceneGave) {
  const Scene scene = parse(kScene);
  const CellPoint c = CellMaker(scene, Grid(scene.sweep->axes))(95);  // the last value of every axis
  EXPECT_EQ(c.params.spring2.form, Spring::Form::stiffness);  // the k2 axis
  EXPECT_EQ(c.params.spring2.value, 4000.0);
  EXPECT_EQ(c.params.damper2.form, Damper::Form::ratio);  // xi2 stays a ratio
  EXPECT_EQ(c.params.damper2.value, 0.02);
  EXPECT_EQ(c.params.omega, 9.0);
  EXPECT_EQ(c.options.analysis.n_max, 16);
  EXPECT_EQ(c.options.integrator.rtol, 1e-10);
  ASSERT_TRUE(c.params.initial.has_value());
  EXPECT_EQ(*c.params.initial, Eigen::Vector4d(0.01, 0.06, 0.0, 0.1));  // x2 follows the cell's D
}

TEST(CellMaker, RefusesAnAxisWithoutASceneKey) {
  const Scene scene = parse("");
  EXPECT_THROW(CellMaker(scene, Grid({{"", "E1", "Pa", "", {1e9}, AxisScale::lin}})), std::invalid_argument);
  EXPECT_THROW(CellMaker(scene, Grid({{"solver.method", "method", "1", "", {1}, AxisScale::lin}})),
               std::invalid_argument);
}

TEST(KeySet, SetsAKeyAsTheReaderDoes) {
  Parameters p;
  PointOptions o;
  Key::at("system.k2").set(p, o, 3000.0);
  EXPECT_EQ(p.spring2.form, Spring::Form::stiffness);
  EXPECT_EQ(p.spring2.value, 3000.0);
  Key::at("system.m2").set(p, o, 310.0);
  EXPECT_EQ(p.damper2.form, Damper::Form::ratio);  // xi2 (the default form) is kept
  Key::at("analysis.max_periods").set(p, o, 500.0);
  EXPECT_EQ(o.analysis.max_periods, 500);
  Key::at("initial.v1").set(p, o, 0.25);  // the other components from the rest state
  ASSERT_TRUE(p.initial.has_value());
  EXPECT_EQ(*p.initial, Eigen::Vector4d(0.0, p.D, 0.25, 0.0));
  Key::at("initial.x1").set(p, o, -0.01);
  EXPECT_EQ(*p.initial, Eigen::Vector4d(-0.01, p.D, 0.25, 0.0));
}

TEST(KeyFind, NamesAKeyInFullOrByANameOneSectionHas) {
  EXPECT_FALSE(Key::find("forcing.omgea").has_value());
  EXPECT_THROW(Key::at("forcing.omgea"), std::invalid_argument);
  EXPECT_EQ(Key::find("omega")->full_name(), "forcing.omega");  // one section has it
  EXPECT_EQ(Key::find("omega2")->full_name(), "system.omega2");
  EXPECT_FALSE(Key::find("solver.method")->is_axis());     // a choice of the solver
  EXPECT_FALSE(Key::find("analysis.lyapunov")->is_axis());  // a boolean
  EXPECT_TRUE(Key::find("contact.law")->is_axis());         // the categorical law
  EXPECT_TRUE(Key::find("analysis.n_max")->is_axis());
  EXPECT_FALSE(Key::find("analysis.n_max")->is_parameter());
  EXPECT_TRUE(Key::find("forcing.lambda")->is_parameter());
}

}  // namespace
}  // namespace vibromap
