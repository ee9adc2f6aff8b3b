// Scenes (io/scene/): defaults, every key, pairs, overrides, one-line errors, the paper's
// scenes and the reference scene. Also the JSON writer and the summary output, which have
// no test file of their own yet.

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vibromap/io/json_writer.hpp"
#include "support/scene_testing.hpp"
#include "support/temp_dir.hpp"
#include "vibromap/io/scene/docs.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/io/summary_output.hpp"

namespace vibromap {
namespace {

using test::concat;
using test::error_of;
using test::kFile;
using test::parse;
using test::read_text;
using test::source_path;

void expect_same_parameters(const Parameters& a, const Parameters& b) {
  for (const Key k : Key::all()) {
    if (k.is_parameter()) {
      EXPECT_DOUBLE_EQ(k.value(a), k.value(b)) << k.full_name();
    }
  }
  EXPECT_EQ(a.spring1.form, b.spring1.form);
  EXPECT_EQ(a.spring2.form, b.spring2.form);
  EXPECT_EQ(a.damper1.form, b.damper1.form);
  EXPECT_EQ(a.damper2.form, b.damper2.form);
  EXPECT_EQ(a.q, b.q);
  EXPECT_EQ(a.lambda, b.lambda);
  EXPECT_EQ(a.phi0, b.phi0);
  ASSERT_EQ(a.initial.has_value(), b.initial.has_value());
  if (a.initial) {
    EXPECT_EQ(*a.initial, *b.initial);
  }
}

void expect_same_options(const PointOptions& a, const PointOptions& b) {
  EXPECT_EQ(a.integrator.method, b.integrator.method);
  EXPECT_EQ(a.integrator.rtol, b.integrator.rtol);
  EXPECT_EQ(a.integrator.atol, b.integrator.atol);
  EXPECT_EQ(a.integrator.max_step, b.integrator.max_step);
  EXPECT_EQ(a.integrator.rk4_steps, b.integrator.rk4_steps);
  EXPECT_EQ(a.integrator.max_steps, b.integrator.max_steps);
  EXPECT_EQ(a.analysis.steady, b.analysis.steady);
  EXPECT_EQ(a.analysis.transient_periods, b.analysis.transient_periods);
  EXPECT_EQ(a.analysis.newton_tol, b.analysis.newton_tol);
  EXPECT_EQ(a.analysis.newton_max_iterations, b.analysis.newton_max_iterations);
  EXPECT_EQ(a.analysis.lyapunov, b.analysis.lyapunov);
  EXPECT_EQ(a.analysis.lyapunov_periods, b.analysis.lyapunov_periods);
  EXPECT_EQ(a.analysis.n_max, b.analysis.n_max);
  EXPECT_EQ(a.analysis.max_periods, b.analysis.max_periods);
  EXPECT_EQ(a.analysis.steady_tol, b.analysis.steady_tol);
  EXPECT_EQ(a.analysis.chatter_impacts, b.analysis.chatter_impacts);
  EXPECT_EQ(a.analysis.hertz_limit, b.analysis.hertz_limit);
  EXPECT_EQ(a.analysis.trajectory_periods, b.analysis.trajectory_periods);
  EXPECT_EQ(a.analysis.trajectory_samples, b.analysis.trajectory_samples);
}

// ---------------------------------------------------------------------------------------
// Reading values

TEST(Scene, EmptySceneHasTheHeaderDefaults) {
  const Scene s = parse("");
  expect_same_parameters(s.params, Parameters{});
  expect_same_options(s.options, PointOptions{});
  EXPECT_FALSE(s.params.initial.has_value());
  EXPECT_EQ(s.path, kFile);
}

TEST(Scene, ReadsEveryParameterKey) {
  const Parameters p = parse(R"(
[system]
m1 = 900.0
m2 = 250
k1 = 40000.0
omega2 = 4.5
c1 = 120.0
xi2 = 0.02
D = 0.01
[contact]
E1 = 1e9
E2 = 2e9
nu1 = 0.25
nu2 = -0.5
R1 = 0.5
R2 = 1.5
q = 0.3
[forcing]
F0 = 400.0
omega = 6.0
lambda = 0.5
phi0 = -1.0
)").params;
  EXPECT_EQ(p.m1, 900.0);
  EXPECT_EQ(p.m2, 250.0);  // a TOML integer is accepted for a float
  EXPECT_EQ(p.spring1.form, Spring::Form::stiffness);
  EXPECT_EQ(p.spring1.value, 40000.0);
  EXPECT_EQ(p.spring2.form, Spring::Form::frequency);
  EXPECT_EQ(p.spring2.value, 4.5);
  EXPECT_EQ(p.damper1.form, Damper::Form::coefficient);
  EXPECT_EQ(p.damper1.value, 120.0);
  EXPECT_EQ(p.damper2.form, Damper::Form::ratio);
  EXPECT_EQ(p.damper2.value, 0.02);
  EXPECT_EQ(p.D, 0.01);
  EXPECT_EQ(p.E1, 1e9);
  EXPECT_EQ(p.E2, 2e9);
  EXPECT_EQ(p.nu1, 0.25);
  EXPECT_EQ(p.nu2, -0.5);
  EXPECT_EQ(p.R1, 0.5);
  EXPECT_EQ(p.R2, 1.5);
  EXPECT_EQ(p.q, 0.3);
  EXPECT_EQ(p.F0, 400.0);
  EXPECT_EQ(p.omega, 6.0);
  EXPECT_EQ(p.lambda, 0.5);
  EXPECT_EQ(p.phi0, -1.0);
}

TEST(Scene, ReadsEveryOptionKey) {
  const PointOptions o = parse(R"(
[solver]
method = "rk4"
rtol = 1e-8
atol = 1e-12
max_step = 0.5
rk4_steps = 4096
max_steps = 100000
[analysis]
steady = "integrate"
transient_periods = 12
newton_tol = 1e-9
newton_max_iterations = 7
lyapunov = true
lyapunov_periods = 150
n_max = 4
max_periods = 300
steady_tol = 1e-6
chatter_impacts = 7
hertz_limit = 0.02
trajectory_periods = 3
trajectory_samples = 500
)").options;
  EXPECT_EQ(o.integrator.method, Method::rk4);
  EXPECT_EQ(o.integrator.rtol, 1e-8);
  EXPECT_EQ(o.integrator.atol, 1e-12);
  EXPECT_EQ(o.integrator.max_step, 0.5);
  EXPECT_EQ(o.integrator.rk4_steps, 4096);
  EXPECT_EQ(o.integrator.max_steps, 100000);
  EXPECT_EQ(o.analysis.steady, SteadyMethod::integrate);
  EXPECT_EQ(o.analysis.transient_periods, 12);
  EXPECT_EQ(o.analysis.newton_tol, 1e-9);
  EXPECT_EQ(o.analysis.newton_max_iterations, 7);
  EXPECT_TRUE(o.analysis.lyapunov);
  EXPECT_EQ(o.analysis.lyapunov_periods, 150);
  EXPECT_EQ(o.analysis.n_max, 4);
  EXPECT_EQ(o.analysis.max_periods, 300);
  EXPECT_EQ(o.analysis.steady_tol, 1e-6);
  EXPECT_EQ(o.analysis.chatter_impacts, 7);
  EXPECT_EQ(o.analysis.hertz_limit, 0.02);
  EXPECT_EQ(o.analysis.trajectory_periods, 3);
  EXPECT_EQ(o.analysis.trajectory_samples, 500);
}

TEST(Scene, MethodsAreNamedAsTheCoreNamesThem) {
  for (const Method m : {Method::hybrid, Method::dopri5, Method::rk4}) {
    EXPECT_EQ(parse("", {concat({"solver.method=", to_string(m)})}).options.integrator.method, m);
  }
  for (const SteadyMethod m : {SteadyMethod::follow, SteadyMethod::shooting, SteadyMethod::integrate}) {
    EXPECT_EQ(parse("", {concat({"analysis.steady=", to_string(m)})}).options.analysis.steady, m);
  }
  EXPECT_EQ(parse("").options.integrator.method, Method::hybrid);
  EXPECT_EQ(parse("").options.analysis.steady, SteadyMethod::follow);  // the motion from the initial state
}

TEST(Scene, BooleanKeyReadsTomlTrueAndFalse) {
  EXPECT_TRUE(parse("[analysis]\nlyapunov = true\n").options.analysis.lyapunov);
  EXPECT_FALSE(parse("[analysis]\nlyapunov = false\n").options.analysis.lyapunov);
  EXPECT_TRUE(parse("", {"analysis.lyapunov=true"}).options.analysis.lyapunov);
  const Scene s = parse("[analysis]\nlyapunov = true\n");
  EXPECT_NE(s.text.find("lyapunov = true"), std::string::npos) << s.text;
  EXPECT_TRUE(parse_scene(s.text, s.path).options.analysis.lyapunov);
}

TEST(Scene, WholeFloatIsAcceptedForAnInteger) {
  const Scene s = parse("[analysis]\nmax_periods = 2500.0\n");
  EXPECT_EQ(s.options.analysis.max_periods, 2500);
}

TEST(Scene, PairFormIsKeptAndDerivesTheOther) {
  const Scene s = parse("[system]\nm2 = 100.0\nk2 = 3000.0\nc2 = 10.0\n");
  EXPECT_EQ(s.params.spring2.form, Spring::Form::stiffness);
  EXPECT_DOUBLE_EQ(Key::at("omega2").value(s.params), std::sqrt(3000.0 / 100.0));
  EXPECT_DOUBLE_EQ(Key::at("xi2").value(s.params), 10.0 / (2.0 * std::sqrt(100.0 * 3000.0)));
}

TEST(Scene, InitialSubsetDefaultsToTheRestState) {
  const Scene s = parse("[system]\nD = 0.1\n[initial]\nv1 = 0.5\n");
  ASSERT_TRUE(s.params.initial.has_value());
  EXPECT_EQ(*s.params.initial, Eigen::Vector4d(0.0, 0.1, 0.5, 0.0));
  // x2 defaults to D as finally set, also when D comes from an override.
  const Scene t = parse("[initial]\nx1 = -0.01\n", {"system.D=0.2"});
  EXPECT_EQ(*t.params.initial, Eigen::Vector4d(-0.01, 0.2, 0.0, 0.0));
}

// ---------------------------------------------------------------------------------------
// Overrides

TEST(Scene, SetOverridesTheFileAndCreatesSections) {
  const Scene s = parse("[system]\nm2 = 200.0\n", {"system.m2=310", "solver.rtol=1e-8", "analysis.n_max=4"});
  EXPECT_EQ(s.params.m2, 310.0);
  EXPECT_EQ(s.options.integrator.rtol, 1e-8);
  EXPECT_EQ(s.options.analysis.n_max, 4);
}

// --set names a key as a [sweep] axis does: section.key, or the key alone when only one section has it.
TEST(Scene, SetTakesTheShortKeyNamesOfSweep) {
  const std::vector<std::string> short_names = {"m2=300", "omega=8.1", "method=rk4", "E2=1e9", "D=0.04"};
  const std::vector<std::string> full_names = {"system.m2=300", "forcing.omega=8.1", "solver.method=rk4",
                                               "contact.E2=1e9", "system.D=0.04"};
  const Scene s = parse("[system]\nm2 = 200.0\n", short_names);
  EXPECT_EQ(s.params.m2, 300.0);
  EXPECT_EQ(s.params.omega, 8.1);
  EXPECT_EQ(s.options.integrator.method, Method::rk4);
  EXPECT_EQ(s.params.E2, 1e9);
  EXPECT_EQ(s.params.D, 0.04);
  // the same scene as with the full names: equal texts after the line recording the overrides
  const Scene full = parse("[system]\nm2 = 200.0\n", full_names);
  EXPECT_EQ(s.text.substr(s.text.find("[system]")), full.text.substr(full.text.find("[system]")));
  // the other form of a pair is replaced, as with the full name
  const Scene k = parse("[system]\nomega2 = 5.0\n", {"k2=3000"});
  EXPECT_EQ(k.params.spring2.form, Spring::Form::stiffness);
  EXPECT_EQ(k.params.spring2.value, 3000.0);
}

TEST(Scene, SetValueIsTomlOrElseAString) {
  EXPECT_EQ(parse("", {"solver.method=rk4"}).options.integrator.method, Method::rk4);
  EXPECT_EQ(parse("", {"solver.method=\"rk4\""}).options.integrator.method, Method::rk4);
  EXPECT_EQ(parse("", {" solver.method = rk4 "}).options.integrator.method, Method::rk4);
  // A value that parses as TOML but is not a number is a type error, not a string.
  EXPECT_NE(error_of("", {"system.m1=true"}).find("must be a finite number > 0 (kg)"), std::string::npos);
}

TEST(Scene, SetReplacesTheOtherKeyOfAPair) {
  const Scene s = parse("[system]\nomega2 = 5.0\nxi1 = 0.02\n", {"system.k2=3000", "system.c1=50"});
  EXPECT_EQ(s.params.spring2.form, Spring::Form::stiffness);
  EXPECT_EQ(s.params.spring2.value, 3000.0);
  EXPECT_EQ(s.params.damper1.form, Damper::Form::coefficient);
  EXPECT_EQ(s.params.damper1.value, 50.0);
  EXPECT_EQ(s.text.find("omega2"), std::string::npos) << s.text;
  EXPECT_NE(s.text.find("k2 = 3000"), std::string::npos) << s.text;
}

TEST(Scene, TextRecordsOverridesAndReadsBackToTheSameScene) {
  const Scene s = parse("[system]\nm2 = 200.0\n[contact]\nE2 = 1e6\n", {"system.m2=310", "solver.method=rk4"});
  EXPECT_NE(s.text.find("# overrides: --set system.m2=310 --set solver.method=rk4"), std::string::npos);
  EXPECT_NE(s.text.find("m2 = 310"), std::string::npos);
  EXPECT_NE(s.text.find("method = \"rk4\""), std::string::npos);
  const Scene again = parse_scene(s.text, s.path);
  expect_same_parameters(again.params, s.params);
  expect_same_options(again.options, s.options);
}

// ---------------------------------------------------------------------------------------
// Errors: one line naming the file, the key and what is allowed.

struct BadScene {
  std::string name;
  std::string text;
  std::vector<std::string> sets;
  std::vector<std::string> expected;  // substrings of the message
};

const std::vector<BadScene>& bad_scenes() {
  static const std::vector<BadScene> cases = {
      {"negative mass", "[system]\nm2 = -5\n", {}, {"jobs/x.toml:2: [system] m2 = -5: must be > 0 (kg)"}},
      {"zero modulus", "[contact]\nE1 = 0.0\n", {}, {"jobs/x.toml:2:", "[contact] E1 = 0", "must be > 0 (Pa)"}},
      {"negative k2", "[system]\nk2 = -1.0\n", {}, {"[system] k2 = -1", "must be >= 0 (N/m)"}},
      {"poisson at 0.5", "[contact]\nnu1 = 0.5\n", {}, {"[contact] nu1 = 0.5", "must be in (-1, 0.5)"}},
      {"rtol too loose", "[solver]\nrtol = 0.1\n", {}, {"[solver] rtol = 0.1", "must be in (0, 0.1)"}},
      {"max_step zero", "[solver]\nmax_step = 0\n", {}, {"[solver] max_step = 0", "must be in (0, 1]"}},
      {"n_max too big", "[analysis]\nn_max = 65\n", {}, {"[analysis] n_max = 65", "must be an integer in [1, 64]"}},
      {"n_max not whole", "[analysis]\nn_max = 2.5\n", {}, {"[analysis] n_max = 2.5", "must be an integer in [1, 64]"}},
      {"few samples", "[analysis]\ntrajectory_samples = 9\n", {}, {"trajectory_samples = 9", "must be an integer >= 10"}},
      {"int overflow", "[solver]\nrk4_steps = 3000000000\n", {}, {"rk4_steps = 3000000000", "must be at most 2147483647"}},
      {"string for number", "[system]\nm1 = \"heavy\"\n", {}, {"[system] m1 = \"heavy\"", "must be a finite number > 0 (kg)"}},
      {"infinite", "[system]\nm1 = inf\n", {}, {"[system] m1 = inf", "must be a finite number > 0 (kg)"}},
      {"nan phase", "[forcing]\nphi0 = nan\n", {}, {"[forcing] phi0 = nan", "must be a finite number in [-1000, 1000] (rad)"}},
      {"huge phase", "[forcing]\nphi0 = -1e308\n", {}, {"[forcing] phi0 = -1e+308", "must be in [-1000, 1000] (rad)"}},
      {"bad method", "[solver]\nmethod = \"rk5\"\n", {}, {"[solver] method = \"rk5\"",
                                                          "must be one of \"hybrid\", \"dopri5\", \"rk4\"",
                                                          "did you mean \"rk4\"?"}},
      {"bad steady", "[analysis]\nsteady = \"shoting\"\n", {}, {"[analysis] steady = \"shoting\"",
                                                                "must be one of \"follow\", \"shooting\", \"integrate\"",
                                                                "did you mean \"shooting\"?"}},
      {"bool as string", "[analysis]\nlyapunov = \"yes\"\n", {}, {"[analysis] lyapunov = \"yes\"", "must be true or false"}},
      {"bool as number", "[analysis]\nlyapunov = 1\n", {}, {"[analysis] lyapunov = 1", "must be true or false"}},
      {"set bad bool", "", {"analysis.lyapunov=yes"}, {"--set analysis.lyapunov=yes", "must be true or false"}},
      {"newton iterations", "[analysis]\nnewton_max_iterations = 1001\n", {},
       {"newton_max_iterations = 1001", "must be an integer in [1, 1000]"}},
      {"newton tol", "[analysis]\nnewton_tol = -1e-9\n", {}, {"newton_tol = -1e-09", "must be >= 0"}},
      {"no transient", "[analysis]\ntransient_periods = 0\n", {}, {"transient_periods = 0", "must be an integer in [1, 1e+06]"}},
      {"short lyapunov", "[analysis]\nlyapunov_periods = 9\n", {}, {"lyapunov_periods = 9", "must be an integer in [10, 1e+07]"}},
      {"both of a pair", "[system]\nk1 = 4e4\nomega1 = 6.0\n", {}, {"jobs/x.toml:", "[system] both k1 and omega1 given",
                                                                  "give only one (k1 in N/m, or omega1 in rad/s)"}},
      {"unknown key", "[system]\nomgea1 = 6.0\n", {}, {"jobs/x.toml:2: unknown key 'omgea1' in [system]",
                                                       "did you mean 'omega1'?", "keys of [system]: m1, m2"}},
      {"key in wrong section", "[system]\nE1 = 1e9\n", {}, {"unknown key 'E1' in [system]", "it belongs in [contact]"}},
      {"unknown section", "[sytem]\nm1 = 1.0\n", {}, {"jobs/x.toml:1: unknown section [sytem]",
                                                      "did you mean [system]?", "sections: system, contact"}},
      {"sweep axis not a table", "[sweep]\nE1 = [1, 2]\n", {}, {"jobs/x.toml:2: [sweep] E1 = [1, 2]", "must be an inline table"}},
      {"key outside section", "m1 = 1.0\n", {}, {"jobs/x.toml:1: key 'm1' is outside any section: put it under [system]"}},
      {"section as value", "system = 5\n", {}, {"'system' must be a section [system]"}},
      {"malformed toml", "[system]\nm1 = = 3\n", {}, {"jobs/x.toml:2:", "malformed TOML"}},
      {"set negative mass", "", {"system.m2=-5"}, {"jobs/x.toml: --set system.m2=-5: [system] m2 = -5: must be > 0 (kg)"}},
      {"set without =", "", {"system.m2"}, {"jobs/x.toml: --set system.m2: expected section.key=value"}},
      {"set unknown short key", "", {"mass=5"}, {"jobs/x.toml: --set mass=5: unknown key 'mass'",
                                                 "key=value when only one section has the key"}},
      {"set short key of two sections", "", {"x1=0.01"}, {"--set x1=0.01: several sections have the key 'x1'",
                                                           "initial.x1 or census.x1"}},
      {"set short key of an option too", "", {"law=flores"}, {"several sections have the key 'law'",
                                                              "contact.law or optimise.law"}},
      {"set short key checked", "", {"m2=-5"}, {"jobs/x.toml: --set m2=-5: [system] m2 = -5: must be > 0 (kg)"}},
      {"set unknown key", "", {"system.mass=5"}, {"--set system.mass=5: unknown key 'mass' in [system]"}},
      {"set unknown section", "", {"sytem.m2=5"}, {"--set sytem.m2=5: unknown section [sytem]"}},
      {"set bad choice", "", {"solver.method=euler"}, {"--set solver.method=euler", "must be one of"}},
      // issue #28: budgets with a ceiling, a forcing the springs can follow, a census box of finite span
      {"step budget", "[solver]\nmax_steps = 1e11\n", {}, {"max_steps = 1e+11", "must be an integer in [1, 1e+10]"}},
      {"period budget", "", {"analysis.max_periods=1000000000"}, {"must be an integer in [1, 1e+08]"}},
      // a period must fit in the step budget at the largest step (fuzz seed 161803, case 1364)
      {"largest step below the budget's", "", {"solver.max_step=1e-300"},
       {"jobs/x.toml: --set solver.max_step=1e-300: [solver] max_step = 1e-300: a forcing period at this largest "
        "step takes more steps than the whole step budget (solver.max_steps = 2e+07): it must be at least "
        "1/max_steps = 5e-08"}},
      {"rk4 period over the budget", "[solver]\nmethod = \"rk4\"\nmax_steps = 1000\n", {"solver.rk4_steps=2048"},
       {"--set solver.rk4_steps=2048: [solver] rk4_steps = 2048: one forcing period takes more steps than the whole "
        "step budget (solver.max_steps = 1000)"}},
      {"forcing too slow", "", {"forcing.omega=1e-9"},
       {"jobs/x.toml: --set forcing.omega=1e-9: forcing.omega = 1e-09 rad/s is 1.43e-10 times omega_n = 6.98 rad/s",
        "omega/omega_n must be in [0.0001, 1e+04], i.e. forcing.omega in [0.000698, 6.98e+04] rad/s"}},
      {"main spring too stiff", "[system]\nomega1 = 2147483647\n", {},
       {"jobs/x.toml: forcing.omega = 7.23 rad/s is 3.37e-09 times omega_n = 2.15e+09 rad/s"}},
      {"census span", "", {"census.x1=[-1e308,1e308]"}, {"--set census.x1=[-1e308,1e308]: [census] x1 = [-1e+308, 1e+308]: must be an array [lo, hi]",
                                                        "a finite hi - lo"}},
      // issue #43 (fuzz seed 141421): a census with rk4 was every cell failed (sweep) or exit 1 (basins);
      // a grid cell of 1e-300 motion scales made every state's cell index overflow
      {"census with rk4", "[census]\ninitial_conditions = 4\n", {"solver.method=rk4"},
       {"jobs/x.toml: [solver] method = \"rk4\": a census needs an adaptive method (hybrid or dopri5)"}},
      {"census cell too fine", "[census]\ncell = 1e-300\n", {}, {"[census] cell = 1e-300", "must be in [1e-06, 1000]"}},
  };
  return cases;
}

TEST(Scene, EachBadInputGivesOneLineNamingFileKeyAndAllowed) {
  for (const BadScene& c : bad_scenes()) {
    const std::string message = error_of(c.text, c.sets);
    EXPECT_EQ(message.find('\n'), std::string::npos) << c.name << ": " << message;
    for (const std::string& part : c.expected) {
      EXPECT_NE(message.find(part), std::string::npos) << c.name << ": '" << part << "' not in: " << message;
    }
  }
}

TEST(Scene, MissingFileIsASceneError) {
  try {
    load_scene("/nonexistent/scene.toml");
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/scene.toml: cannot read scene: no such file");
  }
}

// The SceneError message load_scene gives for `path`, or "" when it loads.
std::string load_error(const std::string& path) {
  try {
    load_scene(path);
  } catch (const SceneError& e) {
    return e.what();
  }
  return {};
}

// A scene path that is not a regular file is refused at once, naming what it is: a device that
// never ends, a FIFO without a writer (which a blocking open would wait on forever), a directory.
using SceneFile = test::TempDir;

TEST_F(SceneFile, OnlyARegularFileIsReadAsAScene) {
  EXPECT_EQ(load_error("/dev/zero"), "/dev/zero: cannot read scene: it is a character device, not a regular file");
  EXPECT_EQ(load_error("/dev/urandom"), "/dev/urandom: cannot read scene: it is a character device, not a regular file");
  EXPECT_EQ(load_error(dir_.string()), dir_.string() + ": cannot read scene: it is a directory, not a regular file");
  const std::string fifo = file("scene.toml");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(load_error(fifo), fifo + ": cannot read scene: it is a FIFO (named pipe), not a regular file");
}

// The cap is kMaxSceneBytes: a file of exactly that size is read (a comment, so it parses), one
// byte more is refused with the cap in the message.
TEST_F(SceneFile, IsReadUpToItsCap) {
  const std::string path = file("scene.toml");
  const std::string head = "[system]\nm2 = 123.0\n#";
  std::string text = head + std::string(kMaxSceneBytes - head.size() - 1, 'x') + "\n";
  ASSERT_EQ(text.size(), kMaxSceneBytes);
  std::ofstream(path, std::ios::binary) << text;
  EXPECT_EQ(load_scene(path).params.m2, 123.0);
  std::ofstream(path, std::ios::binary) << text << "\n";
  EXPECT_EQ(load_error(path), path + ": cannot read scene: 4194305 bytes, more than the 4 MiB (4194304 bytes) a "
                                     "scene may have");
}

// ---------------------------------------------------------------------------------------
// The schema, the paper's scenes and the reference scene

TEST(Scene, SchemaKeysAreUniqueAndPairsMutual) {
  for (const Key key : Key::all()) {
    const KeyInfo& k = key.info();
    int same = 0;
    const KeyInfo* partner = nullptr;
    for (const Key other_key : Key::all()) {
      const KeyInfo& other = other_key.info();
      if (other.section == k.section && other.name == k.name) ++same;
      if (other.section == k.section && other.name == k.partner) partner = &other;
    }
    EXPECT_EQ(same, 1) << k.name;
    if (!k.partner.empty()) {
      ASSERT_NE(partner, nullptr) << k.name;
      EXPECT_EQ(partner->partner, k.name);
    }
  }
}

// A parameter (an axis, a free variable, a continuation key) is named by its name alone: no two
// parameters share one.
TEST(Scene, EveryParameterHasANameOfItsOwn) {
  for (const Key k : Key::all())
    if (k.is_parameter()) {
      EXPECT_EQ(Key::find(k.info().name), k) << k.full_name();
    }
}

TEST(Scene, BoundsText) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ((Bounds{0, inf, true, false}.to_string()), "> 0");
  EXPECT_EQ((Bounds{1, inf, false, false}.to_string()), ">= 1");
  EXPECT_EQ((Bounds{-1, 0.5, true, true}.to_string()), "in (-1, 0.5)");
  EXPECT_EQ((Bounds{0, 1, true, false}.to_string()), "in (0, 1]");
  EXPECT_FALSE((Bounds{0, inf, true, false}.contains(0.0)));
  EXPECT_TRUE((Bounds{0, 1, true, false}.contains(1.0)));
  EXPECT_FALSE((Bounds{-inf, inf, false, false}.contains(std::nan(""))));
}

TEST(Scene, PaperTable1HasTheSpecValues) {
  const Parameters p = load_scene(source_path("jobs/paper/table1.toml")).params;
  EXPECT_EQ(p.m1, 1000.0);
  EXPECT_EQ(p.m2, 100.0);
  EXPECT_EQ(Key::at("omega1").value(p), 6.283);
  EXPECT_EQ(Key::at("omega2").value(p), 5.646);
  EXPECT_DOUBLE_EQ(Key::at("k2").value(p), 100.0 * 5.646 * 5.646);
  EXPECT_EQ(p.E1, 2.099e11);
  EXPECT_EQ(p.E2, 2.099e11);
  EXPECT_EQ(p.R1, 2.0);
  EXPECT_EQ(p.R2, 2.0);
  EXPECT_EQ(p.F0, 500.0);
  EXPECT_EQ(p.omega, 7.23);
  // The calibration of what the paper does not state (docs/model.md).
  EXPECT_EQ(Key::at("xi1").value(p), 0.01);
  EXPECT_EQ(Key::at("xi2").value(p), 0.01);
  EXPECT_EQ(p.D, 0.05);
  EXPECT_EQ(p.nu1, 0.3);
  EXPECT_EQ(p.nu2, 0.3);
  EXPECT_EQ(p.lambda, 1.0);
  EXPECT_EQ(p.phi0, 0.0);
}

TEST(Scene, PaperTable2HasTheSpecValues) {
  const Parameters p = load_scene(source_path("jobs/paper/table2.toml")).params;
  EXPECT_EQ(p.m1, 1000.0);
  EXPECT_EQ(p.m2, 310.0);
  EXPECT_EQ(Key::at("omega1").value(p), 6.283);
  EXPECT_EQ(Key::at("omega2").value(p), 3.606);
  EXPECT_DOUBLE_EQ(Key::at("k2").value(p), 310.0 * 3.606 * 3.606);
  EXPECT_EQ(p.E1, 1.4e10);
  EXPECT_EQ(p.E2, 1.0e6);
  EXPECT_EQ(p.R1, 2.0);
  EXPECT_EQ(p.R2, 2.0);
  EXPECT_EQ(p.F0, 500.0);
  EXPECT_EQ(p.omega, 7.23);
  EXPECT_EQ(Key::at("xi1").value(p), 0.01);
  EXPECT_EQ(p.D, 0.05);
}

TEST(Scene, ReferenceSceneEqualsTheDefaults) {
  const Scene s = load_scene(source_path("jobs/reference.toml"));
  expect_same_parameters(s.params, Parameters{});
  expect_same_options(s.options, PointOptions{});
}

// Every key appears in jobs/reference.toml under its section, as `key = ` or commented out.
// When this fails, regenerate it: `vibromap keys --toml > jobs/reference.toml`.
TEST(Scene, ReferenceSceneDocumentsEveryKey) {
  const std::string text = read_text(source_path("jobs/reference.toml"));
  for (const Key key : Key::all()) {
    const KeyInfo& k = key.info();
    const auto start = text.find(concat({"\n[", k.section, "]\n"}));
    ASSERT_NE(start, std::string::npos) << k.section;
    const auto end = text.find("\n[", start + 1);
    const std::string body = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    const std::string name(k.name);
    EXPECT_TRUE(body.find(concat({"\n", name, " = "})) != std::string::npos ||
                body.find(concat({"\n# ", name, " = "})) != std::string::npos)
        << "[" << k.section << "] " << name << " missing from jobs/reference.toml";
  }
}

TEST(Scene, ReferenceWriterOutputParsesToTheDefaults) {
  std::ostringstream os;
  write_reference_scene(os);
  const Scene s = parse_scene(os.str(), "reference");
  expect_same_parameters(s.params, Parameters{});
  expect_same_options(s.options, PointOptions{});
}

TEST(Scene, KeysListingShowsEveryKeyWithDefaultAndUnit) {
  std::ostringstream os;
  write_scene_keys(os);
  const std::string text = os.str();
  for (const Key k : Key::all()) {
    EXPECT_NE(text.find(concat({k.full_name(), " "})), std::string::npos) << k.full_name();
  }
  EXPECT_NE(text.find("1e-10"), std::string::npos);  // rtol's default
  EXPECT_NE(text.find("rad/s"), std::string::npos);
}

// ---------------------------------------------------------------------------------------
// JSON writer

std::string compact_json(const std::function<void(JsonWriter&)>& write) {
  std::ostringstream os;
  JsonWriter w(os, 0);
  write(w);
  EXPECT_TRUE(w.complete());
  return os.str();
}

TEST(JsonWriter, WritesNestedValues) {
  const std::string s = compact_json([](JsonWriter& w) {
    w.begin_object().field("a", 1).field("b", true).key("c").begin_array().value(0.5).null().value("x");
    w.begin_object().end_object().end_array().field("d", -3L).end_object();
  });
  EXPECT_EQ(s, R"({"a":1,"b":true,"c":[0.5,null,"x",{}],"d":-3})");
}

TEST(JsonWriter, NumbersRoundTripAndNonFiniteIsNull) {
  const std::string s = compact_json([](JsonWriter& w) {
    w.begin_array().value(0.1).value(1e-10).value(1000.0).value(2.0 / 3.0);
    w.value(std::numeric_limits<double>::infinity()).value(std::nan("")).end_array();
  });
  EXPECT_EQ(s, "[0.1,1e-10,1000,0.6666666666666666,null,null]");
}

TEST(JsonWriter, EscapesStrings) {
  EXPECT_EQ(json_quote("a\"b\\c\nd\te\x01"), R"("a\"b\\c\nd\te\u0001")");
  EXPECT_EQ(json_quote("µ"), "\"µ\"");  // UTF-8 passes through
}

TEST(JsonWriter, MisuseThrows) {
  std::ostringstream os;
  JsonWriter w(os);
  w.begin_object();
  EXPECT_THROW(w.value(1.0), std::logic_error);  // no key
  EXPECT_THROW(w.end_array(), std::logic_error);
}

// ---------------------------------------------------------------------------------------
// Summary output

PointSummary example_summary() {
  PointSummary s;
  s.status = SolveStatus::ok;
  s.regime = Regime{RegimeKind::periodic, 1, 1};
  s.T = 2.0;
  Impact im;
  im.period_in = 3;
  im.tau_in = 0.5;
  im.period_out = 3;
  im.tau_out = 0.75;
  im.T_con = 0.25;
  im.F_max = 1000.0;
  s.impacts = {im};
  s.T_con = 0.25;
  s.k_con = 8.0;
  s.counters.steps = 42;
  s.z_ratio = std::numeric_limits<double>::quiet_NaN();
  s.steady_method = SteadyMethod::shooting;
  s.newton_iterations = 4;
  s.floquet = {{0.5, -0.25}, {0.6, 0.8}};  // |mu| = 0.559..., 1
  s.stable = 0;
  return s;
}

TEST(SummaryOutput, JsonHasTheKeysAndAbsoluteImpactTimes) {
  std::ostringstream os;
  write_summary_json(os, example_summary());
  const std::string j = os.str();
  for (const char* key : {"status", "message", "regime", "n", "k", "T", "T_con", "k_con", "F_max", "z_max", "z_ratio",
                          "hertz_valid", "impacts", "t_in", "t_out", "v_in", "impulse", "v_out", "e_effective",
                          "energy_dissipated", "clipped", "periods", "steps", "rejected",
                          "rhs_evals", "steady_residual", "wall_s"}) {
    EXPECT_NE(j.find(concat({"\"", key, "\":"})), std::string::npos) << key;
  }
  EXPECT_NE(j.find("\"regime\": \"(1,1)\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"t_in\": 6.5"), std::string::npos) << j;  // 3 T + 0.5 s
  EXPECT_NE(j.find("\"t_out\": 6.75"), std::string::npos) << j;
  EXPECT_NE(j.find("\"k_con\": 8,"), std::string::npos) << j;
  EXPECT_NE(j.find("\"steps\": 42"), std::string::npos) << j;
  EXPECT_NE(j.find("\"z_ratio\": null"), std::string::npos) << j;
  EXPECT_NE(j.find("\"steady_method\": \"shooting\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"newton_iterations\": 4"), std::string::npos) << j;
  EXPECT_NE(j.find("\"stable\": false"), std::string::npos) << j;
  EXPECT_NE(j.find("\"lyapunov\": null"), std::string::npos) << j;  // NaN: not computed
}

TEST(SummaryOutput, JsonHasFloquetMultipliersStabilityAndLyapunov) {
  PointSummary s = example_summary();
  std::ostringstream compact;
  s.stable = 1;
  s.lyapunov = -0.125;
  write_summary_json(compact, s);
  std::string j = compact.str();
  j.erase(std::remove_if(j.begin(), j.end(), [](char c) { return c == ' ' || c == '\n'; }), j.end());
  EXPECT_NE(j.find(R"("floquet":[{"re":0.5,"im":-0.25,"abs":0.5590169943749475},{"re":0.6,"im":0.8,"abs":1}])"),
            std::string::npos) << j;
  EXPECT_NE(j.find(R"("stable":true)"), std::string::npos) << j;
  EXPECT_NE(j.find(R"("lyapunov":-0.125)"), std::string::npos) << j;
  s.stable = -1;
  s.floquet.clear();
  std::ostringstream unknown;
  write_summary_json(unknown, s);
  EXPECT_NE(unknown.str().find("\"stable\": null"), std::string::npos) << unknown.str();
  EXPECT_NE(unknown.str().find("\"floquet\": []"), std::string::npos) << unknown.str();
}

TEST(SummaryOutput, TableShowsStabilityAndMultipliers) {
  PointSummary s = example_summary();
  std::ostringstream os;
  write_summary_table(os, s, parse(""));
  const std::string t = os.str();
  EXPECT_NE(t.find("shooting, 4 Newton iterations"), std::string::npos) << t;
  EXPECT_NE(t.find("unstable"), std::string::npos) << t;
  EXPECT_NE(t.find("largest |mu| = 1"), std::string::npos) << t;
  EXPECT_NE(t.find("0.5 - 0.25i"), std::string::npos) << t;
  EXPECT_NE(t.find("|mu| = 0.559017"), std::string::npos) << t;
  EXPECT_EQ(t.find("lyapunov"), std::string::npos) << t;  // not computed: not shown
  s.stable = -1;
  s.floquet.clear();
  s.lyapunov = 0.031;
  std::ostringstream again;
  write_summary_table(again, s, parse(""));
  EXPECT_NE(again.str().find("unknown"), std::string::npos) << again.str();
  EXPECT_NE(again.str().find("lyapunov         0.031"), std::string::npos) << again.str();
}

TEST(SummaryOutput, TableShowsRegimeUnitsAndImpacts) {
  std::ostringstream os;
  write_summary_table(os, example_summary(), parse(""));
  const std::string t = os.str();
  EXPECT_NE(t.find("(1,1)"), std::string::npos) << t;
  EXPECT_NE(t.find("k_con"), std::string::npos) << t;
  EXPECT_NE(t.find("T_con (s)"), std::string::npos) << t;
  EXPECT_NE(t.find("6.5"), std::string::npos) << t;
}

}  // namespace
}  // namespace vibromap
