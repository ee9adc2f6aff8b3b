// The contact laws in scenes and output (issue #13): contact.law as a categorical [sweep]
// axis and contact.restitution as a numeric one, the restitution x E2 demo scene,
// restitution as an [optimise] free parameter, and the run summary's dissipation per impact.

#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/scene_testing.hpp"
#include "vibromap/core/grid.hpp"
#include "vibromap/io/scene/cell_maker.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/io/summary_output.hpp"

namespace vibromap {
namespace {

using test::error_of;
using test::parse;
using test::source_path;

std::vector<std::string> axis_names(const SweepOptions& s) {
  std::vector<std::string> names;
  for (const Axis& a : s.axes) names.push_back(a.name);
  return names;
}

}  // namespace

TEST(ContactLawScene, ContactLawIsACategoricalAxisAndRestitutionANumericOne) {
  const Scene s = parse(
      "[contact]\nE2 = 1e6\n[sweep]\n\"contact.law\" = { values = [\"flores\", \"hertz\", \"gonthier\"] }\n"
      "restitution = { from = 0.1, to = 0.9, n = 5 }\n");
  ASSERT_TRUE(s.sweep.has_value());
  const auto& axes = s.sweep->axes;
  ASSERT_EQ(axis_names(*s.sweep), (std::vector<std::string>{"law", "restitution"}));  // schema order
  EXPECT_EQ(axes[0].values, (std::vector<double>{3.0, 0.0, 4.0}));  // indices into the choices
  EXPECT_EQ(axes[0].categories,
            (std::vector<std::string>{"hertz", "hunt-crossley", "lankarani-nikravesh", "flores", "gonthier"}));
  EXPECT_EQ(axes[0].units, "1");
  EXPECT_TRUE(axes[1].categories.empty());
  const Grid grid(axes);
  const CellMaker make(s, grid);
  const CellPoint first = make(0), last = make(grid.size() - 1);
  EXPECT_EQ(first.params.law, ContactLawKind::flores);
  EXPECT_EQ(first.params.restitution, 0.1);
  EXPECT_EQ(last.params.law, ContactLawKind::gonthier);
  EXPECT_EQ(last.params.restitution, 0.9);
  EXPECT_EQ(make(5).params.law, ContactLawKind::hertz);
  EXPECT_EQ(first.params.E2, 1e6);
  const Scene again = parse_scene(s.text, s.path);
  ASSERT_TRUE(again.sweep.has_value());
  ASSERT_EQ(again.sweep->axes.size(), 2u);
  EXPECT_EQ(again.sweep->axes[0].values, axes[0].values);
  EXPECT_EQ(again.sweep->axes[1].values, axes[1].values);
  EXPECT_EQ(again.sweep->axes[0].categories, axes[0].categories);
}

TEST(ContactLawScene, ACategoricalAxisTakesNamesOnly) {
  EXPECT_NE(error_of("[sweep]\n\"contact.law\" = { from = 0, to = 4, n = 5 }\n").find("is categorical"),
            std::string::npos);
  EXPECT_NE(error_of("[sweep]\nlaw = { values = [\"flores\", \"flores\"] }\n").find("repeat"), std::string::npos);
  const std::string unknown = error_of("[sweep]\nlaw = { values = [\"florez\"] }\n");
  EXPECT_NE(unknown.find("did you mean \"flores\""), std::string::npos) << unknown;
  EXPECT_NE(error_of("[contact]\nrestitution = 0\n").find("restitution"), std::string::npos);
}

TEST(ContactLawScene, DemoRestitutionE2IsTable2WithFloresOverEAndThePaperBoxOfE2) {
  const Scene s = load_scene(source_path("jobs/demo/restitution_e2.toml"));
  const Scene table2 = load_scene(source_path("jobs/paper/table2.toml"));
  ASSERT_TRUE(s.sweep.has_value());
  EXPECT_EQ(s.params.m2, table2.params.m2);
  EXPECT_EQ(Key::at("omega2").value(s.params), Key::at("omega2").value(table2.params));
  EXPECT_EQ(s.params.E1, table2.params.E1);
  EXPECT_EQ(s.params.law, ContactLawKind::flores);
  const SweepOptions& w = *s.sweep;
  EXPECT_EQ(axis_names(w), (std::vector<std::string>{"restitution", "E2"}));
  EXPECT_EQ(w.axes[0].values.front(), 0.1);
  EXPECT_EQ(w.axes[0].values.back(), 1.0);  // e = 1: elastic Hertz, the paper's contact
  EXPECT_EQ(w.axes[1].values.front(), 2e4);
  EXPECT_EQ(w.axes[1].values.back(), 2.1e11);
  EXPECT_EQ(Grid(w.axes).size(), 19u * 22u);
}

TEST(ContactLawScene, RestitutionIsAFreeParameterUnderTheSceneLaw) {
  const Scene s = parse("[contact]\nlaw = \"flores\"\n[optimise]\nrestitution = { min = 0.2, max = 0.9 }\n");
  ASSERT_TRUE(s.optimise.has_value());
  ASSERT_EQ(s.optimise->variables.size(), 1u);
  EXPECT_EQ(s.optimise->variables[0].name(), "restitution");
  EXPECT_EQ(s.optimise->variables[0].max, 0.9);
  EXPECT_EQ(s.params.law, ContactLawKind::flores);
  EXPECT_EQ(parameter_override(Key::at("restitution"), 0.5), "contact.restitution=0.5");
  EXPECT_NE(error_of("[optimise]\nrestitution = { min = 0.2, max = 1.5 }\n").find("restitution"), std::string::npos);
}

TEST(ContactLawScene, SummaryTableShowsDissipationOnlyWhereAnImpactLostEnergy) {
  PointSummary s;
  s.status = SolveStatus::ok;
  s.regime = Regime{RegimeKind::periodic, 1, 1};
  s.T = 2.0;
  s.impacts = {Impact{}};
  std::ostringstream elastic;
  write_summary_table(elastic, s, parse(""));
  EXPECT_EQ(elastic.str().find("dissipation per impact"), std::string::npos) << elastic.str();
  s.impacts[0].v_out = -0.125;
  s.impacts[0].e_effective = 0.625;
  s.impacts[0].energy_dissipated = 3.5;
  s.impacts[0].clipped = true;
  std::ostringstream damped, json;
  write_summary_table(damped, s, parse(""));
  EXPECT_NE(damped.str().find("dissipation per impact"), std::string::npos) << damped.str();
  EXPECT_NE(damped.str().find("-0.125        0.625             3.5      yes"), std::string::npos) << damped.str();
  write_summary_json(json, s);
  EXPECT_NE(json.str().find("\"energy_dissipated\": 3.5,"), std::string::npos) << json.str();
  EXPECT_NE(json.str().find("\"clipped\": true"), std::string::npos) << json.str();
}

}  // namespace vibromap

