#include "vibromap/core/model/keys.hpp"
#include "vibromap/core/analysis/census/census.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "attractor_set.hpp"
#include "vibromap/core/analysis/census/basin_entropy.hpp"
#include "vibromap/core/analysis/census/critical_shock.hpp"
#include "vibromap/core/analysis/point/steady_state.hpp"

namespace vibromap {

using census_detail::AttractorSet;
using census_detail::Offsets;

std::string validate(const CensusOptions& o) {
  const std::pair<std::string_view, double> numbers[] = {
      {"census.initial_conditions", o.initial_conditions}, {"census.seed", static_cast<double>(o.seed)},
      {"census.max_attractors", o.max_attractors},           {"census.recurrences", o.recurrences},
      {"census.max_transient_periods", static_cast<double>(o.max_transient_periods)},
      {"census.cell", o.cell},                               {"census.rtol", o.rtol},
      {"census.shock_directions", o.shock_directions},       {"census.shock_tolerance", o.shock_tolerance},
      {"census.shock_max_radius", o.shock_max_radius},
      {"census.family_distance", o.family_distance}};
  for (const auto& [name, v] : numbers)
    if (std::string r = check_option(name, v); !r.empty()) return r;
  const std::pair<const char*, const std::optional<std::array<double, 2>>*> sides[] = {
      {"x1", &o.x1}, {"x2", &o.x2}, {"v1", &o.v1}, {"v2", &o.v2}};
  for (const auto& [name, side] : sides)
    if (*side && !((**side)[0] <= (**side)[1] && std::isfinite((**side)[1] - (**side)[0])))
      return std::string(name) + " must be [lo, hi] with finite lo <= hi and a finite hi - lo";
  if (std::none_of(o.shock_on.begin(), o.shock_on.end(), [](bool on) { return on; }))
    return "shock_on must name at least one of \"x1\", \"x2\", \"v1\", \"v2\"";
  return {};
}

std::array<std::array<double, 2>, 4> census_box(const Parameters& p, const CensusOptions& o) {
  const StateScale scale{Model(p)};
  Parameters at_rest = p;
  at_rest.initial.reset();
  const Eigen::Vector4d rest = at_rest.initial_state();
  const double half[4] = {scale.length(), scale.length(), scale.speed(), scale.speed()};
  const std::optional<std::array<double, 2>>* given[4] = {&o.x1, &o.x2, &o.v1, &o.v2};
  std::array<std::array<double, 2>, 4> box{};
  for (int i = 0; i < 4; ++i)
    box[static_cast<std::size_t>(i)] = *given[i] ? **given[i] : std::array<double, 2>{rest[i] - half[i], rest[i] + half[i]};
  return box;
}

std::string census_box_error(const Parameters& p, const CensusOptions& o) {
  const std::optional<std::array<double, 2>>* given[4] = {&o.x1, &o.x2, &o.v1, &o.v2};
  const auto finite = [&](const Parameters& q) {
    const auto box = census_box(q, o);
    for (std::size_t i = 0; i < 4; ++i)
      if (!*given[i] && !(std::isfinite(box[i][0]) && std::isfinite(box[i][1]) && std::isfinite(box[i][1] - box[i][0])))
        return false;
    return true;
  };
  return derived_refusal(p,
                         {"forcing.omega", "system.D", "forcing.lambda", "forcing.F0", "system.m1", "system.k1",
                          "system.omega1"},
                         "the census box, the rest state +- L in positions and +- omega L in velocities (m, m/s),",
                         finite);
}

namespace {

constexpr int kMaxDraws = 10'000;  // draws per initial state before the box is called all overlap

}  // namespace

std::vector<Eigen::Vector4d> census_initial_conditions(const Parameters& p, const CensusOptions& o) {
  Parameters at_rest = p;
  at_rest.initial.reset();
  std::vector<Eigen::Vector4d> out{at_rest.initial_state()};
  const auto box = census_box(p, o);
  census_detail::SplitMix64 draws(o.seed);
  while (static_cast<int>(out.size()) < o.initial_conditions) {
    Eigen::Vector4d x;
    int tries = 0;
    do {
      if (++tries > kMaxDraws) return out;  // census_point reports the box
      for (int i = 0; i < 4; ++i) {
        const auto& side = box[static_cast<std::size_t>(i)];
        x[i] = side[0] + (side[1] - side[0]) * draws.uniform();
      }
    } while (x[0] - x[1] > 0.0);
    out.push_back(x);
  }
  return out;
}

namespace {

// Newton searches for new orbits from a state not yet decided: after 30, 90 and 270 periods,
// for the period its samples suggest most: earlier searches and more candidate periods cost
// more than the orbits they find earlier. A state that already closes in on a known orbit is not
// searched from.
constexpr long kFirstDiscovery = 30;
constexpr long kLastDiscovery = 270;
constexpr double kApproaching = 16.0;  // V within this many capture levels: no Newton search
constexpr int kCandidates = 1;

// Reads the state at several phases of every forcing period from the integrator's steps.
class PhaseSampler final : public Observer {
 public:
  void set_phases(std::vector<double> phases) {
    phases_ = std::move(phases);
    states_.assign(phases_.size(), State::Zero());
  }
  void on_step(const StepView& step) override {
    for (std::size_t k = 0; k < phases_.size(); ++k)
      if (phases_[k] > 0.0 && step.tau0 < phases_[k] && phases_[k] <= step.tau1) states_[k] = step.eval(phases_[k]);
  }
  bool on_period_end(long /*period*/, const State& u) override {
    for (std::size_t k = 0; k < phases_.size(); ++k)
      if (phases_[k] == 0.0) states_[k] = u;
    return false;
  }
  bool sampled(std::size_t k) const { return phases_[k] >= 0.0; }  // false for NaN
  const State& state(std::size_t k) const { return states_[k]; }

