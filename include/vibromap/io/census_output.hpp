#pragma once
// Output of a census of one point (CensusSummary, census.hpp) as JSON, for scripts, or as a
// table, for people.
//
// JSON: one object with the keys
//   status, message, K, T, soft_fraction, basin_entropy, unresolved, unlisted, decided_early, periods,
//   budget_states, budget_periods, wall_s, initial_states_per_s, ranks (MPI ranks that followed
//   the states),
//   attractors: [{regime, n, k, periodic, T_con, k_con, F_max, z_ratio, hertz_valid,
//                 max_floquet, stable, soft, count, fraction, fraction_stderr, from_rest,
//                 transient (a non-periodic set states were seen to leave: census.hpp),
//                 strobe: [[x1, x2, v1, v2], ...] (the n stroboscopic states; [] when not periodic),
//                 with census.shock: shock: {status, size (motion scales), dx [m, m, m/s, m/s], x_star,
//                 strobe_index, to (index into attractors; -2 not listed, -1 none), to_regime, verified,
//                 random_size, follows, unresolved, wall_s}}],
//   and, when the census kept them (--labels), initial_conditions: [[x1, x2, v1, v2], ...] and
//   labels: [index into attractors, -1 unresolved, -2 unlisted, ...].
// In SI units (s, N, m, m/s); non-finite numbers are null.

#include <iosfwd>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/analysis/census/critical_shock.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {

void write_census_json(std::ostream& os, const CensusSummary& census);
void write_census_table(std::ostream& os, const CensusSummary& census, const Scene& scene);
// After the table, with the labels kept (run --census --labels): a row per initial state, its
// state and the index of its attractor.
void write_census_labels_table(std::ostream& os, const CensusSummary& census);

}  // namespace vibromap
