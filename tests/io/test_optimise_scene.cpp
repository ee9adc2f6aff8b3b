// The [optimise] section of a scene (io/scene/): free parameters and their boxes, the
// objective, the kept regime, algorithms, seeds and stopping rules, overrides, one-line
// errors, provenance, the documentation, and the optimisation job in jobs/paper/.

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/scene_testing.hpp"
#include "vibromap/io/scene/docs.hpp"
#include "vibromap/io/scene/identity.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/core/optimise/optimise_options.hpp"

namespace vibromap {
namespace {

using test::concat;
using test::error_of;
using test::parse;
using test::read_text;
using test::source_path;

OptimiseOptions optimise_of(const std::string& text, const std::vector<std::string>& sets = {}) {
  const Scene s = parse(text, sets);
  if (!s.optimise) {
    ADD_FAILURE() << "no [optimise] in:\n" << text;
    return {};
  }
  return *s.optimise;
}

std::vector<std::string> names_of(const OptimiseOptions& o) {
  std::vector<std::string> names;
  for (const FreeVariable& v : o.variables) names.emplace_back(v.name());
  return names;
}

void expect_same_variables(const std::vector<FreeVariable>& a, const std::vector<FreeVariable>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].name(), b[i].name());
    EXPECT_EQ(a[i].min, b[i].min) << a[i].name();  // exact: the text round-trips
    EXPECT_EQ(a[i].max, b[i].max) << a[i].name();
    EXPECT_EQ(a[i].scale, b[i].scale) << a[i].name();
  }
}

void expect_same_optimise(const OptimiseOptions& a, const OptimiseOptions& b) {
  expect_same_variables(a.variables, b.variables);
  EXPECT_EQ(a.objective, b.objective);
  EXPECT_EQ(a.impact, b.impact);
  EXPECT_EQ(a.regime, b.regime);
  EXPECT_EQ(a.stability, b.stability);
  EXPECT_EQ(a.hertz_valid, b.hertz_valid);
  EXPECT_EQ(a.algorithms, b.algorithms);
  EXPECT_EQ(a.seeds, b.seeds);
  EXPECT_EQ(a.map, b.map);
  EXPECT_EQ(a.local.xtol_rel, b.local.xtol_rel);
  EXPECT_EQ(a.local.ftol_rel, b.local.ftol_rel);
  EXPECT_EQ(a.local.max_evaluations, b.local.max_evaluations);
  EXPECT_EQ(a.local.max_time, b.local.max_time);
  EXPECT_EQ(a.local.initial_step, b.local.initial_step);
  EXPECT_EQ(a.local.fd_step, b.local.fd_step);
  EXPECT_EQ(a.local.barrier, b.local.barrier);
  EXPECT_EQ(a.best, b.best);
  EXPECT_EQ(a.verify_rtol, b.verify_rtol);
  EXPECT_EQ(a.min_soft_fraction, b.min_soft_fraction);
  EXPECT_EQ(a.soft_check_initial_conditions, b.soft_check_initial_conditions);
}

const std::string kFull =
    "[optimise]\n"
    "omega2 = { min = 3.606, max = 5.646 }\n"
    "m2 = { min = 100, max = 310.0 }\n"
    "E2 = { min = 2e4, max = 2.1e11, scale = \"log\" }\n"
    "objective = \"max_T_con\"\n"
    "impact = 1\n"
    "regime = \"(2,2)\"\n"
    "stability = \"required\"\n"
    "hertz_valid = true\n"
    "algorithm = [\"cobyla\", \"gradient_projection\", \"mma\"]\n"
    "seeds = 7\n"
    "map = \"maps/box.h5\"\n"
    "xtol_rel = 1e-5\n"
    "ftol_rel = 0\n"
    "max_evaluations = 500\n"
    "max_time = 30\n"
    "initial_step = 0.2\n"
    "fd_step = 1e-6\n"
    "barrier = 1e8\n"
    "best = 5\n"
    "verify_rtol = 1e-11\n"
    "min_soft_fraction = 0.9\n"
    "soft_check_initial_conditions = 1024\n";

