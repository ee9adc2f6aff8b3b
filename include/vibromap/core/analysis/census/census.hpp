#pragma once
// A census of one parameter point: every attractor the motion can settle into, with the
// fraction of a box of initial states that goes to each (its basin fraction).
//
// Initial condition 0 is the rest state (Parameters::initial_state without [initial]); the
// others are drawn uniformly from a box of physical states (x1, x2, v1, v2), a draw with the
// bodies overlapping (x1 - x2 > 0) being drawn again. Each initial condition is integrated at
// the scene's tolerance, forcing period by forcing period, until it is decided:
//  - captured by a periodic attractor already found (the rule is in census.cpp, where it is
//    applied: the offset from the orbit follows the orbit's linearisation, which contracts);
//  - with decide_by_recurrence only: recurring on a non-periodic attractor already found
//    (Attractors.jl's rule: its stroboscopic points stay `recurrences` periods in a row in the
//    cells that attractor visits), unless states were seen to leave it (census.cpp says why
//    this is off by default);
//  - settled: its stroboscopic samples repeat (steady state); the orbit is refined by shooting;
//  - out of budget (analysis.max_periods): non-periodic when it does not settle, else
//    unresolved.
// Periodic attractors are also looked for by shooting from each undecided initial condition
// after 30, 90 and 270 periods (Newton on the stroboscopic map, as solve_point does, first at
// `rtol` and, when it lands on no known orbit, again at the scene's); a stable orbit found that
// way joins the list, and the initial condition goes on until it is captured.
// Two periodic orbits are the same attractor when they have the same period and the same
// stroboscopic points (up to a cyclic shift) within a tolerance far below their distance
// from any other orbit; an attractor's identity is its orbit, never its (n,k) label.

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/analysis/point/point_solver.hpp"

