#pragma once
// Output of a basins run (`vibromap basins`) as JSON, for scripts, or as a table, for people:
// the farm's figures (FarmFigures, report.hpp), the file's content (BasinsContent,
// basins_file.hpp) and the pixels its fractions are over (BasinsCoverage).
//
// JSON: one object with the keys
//   output, plane, pixels, pixels_resumed, pixels_computed, complete, ranks, wall_s,
//   pixels_per_s, pixels_followed, pixels_to_follow, fractions_cover, stopped_by, unresolved,
//   unlisted, overlap,
//   entropy: {box, boxes, boundary_boxes, S_b, S_bb, log2_test, alpha, dimension, fit_eps_lo,
//             fit_eps_hi, fit_scales, fit_rms, note, uncertain_fraction: [f(1), f(2), f(4), ...]}
//             (basin_entropy.hpp; NaN as null),
//   attractors: [{regime, n, k, k_con, T_con, F_max, max_floquet, soft, pixels, fraction,
//                 stable}, ...].
//
// Table: the file, the plane, ranks, time, the pixels without an attractor, what the
// fractions are over, the basin entropy with its log 2 test and uncertainty exponent, and a row
// per attractor.

#include <cstdint>
#include <iosfwd>
#include <string>

#include "vibromap/io/basins_file.hpp"
#include "vibromap/io/report.hpp"

namespace vibromap {

// What the attractors' fractions are over: the pixels followed so far (done, overlap excluded:
// the fractions' denominator), and those of the whole plane (overlap excluded). They differ
// when the run was stopped, and then the fractions are not yet the plane's.
struct BasinsCoverage {
  std::uint64_t pixels_followed = 0;
  std::uint64_t pixels_to_follow = 0;
};

// `output`: the basins file.
void write_basins_json(std::ostream& out, const FarmFigures& farm, const BasinsContent& content,
                       const BasinsCoverage& coverage, const std::string& output);
void write_basins_table(std::ostream& out, const FarmFigures& farm, const BasinsContent& content,
                        const BasinsCoverage& coverage, const std::string& output);

}  // namespace vibromap