// ---------------------------------------------------------------------------------------
// Reading a valid section

// The forcing against the natural frequencies (parameters.hpp) is checked at the box's corners:
// a coupling spring of up to 1e12 N/m on 100..310 kg puts omega_n at 1e5 rad/s and more, so
// omega = 7.23 rad/s is below 1e-4 of it at the corner (m2 = 100, k2 = 1e12).
TEST(OptimiseScene, TheFrequencyRuleIsCheckedAtTheBoxCorners) {
  EXPECT_NO_THROW(parse("[optimise]\nm2 = { min = 100, max = 310 }\nk2 = { min = 1e3, max = 1e6 }\n"));
  const std::string msg = error_of("[optimise]\nm2 = { min = 100, max = 310 }\nk2 = { min = 1e3, max = 1e12 }\n");
  EXPECT_NE(msg.find("jobs/x.toml: [optimise] at the corner m2 = 100, k2 = 1e+12 of the box: forcing.omega = 7.23 rad/s "
                     "is 6.89e-05 times omega_n = 1.05e+05 rad/s"),
            std::string::npos)
      << msg;
}

TEST(OptimiseScene, SceneWithoutOptimiseHasNone) {
  EXPECT_FALSE(parse("").optimise.has_value());
  EXPECT_FALSE(parse("[contact]\nE1 = 1e9\n").optimise.has_value());
  EXPECT_FALSE(load_scene(source_path("jobs/paper/table2.toml")).optimise.has_value());
  EXPECT_FALSE(load_scene(source_path("jobs/reference.toml")).optimise.has_value());
}

TEST(OptimiseScene, DefaultsAreTheDocumentedOnes) {
  const OptimiseOptions o = optimise_of("[optimise]\nm2 = { min = 100, max = 310 }\n");
  ASSERT_EQ(o.variables.size(), 1u);
  EXPECT_EQ(o.variables[0].name(), "m2");
  EXPECT_EQ(o.variables[0].min, 100.0);
  EXPECT_EQ(o.variables[0].max, 310.0);
  EXPECT_EQ(o.variables[0].scale, AxisScale::lin);
  EXPECT_EQ(o.objective, ObjectiveKind::min_k_con);
  EXPECT_EQ(o.regime, (Regime{RegimeKind::periodic, 1, 1}));
  EXPECT_EQ(o.stability, StabilityRule::if_known);
  EXPECT_TRUE(o.hertz_valid);  // the default: answers within the Hertz law
  EXPECT_EQ(o.algorithms, std::vector<Algorithm>{Algorithm::bobyqa});
  EXPECT_EQ(o.seeds, 4);
  EXPECT_EQ(o.map, "");
  EXPECT_EQ(o.local.xtol_rel, 1e-4);
  EXPECT_EQ(o.local.ftol_rel, 1e-6);
  EXPECT_EQ(o.local.max_evaluations, 200);
  EXPECT_EQ(o.local.max_time, 0.0);
  EXPECT_EQ(o.local.initial_step, 0.1);
  EXPECT_EQ(o.local.fd_step, 1e-4);
  EXPECT_EQ(o.local.barrier, 1e10);
  EXPECT_EQ(o.best, 3);
  EXPECT_EQ(o.verify_rtol, 1e-12);
  EXPECT_EQ(o.min_soft_fraction, 0.0);  // off
  EXPECT_EQ(o.soft_check_initial_conditions, 512);
}