 private:
  std::vector<double> phases_;
  std::vector<State> states_;
};

using Followed = CensusFollower::Outcome;

// One initial state followed to its attractor (census.hpp says how it is decided), for at most
// `budget` forcing periods (analysis.max_periods, or a round of the follow past it); `exact`:
// integrated at the scene's tolerance (brute force's path) rather than census.rtol. The state of
// the follow and its named steps; run() is the driver.
class StateFollow {
 public:
  StateFollow(AttractorSet& set, const PointOptions& o, const CensusOptions& c, const Eigen::Vector4d& x0, long budget,
              bool exact, IntegrationCounters& work);
  Followed run();

 private:
  void track_attractors();  // the per-attractor records grown to the attractors found so far
  void remember(const State& u);  // the sample kept for describing a non-periodic attractor
  std::optional<std::size_t> decided_early();  // captured by an orbit, or staying on a set
  Followed settle(long j);                     // settled: the orbit it settled on (Newton)
  void search_orbits(long j);                  // Newton searches for new orbits from here
  Followed failed(long j);                     // the integration failed: unresolved
  Followed at_budget_end();                    // still settling, or on a non-periodic set
  Followed done(std::optional<std::size_t> index, bool early, long periods);

  AttractorSet& set_;
  const PointOptions& o_;
  const CensusOptions& c_;
  long budget_;
  IntegrationCounters& work_;
  const Model& model_;
  const PointOptions& follow_options_;
  std::unique_ptr<Integrator> integ_;
  State u_;
  ImpactRecorder impacts_;
  // Deciding a state needs its impacts' times only (the Newton section); the peaks, forces and
  // impulses describe a non-periodic attractor from the budget's last n_max periods, so they
  // are measured from the period before those on (an impact begun earlier is not used).
  long measure_from_;
  SteadyStateDetector steady_;
  PhaseSampler sampler_;
  ObserverList observers_;
  std::vector<Offsets> offsets_;
  std::vector<int> in_row_;
  std::deque<State> recent_;  // stroboscopic samples that describe a non-periodic attractor
  std::size_t window_;
  std::size_t known_ = static_cast<std::size_t>(-1);
  long discovery_ = kFirstDiscovery;
  Followed f_;
  std::vector<int> longest_;  // per attractor: the longest run of recurrences on it (non-periodic ones)
};

StateFollow::StateFollow(AttractorSet& set, const PointOptions& o, const CensusOptions& c, const Eigen::Vector4d& x0,
                         long budget, bool exact, IntegrationCounters& work)
    : set_(set),
      o_(o),
      c_(c),
      budget_(budget),
      work_(work),
      model_(set.model()),
      follow_options_(exact ? o : set.follow_options()),
      integ_(make_integrator(model_, follow_options_.integrator)),
      u_(Model::to_internal(x0)),
      impacts_(model_, 2L * o.analysis.n_max + 2),
      measure_from_(budget - o.analysis.n_max - 1),
      steady_(model_, o.analysis.n_max, steady_tolerance(follow_options_)),
      observers_{&impacts_, &steady_, &sampler_},
      window_(2 * static_cast<std::size_t>(c.recurrences)) {
  integ_->reset(u_);
  impacts_.set_measuring(measure_from_ <= 0);
}

Followed StateFollow::run() {
  for (long j = 0; j < budget_; ++j) {
    track_attractors();
    if (j == measure_from_) impacts_.set_measuring(true);
    if (integ_->advance_period(u_, observers_) != IntegrationStatus::ok) return failed(j);
    const bool settled = observers_.on_period_end(j, u_);
    remember(u_);
    if (c_.early_stop)
      if (const std::optional<std::size_t> i = decided_early()) return done(*i, true, j + 1);
    if (settled) return settle(j);
    if (c_.early_stop && j + 1 == discovery_ && discovery_ <= kLastDiscovery && !set_.full()) search_orbits(j);
  }
  return at_budget_end();
}

void StateFollow::track_attractors() {
  if (set_.size() == known_) return;
  known_ = set_.size();
  sampler_.set_phases(set_.phases());
  offsets_.resize(known_);
  in_row_.resize(known_, 0);
  longest_.resize(known_, 0);
}

void StateFollow::remember(const State& u) {
  recent_.push_back(u);
  if (recent_.size() > window_) recent_.pop_front();
}

std::optional<std::size_t> StateFollow::decided_early() {
  const census_detail::Cell cell = set_.cell(u_);
  bool approaching = false;  // close to a stable orbit: no recurrence decision (below)
  for (std::size_t i = 0; i < known_; ++i) {
    if (!sampler_.sampled(i)) continue;
    offsets_[i].push_back(set_.offset(i, sampler_.state(i)));
    if (offsets_[i].size() > 2 * static_cast<std::size_t>(set_.record(i).strobe.size()) + 1) offsets_[i].pop_front();
    if (set_.captured(i, offsets_[i])) return i;
    approaching = approaching || set_.level_ratio(i, offsets_[i].back()) < kApproaching;
  }
  // Stays on a non-periodic set: `recurrences` stroboscopic points in a row in its cells. A
  // state that stays and then ends elsewhere flags the set transient (observe_stay). Such a
  // set is found by a state that ran out of budget without settling, and here it is often
  // a chaotic saddle that states leave after hundreds to thousands of periods, so a stay
  // does not decide a state unless census.decide_by_recurrence asks for it (Attractors.jl's
  // rule), and never on a set seen to leak. Measured: at m2 275.2 kg, omega2 4.2607 rad/s
  // (Table 2's moduli) brute force settles 90 % on (1,1) and deciding after 100 recurrences
  // called 52 % non-periodic; at the demo cell (20, 9), where no state was seen to leave in
  // time, a census that decided only after 8 states had stayed to the budget's end called
  // 20 of 32 states non-periodic against brute force's 7. Not deciding costs the demo map
  // 3 % more time: labels at the budget's end need the state followed there, as brute
  // force does. A state closing in on a stable orbit is that orbit's to decide: its run
  // starts again.
  for (std::size_t i = 0; i < known_; ++i) {
    if (sampler_.sampled(i) || set_.record(i).periodic) continue;
    in_row_[i] = !approaching && set_.visits(i, cell) ? in_row_[i] + 1 : 0;
    longest_[i] = std::max(longest_[i], in_row_[i]);
    if (in_row_[i] >= c_.recurrences && set_.recurrence_decides(i)) return i;
  }
  return std::nullopt;
}

Followed StateFollow::settle(long j) {
  const int n = steady_.period_n();
  const std::optional<State> y = set_.shoot_from(u_, n, impacts_.impacts(), impacts_.open_impact(), j, work_);
  return done(set_.add_periodic(y ? *y : u_, n, work_), false, j + 1);
}

void StateFollow::search_orbits(long j) {
  discovery_ *= 3;
  bool approaching = false;  // a state closing in on a known orbit needs no Newton search
  for (std::size_t i = 0; i < known_ && !approaching; ++i)
    approaching = !offsets_[i].empty() && set_.level_ratio(i, offsets_[i].back()) < kApproaching;
  if (approaching) return;
  for (int n : steady_.candidate_periods(kCandidates))
    if (set_.discover(u_, n, impacts_.impacts(), impacts_.open_impact(), j, work_)) break;
}

Followed StateFollow::failed(long j) {
  f_.periods = j;
  f_.failed = true;
  work_ += integ_->counters();
  return f_;  // unresolved: the integration failed
}

Followed StateFollow::at_budget_end() {
  const long last = budget_ - 1;
  f_.budget = true;
  if (steady_.still_converging()) {
    f_.periods = last + 1;
    f_.end_state = Model::to_physical(u_);
    work_ += integ_->counters();
    return f_;
  }
  const long first = last - std::min<long>(o_.analysis.n_max, last + 1) + 1;
  return done(set_.add_recurrent({recent_.begin(), recent_.end()}, impacts_.impacts(), first, last), false, last + 1);
}

Followed StateFollow::done(std::optional<std::size_t> index, bool early, long periods) {
  for (std::size_t i = 0; i < longest_.size(); ++i)
    if (longest_[i] >= c_.recurrences) set_.observe_stay(i, index);
  f_.label = index ? static_cast<int>(*index) : kUnlistedLabel;
  f_.early = early;
  f_.periods = periods;
  f_.end_state = Model::to_physical(u_);
  work_ += integ_->counters();
  return f_;
}

// One initial state followed to its attractor: see StateFollow.
Followed follow(AttractorSet& set, const PointOptions& o, const CensusOptions& c, const Eigen::Vector4d& x0,
                long budget, bool exact, IntegrationCounters& work) {
  StateFollow state(set, o, c, x0, budget, exact, work);
  return state.run();
}

}  // namespace

namespace {

// On a non-periodic set at the end of its budget; `leaked`: only a set states were seen to leave
// in the follow past the budget (by label; a set beyond it has not leaked).
bool on_set(const CensusFollower::Outcome& f, const std::function<bool(int)>& periodic,
            const std::vector<bool>* leaked) {
  if (!f.budget || f.label < 0 || periodic(f.label)) return false;
  const auto set = static_cast<std::size_t>(f.label);
  return leaked == nullptr || (set < leaked->size() && (*leaked)[set]);
}

// Still settling at the end of its budget (unresolved, not failed): a later round decides it.
bool settling(const CensusFollower::Outcome& f) { return f.budget && !f.failed && f.label == kUnresolvedLabel; }

}  // namespace

// Transient chaos (census.hpp): the states the budget left on a non-periodic set, or still
// settling, are followed on for one round of analysis.max_periods; after it, those on a set
// that a state left in these rounds (a chaotic saddle), or still settling, go on in further
// rounds, until at most sqrt(K)/4 of them remain (states_to_follow_on): their share is then at
// most 1/(4 sqrt K), a quarter of the largest standard error sqrt(p(1-p)/K) of any fraction, so
// they move no fraction by more than that. census.max_transient_periods (cap) bounds a state's
// periods in all. Whether a set leaks is judged by these rounds alone, which run from the
// states' own end points, so the answer does not depend on the order states were followed in
// (or on MPI ranks). Each round's survival gives a set's escape rate: exits over the periods
// followed from it (the maximum-likelihood rate of an exponential lifetime with censoring;
// memoryless, so timed from the round's start).
// The rest state's label is a map's answer and the single-start map's: where the budget left it
// on a non-periodic set or still settling, it is followed again from rest, at the scene's
// tolerance (brute force's own path, which a restart from where it was left would not keep on
// a chaotic set), to the cap in one go. The early decisions still apply.
PastBudget follow_past_budget(std::vector<CensusFollower::Outcome>& states, const Eigen::Vector4d& rest, long round,
                              long cap, const std::function<bool(int)>& periodic, const FollowOn& follow) {
  PastBudget out;
  const auto account = [&](const CensusFollower::Outcome& f, long past) {
    out.periods += f.periods;
    out.transient_periods += past;
    out.budget_periods += f.budget ? f.periods : 0;
  };
  if (!states.empty() && (on_set(states[0], periodic, nullptr) || settling(states[0])) && cap > states[0].periods) {
    states[0] = follow(0, rest, cap, true);
    account(states[0], std::max(0L, states[0].periods - round));
  }
  std::vector<long> spent(states.size());
  for (std::size_t k = 0; k < states.size(); ++k) spent[k] = states[k].periods;
  if (!spent.empty()) spent[0] = std::max(spent[0], cap);  // rest: done above
  std::vector<bool> leaked;
  for (bool first = true;; first = false) {
    std::vector<std::size_t> pending;
    for (std::size_t k = 0; k < states.size(); ++k)
      if ((on_set(states[k], periodic, first ? nullptr : &leaked) || settling(states[k])) && spent[k] + round <= cap)
        pending.push_back(k);
    pending = states_to_follow_on(std::move(pending), states.size());
    if (pending.empty()) break;
    for (const std::size_t k : pending) {
      const int from = states[k].label;
      states[k] = follow(k, states[k].end_state, round, false);
      const CensusFollower::Outcome& f = states[k];
      if (from >= 0) {
        const auto set = static_cast<std::size_t>(from);
        if (out.exposure.size() <= set) {
          out.exposure.resize(set + 1, 0);
          out.exits.resize(set + 1, 0);
        }
        if (leaked.size() <= set) leaked.resize(set + 1, false);
        out.exposure[set] += f.periods;
        out.exits[set] += f.label != from ? 1 : 0;
        if (f.label != from) leaked[set] = true;
      }
      spent[k] += f.periods;
      account(f, f.periods);
    }
  }
  for (const CensusFollower::Outcome& f : states)
    out.transient_states += on_set(f, periodic, &leaked) || settling(f) ? 1 : 0;
  return out;
}

void record_escape(Attractor& a, const PastBudget& p, std::size_t label) {
  if (label >= p.exposure.size() || p.exposure[label] == 0) return;
  a.escape_exposure = p.exposure[label];
  a.escapes = p.exits[label];
  a.escape_rate = static_cast<double>(a.escapes) / static_cast<double>(a.escape_exposure);
  a.transient = a.transient || a.escapes > 0;  // seen to leak past the budget
}

std::vector<std::size_t> states_to_follow_on(std::vector<std::size_t> pending, std::size_t K) {
  if (static_cast<double>(pending.size()) <= std::sqrt(static_cast<double>(K)) / 4.0) pending.clear();
  return pending;
}

std::string census_method_error(const IntegratorOptions& o) {
  if (o.method != Method::rk4) return {};
  return "[solver] method = \"rk4\": a census needs an adaptive method (hybrid or dopri5): it follows its initial "
         "states at an adaptive tolerance and finds their orbits by shooting";
}

std::string census_input_error(const Parameters& p, const PointOptions& o, const CensusOptions& c) {
  std::string msg;
  for (const auto& e : validate(p)) msg += (msg.empty() ? "" : "; ") + e;
  for (const auto& e : {validate(o.integrator), validate(o.analysis), validate(c)})
    if (!e.empty()) msg += (msg.empty() ? "" : "; ") + e;
  if (msg.empty()) msg = census_box_error(p, c);
  if (msg.empty()) msg = census_method_error(o.integrator);
  return msg;
}

CensusSummary census_point(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                           const std::vector<Eigen::Vector4d>& seeds) {
  const auto start = std::chrono::steady_clock::now();
  CensusSummary s;
  s.T = p.period();
  s.K = census.initial_conditions;
  if (std::string err = census_input_error(p, options, census); !err.empty()) {
    s.status = SolveStatus::invalid_input;
    s.message = err;
    return s;
  }
  const std::vector<Eigen::Vector4d> ics = census_initial_conditions(p, census);
  if (static_cast<int>(ics.size()) != census.initial_conditions) {
    s.status = SolveStatus::invalid_input;
    s.message = kCensusBoxOverlaps;
    return s;
  }

  CensusFollower follower(p, options, census);
  for (const Eigen::Vector4d& x0 : seeds) {  // found first, so that the K states are captured by them
    if (!x0.allFinite()) continue;
    s.periods += follower.follow(x0).periods;
    ++s.seeds;
  }
  std::vector<CensusFollower::Outcome> outcomes;
  for (const Eigen::Vector4d& x0 : ics) {
    const CensusFollower::Outcome f = follower.follow(x0);
    s.periods += f.periods;
    s.decided_early += f.early ? 1 : 0;
    s.budget_states += f.budget ? 1 : 0;
    s.budget_periods += f.budget ? f.periods : 0;
    outcomes.push_back(f);
  }
  const PastBudget past = follow_past_budget(
      outcomes, ics.front(), options.analysis.max_periods, census.max_transient_periods,
      [&](int label) { return follower.attractor(static_cast<std::size_t>(label)).periodic; },
      [&](std::size_t, const Eigen::Vector4d& x0, long budget, bool exact) { return follower.follow(x0, budget, exact); });
  s.periods += past.periods;
  s.transient_periods = past.transient_periods;
  s.budget_periods += past.budget_periods;
  s.transient_states = past.transient_states;
  s.budget_states = static_cast<int>(std::count_if(outcomes.begin(), outcomes.end(), [](const auto& f) { return f.budget; }));
  s.counters = follower.counters();
  std::vector<Attractor> found;
  for (std::size_t i = 0; i < follower.size(); ++i) {
    found.push_back(follower.attractor(i));
    record_escape(found.back(), past, i);
  }
  std::vector<int> labels;
  for (const CensusFollower::Outcome& f : outcomes) labels.push_back(f.label);
  list_attractors(s, found, labels, census.max_attractors);
  if (census.labels) {
    s.initial_conditions = ics;
    s.labels = labels;
  }
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  add_critical_shocks(p, options, census, s);  // each shock reports its own time
  return s;
}

void list_attractors(CensusSummary& s, const std::vector<Attractor>& found, std::vector<int>& labels,
                     int max_attractors) {
  // By how many initial states reach them (discovery order on ties), at most max_attractors;
  // the others' initial states become unlisted.
  std::vector<int> counts(found.size(), 0);
  for (int l : labels)
    if (l >= 0) ++counts[static_cast<std::size_t>(l)];
  std::vector<std::size_t> order(found.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return counts[a] > counts[b]; });
  if (order.size() > static_cast<std::size_t>(max_attractors)) {
    // The attractor rest reaches stays listed (a map's motion from rest is one of its cell's).
    const int rest = labels.empty() ? kUnresolvedLabel : labels.front();
    const auto rest_at = std::find(order.begin(), order.end(), static_cast<std::size_t>(rest));
    if (rest >= 0 && rest_at - order.begin() >= max_attractors)
      std::rotate(order.begin() + max_attractors - 1, rest_at, rest_at + 1);
    order.resize(static_cast<std::size_t>(max_attractors));
  }
  std::vector<int> listed(found.size(), kUnlistedLabel);
  s.attractors.clear();
  for (std::size_t k = 0; k < order.size(); ++k) {
    listed[order[k]] = static_cast<int>(k);
    Attractor a = found[order[k]];
    a.count = counts[order[k]];
    a.from_rest = false;
    const double f = static_cast<double>(a.count) / s.K;
    a.fraction = f;
    a.fraction_stderr = std::sqrt(f * (1.0 - f) / s.K);
    s.attractors.push_back(a);
  }
  s.unresolved = s.unlisted = 0;
  for (int& l : labels) {
    if (l >= 0) l = listed[static_cast<std::size_t>(l)];
    if (l == kUnresolvedLabel) ++s.unresolved;
    if (l == kUnlistedLabel) ++s.unlisted;
  }
  if (!labels.empty() && labels.front() >= 0) s.attractors[static_cast<std::size_t>(labels.front())].from_rest = true;
  s.soft_fraction = 0.0;
  for (const Attractor& a : s.attractors)
    if (a.soft) s.soft_fraction += a.fraction;
  std::vector<double> shares;  // the outcomes' shares: each listed attractor, unresolved, unlisted
  for (const Attractor& a : s.attractors) shares.push_back(a.fraction);
  shares.push_back(static_cast<double>(s.unresolved) / s.K);
  shares.push_back(static_cast<double>(s.unlisted) / s.K);
  s.basin_entropy = s.K > 0 ? fraction_entropy(shares) : 0.0;
}

