#pragma once
// Output of a sweep (`vibromap sweep`) as JSON, for scripts, or as a table, for people: the
// farm's figures (FarmFigures, report.hpp) and the whole map's totals (SweepTotals).
//
// JSON: one object with the keys
//   output, cells_total, cells_resumed, cells_computed, complete, ranks, wall_s, cells_per_s,
//   checkpoints, checkpoint_s, checkpoint_max_s, final_checkpoint_s, stopped_by, requests,
//   request_us, with a census census_initial_conditions, initial_conditions_per_s,
//   census_budget_states; soft_cells, impacting_cells, hertz_invalid_cells; for an adaptive map
//   refine_levels, refine_solved_per_level, points_solved_now, points_solved_per_s,
//   refine_solved, refine_inherited, refine_audited, refine_mismatches, refine_mismatch_bound,
//   refine_whole_cells; a finished census map families (count, distance, wall_s, nodes, and top:
//   the largest five by cells, each id, regimes, cells, soft_cells, fraction_min, fraction_max,
//   edge_cells, label_changes); regimes: {label: cells, ...}; classes: {regime kind: {cells,
//   solve_s, cells_per_s}, ...}, the cells solved (wall_s > 0) of each kind, their solve time
//   summed over ranks and the cells one core solves a second.
//
// Table: the map, its cells (or an adaptive map's points by how each got its values), ranks,
// time, checkpoints, the census's budget, the soft and Hertz-invalid cells, the refinement, the
// families (the largest five), the regimes and the speed of each kind of cell.

#include <cstdint>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>

#include "vibromap/io/map_families.hpp"
#include "vibromap/io/map_file.hpp"
#include "vibromap/io/report.hpp"

namespace vibromap {

// The cells of one regime kind that were solved (wall_s > 0) and the seconds their solves took.
struct ClassCost {
  long cells = 0;
  double solve_s = 0.0;
  void add(double wall_s) {
    ++cells;
    solve_s += wall_s;
  }
};

// What a sweep's summary says of the whole map (the cells it already held on resume included),
// as rank 0 counted it.
struct SweepTotals {
  std::map<std::string, long> regimes;   // regime label -> cells
  std::map<std::string, ClassCost> classes;  // regime kind ("periodic", "no-contact", ...) -> its solved cells' cost
  int census_initial_conditions = 0;     // K of each cell's census (0: no census)
  long census_budget_states = 0;         // census: initial states followed to analysis.max_periods
  long soft = 0;                         // cells whose motion is soft (is_soft)
  long impacting = 0;                    // cells whose motion has impacts
  long hertz_invalid = 0;                // of those, cells beyond the Hertz limit
  long fragile = 0;                      // cells marked fragile (analysis.fragility)
  long fragility_assessed = 0;           // cells whose fragility was assessed (0: the option was off)
  // An adaptive map (sweep.refine > 0): levels, and what the run did over the whole map
  // (solved per level, inherited, audited, mismatches and their 95 % bound).
  int refine_levels = 0;
  RefineFigures refine;
  std::uint64_t refine_solved_now = 0;   // points solved (audited too) by this run: the farm's items less the fill
  std::optional<FamilyPassReport> families;  // a finished census map: its family pass
};

// `output`: the map file.
void write_sweep_json(std::ostream& out, const FarmFigures& farm, const SweepTotals& totals, const std::string& output);
void write_sweep_table(std::ostream& out, const FarmFigures& farm, const SweepTotals& totals, const std::string& output);

}  // namespace vibromap
