#pragma once
// Adaptive refinement of a map: the index arithmetic of the fine grid, the blocks
// of each level, which blocks are refined, the points a refined block adds, and which solved
// point an unsolved point inherits from. Pure functions of indices and of a "two solved points
// differ" predicate: no values, no I/O, no ranks (the farm wires them in).
//
// The scheme. The axes given are the coarse grid. With L levels an axis of n points becomes
// (n - 1) 2^L + 1 fine points, coarse point i at fine index i 2^L (refine_axis: the same
// double, bit for bit). Axes that are categorical or have one point are not refined (their
// fine extent is n). In fine index units the level-l lattice has spacing s_l = 2^(L - l) on
// every refined axis: level 0 is the coarse grid, level L every fine point. A point's level is
// the least l whose lattice holds it.
//
//   Block of level l (1 <= l <= L): a cell of the level-(l-1) lattice, named by its lowest
//   corner `lo` (a multiple of s_{l-1} on each refined axis; any index on an unrefined axis,
//   which a block never spans, so nothing is compared across categories). Its 2^R corners
//   (R refined axes) are level-(l-1) points; its new points are the 3^R - 2^R level-l points of
//   the closed cell that are not corners. Blocks of level l tile those of level l - 1: each
//   level-l block lies in exactly one level-(l-1) block, its parent.
//
//   Candidate: every level-1 block; at l > 1 the children of refined level-(l-1) blocks. The
//   corners of a candidate are solved points (by induction).
//   Flagged: a candidate whose corners are not all alike, i.e. some pair of corners differs
//   (within a cell every pair of corners are neighbours, diagonals included).
//   Speckled: a flagged level-1 block around which the answer changes twice along every
//   axis: on each split axis some line of the coarse points of the block and the blocks
//   touching it (up to 4 points a line) changes value at least twice (A B A, A B C). A flat
//   edge, a hyperplane on the scale of those 3 cells, is crossed at most once by any straight
//   line, so it never trips this in any number of axes; structure finer than the coarse grid
//   in every direction (speckle, islands and bands narrower than 3 cells) does. There a block
//   whose corners agree can hide points of another class, which corners alone never see. A
//   speckled block and every block touching it are solved whole: all their descendants are
//   refined, so every fine point in them is solved (RefineOptions::speckle; on by default).
//   Refined: a flagged candidate, or any block inside one solved whole. A refined block
//   has its new points solved. A new point on a face shared by refined blocks is solved once:
//   it is owned by the containing refined block of least id (`owns`).
//   Inherited: a fine point never solved takes the values of the nearest corner of the deepest
//   candidate block that holds it (that block is not refined); per axis the nearer end, the
//   lower one on a tie, which is the nearest corner of least flat index. Points solved on a
//   face by a refined neighbour are not used: a point's source is a function of its own
//   block, so inheritance is local and needs no neighbour's result.
//
// Why it streams (memory O(block frontier), not O(fine grid)). A block's decision reads only
// its 2^R corners and, for candidacy, its ancestors' corners (all inside its closed level-1
// block); ownership of a new point reads the decisions of the <= 2^R blocks of the same level
// that hold it (its face neighbours). Walking the blocks of a level in id order (first axis
// slowest), the blocks with first-axis cell c touch only the fine hyperplanes c s and (c + 1) s
// of the first refined axis, and ownership looks back one slab. So a level can be planned slab
// by slab keeping two hyperplanes of solved values and one slab of decisions; inheritance
// (`decide_point`) likewise needs, for a chunk of fine points, the decisions of the blocks
// around the chunk only. refine_in_memory below is the reference that keeps everything (for
// tests and small maps); docs/design-refine.md says how the farm runs a level.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "vibromap/core/grid.hpp"

