#pragma once
// Runs a scene's [optimise] on all MPI ranks: seeds, the starts spread over the ranks, the
// best points re-solved, and the output file. Compiled into vibromap::parallel (the one
// target that sees MPI); the numerical work is multistart.hpp's.
//
// Steps (collective: every rank calls run_optimise with the same scene and config):
//   1. seeds (rank 0): the best cells of [optimise] map; or, without a map, the scene's
//      [sweep] run first by run_sweep (all ranks) into config.map_output, then its best
//      cells (an existing map of the same scene is resumed or reused, so a second run with
//      other [optimise] settings does not repeat the sweep; --overwrite recomputes it); or,
//      without either, the scene's point. Broadcast to every rank.
//   2. starts: every seed with every algorithm (plan_starts), handed out dynamically: rank 0
//      keeps the queue and computes starts too, while a coordinator thread answers the other
//      ranks (each request carries the previous start's result). A start's result depends
//      only on its seed and the options, so the answer does not depend on the rank count
//      (unless [optimise] max_time cuts starts short). A line per finished start goes to
//      rank 0's stderr when config.progress is set.
//   3. rank 0: the best distinct feasible points (OptimiseOptions::best; distinct: apart by
//      more than 1 % of the box in some scaled variable), each re-solved from
//      scratch at verify_rtol by brute force from rest and by shooting; the best one's
//      trajectory to config.trajectory; the output file (optimise_file.hpp).
// Errors: a scene without [optimise], an existing output without overwrite, a seeding map
// that cannot seed (SceneError); file errors (IoError). Rank 0 throws them, the other ranks
// get QuietExit with the exit code. A failing point is a result, never an error.

#include <string>

#include "vibromap/io/scene/scene.hpp"
#include "vibromap/core/optimise/multistart.hpp"

namespace vibromap {

struct OptimiseRunConfig {
  std::string output;      // the result file (HDF5)
  std::string map_output;  // the map the scene's [sweep] writes when it seeds the starts
  std::string trajectory;  // the best point's trajectory file (HDF5); empty: none
  bool overwrite = false;  // replace an existing output, and recompute the seeding sweep's map
  bool progress = true;    // progress on rank 0's stderr (the sweep's, and a line per start)
};

// Returns the report on rank 0 (after writing the files); on the other ranks, an empty one.
OptimiseReport run_optimise(const Scene& scene, const OptimiseRunConfig& config);

}  // namespace vibromap
