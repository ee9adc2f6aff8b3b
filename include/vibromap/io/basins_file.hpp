#pragma once
// The output file of `vibromap basins` (HDF5, CF-1.8 conventions; read by
// vibromap.files and vibromap.plot). A plane of initial states (basins_plane.hpp),
// each pixel labelled by the attractor its motion settles into (census.hpp's CensusFollower).
//
// Layout (A: N0 x N1 pixels of the plane variables P0, P1; A attractors, S the longest period):
//   root attributes  title, Conventions, vibromap_version, scene (the scene text), identity
//       (what --resume must match: the scene's canonical values, the plane, the grid and the
//       fixed state), plane ("x1,v1"), grid ("N0xN1"), fixed ("x2=0.05 v2=0": the variables not
//       in the plane), fixed_state (4 float64: the state before the plane variables are set,
//       m and m/s), complete (0 | 1), pixels, pixels_done, pixels_overlap, attractors, soft_kcon,
//       version (the basins format's, io/file_format.hpp); the basin entropy of the labels
//       (basin_entropy.hpp; over the pixels done): entropy_box, entropy_boxes,
//       entropy_boundary_boxes (int64), basin_entropy (S_b), boundary_basin_entropy (S_bb),
//       log2_test ("fractal", "not_shown", "no_boundary"), uncertainty_fraction (f at eps = 1, 2,
//       4, ...; absent when no scale is computed), uncertainty_exponent, boundary_dimension, uncertainty_fit_rms (float64, NaN when
//       not fitted), uncertainty_fit_eps_lo, uncertainty_fit_eps_hi, uncertainty_fit_scales
//       (int64, 0 when not fitted), uncertainty_note (why not fitted; empty when fitted)
//   /P0 (N0), /P1 (N1) float64 coordinates (dimension scales), units m or m/s
//   /label (N1, N0) int32: the pixel's attractor index; -1 unresolved (budget ran out while
//       settling), -2 unlisted (more attractors than max_attractors), -3 overlap (x1 > x2 at
//       the start: not followed), -4 not computed yet (flag_values, flag_meanings)
//   /done  (N1, N0) uint8: 1 where the label is final (what --resume skips)
//   /attractor (A) int32 coordinate; per attractor (A):
//       regime (int8, the map's regime codes with flag_values/flag_meanings), n, k (int32),
//       periodic, hertz_valid, soft (uint8), stable (int8: 1, 0, -1 unknown), T_con (s),
//       k_con, F_max (N), z_ratio, z_max (m), v_in (m/s), impulse (N s), max_floquet,
//       pixels (int64), fraction (pixels / pixels followed, overlap excluded), first_pixel
//       (int64, flat: j N0 + i), strobe_points (int32, n or 0), strobe (A, S, 4) float64: the
//       stroboscopic states (x1, x2, v1, v2), NaN past strobe_points, over the coordinates
//       /period_start (S) int32 0..S-1 and /state (4) int8 0..3 (flag_meanings "x1 x2 v1 v2")
// Every axis of every dataset carries a dimension scale: xarray opens the file with either
// netCDF-4 engine (netcdf4, h5netcdf).
// Attractors are numbered by pixel count, descending, ties by first pixel: the file does not
// depend on the number of MPI ranks. Written atomically (write_hdf5_atomically), with the root
// attribute attribute_checksum last: the CRC-32 of every attribute (src/io/attribute_seal.hpp).
// A resume checks the format version (another one is refused: FileVersionError) and the
// checksum before it compares identities.

#include <cstdint>
#include <string>
#include <vector>

#include "vibromap/core/analysis/census/basin_entropy.hpp"
#include "vibromap/core/analysis/census/basins_plane.hpp"
#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/io/file_format.hpp"

namespace vibromap {

constexpr int kNotComputedLabel = -4;  // a pixel not done yet

struct BasinsContent {
  std::string scene_text;
  std::string identity;                   // what a resume must match
  BasinsPlane plane;
  double soft_kcon = 10.0;                // the census's soft_kcon (attribute)
  std::vector<std::int32_t> labels;       // per pixel (plane.pixels())
  std::vector<std::uint8_t> done;         // per pixel
  std::vector<Attractor> attractors;      // count = pixels; fraction filled by the writer's caller
  std::vector<std::int64_t> first_pixel;  // per attractor
  bool complete = false;
  BasinEntropySummary entropy;            // of the labels written (basin_entropy.hpp); written, not read back
};

// Writes `c` atomically (tmp + rename). Throws IoError naming the path.
void write_basins_file(const std::string& path, const BasinsContent& c);
// Reads a file written by write_basins_file. Throws FileVersionError for a file of another
// format version, IoError when it is not one or is damaged.
BasinsContent read_basins_file(const std::string& path);

}  // namespace vibromap