TEST(OptimiseScene, EveryKeyIsRead) {
  const OptimiseOptions o = optimise_of(kFull);
  EXPECT_EQ(names_of(o), (std::vector<std::string>{"E2", "m2", "omega2"}));  // canonical order
  EXPECT_EQ(o.variables[0].scale, AxisScale::log);
  EXPECT_EQ(o.variables[0].min, 2e4);
  EXPECT_EQ(o.variables[0].max, 2.1e11);
  EXPECT_EQ(o.variables[2].min, 3.606);
  EXPECT_EQ(o.objective, ObjectiveKind::max_T_con);
  EXPECT_EQ(o.impact, 1);
  EXPECT_EQ(o.regime, (Regime{RegimeKind::periodic, 2, 2}));
  EXPECT_EQ(o.stability, StabilityRule::required);
  EXPECT_TRUE(o.hertz_valid);
  EXPECT_EQ(o.algorithms,
            (std::vector<Algorithm>{Algorithm::cobyla, Algorithm::gradient_projection, Algorithm::mma}));
  EXPECT_EQ(o.seeds, 7);
  EXPECT_EQ(o.map, "maps/box.h5");
  EXPECT_EQ(o.local.xtol_rel, 1e-5);
  EXPECT_EQ(o.local.ftol_rel, 0.0);
  EXPECT_EQ(o.local.max_evaluations, 500);
  EXPECT_EQ(o.local.max_time, 30.0);
  EXPECT_EQ(o.local.initial_step, 0.2);
  EXPECT_EQ(o.local.fd_step, 1e-6);
  EXPECT_EQ(o.local.barrier, 1e8);
  EXPECT_EQ(o.best, 5);
  EXPECT_EQ(o.verify_rtol, 1e-11);
  EXPECT_EQ(o.min_soft_fraction, 0.9);
  EXPECT_EQ(o.soft_check_initial_conditions, 1024);
}

TEST(OptimiseScene, AnyRegimeAndASingleAlgorithmName) {
  const OptimiseOptions o =
      optimise_of("[optimise]\nR1 = { min = 0.09, max = 2 }\nregime = \"any\"\nalgorithm = \"sbplx\"\n");
  EXPECT_FALSE(o.regime.has_value());
  EXPECT_EQ(o.algorithms, std::vector<Algorithm>{Algorithm::sbplx});
}

TEST(OptimiseScene, OverridesReplaceKeysAndSpringForms) {
  const std::string text = "[optimise]\nm2 = { min = 100, max = 310 }\nomega2 = { min = 3.6, max = 5.6 }\n";
  const OptimiseOptions o = optimise_of(
      text, {"optimise.algorithm=cobyla", "optimise.E1={min=1e5,max=1e9,scale=\"log\"}", "optimise.k2={min=1e3,max=1e4}",
             "optimise.seeds=8", "optimise.regime=(2,1)"});
  EXPECT_EQ(o.algorithms, std::vector<Algorithm>{Algorithm::cobyla});
  EXPECT_EQ(names_of(o), (std::vector<std::string>{"E1", "m2", "k2"}));  // k2 replaced omega2
  EXPECT_EQ(o.variables[0].scale, AxisScale::log);
  EXPECT_EQ(o.variables[0].min, 1e5);
  EXPECT_EQ(o.seeds, 8);
  EXPECT_EQ(o.regime, (Regime{RegimeKind::periodic, 2, 1}));
  const OptimiseOptions many = optimise_of(text, {"optimise.algorithm=[\"bobyqa\",\"gradient_projection\"]"});
  EXPECT_EQ(many.algorithms, (std::vector<Algorithm>{Algorithm::bobyqa, Algorithm::gradient_projection}));
}

TEST(OptimiseScene, TextRoundTrips) {
  const Scene s = parse(kFull, {"optimise.seeds=9"});
  EXPECT_NE(s.text.find("\n[optimise]\n"), std::string::npos);
  EXPECT_NE(s.text.find("E2 = { min = 20000.0, max = 2.1e+11, scale = \"log\" }"), std::string::npos) << s.text;
  const Scene again = parse_scene(s.text, "again.toml");
  ASSERT_TRUE(again.optimise.has_value());
  expect_same_optimise(*again.optimise, *s.optimise);
  EXPECT_EQ(again.optimise->seeds, 9);
}

