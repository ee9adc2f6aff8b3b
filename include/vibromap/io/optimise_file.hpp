#pragma once
// The output file of `vibromap optimise` (HDF5, read by vibromap.plot (postprocess/vibromap)).
//
// Layout (V free parameters, S seeds, E_i evaluations of start i; SI units throughout):
//   root attributes  title, vibromap_version, scene (the scene text), objective ("min_k_con",
//       ...), quantity ("k_con", "T_con", "F_max"), sense ("minimise" | "maximise"), impact,
//       regime ("(1,1)" or "any"), stability, hertz_valid (0 | 1: Hertz validity kept),
//       min_soft_fraction (0: off), soft_check_initial_conditions, variables (names, space separated, the column
//       order of every x), scales ("lin"/"log" per variable), measures (names, space
//       separated), seeds_from (the seeding map's path, or "scene"), ranks, starts,
//       evaluations, wall_s, sweep_wall_s, optimise_wall_s, verify_wall_s, trajectory (the
//       best point's trajectory file, a sibling written by write_trajectory; "" when none)
//   /variable        (V) int32 coordinate 0..V-1: the free parameters (named by `variables`)
//   /bound           (2) int8 coordinate: 0 min, 1 max (flag_values, flag_meanings)
//   /seed            (S) int32 coordinate 0..S-1
//   /bounds          (variable, bound) float64: min, max of each free parameter
//   /seeds           (seed, variable) float64: the starting points
//   /seed_cell       (seed) int64: their flat cell index in the seeding map (-1: the scene's point)
//   /seed_objective  (seed) float64: the quantity there as the map stores it (NaN: scene's point)
//   /starts/NNN      one group per start, NNN = 000, 001, ... (start order: seed-major)
//       attributes   index, seed, algorithm, stop (why it stopped: NLopt's result name or
//                    ours, local_optimiser.hpp), nlopt_code, rank, calls, cache_hits, wall_s,
//                    best (index of its best feasible evaluation, -1: none), best_objective
//       evaluation   (E) int32 coordinate 0..E-1; every dataset below but x is (evaluation)
//       x            (evaluation, variable) float64: every distinct evaluation's parameters, in order
//       objective    (E) float64: the quantity (k_con, T_con of the impact, F_max); NaN where undefined
//       value        (E) float64: the number minimised (sense * objective)
//       violation    (E) float64: the feasibility measure (<= 0 feasible; point_objective.hpp)
//       feasible     (E) uint8
//       regime       (E) int8 with CF flag_values 0..8 / flag_meanings (the map's codes), n, k
//                    (E) int32: with regime they name "(n,k)"
//       stable       (E) int8: 1 stable, 0 unstable, -1 unknown
//       <measure>    (E) float64 per measure name (k_con, T_con, F_max, max_multiplier, z_ratio;
//                    soft_fraction with min_soft_fraction > 0, NaN where no census ran)
//       wall_s       (E) float64: time of each evaluation
//   /best/NN         the best distinct points, best first (with min_soft_fraction > 0: those
//                    that pass the soft check first), each re-solved from scratch
//       attributes   start, evaluation, objective (as found), soft_fraction (the optimiser's
//                    census there; NaN when min_soft_fraction is 0), and the point's E1, E2,
//                    R1, R2, m2, k2 (N/m), omega2, restitution and every other free parameter
//                    (Key::value, SI; a spring given by omega2 gives its k2 too)
//       x            (variable) float64
//       integrate/, shooting/   the two re-solves (rtol verify_rtol): attributes status,
//                    message, regime (label), n, k, stable, T, T_con, k_con, F_max, z_max,
//                    z_ratio, hertz_valid (0|1), periods, steady_residual, max_multiplier,
//                    wall_s; dataset floquet (multiplier, part) float64 (re, im) when
//                    computed, over the coordinates multiplier (M) int32 and part (2) int8
//       soft_check/  with min_soft_fraction > 0 (none when it is 0):
//                    the re-check census (multistart.hpp SoftCheck); attributes status, message,
//                    initial_conditions (K), seed, soft_fraction, soft_fraction_stderr
//                    (sqrt(p(1-p)/K)), threshold (min_soft_fraction - 3 stderr), passed (0|1),
//                    orbit_attractor (the optimised orbit's index below, -1: not found),
//                    orbit_fraction (NaN: not found), unresolved, unlisted, wall_s; coordinate
//                    attractor (A) int32 0..A-1; per attractor (attractor):
//                    regime (int8, CF flags) with n, k (int32), k_con, T_con (s), fraction,
//                    fraction_stderr (float64), stable (int8), soft (uint8)
// Every axis of every dataset carries a dimension scale (the groups' datasets the root's
// /variable), so xarray opens each group with either netCDF-4 engine: open_dataset(path,
// group="/starts/000"). The groups /starts and /best hold only their NNN / NN groups.
// Root attributes version (kOptimiseFormat's, io/file_format.hpp) and attribute_checksum (the
// CRC-32 of every attribute, written last: src/io/attribute_seal.hpp).
// Written atomically (write_hdf5_atomically); throws IoError naming the path.

#include <string>

#include "vibromap/core/optimise/multistart.hpp"

namespace vibromap {

void write_optimise_file(const std::string& path, const OptimiseReport& report, const OptimiseOptions& options,
                         const std::string& scene_text);

}  // namespace vibromap
