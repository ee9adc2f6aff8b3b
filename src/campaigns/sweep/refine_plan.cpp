#include "refine_plan.hpp"

#include <algorithm>
#include <stdexcept>

#include "vibromap/core/refine/refine_stats.hpp"

namespace vibromap::detail {

RefinePlan::RefinePlan(const std::vector<Axis>& coarse_axes, int levels, std::vector<RefineOn> on,
                       double audit_fraction, bool speckle)
    : grid_(coarse_axes, levels), on_(std::move(on)), audit_fraction_(audit_fraction), speckle_(speckle) {
  refined_.resize(static_cast<std::size_t>(levels) + 1);
}

const CellResult& RefinePlan::cell(MapWriter& writer, std::uint64_t flat) {
  ++clock_;
  for (CachedChunk& c : cache_) {
    if (flat >= c.span.begin && flat < c.span.end) {
      c.used = clock_;
      return c.cells[static_cast<std::size_t>(flat - c.span.begin)];
    }
  }
  // The plan's walks stay within a few hyperplanes of the map (a block's corners, its
  // neighbours', a point's source): the chunk used least recently is the one to drop.
  if (cache_.size() >= kCachedChunks)
    cache_.erase(std::min_element(cache_.begin(), cache_.end(),
                                  [](const CachedChunk& a, const CachedChunk& b) { return a.used < b.used; }));
  CachedChunk c;
  c.span = writer.read_chunk(flat, c.cells);
  c.used = clock_;
  if (flat < c.span.begin || flat >= c.span.end) throw std::logic_error("refine plan: the point's chunk is not read");
  cache_.push_back(std::move(c));
  return cache_.back().cells[static_cast<std::size_t>(flat - cache_.back().span.begin)];
}

bool RefinePlan::differ(MapWriter& writer, std::size_t a, std::size_t b) {
  const CellResult& ca = cell(writer, a);
  if (ca.computed < 1) throw std::logic_error("refine plan: a compared point is not solved");
  scratch_.resize(on_.size());
  for (std::size_t q = 0; q < on_.size(); ++q) scratch_[q] = refine_value(ca, on_[q].field);
  const CellResult& cb = cell(writer, b);  // (may evict ca's chunk: its values are copied)
  if (cb.computed < 1) throw std::logic_error("refine plan: a compared point is not solved");
  for (std::size_t q = 0; q < on_.size(); ++q) {
    if (values_differ(scratch_[q], refine_value(cb, on_[q].field), refine_field_is_class(on_[q].field), on_[q].rel))
      return true;
  }
  return false;
}

// Which candidate blocks of `level` are refined: every level-1 block is a candidate, at deeper
// levels the children of refined blocks. Their corners are solved points (earlier phases). A
// block inside a level-1 block solved whole (speckle, decided at level 1) is refined.
void RefinePlan::decide_level(int level, MapWriter& writer) {
  std::vector<bool>& bits = refined_[static_cast<std::size_t>(level)];
  bits.assign(grid_.block_count(level), false);
  const PointsDiffer d = [&](std::size_t a, std::size_t b) { return differ(writer, a, b); };
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

void RefinePlan::begin(int phase, MapWriter& writer) {
  cache_.clear();  // the map has changed since the last phase
  if (phase >= 1 && phase <= levels()) decide_level(phase, writer);
}

std::uint64_t RefinePlan::points_in(int phase) const {
  std::uint64_t n = 0;
  for (std::uint64_t p = 0; p < grid_.fine_size(); ++p) n += in_phase(phase, p) ? 1 : 0;
  return n;
}

std::uint64_t RefinePlan::open_after(int phase) const {
  if (phase >= levels()) return 0;
  const std::vector<bool>& bits = refined_[static_cast<std::size_t>(phase)];
  std::vector<RefineBlock> holders;
  std::uint64_t n = 0;
  for (std::size_t p = 0; p < grid_.fine_size(); ++p) {
    const GridIndex i = grid_.unravel(p);
    if (grid_.point_level(i) <= phase) continue;
    if (phase == 0) {  // every level-1 block is a candidate
      ++n;
      continue;
    }
    grid_.containing_blocks(phase, i, holders);
    if (std::any_of(holders.begin(), holders.end(), [&](const RefineBlock& b) { return bits[grid_.block_id(b)]; })) ++n;
  }
  return n;
}

bool RefinePlan::in_phase(int phase, std::uint64_t flat) const {
  const GridIndex i = grid_.unravel(static_cast<std::size_t>(flat));
  const int own = grid_.point_level(i);
  if (phase == 0) return own == 0;
  if (phase <= levels()) {
    if (own != phase) return false;
    std::vector<RefineBlock> holders;
    grid_.containing_blocks(phase, i, holders);
    const std::vector<bool>& bits = refined_[static_cast<std::size_t>(phase)];
    return std::any_of(holders.begin(), holders.end(), [&](const RefineBlock& b) { return bits[grid_.block_id(b)]; });
  }
  return audit_selects(kRefineAuditSeed, flat, audit_fraction_) && !decide(static_cast<std::size_t>(flat)).solved;
}

PointDecision RefinePlan::decide(std::size_t flat) const {
  const BlockPredicate refined = [this](const RefineBlock& b) {
    return refined_[static_cast<std::size_t>(b.level)][grid_.block_id(b)];
  };
  return decide_point(grid_, grid_.unravel(flat), refined);
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

RefineFigures RefinePlan::figures(MapWriter& writer) {
  cache_.clear();
  RefineFigures f;
  f.solved_per_level.assign(static_cast<std::size_t>(levels()) + 1, 0);
  for (std::size_t p = 0; p < grid_.fine_size(); ++p) {
    const PointDecision d = decide(p);
    if (d.solved) {
      ++f.solved_per_level[static_cast<std::size_t>(d.level)];
    } else if (audit_selects(kRefineAuditSeed, p, audit_fraction_)) {
      ++f.audited;
      if (differ(writer, p, d.source)) ++f.mismatches;
    } else {
      ++f.inherited;
    }
  }
  for (const std::uint64_t n : f.solved_per_level) f.solved += n;
  f.mismatch_bound = mismatch_upper_bound(f.mismatches, f.audited);
  f.whole_blocks = static_cast<std::uint64_t>(std::count(whole_.begin(), whole_.end(), true));
  return f;
}

}  // namespace vibromap::detail