TEST(OptimiseScene, ParameterOverrideNamesTheSection) {
  EXPECT_EQ(parameter_override(Key::at("E1"), 2e4), "contact.E1=20000.0");
  EXPECT_EQ(parameter_override(Key::at("omega2"), 4.5528725974356234), "system.omega2=4.5528725974356234");
  EXPECT_EQ(parameter_override(Key::at("k2"), 6425.875), "system.k2=6425.875");
  EXPECT_THROW(parameter_override(Key::at("seeds"), 1.0), std::invalid_argument);
  EXPECT_THROW(parameter_override(Key::at("E3"), 1.0), std::invalid_argument);
  // The override reads back to the same value.
  const Scene s = parse("", {parameter_override(Key::at("omega2"), 4.5528725974356234)});
  EXPECT_EQ(Key::at("omega2").value(s.params), 4.5528725974356234);
}

// ---------------------------------------------------------------------------------------
// Errors: one line naming the file, the line, [optimise] KEY and what is allowed.

struct BadOptimise {
  std::string name;
  std::string text;
  std::vector<std::string> sets;
  std::vector<std::string> expected;  // substrings of the message
};

const std::string kM2 = "[optimise]\nm2 = { min = 100, max = 310 }\n";

const std::vector<BadOptimise>& bad_optimises() {
  static const std::vector<BadOptimise> cases = {
      {"no free parameter", "[optimise]\nseeds = 2\n", {},
       {"jobs/x.toml:1: [optimise] has no free parameters: give at least one real key of [system], [contact] or "
        "[forcing] (E1, m2, omega2, \"forcing.omega\", ...) as NAME = { min, max[, scale] }"}},
      {"key typo", concat({kM2, "algoritm = \"bobyqa\"\n"}), {},
       {"jobs/x.toml:3: unknown key 'algoritm' in [optimise] (did you mean 'algorithm'?)", "keys of [optimise]: m1, m2, k1, omega1, k2, omega2"}},
      {"not a free parameter", "[optimise]\nn_max = { min = 1, max = 2 }\n", {},
       {"jobs/x.toml:2: unknown key 'n_max' in [optimise] (analysis.n_max cannot be a free parameter: free parameters "
        "are the real keys of [system], [contact] and [forcing])"}},
      {"sweep key in optimise", concat({kM2, "order = [\"m2\"]\n"}), {}, {"unknown key 'order' in [optimise] (it belongs in [sweep])"}},
      {"optimise key elsewhere", "[system]\nseeds = 4\n", {}, {"unknown key 'seeds' in [system] (it belongs in [optimise])"}},
      {"optimise key outside any section", "algorithm = \"bobyqa\"\n", {},
       {"jobs/x.toml:1: key 'algorithm' is outside any section: put it under [optimise]"}},
      {"section typo", "[optimse]\n", {},
       {"unknown section [optimse] (did you mean [optimise]?)", "sweep, optimise"}},
      {"variable not a table", "[optimise]\nE1 = 5e9\n", {},
       {"jobs/x.toml:2: [optimise] E1 = 5e+09: free parameter E1 must be an inline table { min, max[, scale] }"}},
      {"unknown variable field", "[optimise]\nE1 = { min = 1e5, mx = 1e9 }\n", {},
       {"jobs/x.toml:2: [optimise] E1 = ", "unknown field 'mx' in free parameter E1 (did you mean 'max'?)"}},
      {"variable lacks max", "[optimise]\nR1 = { min = 0.09 }\n", {},
       {"[optimise] R1 = { min = 0.09 }: free parameter R1 lacks 'max': give { min, max[, scale] }"}},
      {"min not below max", "[optimise]\nR1 = { min = 2, max = 0.09 }\n", {}, {"[optimise] R1 = ", "min must be < max"}},
      {"log from zero", "[optimise]\nomega2 = { min = 0, max = 5, scale = \"log\" }\n", {},
       {"[optimise] omega2 = ", "a log scale needs min > 0"}},
      {"box outside the key's range", "[optimise]\nE1 = { min = -1, max = 2e11 }\n", {},
       {"jobs/x.toml:2: [optimise] E1 = ", "[optimise] E1 = { min = -1, max = 2e+11 }: the box reaches [contact] E1 = -1: must be > 0 (Pa)"}},
      {"bad scale", "[optimise]\nE1 = { min = 1e5, max = 1e9, scale = \"lgo\" }\n", {},
       {"scale must be one of \"lin\", \"log\"", "did you mean \"log\"?"}},
      {"nan bound", "[optimise]\nE1 = { min = nan, max = 1e9 }\n", {}, {"min must be a finite number"}},
      {"both spring forms", "[optimise]\nk2 = { min = 1e3, max = 1e4 }\nomega2 = { min = 3, max = 5 }\n", {},
       {"jobs/x.toml:3: [optimise] both k2 and omega2 given as free parameters", "(k2 in N/m, or omega2 in rad/s)"}},
      {"objective typo", concat({kM2, "objective = \"min_kcon\"\n"}), {},
       {"jobs/x.toml:3: [optimise] objective = \"min_kcon\": must be one of \"min_k_con\", \"max_T_con\", \"min_F_max\"",
        "(did you mean \"min_k_con\"?)"}},
      {"stability typo", concat({kM2, "stability = \"requried\"\n"}), {}, {"did you mean \"required\"?"}},
      {"hertz_valid not a boolean", concat({kM2, "hertz_valid = 1\n"}), {},
       {"jobs/x.toml:3: [optimise] hertz_valid = 1: must be true or false"}},
      {"regime not periodic", concat({kM2, "regime = \"chatter\"\n"}), {},
       {"[optimise] regime = \"chatter\": must be \"(n,k)\" with n, k >= 1, or \"any\""}},
      {"regime zero", concat({kM2, "regime = \"(0,1)\"\n"}), {}, {"must be \"(n,k)\" with n, k >= 1"}},
      {"regime a number", concat({kM2, "regime = 11\n"}), {}, {"[optimise] regime = 11: must be \"(n,k)\""}},
      {"unknown algorithm", concat({kM2, "algorithm = \"bobyq\"\n"}), {},
       {"jobs/x.toml:3: [optimise] algorithm = \"bobyq\": unknown algorithm 'bobyq' (did you mean 'bobyqa'?); "
        "allowed: bobyqa, cobyla, sbplx, slsqp, mma, gradient_projection"}},
      {"algorithm twice", concat({kM2, "algorithm = [\"mma\", \"mma\"]\n"}), {}, {"algorithm mma is listed twice"}},
      {"no algorithm", concat({kM2, "algorithm = []\n"}), {}, {"give at least one algorithm"}},
      {"algorithm not a string", concat({kM2, "algorithm = 3\n"}), {}, {"must be an array of strings (algorithms: bobyqa"}},
      {"seeds zero", concat({kM2, "seeds = 0\n"}), {}, {"jobs/x.toml:3: [optimise] seeds = 0: must be an integer in [1, 1e+06]"}},
      {"evaluations not whole", concat({kM2, "max_evaluations = 2.5\n"}), {}, {"max_evaluations = 2.5: must be an integer"}},
      {"xtol zero", concat({kM2, "xtol_rel = 0\n"}), {}, {"[optimise] xtol_rel = 0: must be in (0, 1)"}},
      {"barrier infinite", concat({kM2, "barrier = inf\n"}), {}, {"[optimise] barrier = inf: must be a finite number > 0"}},
      {"empty map", concat({kM2, "map = \"\"\n"}), {}, {"[optimise] map = \"\": must be the path of a map file"}},
      {"set bad xtol", kM2, {"optimise.xtol_rel=2"}, {"jobs/x.toml: --set optimise.xtol_rel=2: [optimise] xtol_rel = 2: must be in (0, 1)"}},
      {"set unknown key", kM2, {"optimise.sedes=2"}, {"--set optimise.sedes=2: unknown key 'sedes' in [optimise] (did you mean 'seeds'?)"}},
      {"set section without variables", "", {"optimise.seeds=2"}, {"jobs/x.toml: [optimise] has no free parameters"}},
      {"soft fraction above 1", concat({kM2, "min_soft_fraction = 1.5\n"}), {},
       {"jobs/x.toml:3: [optimise] min_soft_fraction = 1.5: must be in [0, 1]"}},
      {"set soft fraction below 0", kM2, {"optimise.min_soft_fraction=-0.1"},
       {"jobs/x.toml: --set optimise.min_soft_fraction=-0.1: [optimise] min_soft_fraction = -0.1: must be in [0, 1]"}},
      {"soft check without states", concat({kM2, "soft_check_initial_conditions = 0\n"}), {},
       {"[optimise] soft_check_initial_conditions = 0: must be an integer in [1, 1e+06]"}},
  };
  return cases;
}