std::size_t match_attractor(const Parameters& p, const PointOptions& options, std::vector<Attractor>& list,
                            std::vector<std::int64_t>& first, const Attractor& a, std::int64_t item) {
  for (std::size_t g = 0; g < list.size(); ++g)
    if (same_attractor(p, options, list[g], a)) {
      list[g].transient = list[g].transient || a.transient;
      first[g] = std::min(first[g], item);
      return g;
    }
  list.push_back(a);
  list.back().count = 0;
  first.push_back(item);
  return list.size() - 1;
}

Attractor canonical_record(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                           const Eigen::Vector4d& x0, const Attractor& a) {
  try {
    CensusFollower fresh(p, options, census);
    const CensusFollower::Outcome out = fresh.follow(x0);
    if (out.label < 0) return a;
    Attractor found = fresh.attractor(static_cast<std::size_t>(out.label));
    if (!same_attractor(p, options, a, found)) return a;
    found.count = a.count;
    found.transient = found.transient || a.transient;
    return found;
  } catch (const std::exception&) {  // keep the record the ranks sent
    return a;
  }
}

struct CensusFollower::Impl {
  Impl(const Parameters& p, const PointOptions& o, const CensusOptions& c) : options(o), census(c), set(p, o, c) {}
  PointOptions options;
  CensusOptions census;
  AttractorSet set;
  IntegrationCounters counters;
};