namespace vibromap {

// [optimise] law: the contact law as a categorical free variable, a name, a list or "all";
// [] (the default) leaves the scene's law; a wrong name is one line with the allowed ones.
TEST(ContactLawScene, OptimiseLawIsACategoricalFreeVariable) {
  const std::string box = "[optimise]\nrestitution = { min = 0.2, max = 1.0 }\n";
  const Scene listed = test::parse(box + "law = [\"gonthier\", \"flores\"]\n");
  ASSERT_TRUE(listed.optimise.has_value());
  EXPECT_EQ(listed.optimise->laws, (std::vector<ContactLawKind>{ContactLawKind::gonthier, ContactLawKind::flores}));
  EXPECT_EQ(test::parse(box + "law = \"all\"\n").optimise->laws, all_contact_laws());
  EXPECT_EQ(test::parse(box + "law = \"flores\"\n").optimise->laws, (std::vector<ContactLawKind>{ContactLawKind::flores}));
  EXPECT_TRUE(test::parse(box).optimise->laws.empty());
  EXPECT_TRUE(test::parse(box + "law = []\n").optimise->laws.empty());
  const std::string err = test::error_of(box + "law = [\"flores\", \"hunt-crosley\"]\n");
  EXPECT_NE(err.find("unknown contact law 'hunt-crosley' (did you mean 'hunt-crossley'?); allowed: hertz, hunt-crossley, "
                     "lankarani-nikravesh, flores, gonthier, or \"all\""),
            std::string::npos)
      << err;
  EXPECT_NE(test::error_of(box + "law = [\"flores\", \"flores\"]\n").find("contact law flores is listed twice"),
            std::string::npos);
}

}  // namespace vibromap

namespace vibromap {

// jobs/demo/optimise_law.toml: Table 2's point, restitution free in [0.3, 1], every law tried.
TEST(ContactLawScene, OptimiseLawJobIsTable2WithEveryLawAndRestitutionFree) {
  const Scene s = load_scene(test::source_path("jobs/demo/optimise_law.toml"));
  ASSERT_TRUE(s.optimise.has_value());
  EXPECT_EQ(s.optimise->laws, all_contact_laws());
  ASSERT_EQ(s.optimise->variables.size(), 1u);
  EXPECT_EQ(s.optimise->variables[0].name(), "restitution");
  EXPECT_EQ(s.optimise->variables[0].min, 0.3);
  EXPECT_EQ(s.optimise->variables[0].max, 1.0);
  EXPECT_EQ(s.params.m2, 310.0);
  EXPECT_EQ(s.params.E1, 1.4e10);
  EXPECT_EQ(s.params.E2, 1.0e6);
  EXPECT_FALSE(s.sweep.has_value());
}

}  // namespace vibromap
