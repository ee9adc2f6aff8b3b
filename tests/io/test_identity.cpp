// A run's identity (io/scene/identity.hpp): the canonical text of what defines a cell's
// result, from the parsed scene, and the keys by which two of them differ.

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/scene_testing.hpp"
#include "vibromap/io/scene/identity.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {
namespace {

using test::concat;
using test::parse;

std::string sweep_identity(const std::string& text, const std::vector<std::string>& sets = {}) {
  return canonical_text(parse(text, sets), IdentityScope::sweep);
}

std::vector<std::string> differences(const std::string& recorded, const std::string& current) {
  return canonical_differences(sweep_identity(recorded), sweep_identity(current));
}

const std::string kSweep = "[sweep]\nE1 = { from = 2e4, to = 2.1e11, n = 3, scale = \"log\" }\ncheckpoint_interval = 60\n";

TEST(Identity, OneSortedLinePerKeyInShortestForm) {
  const std::string text = sweep_identity(concat({"[forcing]\nF0 = 500.0\n[solver]\nmethod = \"rk4\"\n", kSweep}));
  EXPECT_NE(text.find("\nforcing.F0 = 500\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nsolver.method = rk4\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nanalysis.n_max = 8\n"), std::string::npos) << text;     // a default, an integer
  EXPECT_NE(text.find("\nsystem.omega2 = 5.646\n"), std::string::npos) << text;  // the pair's form held
  EXPECT_EQ(text.find("system.k2"), std::string::npos) << text;
  EXPECT_NE(text.find("\nsweep.axis.0 = contact.E1 log [20000, 64807406.98407869, 2.1e+11]\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("\nsweep.store = [T_con, k_con, F_max, z_max, hertz_valid]\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("interval"), std::string::npos) << text;
  EXPECT_EQ(text.find("initial."), std::string::npos) << text;  // [initial] only where given
  EXPECT_EQ(text.back(), '\n');
  std::vector<std::string> lines;
  for (std::size_t at = 0, end = 0; at < text.size(); at = end + 1) {
    end = text.find('\n', at);
    lines.push_back(text.substr(at, end - at));
  }
  EXPECT_TRUE(std::is_sorted(lines.begin(), lines.end()));
}

TEST(Identity, IntegerAndFloatTextOfOneNumberAgree) {
  EXPECT_EQ(sweep_identity("[forcing]\nF0 = 500\n"), sweep_identity("[forcing]\nF0 = 500.0\n"));
  EXPECT_EQ(sweep_identity("[forcing]\nF0 = 500\n"), sweep_identity(""));  // 500 is the default
  EXPECT_EQ(sweep_identity("[sweep]\nm2 = { values = [100, 310] }\n"),
            sweep_identity("[sweep]\nm2 = { values = [1e2, 310.0] }\n"));
}

TEST(Identity, CommentsKeyOrderAndFormattingDoNotMatter) {
  EXPECT_EQ(sweep_identity("# a scene\n[system]\nm2 = 310 # heavy\nm1 = 1000\n[contact]\nE1 = 1e9\n"),
            sweep_identity("[contact]\nE1 = 1.0e9\n\n# later\n[system]\nm1=1000.0\nm2   =   310.0\n"));
  EXPECT_EQ(sweep_identity("[sweep]\nE1 = { values = [1e9] }\nomega = { values = [7.0] }\n"),
            sweep_identity("[sweep.forcing]\nomega = { values = [7] }\n[sweep.E1]\nvalues = [1000000000]\n"));
}

TEST(Identity, IntervalsAreNotPartOfIt) {
  EXPECT_EQ(sweep_identity(kSweep), sweep_identity(kSweep, {"sweep.checkpoint_interval=5", "sweep.progress_interval=1"}));
  EXPECT_TRUE(differences(kSweep, concat({kSweep, "progress_interval = 2.0\n"})).empty());
}

TEST(Identity, AChangedKeyIsNamedWithBothValues) {
  EXPECT_EQ(differences(kSweep, concat({"[system]\nm2 = 310\n", kSweep})),
            (std::vector<std::string>{"system.m2 (100 in the file, 310 in the scene)"}));
  EXPECT_EQ(differences("", "[system]\nk2 = 3187.6\n"),
            (std::vector<std::string>{"system.k2 (not in the file, 3187.6 in the scene)",
                                      "system.omega2 (5.646 in the file, not in the scene)"}));
  EXPECT_EQ(differences("[initial]\nx1 = 0.01\n", ""),
            (std::vector<std::string>{"initial.x1 (0.01 in the file, not in the scene)"}));
}

TEST(Identity, AChangedAxisIsNamedAndItsValuesClipped) {
  const auto diff = differences(kSweep, "[sweep]\nE1 = { from = 2e4, to = 2.1e11, n = 4, scale = \"log\" }\n");
  ASSERT_EQ(diff.size(), 1u);
  EXPECT_EQ(diff[0].rfind("sweep.axis.0 (contact.E1 log [20000, 64807406.98407869... (50 characters) in the file, "
                          "contact.E1 log [20000, ",
                          0),
            0u)
      << diff[0];
  EXPECT_LT(diff[0].size(), 200u);
  EXPECT_EQ(differences("[sweep]\nE1 = { values = [1e9] }\n", "[sweep]\nE1 = { values = [1e9], scale = \"log\" }\n"),
            (std::vector<std::string>{"sweep.axis.0 (contact.E1 lin [1e+09] in the file, contact.E1 log [1e+09] in "
                                      "the scene)"}));
}

TEST(Identity, OptimiseKeysCountOnlyForAnOptimisation) {
  const std::string a = concat({kSweep, "[optimise]\nE1 = { min = 2e4, max = 2.1e11, scale = \"log\" }\n"});
  const std::string b = concat({kSweep, "[optimise]\nE1 = { min = 2e4, max = 2.1e11, scale = \"log\" }\nseeds = 8\n"});
  EXPECT_EQ(sweep_identity(a), sweep_identity(b));
  EXPECT_EQ(sweep_identity(a), sweep_identity(kSweep));
  const std::string oa = canonical_text(parse(a), IdentityScope::optimise);
  const std::string ob = canonical_text(parse(b), IdentityScope::optimise);
  EXPECT_EQ(canonical_differences(oa, ob), (std::vector<std::string>{"optimise.seeds (4 in the file, 8 in the scene)"}));
  EXPECT_NE(oa.find("\noptimise.E1 = { min = 20000, max = 2.1e+11, scale = log }\n"), std::string::npos) << oa;
  EXPECT_NE(oa.find("\noptimise.regime = (1,1)\n"), std::string::npos) << oa;
  EXPECT_NE(oa.find("\nsweep.axis.0 = contact.E1"), std::string::npos) << oa;  // the seeding sweep counts too
}

// min_soft_fraction and the re-check's size are part of an optimisation's identity, and with
// the constraint on, so are the census options it runs with, the defaults included.
TEST(Identity, RobustSoftnessKeysAndTheCensusItRunsCount) {
  const std::string off = concat({kSweep, "[optimise]\nE1 = { min = 2e4, max = 2.1e11, scale = \"log\" }\n"});
  const std::string on = concat({off, "min_soft_fraction = 0.9\n"});
  const std::string o0 = canonical_text(parse(off), IdentityScope::optimise);
  const std::string o9 = canonical_text(parse(on), IdentityScope::optimise);
  EXPECT_NE(o0.find("\noptimise.min_soft_fraction = 0\n"), std::string::npos) << o0;
  EXPECT_EQ(o0.find("census."), std::string::npos) << o0;  // off: no census, none named
  const std::vector<std::string> diff = canonical_differences(o0, o9);
  EXPECT_NE(std::find(diff.begin(), diff.end(), "optimise.min_soft_fraction (0 in the file, 0.9 in the scene)"),
            diff.end());
  EXPECT_NE(std::find(diff.begin(), diff.end(), "census.initial_conditions (not in the file, 32 in the scene)"),
            diff.end());
  const std::string k64 = canonical_text(parse(on, {"census.initial_conditions=64"}), IdentityScope::optimise);
  EXPECT_EQ(canonical_differences(o9, k64),
            (std::vector<std::string>{"census.initial_conditions (32 in the file, 64 in the scene)"}));
  const std::string check = canonical_text(parse(on, {"optimise.soft_check_initial_conditions=1024"}),
                                           IdentityScope::optimise);
  EXPECT_EQ(canonical_differences(o9, check),
            (std::vector<std::string>{"optimise.soft_check_initial_conditions (512 in the file, 1024 in the scene)"}));
  EXPECT_EQ(sweep_identity(on), sweep_identity(off));  // the seeding map's identity is not the optimiser's
}

}  // namespace
}  // namespace vibromap
