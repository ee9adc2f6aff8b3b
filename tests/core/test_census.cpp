// The census of one point (census.hpp) against references:
//  - its initial states: the rest state first, the others inside the box, never overlapping,
//    the same for the same seed;
//  - a monostable point (the paper's Table 1): one attractor, fraction 1, the orbit solve_point
//    finds (k_con to 1e-6);
//  - the bistable Table 2 point (a soft (1,1) and a (3,3) coexist): every label of the census,
//    with its early decisions, equals the label of brute-force integration of the same initial
//    state with no early stop (census.early_stop = false), attractors matched by their orbits;
//    the fractions add up to one with their standard errors sqrt(p (1 - p) / K).
// VIBROMAP_CENSUS_K sets K of the brute-force comparison (default 48; the closing note of the
// census issue quotes K = 256).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"
#include "support/paper_points.hpp"

namespace vibromap {
namespace {

using test::table2;  // tests/support/paper_points.hpp

TEST(CensusInitialStates, RestFirstThenInsideTheBoxApartAndReproducible) {
  const Parameters p = table2();
  CensusOptions o;
  o.initial_conditions = 200;
  const auto box = census_box(p, o);
  // The default box: the rest state +- L in positions, +- omega L in velocities, L = D here.
  EXPECT_DOUBLE_EQ(box[0][0], -0.05);
  EXPECT_DOUBLE_EQ(box[1][1], 0.1);
  EXPECT_NEAR(box[2][1], 7.23 * 0.05, 1e-12);
  const auto x = census_initial_conditions(p, o);
  ASSERT_EQ(x.size(), 200u);
  EXPECT_EQ(x[0], p.initial_state());
  for (std::size_t i = 1; i < x.size(); ++i) {
    EXPECT_LE(x[i][0] - x[i][1], 0.0) << i;
    for (int c = 0; c < 4; ++c) {
      EXPECT_GE(x[i][c], box[static_cast<std::size_t>(c)][0]);
      EXPECT_LE(x[i][c], box[static_cast<std::size_t>(c)][1]);
    }
  }
  EXPECT_EQ(census_initial_conditions(p, o), x);
  o.seed = 2;
  EXPECT_NE(census_initial_conditions(p, o)[1], x[1]);
}

TEST(CensusInitialStates, AGivenBoxIsUsedAndAnAllOverlappingBoxIsRefused) {
  Parameters p = table2();
  CensusOptions o;
  o.x1 = {{0.2, 0.3}};
  o.x2 = {{0.0, 0.1}};  // x1 - x2 > 0 everywhere
  const CensusSummary s = census_point(p, PointOptions{}, o);
  EXPECT_EQ(s.status, SolveStatus::invalid_input);
  EXPECT_NE(s.message.find("x1 - x2"), std::string::npos) << s.message;
  o.x1 = {{-0.01, 0.01}};
  EXPECT_DOUBLE_EQ(census_box(p, o)[0][1], 0.01);
  CensusOptions bad;
  bad.v1 = {{1.0, -1.0}};
  EXPECT_NE(validate(bad).find("v1"), std::string::npos);
}

TEST(Census, MonostablePointHasOneAttractorThatIsSolvePointsOrbit) {
  const Parameters p;  // Table 1
  CensusOptions o;
  o.initial_conditions = 12;
  const CensusSummary s = census_point(p, PointOptions{}, o);
  ASSERT_EQ(s.status, SolveStatus::ok) << s.message;
  ASSERT_EQ(s.attractors.size(), 1u);
  const Attractor& a = s.attractors.front();
  EXPECT_EQ(a.regime.label(), "(1,1)");
  EXPECT_EQ(a.count, 12);
  EXPECT_DOUBLE_EQ(a.fraction, 1.0);
  EXPECT_DOUBLE_EQ(a.fraction_stderr, 0.0);
  EXPECT_TRUE(a.from_rest);
  EXPECT_EQ(a.stable, 1);
  EXPECT_LT(a.max_floquet, 1.0);
  const PointSummary point = solve_point(p, PointOptions{});
  EXPECT_NEAR(a.k_con, point.k_con, 1e-6 * point.k_con);
  ASSERT_EQ(a.strobe.size(), 1u);
  const Model model(p);
  EXPECT_LT(StateScale(model).distance(Model::to_internal(a.strobe[0]), Model::to_internal(point.final_state)), 1e-6);
  EXPECT_FALSE(a.soft);  // k_con 1111: rigid
}

// The attractor an initial state reached, as an orbit: its period and stroboscopic states
// (empty for a non-periodic attractor, kind only).
struct Identity {
  int label;
  std::string kind;
  std::vector<Eigen::Vector4d> strobe;
};

Identity identity(const CensusSummary& s, std::size_t i) {
  const int l = s.labels[i];
  if (l < 0) return {l, l == kUnresolvedLabel ? "unresolved" : "unlisted", {}};
  const Attractor& a = s.attractors[static_cast<std::size_t>(l)];
  return {l, a.regime.label(), a.strobe};
}

bool same(const Identity& a, const Identity& b, const StateScale& scale) {
  if (a.kind != b.kind || a.strobe.size() != b.strobe.size()) return false;
  const std::size_t n = a.strobe.size();
  if (n == 0) return true;
  for (std::size_t shift = 0; shift < n; ++shift) {
    bool all = true;
    for (std::size_t k = 0; k < n && all; ++k)
      all = scale.distance(Model::to_internal(a.strobe[(k + shift) % n]), Model::to_internal(b.strobe[k])) < 1e-5;
    if (all) return true;
  }
  return false;
}

TEST(Census, EveryLabelEqualsBruteForceAtTheBistableTable2Point) {
  const Parameters p = table2();
  PointOptions options;
  options.analysis.max_periods = 20000;  // the longest transients here take several thousand periods
  CensusOptions o;
  const char* k = std::getenv("VIBROMAP_CENSUS_K");
  o.initial_conditions = k != nullptr ? std::atoi(k) : 48;
  o.seed = 7;
  o.labels = true;
  const CensusSummary census = census_point(p, options, o);
  CensusOptions brute = o;
  brute.early_stop = false;
  const CensusSummary reference = census_point(p, options, brute);
  ASSERT_EQ(census.status, SolveStatus::ok) << census.message;
  ASSERT_EQ(reference.status, SolveStatus::ok) << reference.message;
  EXPECT_EQ(reference.decided_early, 0);
  EXPECT_GT(census.decided_early, o.initial_conditions / 2);
  EXPECT_LT(census.periods, reference.periods / 2);

  // Both the soft (1,1) and the (3,3) are found, and nothing else.
  ASSERT_EQ(census.attractors.size(), 2u);
  EXPECT_EQ(census.attractors[0].regime.label() + census.attractors[1].regime.label(), "(1,1)(3,3)");
  EXPECT_TRUE(census.attractors[0].soft);
  EXPECT_FALSE(census.attractors[1].soft);  // z_max / R* 0.07 > hertz_limit 0.05
  EXPECT_EQ(census.unresolved + census.unlisted, 0);

  const StateScale scale{Model(p)};
  int equal = 0;
  for (std::size_t i = 0; i < census.labels.size(); ++i) {
    const bool ok = same(identity(census, i), identity(reference, i), scale);
    equal += ok ? 1 : 0;
    EXPECT_TRUE(ok) << "initial state " << i << ": census " << identity(census, i).kind << ", brute force "
                    << identity(reference, i).kind;
  }
  std::printf("labels equal to brute force: %d/%d; census %ld periods in %.3f s, brute force %ld periods in %.3f s\n",
              equal, o.initial_conditions, census.periods, census.wall_s, reference.periods, reference.wall_s);

  double total = 0.0;
  for (const Attractor& a : census.attractors) {
    total += a.fraction;
    EXPECT_DOUBLE_EQ(a.fraction, static_cast<double>(a.count) / o.initial_conditions);
    EXPECT_DOUBLE_EQ(a.fraction_stderr, std::sqrt(a.fraction * (1.0 - a.fraction) / o.initial_conditions));
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(census.soft_fraction, census.attractors[0].fraction);
}

// A seed state (census_point's seeds) is followed first and does not count: at Table 2, the rest
// state alone (K = 1) reaches the soft (1,1); seeded with a state of the (3,3) that a K = 16 census
// finds, the census lists that same (3,3) orbit too, with count 0, and the (1,1)'s fraction stays 1.
TEST(Census, ASeedStateAddsItsAttractorWithFractionZero) {
  const Parameters p = table2();
  const PointOptions options;
  CensusOptions o;
  o.initial_conditions = 16;
  o.seed = 7;
  const CensusSummary wide = census_point(p, options, o);
  ASSERT_EQ(wide.attractors.size(), 2u);
  const Attractor& three = wide.attractors[0].regime.n == 3 ? wide.attractors[0] : wide.attractors[1];
  ASSERT_EQ(three.regime.label(), "(3,3)");

  o.initial_conditions = 1;
  const CensusSummary rest = census_point(p, options, o);
  ASSERT_EQ(rest.attractors.size(), 1u);
  EXPECT_EQ(rest.attractors[0].regime.label(), "(1,1)");
  EXPECT_EQ(rest.seeds, 0);

  const CensusSummary seeded = census_point(p, options, o, {three.strobe[1]});
  ASSERT_EQ(seeded.status, SolveStatus::ok) << seeded.message;
  EXPECT_EQ(seeded.seeds, 1);
  ASSERT_EQ(seeded.attractors.size(), 2u);
  EXPECT_EQ(seeded.attractors[0].regime.label(), "(1,1)");
  EXPECT_EQ(seeded.attractors[0].count, 1);
  EXPECT_EQ(seeded.attractors[0].fraction, 1.0);
  EXPECT_TRUE(seeded.attractors[0].from_rest);
  EXPECT_EQ(seeded.attractors[1].count, 0);
  EXPECT_EQ(seeded.attractors[1].fraction, 0.0);
  EXPECT_TRUE(same_attractor(p, options, seeded.attractors[1], three));
  EXPECT_EQ(seeded.soft_fraction, 1.0);
  EXPECT_EQ(seeded.basin_entropy, 0.0);
}

TEST(CensusFollower, OrbitStatesAreDecidedEarlyAndAttractorsFoundApartAreMatched) {
  const Parameters p = table2();
  const PointOptions options;
  CensusOptions o;
  o.initial_conditions = 8;
  o.seed = 7;
  const CensusSummary census = census_point(p, options, o);
  ASSERT_EQ(census.attractors.size(), 2u);
  const Attractor& soft = census.attractors[0];   // (1,1)
  const Attractor& three = census.attractors[1];  // (3,3)
  ASSERT_EQ(three.strobe.size(), 3u);

  // A follower that has seen both attractors decides a state on the (3,3) cycle at once.
  CensusFollower follower(p, options, o);
  for (const Eigen::Vector4d& x0 : census_initial_conditions(p, o)) follower.follow(x0);
  ASSERT_EQ(follower.size(), 2u);
  const CensusFollower::Outcome on_cycle = follower.follow(three.strobe[1]);
  ASSERT_GE(on_cycle.label, 0);
  EXPECT_TRUE(on_cycle.early);
  EXPECT_LE(on_cycle.periods, 3 * 2 + 1);  // its offsets are ~0 from the first cycle on
  EXPECT_TRUE(same_attractor(p, options, follower.attractor(static_cast<std::size_t>(on_cycle.label)), three));

  // The same orbit up to a cyclic shift is the same attractor; another orbit or a perturbed one is not.
  Attractor shifted = three;
  std::rotate(shifted.strobe.begin(), shifted.strobe.begin() + 1, shifted.strobe.end());
  EXPECT_TRUE(same_attractor(p, options, three, shifted));
  EXPECT_FALSE(same_attractor(p, options, three, soft));
  Attractor moved = three;
  moved.strobe[2][0] += 1e-3 * StateScale(Model(p)).length();
  EXPECT_FALSE(same_attractor(p, options, three, moved));
  CensusOptions bad;
  bad.initial_conditions = 0;
  EXPECT_THROW(CensusFollower(p, options, bad), std::invalid_argument);
}

// A chaotic saddle: at m2 = 275.2 kg, omega2 = 4.2607 rad/s (Table 2's moduli) states wander
// on a chaotic set for up to ~1400 periods before most settle on (1,1). The census, which by
// default decides a state non-periodic only at the budget's end, must give a (1,1) fraction
// within 3 standard errors of brute force's (the same budget). With decide_by_recurrence
// (Attractors.jl's rule: 100 recurrences on a known set decide) it integrates fewer periods but
// calls states non-periodic that brute force sees settle on (1,1): the reason the rule is off
// by default (measured: 30 of 48 on (1,1) against brute force's 40). (Labels are not compared
// one by one: on a chaotic transient the outcome depends on the integration tolerance, and
// states are followed at census.rtol.)
TEST(Census, AChaoticSaddleIsNotTakenForANonPeriodicAttractor) {
  Parameters p = table2();
  p.m2 = 275.2;
  p.spring2 = {Spring::Form::frequency, 4.2607};
  const PointOptions options;
  CensusOptions o;
  o.initial_conditions = 48;
  o.seed = 2;
  const CensusSummary census = census_point(p, options, o);
  CensusOptions brute = o;
  brute.early_stop = false;
  const CensusSummary reference = census_point(p, options, brute);
  const auto periodic11 = [](const CensusSummary& s) {
    for (const Attractor& a : s.attractors)
      if (a.regime.label() == "(1,1)") return a.fraction;
    return 0.0;
  };
  const double p_ref = periodic11(reference);
  EXPECT_GT(p_ref, 0.8);
  const double stderr_ref = std::sqrt(p_ref * (1.0 - p_ref) / o.initial_conditions);
  EXPECT_NEAR(periodic11(census), p_ref, 3.0 * std::max(stderr_ref, 1.0 / o.initial_conditions));
  std::printf("(1,1) fraction: census %.4f, brute force %.4f +- %.4f\n", periodic11(census), p_ref, stderr_ref);
  // Brute force settles most states on (1,1): whatever non-periodic set the census lists here,
  // states were seen to leave it.
  for (const Attractor& a : census.attractors) {
    if (a.periodic) continue;
    EXPECT_TRUE(a.transient) << a.regime.label() << " fraction " << a.fraction;
  }
  CensusOptions eager = o;
  eager.decide_by_recurrence = true;
  const CensusSummary fast = census_point(p, options, eager);
  std::printf("decide_by_recurrence: (1,1) fraction %.4f in %ld periods (default: %ld)\n", periodic11(fast),
              fast.periods, census.periods);
  EXPECT_LT(fast.periods, census.periods);
  EXPECT_LT(periodic11(fast), p_ref - 3.0 * stderr_ref);
}

// A long-lived chaotic saddle of the demo map (cell E1 index 19, E2 index 11 of
// jobs/demo/e1_e2.toml): about half the states are still on a non-periodic set after
// analysis.max_periods = 2000, some seen to leave it after 100 periods on it. The census flags
// it transient, and the reference for that flag is the same census with 4x the budget: the
// set then holds a smaller fraction (measured with K = 128: 0.47 at 2000 periods, 0.25 at
// 8000), while the periodic attractors' fractions do not fall.
TEST(Census, ASetStatesLeaveIsFlaggedTransientAndHoldsLessWithALongerBudget) {
  Parameters p = table2();
  const auto demo_axis = [](int i, int last) {
    return std::pow(10.0, std::log10(2e4) + i * (std::log10(2.1e11) - std::log10(2e4)) / last);
  };
  p.E1 = demo_axis(19, 22);
  p.E2 = demo_axis(11, 21);
  PointOptions options;
  CensusOptions o;
  o.initial_conditions = 128;
  o.max_transient_periods = 0;  // the budget's cut alone (the follow past it: TransientChaos... below)
  const auto non_periodic = [](const CensusSummary& s) {
    double f = 0.0;
    bool transient = false;
    for (const Attractor& a : s.attractors)
      if (!a.periodic) {
        f += a.fraction;
        transient = transient || a.transient;
      }
    return std::make_pair(f, transient);
  };
  const CensusSummary at2000 = census_point(p, options, o);
  options.analysis.max_periods = 8000;
  const CensusSummary at8000 = census_point(p, options, o);
  const auto [f2000, flagged] = non_periodic(at2000);
  const auto [f8000, flagged8000] = non_periodic(at8000);
  std::printf("non-periodic fraction: %.4f after 2000 periods (transient %d), %.4f after 8000\n", f2000, flagged,
              f8000);
  EXPECT_TRUE(flagged);
  EXPECT_GT(f2000, 0.25);
  EXPECT_LT(f8000, f2000 - 8.0 / o.initial_conditions);  // at least eight states fewer
  for (const Attractor& a : at2000.attractors) {
    if (!a.periodic) continue;
    EXPECT_FALSE(a.transient);
    for (const Attractor& b : at8000.attractors) {
      if (!same_attractor(p, options, a, b)) continue;
      EXPECT_GE(b.count, a.count) << a.regime.label();
    }
  }
}

// Transient chaos resolved to the census's precision: at m2 275.2 kg, omega2 4.2607 rad/s
// (Table 2's moduli) some states wander on a chaotic saddle past analysis.max_periods = 2000.
// The default census follows those on (census.max_transient_periods) and then agrees with a
// brute-force census at a 10,000-period budget within 3 standard errors, rest included; the
// saddle's escape rate comes from the states that left it.
TEST(Census, TransientChaosIsFollowedPastTheBudgetAsBruteForceWithALongerOne) {
  Parameters p = table2();
  p.m2 = 275.2;
  p.spring2 = {Spring::Form::frequency, 4.2607};
  const PointOptions options;
  CensusOptions o;  // K = 32: two states are still on the saddle at the budget, more than sqrt(K)/4
  const CensusSummary census = census_point(p, options, o);
  CensusOptions cut = o;
  cut.max_transient_periods = 0;
  const CensusSummary at_budget = census_point(p, options, cut);
  CensusOptions brute = o;
  brute.early_stop = false;
  PointOptions long_budget = options;
  long_budget.analysis.max_periods = 10'000;
  const CensusSummary reference = census_point(p, long_budget, brute);
  ASSERT_EQ(census.status, SolveStatus::ok);
  ASSERT_EQ(reference.status, SolveStatus::ok);
  EXPECT_GT(census.transient_periods, 0);
  EXPECT_EQ(at_budget.transient_periods, 0);
  const auto fraction = [](const CensusSummary& s, const std::string& label) {
    double f = 0.0;
    for (const Attractor& a : s.attractors)
      if (a.regime.label() == label) f += a.fraction;
    return f;
  };
  const auto rest_label = [](const CensusSummary& s) {
    for (const Attractor& a : s.attractors)
      if (a.from_rest) return a.regime.label();
    return std::string("undecided");
  };
  const double K = o.initial_conditions;
  for (const std::string label : {"(1,1)", "non-periodic"}) {
    const double f_ref = fraction(reference, label);
    const double sigma = std::max(std::sqrt(f_ref * (1.0 - f_ref) / K), 1.0 / K);
    std::printf("%s: census %.4f (at the budget %.4f), brute force at 10000 periods %.4f +- %.4f\n", label.c_str(),
                fraction(census, label), fraction(at_budget, label), f_ref, sigma);
    EXPECT_NEAR(fraction(census, label), f_ref, 3.0 * sigma) << label;
  }
  EXPECT_LT(fraction(census, "non-periodic"), fraction(at_budget, "non-periodic"));
  EXPECT_EQ(rest_label(census), rest_label(reference));
  EXPECT_LE(census.transient_states, std::sqrt(K) / 4.0);
  for (const Attractor& a : census.attractors) {
    if (a.periodic || a.escape_exposure == 0) continue;
    EXPECT_TRUE(a.transient);
    EXPECT_NEAR(a.escape_rate, static_cast<double>(a.escapes) / static_cast<double>(a.escape_exposure), 1e-15);
  }
}

// The stop rule of the follow past the budget: go on while more than sqrt(K)/4 states remain.
TEST(Census, StatesFollowOnWhileMoreThanAQuarterOfRootKRemain) {
  using List = std::vector<std::size_t>;
  EXPECT_EQ(states_to_follow_on({3, 5, 9}, 64), (List{3, 5, 9}));  // sqrt(64)/4 = 2: three go on
  EXPECT_EQ(states_to_follow_on({3, 5}, 64), List{});                // two are few enough
  EXPECT_EQ(states_to_follow_on({4, 7}, 16), (List{4, 7}));          // sqrt(16)/4 = 1
  EXPECT_EQ(states_to_follow_on({4}, 16), List{});
  EXPECT_EQ(states_to_follow_on({0}, 1), List{0});                   // K = 1: any state left goes on
  EXPECT_EQ(states_to_follow_on({}, 256), List{});
}

}  // namespace
}  // namespace vibromap
