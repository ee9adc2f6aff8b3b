#pragma once
// Writes a kept trajectory (PointSummary::trajectory) to an HDF5 file for postprocess/.
//
// Layout: datasets t, x1, x2, v1, v2, Fc, F (1-D, float64, each with a `units` attribute);
// t is the dimension scale "t" of the others (xarray: the time coordinate, either engine);
// root attributes: T (s), regime (label), n, k, T_con, k_con, scene (full scene text),
// vibromap_version, attribute_checksum (the CRC-32 of every attribute, written last: src/io/attribute_seal.hpp). Written to FILE.tmp and renamed, so a failure never leaves a
// half-written FILE behind. Throws vibromap::IoError (hdf5_file.hpp) with the path on failure.

#include <string>

#include "vibromap/core/analysis/point_solver.hpp"

namespace vibromap {

void write_trajectory(const std::string& path, const PointSummary& summary, const std::string& scene_text);

}  // namespace vibromap
