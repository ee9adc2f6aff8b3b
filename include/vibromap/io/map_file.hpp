#pragma once
// Regime maps: one HDF5 file per sweep, readable by h5py and by xarray (netCDF-4 compatible).
//
// Layout (N = number of axes, shape = the axes' lengths, first axis slowest):
//   /<axis>          1-D float64 coordinate per swept parameter (E1, E2, ...), a dimension
//                    scale, attributes units, long_name, scale ("lin" | "log")
//   /done            N-D uint8: 1 where the cell has been computed
//   /status          N-D int8: flag_values -1..3, flag_meanings
//                    "not_computed ok budget failed invalid_input"
//   /regime          N-D int8: flag_values -1..8, flag_meanings "not_computed periodic chatter
//                    no_contact permanent_contact quasi_periodic chaotic non_periodic
//                    unresolved failed" (RegimeKind order); with n and k it names (n,k)
//   /stable          N-D int8: flag_values -1..1, flag_meanings "unknown unstable stable":
//                    the periodic orbit's stability from its Floquet multipliers; -1 where
//                    it was not computed (no periodic orbit, not asked, or cell not done)
//   /n, /k           N-D int32 (0 where not periodic or not computed)
//   /wall_s          N-D float64, units s
//   /steady_residual N-D float64, units 1
//   /<quantity>      N-D, only for the scene's [sweep] store list, with units and long_name
//                    from cell_result.cpp's quantity table: int64 for the integer quantities
//                    (hertz_valid, periods, rhs_evals), float64 for the others (T_con, k_con,
//                    F_max, z_max, z_ratio, v_in, impulse, max_multiplier, lyapunov).
//                    max_multiplier and lyapunov are NaN also in cells done where the solver
//                    did not compute them (no periodic orbit; Lyapunov exponent not asked).
// Every N-D dataset has the axes attached as dimension scales, in order. Float datasets
// hold NaN (their _FillValue) where done == 0; integer ones hold 0 and regime/status/stable
// -1. So a NaN alone does not say whether a cell was reached: /done does.
// Root attributes: title, Conventions ("CF-1.8"), vibromap_version, scene (the full scene
// text), ranks (MPI ranks of the run that wrote the file), cells_total, cells_done,
// complete (0 | 1), stored (the quantity names, space separated).
//
// Writing is atomic (FILE.tmp, fsync, rename), so a run killed at any moment leaves either
// the previous checkpoint or the new one, never a half-written file.

#include <cstdint>
#include <string>
#include <vector>

#include "vibromap/core/quantities.hpp"
#include "vibromap/core/grid.hpp"

namespace vibromap {

struct SweepMap {
  Grid grid;
  std::vector<Quantity> stored;     // optional quantities kept in the file
  std::vector<CellResult> cells;    // grid.size() records, flat index order
  std::vector<std::uint8_t> done;   // grid.size() flags
  std::string scene_text;           // provenance
  int ranks = 1;                    // MPI ranks of the run
};

// Writes the whole map atomically. Throws IoError naming the path.
void write_map(const std::string& path, const SweepMap& map);

// Reads a map written by write_map (for --resume and tests), every value exactly as written
// (NaN stays NaN). Records of cells not done are default CellResult, and so are optional
// quantities not stored (0; NaN for max_multiplier and lyapunov). Throws IoError naming the
// path and what is missing or malformed (a map without /stable, from before it was kept,
// included).
SweepMap read_map(const std::string& path);

}  // namespace vibromap
