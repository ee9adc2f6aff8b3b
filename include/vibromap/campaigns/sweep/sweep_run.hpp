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

#include <string>

#include "vibromap/io/scene/scene.hpp"
#include "vibromap/io/sweep_output.hpp"
#include "vibromap/parallel/farm.hpp"

namespace vibromap {

struct SweepRunConfig {
  std::string output;      // the map file (HDF5)
  bool resume = false;     // continue an existing map of the same scene (a new one when none exists)
  bool overwrite = false;  // replace an existing map instead of refusing
  bool progress = true;    // progress lines on rank 0's stderr
};

struct SweepReport {
  FarmReport farm;      // cells, ranks, time, checkpoints, stop signal
  SweepTotals totals;   // the whole map's counts and refinement figures (rank 0; io/sweep_output.hpp)
};

// Collective: every rank calls it with the same scene and config. Throws SceneError (no
// [sweep]; an existing map without --resume or --overwrite; a map of another scene), IoError
// (file errors) on rank 0, QuietExit with the same exit code on the others.
SweepReport run_sweep(const MpiSession& mpi, const Scene& scene, const SweepRunConfig& config);

}  // namespace vibromap
