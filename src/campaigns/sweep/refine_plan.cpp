#include "refine_plan.hpp"

#include <algorithm>
#include <stdexcept>

#include "vibromap/core/refine_stats.hpp"

namespace vibromap::detail {

RefinePlan::RefinePlan(const std::vector<Axis>& coarse_axes, int levels, std::vector<RefineOn> on,
                       double audit_fraction, bool speckle)
    : grid_(coarse_axes, levels), on_(std::move(on)), audit_fraction_(audit_fraction), speckle_(speckle) {
  const std::size_t n = grid_.fine_size();
  values_.assign(n * on_.size(), 0.0);
  computed_.assign(n, -1);
  level_.assign(n, -1);
  inferred_bit_.assign(n, false);
  refined_.resize(static_cast<std::size_t>(levels) + 1);
}

bool RefinePlan::differ(std::size_t a, std::size_t b) const {
  const std::size_t f = on_.size();
  for (std::size_t q = 0; q < f; ++q) {
    if (values_differ(values_[a * f + q], values_[b * f + q], refine_field_is_class(on_[q].field), on_[q].rel))
      return true;
  }
  return false;
}

void RefinePlan::record(std::uint64_t flat, const CellResult& c) {
  const auto p = static_cast<std::size_t>(flat);
  const std::size_t f = on_.size();
  for (std::size_t q = 0; q < f; ++q) values_[p * f + q] = refine_value(c, on_[q].field);
  if (c.computed >= 1 && computed_[p] < 1) ++solved_;
  if (c.computed >= 0 && (c.computed >= 1) == inferred_bit_[p]) {  // audited after counted as inferred, or filled
    inferred_bit_[p] = !inferred_bit_[p];
    inferred_ = inferred_bit_[p] ? inferred_ + 1 : inferred_ - 1;
  }
  computed_[p] = c.computed;
  level_[p] = c.level;
}

// Which candidate blocks of `level` are refined: every level-1 block is a candidate, at deeper
// levels the children of refined blocks. Their corners are solved points (earlier phases). A
// block inside a level-1 block solved whole (speckle, decided at level 1) is refined.
void RefinePlan::decide_level(int level) {
  std::vector<bool>& bits = refined_[static_cast<std::size_t>(level)];
  bits.assign(grid_.block_count(level), false);
  const PointsDiffer d = [this](std::size_t a, std::size_t b) {
    if (computed_[a] < 1 || computed_[b] < 1) throw std::logic_error("refine plan: a corner is not solved");
    return differ(a, b);
  };
  std::vector<std::size_t> scratch;
  const auto consider = [&](const RefineBlock& b) {
    const bool whole = !whole_.empty() && whole_[grid_.block_id(grid_.ancestor(b, 1))];
    if (whole || corners_differ(grid_, b, d, scratch)) bits[grid_.block_id(b)] = true;
  };
  if (level == 1) {
    for (std::size_t id = 0; id < bits.size(); ++id) consider(grid_.block(1, id));
    if (!speckle_) return;
    whole_ = whole_blocks(grid_, d);
    for (std::size_t id = 0; id < bits.size(); ++id) bits[id] = bits[id] || whole_[id];
    return;
  }
  const std::vector<bool>& parents = refined_[static_cast<std::size_t>(level) - 1];
  std::vector<RefineBlock> children;
  for (std::size_t id = 0; id < parents.size(); ++id) {
    if (!parents[id]) continue;
    grid_.children(grid_.block(level - 1, id), children);
    for (const RefineBlock& c : children) consider(c);
  }
}

// Counts the points not recorded that no level after `level` can solve: those outside every
// refined block of `level` (the candidates of level + 1 are their children, as decide_level
// says), or every one when `level` is the audit's. Progress lines only: the plan never reads it.
void RefinePlan::infer(int level) {
  std::vector<RefineBlock> around;
  const std::vector<bool>* bits = level <= levels() ? &refined_[static_cast<std::size_t>(level)] : nullptr;
  for (std::size_t p = 0; p < computed_.size(); ++p) {
    if (computed_[p] >= 0 || inferred_bit_[p]) continue;
    if (bits) {
      grid_.containing_blocks(level, grid_.unravel(p), around);
      if (std::any_of(around.begin(), around.end(), [&](const RefineBlock& b) { return (*bits)[grid_.block_id(b)]; }))
        continue;
    }
    inferred_bit_[p] = true;
    ++inferred_;
  }
}

PointDecision RefinePlan::decide(std::size_t flat) const {
  const BlockPredicate refined = [this](const RefineBlock& b) {
    return refined_[static_cast<std::size_t>(b.level)][grid_.block_id(b)];
  };
  return decide_point(grid_, grid_.unravel(flat), refined);
}

std::vector<std::uint64_t> RefinePlan::plan(int phase) {
  std::vector<std::uint64_t> points;
  if (phase == 0) {
    std::size_t coarse = 1;
    for (std::size_t d = 0; d < grid_.dims(); ++d) coarse *= grid_.coarse_extent(d);
    for (std::size_t i = 0; i < coarse; ++i) points.push_back(grid_.coarse_to_fine(i));
    return points;
  }
  if (phase <= levels()) {
    decide_level(phase);
    infer(phase);
    const std::vector<bool>& bits = refined_[static_cast<std::size_t>(phase)];
    std::vector<std::size_t> fresh;
    for (std::size_t id = 0; id < bits.size(); ++id) {
      if (!bits[id]) continue;
      grid_.new_points(grid_.block(phase, id), fresh);
      points.insert(points.end(), fresh.begin(), fresh.end());
    }
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    return points;
  }
  // The audit: the points the levels did not solve (inherited, filled or audited already).
  infer(phase);
  for (std::size_t p = 0; p < computed_.size(); ++p)
    if (computed_[p] != 1 && audit_selects(kRefineAuditSeed, p, audit_fraction_)) points.push_back(p);
  return points;
}

void RefinePlan::stamp(int phase, std::uint64_t flat, CellResult& c) const {
  if (phase <= levels()) {
    c.computed = 1;
    c.level = static_cast<std::int8_t>(phase);
    return;
  }
  c.computed = 2;
  c.level = static_cast<std::int8_t>(decide(static_cast<std::size_t>(flat)).level);
}

const CellResult& RefinePlan::source_cell(MapWriter& writer, std::uint64_t flat) {
  for (const auto& [span, cells] : cache_)
    if (flat >= span.begin && flat < span.end) return cells[static_cast<std::size_t>(flat - span.begin)];
  // Sources lie within a coarse cell of the points that need them, which the fill walks in
  // order: the chunk of least index is the one no longer needed.
  if (cache_.size() >= 16) cache_.erase(cache_.begin());
  std::vector<CellResult> cells;
  const CellSpan span = writer.read_chunk(flat, cells);
  cache_.emplace_back(span, std::move(cells));
  std::sort(cache_.begin(), cache_.end(), [](const auto& a, const auto& b) { return a.first.begin < b.first.begin; });
  for (const auto& [s, c] : cache_)
    if (flat >= s.begin && flat < s.end) return c[static_cast<std::size_t>(flat - s.begin)];
  throw std::logic_error("refine plan: the source's chunk is not read");
}

void RefinePlan::fill_run(MapWriter& writer, std::uint64_t first, std::vector<CellResult>& run) {
  if (run.empty()) return;
  writer.write(first, run);
  for (std::size_t k = 0; k < run.size(); ++k) record(first + k, run[k]);
  run.clear();  // (the cache holds sources, solved points, which the fill never writes)
}

RefineFigures RefinePlan::figures() const {
  RefineFigures f;
  f.solved_per_level.assign(static_cast<std::size_t>(levels()) + 1, 0);
  for (std::size_t p = 0; p < computed_.size(); ++p) {
    switch (computed_[p]) {
      case 1:
        ++f.solved;
        ++f.solved_per_level[static_cast<std::size_t>(std::max<int>(0, level_[p]))];
        break;
      case 0: ++f.inherited; break;
      case 2:
        ++f.audited;
        if (differ(p, decide(p).source)) ++f.mismatches;
        break;
      default: break;
    }
  }
  f.mismatch_bound = mismatch_upper_bound(f.mismatches, f.audited);
  f.whole_blocks = static_cast<std::uint64_t>(std::count(whole_.begin(), whole_.end(), true));
  return f;
}

}  // namespace vibromap::detail