TEST(OptimiseScene, EachBadInputGivesOneLineNamingFileKeyAndAllowed) {
  for (const BadOptimise& c : bad_optimises()) {
    const std::string message = error_of(c.text, c.sets);
    EXPECT_EQ(message.find('\n'), std::string::npos) << c.name << ": " << message;
    for (const std::string& part : c.expected) {
      EXPECT_NE(message.find(part), std::string::npos) << c.name << ": '" << part << "' not in: " << message;
    }
  }
}

// ---------------------------------------------------------------------------------------
// Documentation: keys listing, --help summary, reference scene

TEST(OptimiseScene, KeysListingDocumentsTheOptimiseKeys) {
  std::ostringstream os;
  write_scene_keys(os);
  const std::string text = os.str();
  EXPECT_NE(text.find("optimise.KEY "), std::string::npos);
  for (const char* key : {"optimise.objective ", "optimise.regime ", "optimise.algorithm ", "optimise.seeds ",
                          "optimise.map ", "optimise.xtol_rel ", "optimise.max_evaluations ", "optimise.barrier ",
                          "optimise.verify_rtol ", "optimise.min_soft_fraction ",
                          "optimise.soft_check_initial_conditions "}) {
    EXPECT_NE(text.find(key), std::string::npos) << key;
  }
  EXPECT_NE(text.find("\"min_k_con\""), std::string::npos);
  EXPECT_NE(text.find("gradient_projection"), std::string::npos);
}

