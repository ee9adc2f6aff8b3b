#pragma once
// The curve file of `vibromap continue --curve KIND ... -o`: curves of codimension-one
// points in two parameters (core/analysis/continuation/curve_continuation.hpp), HDF5, CF/netCDF-4 compatible,
// written whole (tmp + rename). One group per curve, in the order found:
//   /curve_i                attributes kind ("fold", ..., "level:k_con=10"), stop, n (int)
//   /curve_i/point          1-D int32 dimension scale 0..N-1, ordered along the curve
//   /curve_i/param, param2  (point) float64: the curve in the plane, with units and long_name
//   /curve_i/T_con, k_con, z_ratio, F_max  (point) float64 (NaN where the orbit has no contact)
//   /curve_i/stable         (point) int8: 1 every |mu| < 1, else 0
//   /curve_i/multiplier     1-D int32 dimension scale 0..3
//   /curve_i/multipliers_re, multipliers_im  (point, multiplier) float64, largest |mu| first
//   /curve_i/residual       (point) float64: |defining condition| (as curve_continuation.hpp scales it)
//   /curve_i/codim2/codim2  1-D int32 dimension scale 0..M-1 (M may be 0)
//   /curve_i/codim2/param, param2 (codim2) float64, kind (codim2) variable-length string
// Root attributes: vibromap_file = "curves", title, Conventions = "CF-1.8", vibromap_version, scene
// (its text), key and param (the first key), param2, param_unit, param2_unit, version
// (kCurveFormat's, io/file_format.hpp), attribute_checksum (written last: src/io/attribute_seal.hpp).

#include <string>
#include <vector>

#include "vibromap/core/analysis/continuation/curve_continuation.hpp"
#include "vibromap/core/grid.hpp"

namespace vibromap {

struct CurveCycle {  // what `continue` measures on each curve point's cycle
  double T_con = 0.0, k_con = 0.0, z_ratio = 0.0, F_max = 0.0;
  int impacts = 0;
};

struct CurveFileData {
  Axis axis, axis2;                            // P and Q (values unused): key, units, long_name
  std::vector<Curve> curves;
  std::vector<std::vector<CurveCycle>> cycles;  // per curve, one per point
  std::string scene_text;
};

// Throws IoError naming the path; leaves no file behind on failure.
void write_curves(const std::string& path, const CurveFileData& data);

}  // namespace vibromap