namespace vibromap {

struct CensusOptions {
  int initial_conditions = 32;  // K: initial states, the rest state included, -
  // The box of initial states, [lo, hi] each; unset: the rest state +- the motion's scale
  // (L = max(D, lambda F0 / k1) in positions, omega L in velocities).
  std::optional<std::array<double, 2>> x1, x2;  // m
  std::optional<std::array<double, 2>> v1, v2;  // m/s
  std::uint64_t seed = 1;       // seed of the draws, -
  int max_attractors = 8;       // attractors listed; initial states reaching others are counted as unlisted, -
  int recurrences = 100;        // stroboscopic points in a row on a non-periodic attractor's cells: a stay on it, -
  bool decide_by_recurrence = false;  // true: a stay on a known non-periodic attractor decides the state (Attractors.jl's
                                      // rule), unless states were seen to leave that set (census.cpp: why it is off)
  double cell = 0.25;           // cell size of the non-periodic recurrence grid, in motion scales, -
  double rtol = 1e-6;           // tolerance at which initial states are followed (orbits are refined at the
                                // scene's); the scene's when looser. Ignored without early_stop, -
  long max_transient_periods = 10000;  // a state on a leaking non-periodic set (transient chaos) is followed
                                       // past analysis.max_periods, in rounds of it, up to this many periods
                                       // in all (census.cpp: until few such states remain); 0: not at all, -
  bool early_stop = true;       // false: follow every initial state to its steady state at the scene's
                                // tolerance, with no capture, recurrence or Newton search (brute force, for checks)
  bool labels = false;          // keep each initial state and its attractor index in the summary
  // The minimal critical shock of each attractor (critical_shock.hpp), when `shock`.
  bool shock = false;           // look for each listed attractor's minimal critical shock
  std::array<bool, 4> shock_on = {true, true, true, true};  // coordinates the shock moves: x1, x2, v1, v2
  int shock_directions = 512;   // random directions of the search's first step, -
  double shock_tolerance = 1e-3;  // relative tolerance on the shock's size, -
  double shock_max_radius = 2.0;  // largest shock looked for, in motion scales (2: the default box's half-diagonal), -
  bool shock_optimise = true;   // false: the random directions alone, no compass search (for checks)
  bool shock_soft_only = false; // true: only soft attractors (is_soft) are searched, the others stay not_computed
  // Census maps (a sweep with [census]): attractors of neighbouring cells whose stroboscopic sets
  // lie closer than this (symmetric Hausdorff distance in motion scales) are one family
  // (core/analysis/census/families.hpp), -
  double family_distance = 3.0;
  // Census maps: each cell of a line along the map's last axis first follows, as extra initial
  // states, one period-start state of each periodic attractor of the cell before it on that line
  // (seed states, census_point's `seeds`): Attractors.jl's seeded continuation. Every line is
  // computed in order on one rank, so a cell's seeds do not depend on the rank count.
  bool seed_from_neighbour = false;
};

std::string validate(const CensusOptions& o);

// The box actually used for p: [lo, hi] for x1, x2, v1, v2.
std::array<std::array<double, 2>, 4> census_box(const Parameters& p, const CensusOptions& o);
// Empty when every side of that box has finite ends and a finite width, else the refusal of the
// key that made a side derived from the motion's scales overflow (derived_refusal, keys.hpp):
// "[forcing] F0 = 1e+308: makes the census box, the rest state +- L in positions and +- omega L
// in velocities (m, m/s), not finite; ...". A side the scene gives is checked by validate().
std::string census_box_error(const Parameters& p, const CensusOptions& o);
// Empty for an adaptive method, else the refusal of solver.method = "rk4": a census follows its
// initial states at an adaptive tolerance and finds its orbits by shooting, which rk4 offers neither.
std::string census_method_error(const IntegratorOptions& o);
// The K initial states (physical), the rest state first.
std::vector<Eigen::Vector4d> census_initial_conditions(const Parameters& p, const CensusOptions& o);

// What a shock search found (critical_shock.hpp).
enum class ShockStatus {
  not_computed,  // census.shock off, or not looked for
  found,         // a perturbation of `size` leads elsewhere
  none,          // no perturbation up to census.shock_max_radius leads elsewhere
  not_periodic,  // a non-periodic attractor: no period-start states to perturb
  failed,        // the attractor's own state was not decided as itself
};
std::string to_string(ShockStatus s);

// Index a shock leads to when that attractor is not in the census's list.
constexpr int kShockToUnlisted = -2;

// The minimal critical shock of one attractor (docs/model.md): x_star + dx leads to attractor
// `to` of the census's list.
struct CriticalShock {
  ShockStatus status = ShockStatus::not_computed;
  double size = std::numeric_limits<double>::quiet_NaN();  // |dx| in motion scales (L, omega L), -
  Eigen::Vector4d dx = Eigen::Vector4d::Constant(std::numeric_limits<double>::quiet_NaN());  // m, m, m/s, m/s
  Eigen::Vector4d x_star = Eigen::Vector4d::Constant(std::numeric_limits<double>::quiet_NaN());  // the state perturbed
  int strobe_index = -1;        // which of the attractor's stroboscopic states is x_star
  int to = -1;                  // index into the census's attractors of where x_star + dx leads (verified by a
                                // fresh follower); kShockToUnlisted: an attractor the census does not list; -1: none
  Regime to_regime;             // that attractor's regime (unresolved when the verification did not decide)
  bool verified = false;        // the fresh follow of x_star + dx ends on a decided attractor other than this one
  double random_size = std::numeric_limits<double>::quiet_NaN();  // the best of the random directions alone, -
  long follows = 0;             // states followed by the search (the verification included)
  int unresolved = 0;           // of those, undecided (counted as not leading elsewhere)
  double wall_s = 0.0;
};

struct Attractor {
  bool periodic = true;         // false: a non-periodic (or chatter) attractor, told by recurrence
  Regime regime;                // (n,k), no contact, chatter, permanent contact or non-periodic
  double T_con = 0.0;           // longest impact of the cycle (non-periodic: of the recurrent window), s
  double k_con = 0.0;           // T / T_con, -
  double F_max = 0.0;           // largest peak contact force, N
  double z_ratio = 0.0;         // largest z_max / R*, -
  double z_max = 0.0;           // largest peak penetration, m
  double v_in = 0.0;            // entry velocity of the longest impact, m/s
  double impulse = 0.0;         // impulse of the longest impact, N s
  bool hertz_valid = true;
  double max_floquet = 0.0;     // largest |Floquet multiplier| (NaN when not computed)
  int stable = -1;              // 1 stable, 0 unstable, -1 unknown
  int count = 0;                // initial states that reach it
  double fraction = 0.0;        // count / K
  double fraction_stderr = 0.0; // sqrt(p (1 - p) / K)
  bool from_rest = false;       // the rest state reaches it
  std::vector<Eigen::Vector4d> strobe;  // periodic: the n stroboscopic states (x1, x2, v1, v2) at period starts
  bool soft = false;            // is_soft (regime.hpp): periodic with impacts, stable, Hertz-valid, k_con <= analysis.soft_kcon
  double escape_rate = std::numeric_limits<double>::quiet_NaN();  // transient: states' exits per period followed
                                // past the budget (1 / mean lifetime); NaN when none was followed on
  long escape_exposure = 0;     // the periods followed past the budget from this set
  int escapes = 0;              // the states that left it then
  bool transient = false;       // non-periodic: a state seen `recurrences` periods in a row on it left it
                                // later for another attractor. A chaotic saddle (transient chaos): its
                                // fraction is the share still on it at the budget's end, and falls as
                                // analysis.max_periods grows
  CriticalShock shock;          // with census.shock (critical_shock.hpp)
};

// Labels of initial states that reach no listed attractor.
constexpr int kUnresolvedLabel = -1;  // the budget ran out while the motion was still settling, or it failed
constexpr int kUnlistedLabel = -2;    // an attractor beyond max_attractors

struct CensusSummary {
  SolveStatus status = SolveStatus::ok;
  std::string message;
  double T = 0.0;                      // forcing period, s
  std::vector<Attractor> attractors;   // by basin fraction (discovery order on ties), at most
                                       // max_attractors; the one rest reaches is always listed
  int K = 0;
  int unresolved = 0;                  // initial states labelled kUnresolvedLabel
  int unlisted = 0;                    // initial states labelled kUnlistedLabel
  double soft_fraction = 0.0;          // sum of the fractions of soft attractors (is_soft, regime.hpp)
  double basin_entropy = 0.0;          // -sum f ln f over the outcomes' shares (listed attractors, unresolved,
                                       // unlisted), nats: basin_entropy.hpp's S_b with the box as one box
  int decided_early = 0;               // initial states decided by capture or recurrence
  int seeds = 0;                       // seed states followed before the K (census_point's seeds)
  std::vector<Eigen::Vector4d> initial_conditions;  // with CensusOptions::labels
  std::vector<int> labels;                          // with CensusOptions::labels: index into attractors
  long periods = 0;                    // forcing periods integrated for all initial states
  int budget_states = 0;               // initial states followed to the end of the budget (undecided)
  long budget_periods = 0;             // the periods those took: what early decisions cannot save
  long transient_periods = 0;          // periods spent following states on leaking sets past analysis.max_periods
  int transient_states = 0;            // states still on a leaking non-periodic set, or still settling, at the end
  IntegrationCounters counters;       // one process's (census_point); empty from several ranks
  double wall_s = 0.0;
  int ranks = 1;                       // MPI ranks the initial states were shared out over
};

// seeds: physical states followed before the K initial states (a neighbouring cell's attractors,
// CensusOptions::seed_from_neighbour). They do not count in the fractions: an attractor only
// seeds reach is listed (after those the K states reach, room allowing) with count 0.
CensusSummary census_point(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                           const std::vector<Eigen::Vector4d>& seeds = {});
// What census_point reports as invalid input: the point, its options or the census options
// failing validation, the census box not finite (census_box_error), or rk4 (census_method_error); empty when they pass. The box is checked by drawing the states:
// census_initial_conditions then gives fewer than K, and kCensusBoxOverlaps says why.
std::string census_input_error(const Parameters& p, const PointOptions& options, const CensusOptions& census);
inline constexpr const char* kCensusBoxOverlaps =
    "the census box holds (almost) no state with the bodies apart (x1 - x2 <= 0)";

// Follows initial states one at a time to their attractors, keeping every attractor it finds so
// that later states are decided early against them (census_point runs one over its K states;
// `vibromap basins` keeps one per MPI rank over the pixels it is given). Not thread-safe.
class CensusFollower {
 public:
  // Throws std::invalid_argument when p, options or census do not validate (or use rk4).
  CensusFollower(const Parameters& p, const PointOptions& options, const CensusOptions& census);
  ~CensusFollower();
  CensusFollower(CensusFollower&&) noexcept;
  CensusFollower& operator=(CensusFollower&&) noexcept;

