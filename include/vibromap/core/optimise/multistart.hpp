#pragma once
// Multistart: seeds from the best cells of a regime map, the plan of starts (every seed with
// every algorithm), one start end to end, and the overall best points re-solved from scratch.
// The MPI distribution of the starts is the multistart campaign's (campaigns/multistart/
// optimise_run.hpp); everything here is serial and deterministic, so a start's result depends
// only on its seed and the options, never on the rank that runs it (except through
// LocalOptions::max_time, a wall-clock limit).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/model/parameters.hpp"
#include "vibromap/core/optimise/box.hpp"
#include "vibromap/core/optimise/local_optimiser.hpp"
#include "vibromap/core/optimise/optimise_options.hpp"
#include "vibromap/core/quantities.hpp"
#include "vibromap/core/grid.hpp"

namespace vibromap {

// A starting point: the free parameters' values (OptimiseOptions::variables order, SI).
struct Seed {
  std::vector<double> x;
  long cell = -1;      // flat index of the map cell it came from; -1: the scene's point
  double value = 0.0;  // the objective as the map stores it (minimised sense); 0 for the scene's point
};

// The best `o.seeds` cells of a map for starting local optimisations: done, status ok, in the
// kept regime with its stability rule (map column `stable`), inside the box, with the value
// the objective ranks by stored (k_con; T_con for max_T_con, the longest impact standing in
// for impact `o.impact`; F_max), best first, ties by cell index. A map axis (its Axis::key, or
// Axis::name in a map that names only that) must be a free parameter or the other form of a free
// spring or damper (omega2 for k2, k2 for omega2): the seed takes the free values from the
// cell (Key::value). With o.hertz_valid, only cells where Hertz theory holds qualify: the map's
// hertz_valid (every map a sweep writes stores it). Throws
// std::invalid_argument with a one-line reason when the map lacks a quantity it needs, an axis
// is not free, or no cell qualifies.
std::vector<Seed> select_seeds(const Grid& grid, const std::vector<CellResult>& cells,
                               const std::vector<std::uint8_t>& done, const std::vector<Quantity>& stored,
                               const Parameters& base, const OptimiseOptions& o);

// select_seeds one cell at a time, for maps too big to hold: offer() every done cell in flat
// order, then seeds(). Memory: a few times o.seeds candidates. The constructor and seeds()
// throw as select_seeds does.
class SeedSelector {
 public:
  SeedSelector(const Grid& grid, const std::vector<Quantity>& stored, const Parameters& base, const OptimiseOptions& o);
  void offer(std::uint64_t flat, const CellResult& cell);
  std::vector<Seed> seeds();

