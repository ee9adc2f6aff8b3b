#pragma once
// The attractors a census has found in one cell so far, and the tests that decide an initial
// state early (census.hpp). Private to the census.

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <set>
#include <unordered_set>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/analysis/point/impact.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"

namespace vibromap::census_detail {

// A periodic orbit: its cycle at period starts, and what the capture test needs at the
// Poincare section where its map is smooth (section.hpp).
struct Orbit {
  int n = 1;
  std::vector<State> points;      // the n states at period starts (internal coordinates)
  bool linearised = false;        // Newton converged at the section: M is known
  bool capture = false;           // the capture test applies (stable, M and S known)
  double phase = 0.0;             // section phase s in [0, T)
  State y = State::Zero();        // the orbit's point at phase s
  Eigen::Matrix4d M;              // monodromy of P^n at y, in scaled coordinates
  int cycles = 1;                 // J: cycles after which M^J has contracted by half
  Eigen::Matrix4d S;              // Lyapunov matrix of M^J: (M^J)^T S M^J - S = -I
  double level = 0.0;             // V(d) = d^T S d below which a state is captured (0: none verified)
};


// SplitMix64 (Steele, Lea, Flood 2014): uniform doubles in [0, 1), the same on every machine
// and compiler.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : s_(seed) {}
  double uniform() {
    std::uint64_t z = (s_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t s_;
};

// A cell of the recurrence grid: the stroboscopic state over (census.cell motion scales), floored.
using Cell = std::array<std::int64_t, 4>;

// A non-periodic attractor: the (hashed) cells of the recurrence grid its stroboscopic points
// visit, with their 80 neighbours (a chaotic set is covered sparsely by the samples seen).
struct Recurrent {
  std::unordered_set<std::uint64_t> near;  // visited cells and their neighbours
  std::set<Cell> visited;                  // the cells added (one that comes again adds nothing new)
  void add(const Cell& cell);  // a visited cell and its neighbours
};

// The orbit's offset history of one initial state, one scaled offset per period.
using Offsets = std::deque<Eigen::Vector4d>;

class AttractorSet {
 public:
  AttractorSet(const Parameters& p, const PointOptions& options, const CensusOptions& census);

  std::size_t size() const { return records_.size(); }
  const Attractor& record(std::size_t i) const { return records_[i]; }
  bool full() const;  // no room for another attractor (they are then unlisted)

  // The section phases of the periodic attractors, by attractor index (NaN for the others).
  std::vector<double> phases() const;
  // Scaled offset of a state at attractor i's section phase from its orbit point there.
  Eigen::Vector4d offset(std::size_t i, const State& at_phase) const;
  // The capture test on attractor i's offsets of one initial state (newest at the back).
  bool captured(std::size_t i, const Offsets& offsets) const;
  // V(d) of attractor i relative to its capture level (captured when <= 1 on two cycles).
  double level_ratio(std::size_t i, const Eigen::Vector4d& d) const;
  // The recurrence-grid cell of a stroboscopic state, and whether attractor i visits it or
  // one of its 80 neighbours.
  Cell cell(const State& u) const;
  bool visits(std::size_t i, const Cell& cell) const;
  // Whether a stay on non-periodic attractor i decides a state: with census.decide_by_recurrence,
  // while no state was seen to leave it.
  bool recurrence_decides(std::size_t i) const;
  // A state that stayed `recurrences` periods in a row on non-periodic attractor i ended on
  // attractor `outcome` (nullopt: unlisted or unresolved); another attractor: i is transient.
  void observe_stay(std::size_t i, std::optional<std::size_t> outcome);

  // The attractor of the periodic orbit through the period-start point y0 (internal) of
  // period n (reduced to its least period), added when new. With a monodromy (Newton
  // converged at y0's section) its stability is known; without, it is -1. Returns its
  // index, or nullopt when there is no room (unlisted).
  std::optional<std::size_t> add_periodic(const State& y0, int n, IntegrationCounters& counters);
  // The non-periodic attractor whose cells hold most of these stroboscopic states (at least
  // half), extended by them; or a new one described by them and the impacts seen.
  std::optional<std::size_t> add_recurrent(const std::vector<State>& samples, const std::deque<Impact>& impacts,
                                           long first_period, long last_period);

  // Newton from u (a period start) for period n at the section chosen from the impacts
  // seen: the orbit's period-start point when Newton converges to a stable orbit.
  std::optional<State> shoot_from(const State& u, int n, const std::deque<Impact>& impacts,
                                  const std::optional<Impact>& open, long last_period, IntegrationCounters& counters);

  // A search for a new orbit of period n from u (a period start): Newton at the follow
  // tolerance; when it lands on a known orbit, that orbit's index, else the orbit refined at
  // the scene's tolerance and added (add_periodic). nullopt when Newton fails or finds an
  // unstable orbit, or when there is no room.
  std::optional<std::size_t> discover(const State& u, int n, const std::deque<Impact>& impacts,
                                      const std::optional<Impact>& open, long last_period,
                                      IntegrationCounters& counters);

  const Model& model() const { return model_; }
  // The options initial states are followed with: the scene's, at census.rtol with early_stop.
  const PointOptions& follow_options() const { return follow_; }
  double newton_tol() const;

 private:
  std::optional<State> newton(const State& u, int n, double s, const IntegratorOptions& io, double tol,
                              IntegrationCounters& counters) const;
  bool same_orbit(const Orbit& o, const std::vector<State>& points) const;
  void prepare_capture(Orbit& o, const std::deque<Impact>& cycle_impacts, IntegrationCounters& counters) const;
  double verified_level(const Orbit& o, const Model& section, IntegrationCounters& counters) const;

  Parameters p_;
  PointOptions options_;
  CensusOptions census_;
  Model model_;
  StateScale scale_;
  Eigen::Array4d unit_;
  PointOptions follow_;  // options_ at the tolerance initial states are followed at (and levels verified at)
  std::vector<Attractor> records_;
  std::vector<std::optional<Orbit>> orbits_;         // by attractor index
  std::vector<std::optional<Recurrent>> recurrent_;  // by attractor index
};

}  // namespace vibromap::census_detail