CensusFollower::CensusFollower(const Parameters& p, const PointOptions& options, const CensusOptions& census) {
  if (std::string err = census_input_error(p, options, census); !err.empty()) throw std::invalid_argument(err);
  impl_ = std::make_unique<Impl>(p, options, census);
}
CensusFollower::~CensusFollower() = default;
CensusFollower::CensusFollower(CensusFollower&&) noexcept = default;
CensusFollower& CensusFollower::operator=(CensusFollower&&) noexcept = default;

CensusFollower::Outcome CensusFollower::follow(const Eigen::Vector4d& x0) {
  return follow(x0, impl_->options.analysis.max_periods);
}
CensusFollower::Outcome CensusFollower::follow(const Eigen::Vector4d& x0, long budget, bool exact) {
  return vibromap::follow(impl_->set, impl_->options, impl_->census, x0, budget, exact, impl_->counters);
}
std::size_t CensusFollower::size() const { return impl_->set.size(); }
const Attractor& CensusFollower::attractor(std::size_t i) const { return impl_->set.record(i); }
const IntegrationCounters& CensusFollower::counters() const { return impl_->counters; }

bool same_attractor(const Parameters& p, const PointOptions& options, const Attractor& a, const Attractor& b) {
  if (a.periodic != b.periodic) return false;
  if (!a.periodic) return a.regime.kind == b.regime.kind;
  if (a.strobe.empty()) return false;
  std::vector<State> x, y;
  for (const Eigen::Vector4d& s : a.strobe) x.push_back(Model::to_internal(s));
  for (const Eigen::Vector4d& s : b.strobe) y.push_back(Model::to_internal(s));
  return same_cycle(Model(p), x, y, same_orbit_tolerance(options));
}

}  // namespace vibromap