 private:
  void trim();
  const Grid& grid_;
  std::vector<Quantity> stored_;
  const Parameters& base_;
  const OptimiseOptions& o_;
  Box box_;
  Quantity quantity_;
  std::vector<Key> axis_keys_;  // the key of each map axis
  std::vector<double> x_;
  std::vector<Seed> best_;
};

// The scene's own point as the one seed (clamped into the box).
Seed scene_seed(const Parameters& base, const OptimiseOptions& o);

// One start: seed `seed` (index into the seeds) run with `algorithm`, with contact law `law`.
struct StartSpec {
  int index = 0;  // start number, 0-based
  int seed = 0;   // index into the seeds
  Algorithm algorithm = Algorithm::bobyqa;
  std::optional<ContactLawKind> law;  // OptimiseOptions::laws: this start's law; none: the scene's
};

// Every seed with every law (OptimiseOptions::laws; none: the scene's) and every algorithm,
// seed-major, then law: start i is seed i / (L A), law (i / A) % L, algorithm i % A.
std::vector<StartSpec> plan_starts(std::size_t seeds, const std::vector<Algorithm>& algorithms,
                                   const std::vector<ContactLawKind>& laws = {});

// The base parameters of a start: `base` with the start's law when it has one.
Parameters start_parameters(const Parameters& base, const StartSpec& spec);


// A start and its result, as gathered on rank 0.
struct StartRecord {
  StartSpec spec;
  LocalResult result;
  int rank = 0;  // MPI rank that ran it
};

// The re-check of a best point's soft fraction (OptimiseOptions::min_soft_fraction > 0): a
// larger census than the optimiser's, with draws of its own. The optimiser picks points where
// its K-state census reaches the minimum, so that census is biased upward at the answer; a
// census of other states is not.
struct SoftCheck {
  CensusSummary census;                 // the re-check census itself (soft_check_options())
  std::uint64_t seed = 0;               // its seed
  double fraction = 0.0;                // census.soft_fraction, p
  double fraction_stderr = 0.0;         // sqrt(p (1 - p) / K)
  bool passed = false;                  // p >= min_soft_fraction - kSoftCheckSigmas * stderr
  int orbit_attractor = -1;             // index into census.attractors of the optimised orbit; -1: not among them
  double orbit_fraction = std::numeric_limits<double>::quiet_NaN();  // its basin fraction; NaN: not found
};

// Standard errors a re-checked fraction may fall below min_soft_fraction and still pass.
inline constexpr double kSoftCheckSigmas = 3.0;

// The lowest re-checked fraction that passes: min_soft_fraction - kSoftCheckSigmas * stderr.
inline double soft_check_threshold(const SoftCheck& c, const OptimiseOptions& o) {
  return o.min_soft_fraction - kSoftCheckSigmas * c.fraction_stderr;
}

// The re-check census's options: the scene's [census] (`census`) with K = max(
// o.soft_check_initial_conditions, 4 census.initial_conditions) initial states and seed
// census.seed + 1 (the optimiser's census states are the first K draws of census.seed).
CensusOptions soft_check_options(const CensusOptions& census, const OptimiseOptions& o);

// The re-check at p. `orbit` is the optimised orbit re-solved (its regime and final state
// find it among the census's attractors: same regime, a stroboscopic state within 1e-4 in
// StateScale's scaled norm).
SoftCheck check_soft_fraction(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                              const OptimiseOptions& o, const PointSummary& orbit);

// A best point: where a start found it, and its re-solves from scratch.
struct VerifiedPoint {
  int start = 0;                   // the start that found it
  std::size_t evaluation = 0;      // its index among that start's evaluations
  std::vector<double> x;           // free parameters, SI
  Parameters params;               // the full parameter set
  double value = 0.0;              // the objective (minimised sense) as the optimiser saw it
  PointSummary integrate;          // brute force from rest, rtol verify_rtol
  PointSummary shooting;           // shooting, rtol verify_rtol
  double soft_fraction = std::numeric_limits<double>::quiet_NaN();  // the optimiser's census there (NaN: off)
  std::optional<SoftCheck> soft_check;  // with min_soft_fraction > 0
};

// Best points whose soft check passed first, then those that failed it, each in their order
// (a point without a check counts as passed): the answer is the best point that passes.
void prefer_passing(std::vector<VerifiedPoint>& best);

// The best feasible evaluation of each start, best first (ties: start index), keeping one of
// points closer than `merge` (scaled max-norm) to a better one, at most `count`: pairs
// (start position in `starts`, evaluation index).
std::vector<std::pair<std::size_t, std::size_t>> best_points(const std::vector<StartRecord>& starts, const Box& box,
                                                             int count, double merge);

// Re-solves a best point twice from scratch (integrate and shooting, rtol o.verify_rtol),
// the first with `trajectory_periods` periods of trajectory; with o.min_soft_fraction > 0 also
// re-checks its soft fraction (check_soft_fraction, `census` the scene's [census]).
VerifiedPoint verify_point(const Parameters& base, const PointOptions& options, const OptimiseOptions& o,
                           const StartRecord& start, std::size_t evaluation, int trajectory_periods,
                           const CensusOptions& census = {});

// Everything `vibromap optimise` found, gathered on rank 0 (campaigns/multistart/optimise_run.hpp).
struct OptimiseReport {
  std::vector<std::string> variables;     // free parameter names, in order
  std::vector<std::string> measures;      // names of Evaluation::measures
  std::string seeds_from;                 // the seeding map's path, or "scene"
  std::vector<Seed> seeds;
  std::vector<StartRecord> starts;        // in start order
  std::vector<VerifiedPoint> best;        // best first
  std::string trajectory_file;            // the best point's trajectory (HDF5), "" when none
  int ranks = 1;
  double sweep_wall_s = 0.0;              // the seeding sweep's time, s (0: no sweep run)
  double optimise_wall_s = 0.0;           // the starts' time, s
  double verify_wall_s = 0.0;             // the re-solves' time, s
  double wall_s = 0.0;                    // the whole command, s
  long evaluations() const;               // over all starts
};

}  // namespace vibromap