TEST(OptimiseScene, HelpSummaryListsTheOptimiseKeys) {
  std::ostringstream os;
  write_scene_key_summary(os);
  EXPECT_NE(os.str().find("[optimise]  m1 m2 k1|omega1 k2|omega2 xi1|c1 xi2|c2 D E1 E2 nu1 nu2 R1 R2 q restitution damping F0 omega "
                          "lambda phi0 objective impact regime stability hertz_valid algorithm law seeds map "
                          "xtol_rel ftol_rel max_evaluations max_time initial_step fd_step barrier best verify_rtol "
                          "min_soft_fraction soft_check_initial_conditions\n"),
            std::string::npos)
      << os.str();
}

// The example [optimise] of the reference scene, uncommented, parses to the defaults.
TEST(OptimiseScene, ReferenceExampleParses) {
  std::ostringstream os;
  write_reference_scene(os);
  const std::string ref = os.str();
  const auto start = ref.find("# [optimise]\n");
  const auto end = ref.find("\n\n", start);
  ASSERT_NE(start, std::string::npos) << ref;
  std::istringstream lines(ref.substr(start, end - start));
  std::string example, line;
  while (std::getline(lines, line)) {
    ASSERT_EQ(line.rfind("# ", 0), 0u) << line;
    example += concat({line.substr(2), "\n"});
  }
  OptimiseOptions o = optimise_of(example);
  EXPECT_EQ(names_of(o), (std::vector<std::string>{"E1", "m2"}));
  EXPECT_EQ(o.variables[0].scale, AxisScale::log);
  EXPECT_EQ(o.map, "box.h5");
  o.map.clear();
  OptimiseOptions defaults;
  defaults.variables = o.variables;
  expect_same_optimise(o, defaults);
}

