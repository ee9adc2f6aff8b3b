// The numeric options of [census], [optimise] and [sweep] in the key table: see
// include/vibromap/core/model/keys.hpp. Their ranges are declared here once: io/scene reads the
// options by these rows, and the core's validate() of CensusOptions, OptimiseOptions and
// LocalOptions checks them by the same rows.

#include <stdexcept>

#include "vibromap/core/model/keys.hpp"
#include "vibromap/core/refine/refine.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap {
namespace {

using B = Bounds;

KeyInfo option(std::string_view s, std::string_view k, KeyType type, Bounds b, std::string_view unit,
               std::string_view meaning) {
  return KeyInfo{s, k, type, b, {}, unit, meaning};
}

void add_census_options(std::vector<KeyInfo>& rows) {
  constexpr std::string_view s = "census";
  rows.push_back(option(s, "initial_conditions", KeyType::integer, B::between(1, 1e6), "-",
                        "initial states followed, the rest state (initial condition 0) included"));
  rows.push_back(option(s, "seed", KeyType::integer, B::between(0, 9e15), "-",
                        "seed of the uniform draws in the box (a draw with x1 - x2 > 0 is drawn again)"));
  rows.push_back(option(s, "max_attractors", KeyType::integer, B::between(1, 64), "-",
                        "attractors listed, most visited first; states reaching others are counted as unlisted"));
  rows.push_back(option(s, "recurrences", KeyType::integer, B::between(2, 1e5), "-",
                        "stroboscopic points in a row on a known non-periodic attractor's cells: a stay on it (a "
                        "state that stays, then leaves, flags the attractor transient)"));
  rows.push_back(option(s, "max_transient_periods", KeyType::integer, B::between(0, 1e8), "-",
                        "transient chaos: a state the budget leaves on a non-periodic set that states were seen "
                        "to leave is followed on in rounds of analysis.max_periods, until at most sqrt(K)/4 "
                        "such states (and not rest) remain, up to this many periods in all; 0: not at all"));
  rows.push_back(option(s, "cell", KeyType::real, B::between(1e-6, 1e3), "-",
                        "cell of the non-periodic recurrence grid, in motion scales (L, omega L)"));
  rows.push_back(option(s, "rtol", KeyType::real, B::between(1e-14, 1e-3), "-",
                        "tolerance initial states are followed at (orbits are refined at [solver] rtol); the "
                        "scene's when looser"));
  rows.push_back(option(s, "shock_directions", KeyType::integer, B::between(1, 1e6), "-",
                        "shock: random directions whose rays are scanned and bisected before the compass search"));
  rows.push_back(option(s, "shock_tolerance", KeyType::real, B::between(1e-8, 0.1), "-",
                        "shock: relative tolerance on the shock's size (each ray's bisection; the compass search "
                        "stops when its turn falls below this many rad)"));
  rows.push_back(option(s, "shock_max_radius", KeyType::real, B::between(0.0, 1e3, true, false), "-",
                        "shock: largest shock looked for, in motion scales (L, omega L); a ray that leads nowhere "
                        "else up to it gives none (2: the default box's half-diagonal)"));
  rows.push_back(option(s, "family_distance", KeyType::real, B::between(0.0, 10.0, true, false), "-",
                        "census maps: attractors of neighbouring cells whose period-start states lie closer than "
                        "this (symmetric Hausdorff distance, motion scales L, omega L) are one family"));
}

void add_optimise_options(std::vector<KeyInfo>& rows) {
  constexpr std::string_view s = "optimise";
  const auto real_option = [&](std::string_view k, Bounds b, std::string_view unit, std::string_view meaning) {
    rows.push_back(option(s, k, KeyType::real, b, unit, meaning));
  };
  const auto integer_option = [&](std::string_view k, Bounds b, std::string_view meaning) {
    rows.push_back(option(s, k, KeyType::integer, b, "-", meaning));
  };
  integer_option("impact", B::between(0, 1000), "max_T_con: which impact of the steady cycle, in time order (0: the first)");
  integer_option("seeds", B::between(1, 1e6),
                 "starts per algorithm: the best cells of the seeding map that keep the regime inside the box");
  real_option("xtol_rel", B::between(0.0, 1.0, true, true), "-",
              "stop when a step moves every scaled variable by less than this fraction of its box");
  real_option("ftol_rel", B::between(0.0, 1.0, false, true), "-",
              "stop when a step changes the objective by less than this, relative (0: off)");
  integer_option("max_evaluations", B::between(1, 1e9),
                 "point solves per start, finite-difference ones included (cache hits are free)");
  real_option("max_time", B::at_least(0), "s", "wall time per start; 0: no limit (a limit makes results depend on the machine)");
  real_option("initial_step", B::between(0.0, 1.0, true, false), "-",
              "first step, a fraction of the box (NLopt initial_step, BOBYQA's rhobeg)");
  real_option("fd_step", B::between(0.0, 0.1, true, false), "-",
              "finite-difference step of the gradients (slsqp, mma, gradient_projection), a fraction of the box");
  real_option("barrier", B::above(0), "-",
              "bobyqa, sbplx: the objective given for a point outside the kept regime (plus its violation; finite, as "
              "BOBYQA needs)");
  integer_option("best", B::between(1, 1000),
                 "best distinct points re-solved from scratch (integrate from rest and shooting) and reported");
  real_option("verify_rtol", B::between(0.0, 0.1, true, true), "-", "rtol of those re-solves");
  real_option("min_soft_fraction", B::between(0.0, 1.0), "-",
              "robust softness, a constraint: the point's soft attractors (stable, Hertz-valid, k_con <= [census] "
              "soft_kcon) must hold at least this basin fraction, by a census ([census] options) of each point that "
              "passes the other constraints (0.01-1 s a point); use with hertz_valid = true (a soft attractor is "
              "Hertz-valid); 0: off");
  integer_option("soft_check_initial_conditions", B::between(1, 1e6),
                 "min_soft_fraction: the best points' soft fraction is re-checked by a census of max(this, 4 [census] "
                 "initial_conditions) other initial states; a point below min_soft_fraction - 3 standard errors fails "
                 "the check and is reported after those that pass");
}

void add_sweep_options(std::vector<KeyInfo>& rows) {
  constexpr std::string_view s = "sweep";
  rows.push_back(option(s, "checkpoint_interval", KeyType::real, B::above(0), "s",
                        "seconds between checkpoints of the map file"));
  rows.push_back(option(s, "progress_interval", KeyType::real, B::above(0), "s",
                        "seconds between progress lines when stderr is not a terminal"));
  rows.push_back(option(s, "refine", KeyType::integer, B::between(0, kMaxRefineLevels), "-",
                        "levels of adaptive refinement: each halves every lin/log axis's spacing where a cell's corners "
                        "differ in refine_on ((n - 1) 2^L + 1 points per axis, categorical axes whole); 0: the uniform "
                        "map of the axes given"));
  rows.push_back(option(s, "refine_audit", KeyType::real, B::between(0, 1), "-",
                        "share of the inherited points solved again, drawn at random, to count how often inheritance "
                        "was wrong (with a 95 % upper bound)"));
}

}  // namespace

const std::vector<KeyInfo>& option_keys() {
  static const std::vector<KeyInfo> rows = [] {
    std::vector<KeyInfo> r;
    add_census_options(r);
    add_optimise_options(r);
    add_sweep_options(r);
    return r;
  }();
  return rows;
}

const KeyInfo& option_key(std::string_view full_name) {
  for (const KeyInfo& k : option_keys())
    if (k.full_name() == full_name) return k;
  throw std::logic_error(cat("option_key: no option ", full_name));
}

std::string check_option(std::string_view full_name, double v) {
  const KeyInfo& k = option_key(full_name);
  const std::string need = k.requirement(v);
  return need.empty() ? need : k.refusal(value_text(v), need);
}

}  // namespace vibromap
