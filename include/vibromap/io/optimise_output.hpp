#pragma once
// Output of an optimisation (`vibromap optimise`; OptimiseReport, core/optimise/multistart.hpp)
// as JSON, for scripts, or as a table, for people.
//
// JSON: one object with the keys
//   output, seeds_from, trajectory, objective, quantity, regime, stability, hertz_valid,
//   min_soft_fraction, soft_check_initial_conditions, ranks, seeds, evaluations,
//   starts_resumed, sweep_cells_computed, wall_s, sweep_wall_s, optimise_wall_s, verify_wall_s,
//   starts: [{start, seed, algorithm, law (when free), evaluations, cache_hits, calls,
//             best_objective, stop, nlopt_code, rank, wall_s}, ...],
//   algorithms: [{algorithm, starts, evaluations, best_objective, wall_s}, ...],
//   best: [{params: {m2, k2, omega2, E1, E2, R1, R2}, k_con, T_con, F_max, regime, stable,
//           z_ratio, hertz_valid, soft, objective_found, start, algorithm, law, restitution,
//           set: ["section.key=value", ...], integrate, shooting (each {status, regime, stable,
//           k_con, T_con, F_max, z_ratio, max_multiplier, periods, wall_s}), agree,
//           soft_fraction, soft_check (null, or the re-check's census)}, ...], best first.
// Objectives in the quantity's own sense (k_con, T_con, F_max), SI units; non-finite numbers
// are null.
//
// Table: the run's lines, a row per start, the best per algorithm (and per law when the law is
// free), then each best point with both re-solves, its soft check and its --set overrides.

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>

#include "vibromap/core/optimise/multistart.hpp"

namespace vibromap {

// What the output says besides the report: the result file, and what this run took from
// earlier ones.
struct OptimiseRunInfo {
  std::string output;                     // the result file (FILE.h5)
  std::size_t starts_resumed = 0;         // starts taken from the journal
  std::uint64_t sweep_cells_computed = 0; // cells the seeding sweep computed in this run
};

void write_optimise_json(std::ostream& out, const OptimiseReport& report, const OptimiseOptions& options,
                         const OptimiseRunInfo& run);
void write_optimise_table(std::ostream& out, const OptimiseReport& report, const OptimiseOptions& options,
                          const OptimiseRunInfo& run);

}  // namespace vibromap