// ---------------------------------------------------------------------------------------
// The optimisation job

TEST(OptimiseScene, PaperBoxJobIsTheBoxOfSpec) {
  const Scene s = load_scene(source_path("jobs/paper/optimise_box.toml"));
  ASSERT_TRUE(s.optimise.has_value());
  ASSERT_TRUE(s.sweep.has_value());
  const OptimiseOptions& o = *s.optimise;
  EXPECT_EQ(names_of(o), (std::vector<std::string>{"E1", "E2", "R1", "R2", "m2", "omega2"}));
  const std::vector<FreeVariable> box = {{Key::at("E1"), 2e4, 2.1e11, AxisScale::log}, {Key::at("E2"), 2e4, 2.1e11, AxisScale::log},
                                         {Key::at("R1"), 0.09, 2.0, AxisScale::lin},   {Key::at("R2"), 0.09, 2.0, AxisScale::lin},
                                         {Key::at("m2"), 100.0, 310.0, AxisScale::lin}, {Key::at("omega2"), 3.606, 5.646, AxisScale::lin}};
  expect_same_variables(o.variables, box);
  EXPECT_EQ(o.objective, ObjectiveKind::min_k_con);
  EXPECT_EQ(o.regime, (Regime{RegimeKind::periodic, 1, 1}));
  EXPECT_EQ(o.stability, StabilityRule::if_known);
  EXPECT_EQ(o.algorithms, (std::vector<Algorithm>{Algorithm::bobyqa, Algorithm::gradient_projection}));
  std::size_t cells = 1;
  for (const Axis& a : s.sweep->axes) cells *= a.values.size();
  EXPECT_EQ(cells, 2916u);  // a modest map: the whole job runs in about a minute on 2 cores
  for (const Axis& a : s.sweep->axes) {
    const auto it = std::find_if(box.begin(), box.end(), [&](const FreeVariable& v) { return v.name() == a.name; });
    ASSERT_NE(it, box.end()) << a.name;
    EXPECT_EQ(a.values.front(), it->min) << a.name;
    EXPECT_EQ(a.values.back(), it->max) << a.name;
  }
  EXPECT_EQ(s.params.m1, 1000.0);
  EXPECT_EQ(s.params.F0, 500.0);
  EXPECT_EQ(s.params.omega, 7.23);
  EXPECT_EQ(o.min_soft_fraction, 0.0);  // the plain job: no census
}

// The robust job is the paper box job with Hertz validity and 90 % soft basin kept, and no
// [census] (the defaults: 32 states per point, 512 in the re-check).
TEST(OptimiseScene, RobustJobIsThePaperBoxWithRobustSoftness) {
  const Scene box = load_scene(source_path("jobs/paper/optimise_box.toml"));
  const Scene robust = load_scene(source_path("jobs/paper/optimise_robust.toml"));
  ASSERT_TRUE(robust.optimise.has_value());
  OptimiseOptions o = *robust.optimise;
  EXPECT_EQ(o.min_soft_fraction, 0.9);
  EXPECT_TRUE(o.hertz_valid);
  EXPECT_EQ(o.soft_check_initial_conditions, 512);
  EXPECT_FALSE(robust.census.has_value());
  o.min_soft_fraction = 0.0;
  expect_same_optimise(o, *box.optimise);
  const Scene same = load_scene(source_path("jobs/paper/optimise_robust.toml"), {"optimise.min_soft_fraction=0"});
  EXPECT_EQ(canonical_text(same, IdentityScope::optimise), canonical_text(box, IdentityScope::optimise));
}

}  // namespace
}  // namespace vibromap
