#pragma once
// Writes a kept trajectory (PointSummary::trajectory) to an HDF5 file for postprocess/.
//
// Layout: datasets t, x1, x2, v1, v2, Fc, F (1-D, float64, each with a `units` attribute);
// t is the dimension scale "t" of the others (xarray: the time coordinate, either engine);
// root attributes: T (s), regime (label), n, k, T_con, k_con, scene (full scene text),
// vibromap_version, version (kTrajectoryFormat's, io/file_format.hpp), attribute_checksum (the
// CRC-32 of every attribute, written last: src/io/attribute_seal.hpp). Written to FILE.tmp and
// renamed, so a failure never leaves a half-written FILE behind. Throws vibromap::IoError (hdf5_file.hpp) with the path on failure.

#include <array>
#include <string>

#include "vibromap/core/analysis/point/point_solver.hpp"

namespace vibromap {

// One column of a kept trajectory: its dataset name, units, meaning, and the sample's member.
struct TrajectoryColumn {
  const char* name;
  const char* units;
  const char* description;
  double TrajectorySample::*member;
};

// The columns the file holds, in its order (t first); the Python module's Dataset has the same.
const std::array<TrajectoryColumn, 7>& trajectory_columns();

void write_trajectory(const std::string& path, const PointSummary& summary, const std::string& scene_text);

// Checks, before the solve that keeps it, that a trajectory of `periods` x `samples` samples
// ([analysis] trajectory_periods, trajectory_samples) fits: `copies` of it held at once (the
// solver's samples, the writer's columns and a growing vector's slack counted) must need at
// most half the memory available (MemAvailable), and its file at most the space free where
// `path` goes. Throws IoError "PATH: OPTION: P periods x S samples (...) need about ..." (`option`
// names what asked for it: "--trajectory", "the best point's trajectory"). Every command that
// keeps a trajectory calls this one check (run --trajectory, optimise).
void check_trajectory_fits(const std::string& path, const std::string& option, long periods, long samples,
                           int copies = 1);

}  // namespace vibromap
