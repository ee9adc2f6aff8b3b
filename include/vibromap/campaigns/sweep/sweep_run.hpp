#pragma once
// The sweep campaign: a scene's [sweep] grid on every MPI rank into one HDF5 map.
//   plan   the grid's cells in flat order; resume: the cells the map does not mark done
//   solve  one cell: the scene's point with the cell's axis values, solved by the core
//          (solve_point; with [census], census_point: every attractor of the cell); an
//          exception is the cell's status `failed`, never the run's
//   codec  CellResult, field by field
//   sink   the map file (io/map_file.hpp) on rank 0, with the regime counts for progress
// The farm (parallel/farm.hpp) distributes, checkpoints and stops on signals.
// With sweep.refine = L > 0 the map is the fine grid and the run goes in phases (the coarse
// points, each level's new points, the audit; then rank 0 fills the inherited points), one farm
// run per phase on the same MPI session (docs/design-refine.md).

#include <cstdint>
#include <map>
#include <string>

#include "vibromap/io/map_file.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/farm.hpp"

namespace vibromap {

struct SweepRunConfig {
  std::string output;      // the map file (HDF5)
  bool resume = false;     // continue an existing map of the same scene (a new one when none exists)
  bool overwrite = false;  // replace an existing map instead of refusing
  bool progress = true;    // progress lines on rank 0's stderr
};

struct SweepReport {
  FarmReport farm;                       // cells, ranks, time, checkpoints, stop signal
  std::map<std::string, long> regimes;   // regime label -> cells, over the whole map (rank 0)
  int census_initial_conditions = 0;     // K of each cell's census (0: no census)
  long census_budget_states = 0;         // census: initial states followed to analysis.max_periods, whole map
  long soft = 0;                         // cells whose motion is soft (is_soft), whole map
  long impacting = 0;                    // cells whose motion has impacts, whole map
  long hertz_invalid = 0;                // of those, cells beyond the Hertz limit
  // An adaptive map (sweep.refine > 0; rank 0): levels, and what the run did over the whole map
  // (solved per level, inherited, audited, mismatches and their 95 % bound).
  int refine_levels = 0;
  RefineFigures refine;
  std::uint64_t refine_solved_now = 0;   // points solved (audited too) by this run: farm.items_computed less the fill
};

// Collective: every rank calls it with the same scene and config. Throws SceneError (no
// [sweep]; an existing map without --resume or --overwrite; a map of another scene), IoError
// (file errors) on rank 0, QuietExit with the same exit code on the others.
SweepReport run_sweep(const MpiSession& mpi, const Scene& scene, const SweepRunConfig& config);

}  // namespace vibromap
