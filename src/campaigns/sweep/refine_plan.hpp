#pragma once
// Internal to the sweep campaign: the plan of an adaptive map (sweep.refine = L > 0, issue #30),
// on rank 0. The run is a sequence of phases (docs/design-refine.md):
//   0        the coarse points
//   1..L     the new points of the refined blocks of that level
//   L + 1    the audit: the inherited points audit_selects picks
//   then     the fill: every other point takes its source's values (no solve)
// Each phase's points are a function of the values recorded before it, so a resumed run that
// records what its map holds and replays the phases plans the same points.
//
// Memory (a first step, not yet the O(chunk) of design-refine.md): per fine point the refine
// quantities (8 bytes each) and two bytes (computed, level), plus one bit per block of each
// level and 8 bytes per point of the phase in progress: 8 F + 2 bytes a point, F the number of
// refine_on quantities (the default 4: 34 bytes, 340 MB for 10^7 points), and one bit a point
// for the progress lines' count of points known to be inherited.

#include <cstdint>
#include <vector>

#include "vibromap/core/grid.hpp"
#include "vibromap/core/quantities.hpp"
#include "vibromap/core/refine.hpp"
#include "vibromap/core/refine_compare.hpp"
#include "vibromap/io/map_file.hpp"

namespace vibromap::detail {

// The audit sample's seed: fixed, so that every run of a scene audits the same points.
constexpr std::uint64_t kRefineAuditSeed = 30;

class RefinePlan {
 public:
  RefinePlan(const std::vector<Axis>& coarse_axes, int levels, std::vector<RefineOn> on, double audit_fraction,
             bool speckle);

  const RefineGrid& grid() const { return grid_; }
  int levels() const { return grid_.levels(); }
  int audit_phase() const { return levels() + 1; }

  // The points of `phase` (0..audit_phase()), ascending; every earlier phase must be recorded whole.
  std::vector<std::uint64_t> plan(int phase);
  // Sets c.computed and c.level for the point `flat` solved in `phase`.
  void stamp(int phase, std::uint64_t flat, CellResult& c) const;
  // Keeps what the plan needs of a point stored (its computed and level set).
  void record(std::uint64_t flat, const CellResult& c);
  bool recorded(std::uint64_t flat) const { return computed_[static_cast<std::size_t>(flat)] >= 0; }
  // After the audit: writes every point not recorded with its source's values (computed 0);
  // `visit` sees each cell written.
  template <class Visit>
  void fill(MapWriter& writer, Visit visit);
  // The figures of the points recorded (the audit's mismatches compared in the refine quantities).
  RefineFigures figures() const;
  // For progress lines: points solved so far (audited too), and points known to be inherited
  // and not solved: outside every refined block of the last level planned (no later level
  // solves them), every point the levels left once the audit is planned, and those filled.
  std::uint64_t solved() const { return solved_; }
  std::uint64_t inferred() const { return inferred_; }

 private:
  bool differ(std::size_t a, std::size_t b) const;
  void decide_level(int level);
  PointDecision decide(std::size_t flat) const;
  void infer(int level);
  void fill_run(MapWriter& writer, std::uint64_t first, std::vector<CellResult>& run);
  const CellResult& source_cell(MapWriter& writer, std::uint64_t flat);

  RefineGrid grid_;
  std::vector<RefineOn> on_;
  double audit_fraction_;
  std::vector<double> values_;                // per point, on_.size() refine quantities
  std::vector<std::int8_t> computed_, level_;  // per point, -1: not recorded
  std::vector<std::vector<bool>> refined_;    // [l][block id], l = 1..L, once decided
  bool speckle_;
  std::vector<bool> whole_;                   // [level-1 block id]: solved whole (speckle), once level 1 is decided
  std::vector<std::pair<CellSpan, std::vector<CellResult>>> cache_;  // fill: chunks read
  std::vector<bool> inferred_bit_;            // per point: counted in inferred_
  std::uint64_t solved_ = 0, inferred_ = 0;
};

template <class Visit>
void RefinePlan::fill(MapWriter& writer, Visit visit) {
  std::vector<CellResult> run;
  std::uint64_t first = 0;
  const std::uint64_t n = grid_.fine_size();
  for (std::uint64_t p = 0; p < n; ++p) {
    if (recorded(p)) {
      for (const CellResult& c : run) visit(c);
      fill_run(writer, first, run);
      continue;
    }
    const PointDecision d = decide(static_cast<std::size_t>(p));
    if (run.empty()) first = p;
    CellResult c = source_cell(writer, d.source);
    c.computed = 0;
    c.level = static_cast<std::int8_t>(d.level);
    run.push_back(std::move(c));
    if (run.size() >= 4096) {
      for (const CellResult& r : run) visit(r);
      fill_run(writer, first, run);
    }
  }
  for (const CellResult& c : run) visit(c);
  fill_run(writer, first, run);
}

}  // namespace vibromap::detail
