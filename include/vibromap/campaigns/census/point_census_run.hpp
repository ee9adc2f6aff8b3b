#pragma once
// The point census on MPI ranks: `mpirun -n N vibromap run SCENE --census`, the census of one
// parameter point (census.hpp) with its K initial states shared out over the ranks.
//   plan   the K initial states of census_initial_conditions, in order (the rest state first)
//   solve  one initial state followed to its attractor by the rank's one CensusFollower, kept
//          for the whole run (as the basins campaign's: captures by periodic orbits, never by
//          recurrence, so that a label does not depend on what the rank followed before); an
//          exception is the state's label kUnresolvedLabel, never the run's
//   codec  state_codec.hpp (basins uses it too): label, periods, early, budget, record
//   sink   rank 0 keeps the K labels and the global attractor list in memory, matching the
//          ranks' attractors with match_attractor; nothing is written (the summary is printed)
// At the end rank 0 re-derives each attractor's record from the first initial state that
// reached it with a fresh follower (canonical_record), and lists the attractors as the serial
// census does (list_attractors): attractors, fractions and labels do not depend on the number of
// ranks; the work figures (periods, states decided early) depend on which rank followed what.

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/farm.hpp"

namespace vibromap {

struct PointCensusReport {
  FarmReport farm;
  CensusSummary summary;  // rank 0, when farm.complete(); wall_s is the farm's
};

// Collective. `census` is the scene's [census] with labels as asked. Throws SceneError on rank 0
// (and QuietExit on the others) when the point, its options or the census do not validate.
PointCensusReport run_point_census(const MpiSession& mpi, const Scene& scene, const CensusOptions& census,
                                   bool progress);

}  // namespace vibromap
