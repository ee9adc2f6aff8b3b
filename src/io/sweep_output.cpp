// A sweep's output: see include/vibromap/io/sweep_output.hpp.

#include "vibromap/io/sweep_output.hpp"

#include <algorithm>
#include <iomanip>
#include <ostream>
#include <string>
#include <vector>

#include "vibromap/io/json_writer.hpp"

namespace vibromap {

namespace {

// A census map: initial states followed per second (K per cell computed).
double state_rate(const FarmFigures& f, const SweepTotals& t) { return f.items_per_s * t.census_initial_conditions; }

// An adaptive map: its points solved per second of this run (the fill copies, it solves nothing).
double solved_rate(const FarmFigures& f, const SweepTotals& t) {
  return f.wall_s > 0 ? static_cast<double>(t.refine_solved_now) / f.wall_s : 0.0;
}

void write_refine_json(JsonWriter& w, const FarmFigures& f, const SweepTotals& t) {
  const RefineFigures& x = t.refine;
  w.field("refine_levels", t.refine_levels).key("refine_solved_per_level").begin_array();
  for (const std::uint64_t n : x.solved_per_level) w.value(n);
  w.end_array()
      .field("points_solved_now", t.refine_solved_now)
      .field("points_solved_per_s", solved_rate(f, t))
      .field("refine_solved", x.solved)
      .field("refine_inherited", x.inherited)
      .field("refine_audited", x.audited)
      .field("refine_mismatches", x.mismatches)
      .field("refine_mismatch_bound", x.mismatch_bound)
      .field("refine_whole_cells", x.whole_blocks);
}

// The counts and the rate: of cells for a uniform map; for an adaptive map of points, by how
// each got its values, and the rate per point solved.
// The cells of a kind one core solves a second (0 when none took time).
double class_rate(const ClassCost& c) { return c.solve_s > 0.0 ? static_cast<double>(c.cells) / c.solve_s : 0.0; }

void write_counts(std::ostream& out, const FarmFigures& f, const SweepTotals& t) {
  if (t.refine_levels == 0) {
    out << "cells          " << f.items << " (" << f.items_resumed << " from the resumed map, " << f.items_computed
        << " computed now)\n"
        << "ranks          " << f.ranks << "\n"
        << "wall time      " << std::setprecision(4) << f.wall_s << " s, " << f.items_per_s << " cells/s\n";
    return;
  }
  const RefineFigures& x = t.refine;
  const std::uint64_t decided = x.solved + x.audited + x.inherited;
  out << "points         " << f.items << " (" << x.solved << " solved, " << x.audited << " audited, " << x.inherited
      << " inherited";
  if (decided < f.items) out << ", " << f.items - decided << " not decided yet";
  out << "; " << f.items_resumed << " from the resumed map, " << t.refine_solved_now << " solved now)\n"
      << "ranks          " << f.ranks << "\n"
      << "wall time      " << std::setprecision(4) << f.wall_s << " s, " << solved_rate(f, t) << " points solved/s\n";
}

// An adaptive map's line: points solved per level, inherited, and the audit's verdict.
void write_refine_line(std::ostream& out, const FarmFigures& f, const SweepTotals& t) {
  const RefineFigures& x = t.refine;
  out << "refine         " << t.refine_levels << " levels: " << x.solved << " points solved (" << std::setprecision(3)
      << 100.0 * static_cast<double>(x.solved) / static_cast<double>(std::max<std::uint64_t>(f.items, 1))
      << " %; per level";
  for (const std::uint64_t n : x.solved_per_level) out << " " << n;
  out << "; " << x.whole_blocks << " speckled coarse cells solved whole), " << x.inherited << " inherited, ";
  if (x.audited == 0) out << "no audit (sweep.refine_audit = 0 or nothing inherited: the inherited points' mismatch is unmeasured)\n";
  else
    out << "audit " << x.mismatches << " of " << x.audited << " audited points differ (95 % upper bound on the mismatch rate "
        << std::setprecision(3) << x.mismatch_bound << ")\n";
}

// The largest families (by cells, then id), at most `n`.
std::vector<std::size_t> top_families(const FamilyPassReport& r, std::size_t n) {
  std::vector<std::size_t> ids(r.families.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = i;
  std::stable_sort(ids.begin(), ids.end(),
                   [&](std::size_t a, std::size_t b) { return r.families[a].cells > r.families[b].cells; });
  ids.resize(std::min(ids.size(), n));
  return ids;
}

constexpr std::size_t kTopFamilies = 5;

void write_families_json(JsonWriter& w, const FamilyPassReport& r) {
  w.key("families").begin_object();
  w.field("count", r.families.size()).field("distance", r.distance).field("wall_s", r.wall_s).field("nodes", r.nodes);
  w.key("top").begin_array();
  for (const std::size_t id : top_families(r, kTopFamilies)) {
    const FamilyRecord& f = r.families[id];
    w.begin_object()
        .field("id", id)
        .field("regimes", family_regimes_text(f))
        .field("cells", f.cells)
        .field("soft_cells", f.soft_cells)
        .field("fraction_min", f.fraction_min)
        .field("fraction_max", f.fraction_max)
        .field("edge_cells", f.edge_cells)
        .field("label_changes", f.label_changes)
        .end_object();
  }
  w.end_array().end_object();
}

void write_families_lines(std::ostream& out, const FamilyPassReport& r) {
  out << "families       " << r.families.size() << " (attractors of neighbouring cells within " << r.distance
      << " motion scales; the pass took " << std::setprecision(3) << r.wall_s << " s); the largest:\n";
  for (const std::size_t id : top_families(r, kTopFamilies)) {
    const FamilyRecord& f = r.families[id];
    out << "  family " << id << ": " << family_regimes_text(f) << ", " << f.cells << " cells (" << f.soft_cells
        << " soft), fraction " << std::setprecision(3) << f.fraction_min << " to " << f.fraction_max << ", "
        << f.edge_cells << " at its edge, " << f.label_changes << " label changes\n";
  }
}

}  // namespace

void write_sweep_json(std::ostream& out, const FarmFigures& f, const SweepTotals& t, const std::string& output) {
  JsonWriter w(out);
  w.begin_object()
      .field("output", output)
      .field("cells_total", f.items)
      .field("cells_resumed", f.items_resumed)
      .field("cells_computed", f.items_computed)
      .field("complete", f.complete)
      .field("ranks", f.ranks)
      .field("wall_s", f.wall_s)
      .field("cells_per_s", f.items_per_s)
      .field("checkpoints", f.checkpoints)
      .field("checkpoint_s", f.checkpoint_s)
      .field("checkpoint_max_s", f.checkpoint_max_s)
      .field("final_checkpoint_s", f.final_checkpoint_s)
      .field("stopped_by", f.stopped_by)
      .field("requests", f.requests)
      .field("request_us", f.requests ? 1e6 * f.request_s / static_cast<double>(f.requests) : 0.0);
  if (t.census_initial_conditions > 0)
    w.field("census_initial_conditions", t.census_initial_conditions)
        .field("initial_conditions_per_s", state_rate(f, t))
        .field("census_budget_states", t.census_budget_states);
  w.field("soft_cells", t.soft).field("impacting_cells", t.impacting).field("hertz_invalid_cells", t.hertz_invalid);
  if (t.fragility_assessed > 0) w.field("fragile_cells", t.fragile).field("fragility_assessed_cells", t.fragility_assessed);
  if (t.refine_levels > 0) write_refine_json(w, f, t);
  if (t.families) write_families_json(w, *t.families);
  w.key("regimes").begin_object();
  for (const auto& [label, count] : t.regimes) w.field(label, count);
  w.end_object();
  w.key("classes").begin_object();
  for (const auto& [kind, cost] : t.classes)
    w.key(kind).begin_object().field("cells", cost.cells).field("solve_s", cost.solve_s).field("cells_per_s", class_rate(cost)).end_object();
  w.end_object().end_object();
  out << "\n";
}

void write_sweep_table(std::ostream& out, const FarmFigures& f, const SweepTotals& t, const std::string& output) {
  out << "map            " << output << stopped_note(f) << "\n";
  write_counts(out, f, t);
  out << "checkpoints    " << f.checkpoints << " (" << f.checkpoint_s << " s writing, longest " << f.checkpoint_max_s
      << " s)\n";
  if (t.census_initial_conditions > 0)
    out << "census         " << t.census_initial_conditions << " initial states per cell, " << state_rate(f, t)
        << " initial states/s\n"
        << "budget         " << t.census_budget_states << " of "
        << (f.items_resumed + f.items_computed) * static_cast<std::uint64_t>(t.census_initial_conditions)
        << " initial states followed to analysis.max_periods (no early decision: brute force follows them as far)\n";
  out << "soft           " << t.soft << " cells (periodic with impacts, stable, Hertz-valid, k_con <= analysis.soft_kcon); "
      << t.hertz_invalid << " of " << t.impacting << " cells with impacts beyond the Hertz limit\n";
  if (t.fragility_assessed > 0)
    out << "fragile        " << t.fragile << " of " << t.fragility_assessed
        << " cells assessed (a perturbation of the initial state ends on another attractor: the label is not an answer)\n";
  if (t.refine_levels > 0) write_refine_line(out, f, t);
  if (t.families) write_families_lines(out, *t.families);
  out << "regimes       ";
  for (const auto& [label, count] : t.regimes) out << " " << label << " " << count;
  out << "\n";
  if (t.classes.empty()) return;
  out << "speed         ";
  const char* sep = " ";
  for (const auto& [kind, cost] : t.classes) {
    out << sep << kind << " " << std::setprecision(3) << class_rate(cost) << " cells/s";
    sep = ", ";
  }
  out << " (one core: each kind's solved cells over their solve time)\n";
}

}  // namespace vibromap
