#pragma once
// Output of the accuracy study (`vibromap accuracy`; AccuracyReport,
// core/analysis/point/accuracy.hpp) as JSON, for scripts, or as a table, for people, and its
// progress lines.
//
// JSON: one object with the keys
//   scene, reference, rows: [...], each row {method, setting, integrator, steady, rtol, atol,
//   rk4_steps, status, regime, regime_matches, steady_used, newton_iterations, wall_s,
//   rhs_evals, steps, periods, T_con, F_max, k_con, rel_err_T_con, rel_err_F_max,
//   rel_err_k_con, note}; SI units, non-finite numbers null.
//
// Table: the reference solve, then a row per case: method, setting, status, regime, steady
// state method, wall s, right-hand side evaluations, periods and the three relative errors.

#include <cstddef>
#include <iosfwd>

#include "vibromap/core/analysis/point/accuracy.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {

void write_accuracy_json(std::ostream& out, const AccuracyReport& report, const Scene& scene);
void write_accuracy_table(std::ostream& out, const AccuracyReport& report, const Scene& scene);

// One progress line: "vibromap: accuracy 3/13: rk4 2^13 steps: ok (1,1) in 0.123 s".
void write_accuracy_progress(std::ostream& out, const AccuracyRow& row, std::size_t done, std::size_t total);

}  // namespace vibromap
