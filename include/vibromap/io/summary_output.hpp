#pragma once
// Output of one solved point (PointSummary) as JSON, for scripts, or as a table, for people.
//
// JSON: one object with the keys
//   status, message, regime (Regime::label(): "(1,1)", "chatter", ...), regime_kind, n, k,
//   T, T_con, k_con, F_max, z_max, z_ratio, hertz_valid,
//   impacts: [{t_in, t_out, T_con, F_max, z_max, z_ratio, v_in, impulse}, ...],
//   periods, steps, rejected, rhs_evals, events, steady_residual,
//   steady_method ("shooting" | "integrate": the method that produced the answer),
//   newton_iterations, floquet: [{re, im, abs}, ...] (empty when not computed),
//   stable (true | false | null: unknown), lyapunov (1/s, null when not computed), wall_s,
//   final_state: [x1, x2, v1, v2]
// in SI units (s, N, m, m/s, N s); t_in and t_out are absolute times since t = 0
// (Impact::t_in(T)). Non-finite numbers are written as null. The trajectory is not written
// here: it goes to HDF5 (trajectory_file.hpp).
//
// Table: the same quantities with units, aligned: stability as "stable", "unstable" or
// "unknown", one row per Floquet multiplier (mu, |mu|) and one row per impact.

#include <iosfwd>

#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {

void write_summary_json(std::ostream& os, const PointSummary& summary);
void write_summary_table(std::ostream& os, const PointSummary& summary, const Scene& scene);

}  // namespace vibromap
