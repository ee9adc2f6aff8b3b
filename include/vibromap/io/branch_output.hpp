#pragma once
// Output of a continuation (`vibromap continue`; ContinuationReport and CurvesReport,
// core/analysis/continuation/continuation_report.hpp) as JSON, for scripts, or as a table, for
// people.
//
// JSON: one object with the keys
//   key, n, stop, points, bifurcations (the first branch), branches: [{n, parent, born_at,
//   born_at_param, stop, points, bifurcations}, ...] (the switched ones), and with curves also
//   curves: [{kind, n, stop, start, grazing (when set), codim2: [{param, param2, kind}],
//             points: [{param, param2, T_con, k_con, z_ratio, F_max, impacts, stable,
//                       multipliers, residual, orbit_residual, y}]}, ...] and skipped;
//   a point is {param, stable, multipliers: [[re, im], ...], T_con, k_con, F_max, impacts,
//   x1_max, x2_max, clearance_min, regime, y: [x1, x2, v1, v2], strobe_x1}, a bifurcation
//   {type, param, multipliers, y}.
// In SI units and the key's own units; non-finite numbers are null.
//
// Table: the first branch and its bifurcations, the switched branches and theirs, a line per
// branch, every point only when asked; with curves a paragraph per curve.

#include <iosfwd>
#include <string>

#include "vibromap/core/analysis/continuation/continuation_report.hpp"

namespace vibromap {

// What the branch table says besides the report: the key and its range as asked, the branch
// file written, and whether every point of every branch is listed.
struct BranchTable {
  std::string key;
  double from = 0.0, to = 0.0;
  std::string file;     // empty: none written
  bool points = false;  // every point too (the JSON always has them)
};

void write_branch_table(std::ostream& out, const ContinuationReport& report, const BranchTable& table);
// `curves`: the curves followed from the branch's points (continue --curve), or nullptr.
void write_branch_json(std::ostream& out, const std::string& key, const ContinuationReport& report,
                       const CurvesReport* curves = nullptr);
// The curves' paragraphs, after write_branch_table: `key` and `key2` name P and Q.
void write_curves_table(std::ostream& out, const std::string& key, const std::string& key2, const CurvesReport& r);

}  // namespace vibromap