namespace vibromap {

inline constexpr std::size_t kMaxRefineAxes = 16;
inline constexpr int kMaxRefineLevels = 20;
// A fine-grid multi-index (entries past dims() are 0).
using GridIndex = std::array<std::size_t, kMaxRefineAxes>;

// (n - 1) 2^levels + 1 for n >= 2; n for n <= 1. Throws std::invalid_argument for levels
// outside [0, kMaxRefineLevels] or when the result does not fit a std::size_t.
std::size_t refined_extent(std::size_t n, int levels);
// True when refinement splits the axis: not categorical and at least two points.
bool axis_is_refined(const Axis& a);
// The axis with its fine points: coarse point i is values[i << levels] (the same double), and
// between coarse points a and b the fine point r of 2^levels is a + f (b - a) (lin) or
// exp(log a + f (log b - log a)) (log), f = r / 2^levels. An axis refinement does not split is
// returned unchanged. Throws std::invalid_argument (naming the axis) when the values of a split
// axis are not strictly monotone.
Axis refine_axis(const Axis& a, int levels);

// A block of level `level`, by the fine index of its lowest corner.
struct RefineBlock {
  int level = 0;
  GridIndex lo{};
  bool operator==(const RefineBlock&) const = default;
};

class RefineGrid {
 public:
  // coarse_shape[d] points on axis d, split when split[d] (and coarse_shape[d] >= 2).
  // Throws std::invalid_argument for no axes or more than kMaxRefineAxes, an empty axis, a bad
  // level count, or a fine grid whose size does not fit a std::size_t.
  RefineGrid(std::vector<std::size_t> coarse_shape, std::vector<bool> split, int levels);
  // The coarse axes of a map: split as axis_is_refined says.
  RefineGrid(const std::vector<Axis>& coarse_axes, int levels);

  int levels() const { return levels_; }
  std::size_t dims() const { return coarse_.size(); }
  std::size_t refined_dims() const { return refined_dims_; }
  bool split(std::size_t d) const { return split_[d]; }
  std::size_t coarse_extent(std::size_t d) const { return coarse_[d]; }
  std::size_t fine_extent(std::size_t d) const { return fine_[d]; }
  std::size_t fine_size() const { return fine_size_; }
  std::vector<std::size_t> fine_shape() const { return fine_; }

  // Row-major (first axis slowest) flat index of the fine grid, and its inverse.
  std::size_t ravel(const GridIndex& i) const;
  GridIndex unravel(std::size_t flat) const;
  // Lattice spacing of level l in fine steps on a split axis: 2^(L - l).
  std::size_t spacing(int level) const { return std::size_t{1} << (levels_ - level); }
  // The least level whose lattice holds the point (0: a coarse point).
  int point_level(const GridIndex& i) const;
  // The fine flat index of coarse point `coarse_flat` (row-major over the coarse shape).
  std::size_t coarse_to_fine(std::size_t coarse_flat) const;

  // Blocks of level l in [1, levels()], with ids 0 .. block_count(l) - 1 row-major over cells.
  std::size_t block_count(int level) const;
  std::size_t block_id(const RefineBlock& b) const;
  RefineBlock block(int level, std::size_t id) const;
  bool contains(const RefineBlock& b, const GridIndex& p) const;  // the closed cell
  // Fine flat indices, ascending (`out` is cleared first).
  void corners(const RefineBlock& b, std::vector<std::size_t>& out) const;
  void new_points(const RefineBlock& b, std::vector<std::size_t>& out) const;
  // The 2^R blocks of level + 1 inside b, ascending id (none when b.level == levels()).
  void children(const RefineBlock& b, std::vector<RefineBlock>& out) const;
  RefineBlock parent(const RefineBlock& b) const;  // b.level >= 2
  RefineBlock ancestor(const RefineBlock& b, int level) const;  // the block of `level` <= b.level holding b
  // The blocks of level l whose closed cell holds p, ascending id (1 to 2^R of them).
  void containing_blocks(int level, const GridIndex& p, std::vector<RefineBlock>& out) const;
  // The blocks of b's level whose closed cells share a point with b's, b included, ascending id
  // (3^R of them inside the grid; never across an unsplit axis).
  void touching(const RefineBlock& b, std::vector<RefineBlock>& out) const;
  // The corner of b nearest to p (p in b): per split axis the nearer end, the lower on a tie.
  std::size_t nearest_corner(const RefineBlock& b, const GridIndex& p) const;

