#pragma once
// The multistart campaign: `vibromap optimise`, a scene's [optimise] on every MPI rank.
//   seeds  the best cells of [optimise] map; or, without a map, the scene's [sweep] run first
//          (the sweep campaign) into config.map_output, then its best cells (an existing map of
//          the same scene is resumed or reused; --overwrite recomputes it); or the scene's point
//   plan   every seed with every algorithm (plan_starts), one farm item per start
//   solve  one start: a local optimisation from its seed (run_start); an exception is the
//          start's result ("FAILURE (...)"), never the run's
//   codec  StartRecord: every evaluation of the start
//   sink   the starts in memory and in a journal (config.journal), synced at checkpoints, so
//          that --resume finishes a killed run with the same answer
// Then rank 0 re-solves the best distinct feasible points from scratch (verify_point), writes
// the best one's trajectory and the output file, and removes the journal. A start's result
// depends only on its seed and the options, so the answer does not depend on the rank count or
// on a kill and resume (unless [optimise] max_time cuts starts short).

#include <string>

#include "vibromap/core/optimise/multistart.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/farm.hpp"

namespace vibromap {

struct OptimiseRunConfig {
  std::string output;      // the result file (HDF5)
  std::string map_output;  // the map the scene's [sweep] writes when it seeds the starts
  std::string trajectory;  // the best point's trajectory file (HDF5); empty: none
  std::string journal;     // the finished starts of an unfinished run; removed when the output is written
  bool resume = false;     // finish a killed run from its journal (a new run when there is none)
  bool overwrite = false;  // replace an existing output and journal, and recompute the seeding sweep's map
  bool progress = true;    // progress on rank 0's stderr (the sweep's, and a line per start)
};

struct OptimiseRun {
  OptimiseReport report;   // rank 0 (empty on the other ranks)
  FarmReport sweep;        // the seeding sweep's farm, when one ran
  FarmReport starts;       // the starts' farm
  int stop_signal = 0;     // the signal that stopped the run (sweep or starts); 0: it ran to the end
  std::size_t starts_resumed = 0;  // starts taken from the journal
};

// Collective. Throws SceneError (no [optimise]; an existing output or journal without --resume
// or --overwrite; a journal of another run; a seeding map that cannot seed) and IoError on rank
// 0, QuietExit with the same exit code on the others.
OptimiseRun run_optimise(const MpiSession& mpi, const Scene& scene, const OptimiseRunConfig& config);

}  // namespace vibromap
