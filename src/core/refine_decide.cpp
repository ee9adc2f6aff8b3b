// Which blocks are refined, who owns a new point, where an unsolved point inherits from, and
// the in-memory reference run (refine.hpp).
#include <stdexcept>

#include "vibromap/core/refine.hpp"
#include "vibromap/core/refine_stats.hpp"

namespace vibromap {

bool corners_differ(const RefineGrid& g, const RefineBlock& b, const PointsDiffer& differ,
                    std::vector<std::size_t>& scratch) {
  g.corners(b, scratch);
  for (std::size_t i = 0; i < scratch.size(); ++i)
    for (std::size_t j = i + 1; j < scratch.size(); ++j)
      if (differ(scratch[i], scratch[j])) return true;
  return false;
}

bool block_is_refined(const RefineGrid& g, const RefineBlock& b, const PointsDiffer& differ) {
  std::vector<RefineBlock> chain{b};
  while (chain.back().level > 1) chain.push_back(g.parent(chain.back()));
  std::vector<std::size_t> scratch;
  for (auto it = chain.rbegin(); it != chain.rend(); ++it)
    if (!corners_differ(g, *it, differ, scratch)) return false;
  return true;
}

bool owns(const RefineGrid& g, const RefineBlock& b, const GridIndex& p, const BlockPredicate& refined) {
  std::vector<RefineBlock> holders;
  g.containing_blocks(b.level, p, holders);
  for (const RefineBlock& h : holders) {  // ascending id: the first refined one owns p
    if (h == b) return true;
    if (refined(h)) return false;
  }
  return false;  // b does not hold p
}

PointDecision decide_point(const RefineGrid& g, const GridIndex& p, const BlockPredicate& refined) {
  const int own = g.point_level(p);
  if (own == 0) return {true, 0, g.ravel(p)};
  std::vector<RefineBlock> set, next, kids;
  g.containing_blocks(1, p, set);
  for (int l = 1; l <= g.levels(); ++l) {
    next.clear();
    for (const RefineBlock& b : set) {
      if (!refined(b)) continue;
      if (own == l) return {true, l, g.ravel(p)};
      g.children(b, kids);
      for (const RefineBlock& k : kids)
        if (g.contains(k, p)) next.push_back(k);
    }
    // No candidate holding p is refined: its nearest corner is the same in each of them (p
    // lies on their shared faces, where the nearer end on those axes is p's own index).
    if (next.empty()) return {false, l, g.nearest_corner(set.front(), p)};
    set.swap(next);
  }
  throw std::logic_error("decide_point: a refined block of the last level holds an unsolved point");
}

namespace {

// Level l of the reference run: decides the candidates, solves the points refined blocks own.
void run_level(const RefineGrid& g, int l, const std::function<void(std::size_t)>& solve,
               const PointsDiffer& differ, RefineOutcome& out, std::vector<std::vector<char>>& refined) {
  std::vector<std::size_t> candidates, scratch, fresh;
  if (l == 1) {
    for (std::size_t id = 0; id < g.block_count(1); ++id) candidates.push_back(id);
  } else {
    std::vector<RefineBlock> kids;
    for (std::size_t id : out.refined_blocks[static_cast<std::size_t>(l - 1)]) {
      g.children(g.block(l - 1, id), kids);
      for (const RefineBlock& k : kids) candidates.push_back(g.block_id(k));
    }
  }
  auto& flags = refined[static_cast<std::size_t>(l)];
  flags.assign(g.block_count(l), 0);
  auto& ids = out.refined_blocks[static_cast<std::size_t>(l)];
  for (std::size_t id : candidates)
    if (corners_differ(g, g.block(l, id), differ, scratch)) flags[id] = 1;
  for (std::size_t id = 0; id < flags.size(); ++id)
    if (flags[id]) ids.push_back(id);
  const BlockPredicate is_refined = [&](const RefineBlock& b) { return flags[g.block_id(b)] != 0; };
  for (std::size_t id : ids) {
    const RefineBlock b = g.block(l, id);
    g.new_points(b, fresh);
    for (std::size_t p : fresh) {
      if (!owns(g, b, g.unravel(p), is_refined)) continue;
      solve(p);
      out.computed[p] = 1;
      ++out.solved_per_level[static_cast<std::size_t>(l)];
    }
  }
  out.refined_per_level[static_cast<std::size_t>(l)] = ids.size();
}

}  // namespace

RefineOutcome refine_in_memory(const RefineGrid& g, const std::function<void(std::size_t)>& solve,
                               const PointsDiffer& differ, const RefineOptions& options) {
  const auto levels = static_cast<std::size_t>(g.levels());
  RefineOutcome out;
  out.computed.assign(g.fine_size(), 0);
  out.decision.assign(g.fine_size(), {});
  out.solved_per_level.assign(levels + 1, 0);
  out.refined_per_level.assign(levels + 1, 0);
  out.refined_blocks.assign(levels + 1, {});
  std::size_t coarse = 1;
  for (std::size_t d = 0; d < g.dims(); ++d) coarse *= g.coarse_extent(d);
  for (std::size_t c = 0; c < coarse; ++c) {
    const std::size_t p = g.coarse_to_fine(c);
    solve(p);
    out.computed[p] = 1;
  }
  out.solved_per_level[0] = coarse;
  std::vector<std::vector<char>> refined(levels + 1);
  for (int l = 1; l <= g.levels(); ++l) run_level(g, l, solve, differ, out, refined);
  const BlockPredicate is_refined = [&](const RefineBlock& b) {
    return refined[static_cast<std::size_t>(b.level)][g.block_id(b)] != 0;
  };
  for (std::size_t p = 0; p < g.fine_size(); ++p) {
    out.decision[p] = decide_point(g, g.unravel(p), is_refined);
    if (out.decision[p].solved || !audit_selects(options.audit_seed, p, options.audit_fraction)) continue;
    solve(p);
    out.computed[p] = 2;
    ++out.audited;
    if (differ(p, out.decision[p].source)) ++out.mismatches;
  }
  return out;
}

}  // namespace vibromap
