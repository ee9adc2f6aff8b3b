#pragma once
// The basins campaign: `vibromap basins`, the attractor of every initial state of a plane
// (basins_plane.hpp) on every MPI rank, into one HDF5 file (io/basins_file.hpp).
//   plan   the plane's pixels in flat order (row-major, the first plane variable fastest);
//          resume: the pixels the file does not mark done
//   solve  one pixel: its state followed to its attractor by the rank's one CensusFollower
//          (census.hpp), kept for the whole run so that each attractor is found once per rank
//          and later pixels are captured early against it (by periodic orbits only: no
//          recurrence capture, basins_run.cpp says why); a pixel with the bodies overlapping
//          (x1 > x2) is labelled kOverlapLabel and not followed; an exception is the pixel's
//          label kUnresolvedLabel, never the run's
//   codec  PixelResult: the label and the attractor's record (regime, orbit, stability)
//   sink   rank 0 keeps every label and the global attractor list in memory (a 200 x 200
//          plane is 40,000 labels), matching the ranks' attractors with same_attractor, and
//          rewrites the whole file atomically at each checkpoint
// At the end, rank 0 re-derives each attractor's record from its first pixel with a fresh
// follower (so that the record does not depend on which rank found the attractor first) and
// numbers the attractors by pixel count: the file does not depend on the number of ranks. Every
// write adds the basin entropy of the labels written (basin_entropy.hpp, over the pixels done).

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "vibromap/core/analysis/census/basin_entropy.hpp"
#include "vibromap/core/analysis/census/basins_plane.hpp"
#include "vibromap/io/basins_file.hpp"
#include "vibromap/io/basins_output.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/farm.hpp"

namespace vibromap {

// What the command line asks for: the plane variables, the grid and the fixed values given.
struct BasinsSpec {
  std::array<int, 2> vars{0, 2};       // indices into (x1, x2, v1, v2)
  std::array<int, 2> n{200, 200};      // points along each plane variable (2..4096)
  std::map<int, double> at;            // fixed values of variables outside the plane (m, m/s)
};

// The plane of `spec` for the scene's point: each plane variable spans census_box (the
// scene's [census] box, or its default scaled on the system), evenly spaced, ends included;
// the other variables are the rest state's (0, D, 0, 0) unless `spec.at` gives them.
BasinsPlane make_basins_plane(const Scene& scene, const BasinsSpec& spec);

struct BasinsRunConfig {
  std::string output;                // the file (HDF5)
  bool resume = false;               // continue an existing file of the same run (a new one when none exists)
  bool overwrite = false;            // replace an existing file instead of refusing
  bool progress = true;              // progress lines on rank 0's stderr
  double checkpoint_interval = 30.0; // s between rewrites of the file
  BasinEntropyOptions entropy;       // the basin entropy of the labels, computed at every write (not in the identity)
};

struct BasinsReport {
  FarmReport farm;
  BasinsContent content;    // rank 0: the file's content as written last
  BasinsCoverage coverage;  // rank 0: the pixels the attractors' fractions are over (io/basins_output.hpp)
};

// Collective. Throws SceneError (an existing file without --resume or --overwrite; a file of
// another run) and IoError on rank 0, QuietExit with the same exit code on the others.
BasinsReport run_basins(const MpiSession& mpi, const Scene& scene, const BasinsPlane& plane,
                        const BasinsRunConfig& config);

}  // namespace vibromap