  struct Outcome {
    int label = kUnresolvedLabel;  // index into attractor(), kUnresolvedLabel or kUnlistedLabel
    bool early = false;            // decided by capture or recurrence
    long periods = 0;              // forcing periods integrated
    bool budget = false;           // followed to the end of its budget without a decision
    bool failed = false;           // the integration failed
    Eigen::Vector4d end_state = Eigen::Vector4d::Zero();  // physical state where it was left (budget: to go on from)
  };
  // x0: physical state (x1, x2, v1, v2). Unlisted here means no room for another attractor
  // (4 max_attractors kept); count, fraction, from_rest of the attractors are not filled in.
  Outcome follow(const Eigen::Vector4d& x0);
  // As follow, for `budget` periods (a later round of a state left on a leaking set); `exact`:
  // at the scene's tolerance ([solver] rtol, brute force's path) rather than census.rtol.
  Outcome follow(const Eigen::Vector4d& x0, long budget, bool exact = false);
  std::size_t size() const;
  const Attractor& attractor(std::size_t i) const;
  const IntegrationCounters& counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The follow past the budget (transient chaos; census.cpp says the rule), shared by the census of
// one process and the census on MPI ranks (rank 0, once every rank is done). states: per initial
// state (rest first) its last outcome, label indexing the caller's attractor list; updated in
// place. periodic(label): whether that attractor is periodic. follow(k, x0, budget, exact): state
// k followed from x0 (exact: at the scene's tolerance), its label in the caller's list.
struct PastBudget {
  long periods = 0;            // forcing periods integrated (rest's repeated ones included)
  long transient_periods = 0;  // of those, past analysis.max_periods
  long budget_periods = 0;     // periods of the follows that ended at their budget undecided
  int transient_states = 0;    // states still on a leaking set, or settling, at the end
  std::vector<long> exposure;  // by label: periods followed on from that set
  std::vector<int> exits;      // by label: states that left it then
};
using FollowOn = std::function<CensusFollower::Outcome(std::size_t k, const Eigen::Vector4d& x0, long budget, bool exact)>;
PastBudget follow_past_budget(std::vector<CensusFollower::Outcome>& states, const Eigen::Vector4d& rest, long round,
                              long cap, const std::function<bool(int)>& periodic, const FollowOn& follow);
// Attractor `label`'s escape figures from p (rate, exposure, exits; transient when a state left it).
void record_escape(Attractor& a, const PastBudget& p, std::size_t label);

// The follow past the budget (transient chaos, census.cpp): which of a census's K states go on
// for another round of analysis.max_periods. pending: the states the last round left on a
// leaking non-periodic set or still settling whose periods so far leave room for a round under
// census.max_transient_periods (rest is followed apart). They all go on while more than
// sqrt(K)/4 remain; then none (an empty list).
std::vector<std::size_t> states_to_follow_on(std::vector<std::size_t> pending, std::size_t K);

// Whether two attractors of the point (p, options) found apart (other ranks, other runs) are the
// same one: periodic ones of the same period whose stroboscopic states agree up to a cyclic shift
// within the census's orbit tolerance (scaled distance max(1e-6, 1000 Newton tolerances)); two
// non-periodic ones when they have the same regime kind (their recurrence sets are not compared).
bool same_attractor(const Parameters& p, const PointOptions& options, const Attractor& a, const Attractor& b);

// Census results gathered from several followers (MPI ranks: `vibromap basins`, `run --census`
// on several ranks).
// The index of `a`, which reached item `item` (a pixel, an initial state), in `list`: an
// attractor there when it is the same one (same_attractor; its transient flag then takes a's
// too), else `a` appended with count 0. first[g]: the least item seen reaching list[g].
std::size_t match_attractor(const Parameters& p, const PointOptions& options, std::vector<Attractor>& list,
                            std::vector<std::int64_t>& first, const Attractor& a, std::int64_t item);
// The record of attractor `a` as a fresh follower finds it from x0 (physical), so that it does
// not depend on which rank found the orbit first (its refined digits, the cyclic shift of its
// stroboscopic states); `a` when the follower finds another attractor or fails. Keeps a's count
// and transient flag.
Attractor canonical_record(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                           const Eigen::Vector4d& x0, const Attractor& a);
// A census's attractor list from the label of each initial state (`labels`: indices into
// `found`, or kUnresolvedLabel / kUnlistedLabel; labels[0] is the rest state's): attractors by
// how many states reach them (first found on ties), at most max_attractors, the one rest reaches
// always among them, with count, fraction, stderr and from_rest; `labels` renumbered to the
// list. Sets s.attractors, s.unresolved, s.unlisted, s.soft_fraction and s.basin_entropy from s.K.
void list_attractors(CensusSummary& s, const std::vector<Attractor>& found, std::vector<int>& labels,
                     int max_attractors);

}  // namespace vibromap
