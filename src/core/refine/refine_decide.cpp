// Which blocks are refined, who owns a new point, where an unsolved point inherits from, and
// the in-memory reference run (refine.hpp).
#include <array>
#include <stdexcept>

#include "vibromap/core/refine/refine.hpp"
#include "vibromap/core/refine/refine_stats.hpp"

namespace vibromap {

bool corners_differ(const RefineGrid& g, const RefineBlock& b, const PointsDiffer& differ,
                    std::vector<std::size_t>& scratch) {
  g.corners(b, scratch);
  for (std::size_t i = 0; i < scratch.size(); ++i)
    for (std::size_t j = i + 1; j < scratch.size(); ++j)
      if (differ(scratch[i], scratch[j])) return true;
  return false;
}

namespace {

// The lattice points of level 0 in b's closed level-1 cell and the cells touching it: per split
// axis up to 4 values (lo - s .. lo + 2 s, inside the grid), per unsplit axis b's own index.
struct Patch {
  std::array<std::array<std::size_t, 4>, kMaxRefineAxes> value{};
  std::array<std::size_t, kMaxRefineAxes> count{};
};

Patch patch_of(const RefineGrid& g, const RefineBlock& b) {
  Patch p;
  const std::size_t s = g.spacing(0);
  for (std::size_t d = 0; d < g.dims(); ++d) {
    if (!g.split(d)) {
      p.value[d][p.count[d]++] = b.lo[d];
      continue;
    }
    for (std::size_t k = 0; k < 4; ++k) {
      if (b.lo[d] + k * s < s) continue;  // lo - s below the grid
      const std::size_t x = b.lo[d] + k * s - s;
      if (x < g.fine_extent(d)) p.value[d][p.count[d]++] = x;
    }
  }
  return p;
}

// Some line of the patch along `axis` changes value at least twice (A B A, A B C).
bool changes_twice_along(const RefineGrid& g, const Patch& p, std::size_t axis, const PointsDiffer& differ) {
  std::array<std::size_t, kMaxRefineAxes> pos{};
  while (true) {
    GridIndex i{};
    for (std::size_t d = 0; d < g.dims(); ++d) i[d] = p.value[d][pos[d]];
    int changes = 0;
    std::size_t prev = g.ravel(i);
    for (std::size_t k = 1; k < p.count[axis]; ++k) {
      i[axis] = p.value[axis][k];
      const std::size_t here = g.ravel(i);
      if (differ(prev, here)) ++changes;
      prev = here;
    }
    if (changes >= 2) return true;
    bool advanced = false;  // the next line: an odometer over the other axes, last fastest
    for (std::size_t d = g.dims(); d-- > 0 && !advanced;) {
      if (d == axis) continue;
      if (++pos[d] < p.count[d]) {
        advanced = true;
      } else {
        pos[d] = 0;
      }
    }
    if (!advanced) return false;
  }
}

}  // namespace

bool speckled(const RefineGrid& g, const RefineBlock& b, const PointsDiffer& differ) {
  std::vector<std::size_t> scratch;
  if (!corners_differ(g, b, differ, scratch)) return false;
  const Patch p = patch_of(g, b);
  for (std::size_t d = 0; d < g.dims(); ++d)
    if (g.split(d) && !changes_twice_along(g, p, d, differ)) return false;
  return true;
}

bool solved_whole(const RefineGrid& g, const RefineBlock& b, const PointsDiffer& differ) {
  std::vector<RefineBlock> around;
  g.touching(b, around);
  for (const RefineBlock& n : around)
    if (speckled(g, n, differ)) return true;
  return false;
}

std::vector<bool> whole_blocks(const RefineGrid& g, const PointsDiffer& differ) {
  std::vector<bool> whole(g.block_count(1));
  std::vector<RefineBlock> around;
  for (std::size_t id = 0; id < whole.size(); ++id) {
    const RefineBlock b = g.block(1, id);
    if (!speckled(g, b, differ)) continue;
    g.touching(b, around);
    for (const RefineBlock& n : around) whole[g.block_id(n)] = true;
  }
  return whole;
}

bool block_is_refined(const RefineGrid& g, const RefineBlock& b, const PointsDiffer& differ, bool speckle) {
  std::vector<std::size_t> scratch;
  const BlockPredicate flagged = [&](const RefineBlock& c) { return corners_differ(g, c, differ, scratch); };
  if (speckle && solved_whole(g, g.ancestor(b, 1), differ)) return true;
  std::vector<RefineBlock> chain{b};
  while (chain.back().level > 1) chain.push_back(g.parent(chain.back()));
  for (auto it = chain.rbegin(); it != chain.rend(); ++it)
    if (!flagged(*it)) return false;
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
// `whole` (level-1 block ids solved whole) is made at level 1 and read below it.
void run_level(const RefineGrid& g, int l, const std::function<void(std::size_t)>& solve,
               const PointsDiffer& differ, RefineOutcome& out, std::vector<std::vector<char>>& refined,
               std::vector<bool>& whole) {
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
  if (l == 1 && !whole.empty()) {  // whole is sized when speckle is on
    whole = whole_blocks(g, differ);
    for (std::size_t id = 0; id < whole.size(); ++id)
      if (whole[id]) out.whole.push_back(id);
  }
  if (!whole.empty())
    for (std::size_t id : candidates)
      if (whole[g.block_id(g.ancestor(g.block(l, id), 1))]) flags[id] = 1;
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
  std::vector<bool> whole(options.speckle ? g.block_count(1) : 0);
  for (int l = 1; l <= g.levels(); ++l) run_level(g, l, solve, differ, out, refined, whole);
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