 private:
  std::size_t cells(int level, std::size_t d) const;  // cells of block level `level` on axis d
  std::vector<std::size_t> coarse_, fine_;
  std::vector<bool> split_;
  std::size_t refined_dims_ = 0, fine_size_ = 1;
  int levels_ = 0;
};

// Do two solved points (fine flat indices) differ in the refinement quantities?
using PointsDiffer = std::function<bool(std::size_t, std::size_t)>;
// Is a block refined (a candidate whose corners differ)?
using BlockPredicate = std::function<bool(const RefineBlock&)>;

// Some pair of b's corners differ. `scratch` holds the corners (reused to spare allocations).
bool corners_differ(const RefineGrid& g, const RefineBlock& b, const PointsDiffer& differ,
                    std::vector<std::size_t>& scratch);
// The level-1 block b is speckled (above). Reads the coarse points of b and the blocks touching it.
bool speckled(const RefineGrid& g, const RefineBlock& b, const PointsDiffer& differ);
// The level-1 block b is solved whole: it or a block touching it is speckled.
bool solved_whole(const RefineGrid& g, const RefineBlock& b, const PointsDiffer& differ);
// solved_whole for every level-1 block (block id order), once the coarse points are solved.
std::vector<bool> whole_blocks(const RefineGrid& g, const PointsDiffer& differ);
// b is refined: with `speckle`, its level-1 ancestor is solved whole; else (or also) its
// ancestors (level 1 first) and b itself all have corners that differ. Calls `differ` only on
// solved points (it stops at the first ancestor that is not refined).
bool block_is_refined(const RefineGrid& g, const RefineBlock& b, const PointsDiffer& differ, bool speckle = true);
// The refined block b owns its new point p: no refined block of b's level with a smaller id
// holds p.
bool owns(const RefineGrid& g, const RefineBlock& b, const GridIndex& p, const BlockPredicate& refined);

// How a fine point got its values: solved at `level`, or inherited at `level` (the level of
// the candidate block that decided it) from the solved point `source` (== the point if solved).
struct PointDecision {
  bool solved = false;
  int level = 0;
  std::size_t source = 0;
  bool operator==(const PointDecision&) const = default;
};
// Walks p's candidate blocks from level 1 down; `refined` is asked only about candidates.
PointDecision decide_point(const RefineGrid& g, const GridIndex& p, const BlockPredicate& refined);

// The reference run, everything in memory (O(fine grid)): solves the coarse points, then
// level by level the points refined blocks own, then (audit_fraction > 0) the inherited
// points audit_selects picks, and fills in every decision. `solve(p)` must make point p
// comparable by `differ`; an audited point is solved and compared with its source.
struct RefineOptions {
  double audit_fraction = 0.0;  // [0, 1]
  std::uint64_t audit_seed = 0;
  bool speckle = true;          // speckled level-1 blocks and their touching ones solved whole
};
struct RefineOutcome {
  std::vector<std::int8_t> computed;              // per fine point: 1 solved, 0 inherited, 2 audited
  std::vector<PointDecision> decision;            // per fine point (an audited point: its inherited decision)
  std::vector<std::size_t> solved_per_level;      // [0..L]: points solved at each level
  std::vector<std::size_t> refined_per_level;     // [0..L]: refined blocks (index 0 unused: 0)
  std::vector<std::vector<std::size_t>> refined_blocks;  // [l]: ids of the refined blocks of level l
  std::vector<std::size_t> whole;                 // ids of the level-1 blocks solved whole (speckle)
  std::size_t audited = 0, mismatches = 0;
};
RefineOutcome refine_in_memory(const RefineGrid& g, const std::function<void(std::size_t)>& solve,
                               const PointsDiffer& differ, const RefineOptions& options = {});

}  // namespace vibromap
