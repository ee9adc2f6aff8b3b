#pragma once
// Internal to the sweep campaign: the plan of an adaptive map (sweep.refine = L > 0),
// on rank 0. The run is a sequence of phases (docs/design-refine.md):
//   0        the coarse points
//   1..L     the new points of the refined blocks of that level
//   L + 1    the audit: the inherited points audit_selects picks
//   then     the fill: every other point takes its source's values (no solve)
// Each phase's points are a function of the values in the map before it, so a resumed run that
// replays the phases on its map plans the same points.
//
// Memory: O(chunk), as for a uniform map. The plan keeps one bit per block of each level (a
// level-l block holds 2^(R (L - l)) fine points or more, R refined axes: at most one bit per
// 2^R points at the last level) and which level-1 blocks are solved whole; the values it
// compares are read from the map a chunk at a time (the kCachedChunks used last), and whether a point belongs to a phase is computed from the bits when the
// farm asks (`pending`), never listed.

#include <cstdint>
#include <vector>

#include "vibromap/core/grid.hpp"
#include "vibromap/core/quantities.hpp"
#include "vibromap/core/refine/refine.hpp"
#include "vibromap/core/refine/refine_compare.hpp"
#include "vibromap/core/refine/refine_stats.hpp"
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

  // Decides `phase` (0..audit_phase(), in order): at a level, which of its blocks are refined,
  // reading the values of their corners from `writer` (every earlier phase must be in the map).
  void begin(int phase, MapWriter& writer);
  // The point `flat` is solved in `phase` (begun).
  bool in_phase(int phase, std::uint64_t flat) const;
  // How many points `phase` (begun) solves, done or not.
  std::uint64_t points_in(int phase) const;
  // Points a level after `phase` (begun) may still solve: those above its lattice inside a
  // refined block of its level (0 from the last level on).
  std::uint64_t open_after(int phase) const;
  // Sets c.computed and c.level for the point `flat` solved in `phase`.
  void stamp(int phase, std::uint64_t flat, CellResult& c) const;
  // After the audit: writes every point not done in the map that no phase solved with its
  // source's values (computed 0); `visit` sees each cell written.
  template <class Visit>
  void fill(MapWriter& writer, Visit visit);
  // The figures of a whole run (after the fill): points solved per level, inherited, audited
  // and the audit's mismatches compared in the refine quantities (read from the map).
  RefineFigures figures(MapWriter& writer);

 private:
  static constexpr std::size_t kCachedChunks = 16;
  bool differ(MapWriter& writer, std::size_t a, std::size_t b);
  void decide_level(int level, MapWriter& writer);
  PointDecision decide(std::size_t flat) const;
  const CellResult& cell(MapWriter& writer, std::uint64_t flat);

  RefineGrid grid_;
  std::vector<RefineOn> on_;
  double audit_fraction_;
  bool speckle_;
  std::vector<std::vector<bool>> refined_;    // [l][block id], l = 1..L, once decided
  std::vector<bool> whole_;                   // [level-1 block id]: solved whole (speckle), once level 1 is decided
  struct CachedChunk {
    CellSpan span;
    std::vector<CellResult> cells;
    std::uint64_t used = 0;  // clock_ at the last use
  };
  std::vector<CachedChunk> cache_;            // chunks read, at most kCachedChunks
  std::uint64_t clock_ = 0;
  std::vector<double> scratch_;               // differ: the first point's refine quantities
};

template <class Visit>
void RefinePlan::fill(MapWriter& writer, Visit visit) {
  std::vector<CellResult> run;
  std::uint64_t first = 0;
  const auto flush = [&] {
    if (run.empty()) return;
    writer.write(first, run);
    for (const CellResult& c : run) visit(c);
    run.clear();  // (the cache holds sources, solved points, which the fill never writes)
  };
  std::vector<CellSpan> spans;
  const std::uint64_t n = grid_.fine_size();
  for (std::uint64_t from = 0; from < n;) {
    spans.clear();
    from = writer.pending(from, 1 << 16, spans);
    for (const CellSpan& s : spans) {
      for (std::uint64_t p = s.begin; p < s.end; ++p) {
        const PointDecision d = decide(static_cast<std::size_t>(p));
        if (d.solved || audit_selects(kRefineAuditSeed, p, audit_fraction_)) continue;  // (done: the run is whole)
        if (!run.empty() && first + run.size() != p) flush();
        if (run.empty()) first = p;
        CellResult c = cell(writer, d.source);
        c.computed = 0;
        c.level = static_cast<std::int8_t>(d.level);
        run.push_back(std::move(c));
        if (run.size() >= 4096) flush();
      }
    }
  }
  flush();
}

}  // namespace vibromap::detail
