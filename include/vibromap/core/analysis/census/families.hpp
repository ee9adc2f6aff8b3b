#pragma once
// Families of attractors across a census map: which attractor of one cell is the same motion as
// which attractor of the next (after Attractors.jl's global continuation, matched by state-space
// set distance, `MatchBySSSetDistance` with `match_sequentially!`, here over every axis of a grid).
//
// Matching. Two attractors of grid neighbours (cells one step apart along one axis) are
// compared by their stroboscopic sets in motion scales, each cell's own: (x1/L, x2/L,
// v1/(omega L), v2/(omega L)), L = max(D, lambda F0 / k1) (StateScale, point/shooting.hpp):
//   - two periodic attractors: the symmetric Hausdorff distance of their sets of period-start
//     states (the n states each, or as many as the map keeps), so a cyclic shift of the states
//     and a period doubling (a (1,1) beside the (2,2) born from it) cost nothing by themselves;
//   - two non-periodic attractors of the same regime kind: distance 0 (a census keeps no state of
//     a non-periodic set; census.hpp's same_attractor matches them the same way);
//   - a periodic one and a non-periodic one, or non-periodic ones of different kinds: never.
// Pairs below the threshold are matched one to one, greedily by increasing distance (ties by
// attractor index in the cell, then in the neighbour), as MatchBySSSetDistance does. A regime
// label plays no part: a matched pair whose regimes differ is a label change within a family.
//
// Labelling. FamilyLabeller takes the cells in flat (raster) order and joins matched attractors
// with a union-find over provisional labels (two-pass connected-component labelling): a node
// (cell, attractor) takes the label of a node it matches in an earlier neighbour, joins the
// labels of all it matches, or gets a new label. A family's id is then fixed by its first node in
// (cell, attractor) order, and ids are numbered densely in that order: they depend only on the
// map's contents, never on how (on how many ranks, in how many runs) the map was made. Memory is
// one slab of the grid (the cells one step back along the slowest axis) plus one entry per
// provisional label, never the whole map.

#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/analysis/point/regime.hpp"

namespace vibromap {

// One listed attractor of one cell, as the matching sees it.
struct FamilyNode {
  Regime regime;
  bool periodic = true;                 // false: compared by regime kind only
  bool soft = false;
  double fraction = 0.0;                // basin fraction, -
  std::vector<Eigen::Vector4d> points;  // periodic: period-start states in motion scales, -
};

// The flags of a node (bits of /family_flags).
inline constexpr std::int8_t kFamilyLabelChange = 1;  // its regime differs from a matched neighbour's
inline constexpr std::int8_t kFamilyEdge = 2;         // a computed neighbour along some axis has no node matched to it

// The distance of a and b (above); +infinity when they are never matched.
double family_distance(const FamilyNode& a, const FamilyNode& b);

// The matched pairs (index in a, index in b): greedy one to one by increasing distance, each
// below `threshold`.
std::vector<std::pair<int, int>> match_families(std::span<const FamilyNode> a, std::span<const FamilyNode> b,
                                                double threshold);

// What the family table holds of one family (ids dense, in order of first node).
struct FamilyRecord {
  std::vector<Regime> regimes;   // every regime its nodes have, in order of first appearance
  std::int64_t cells = 0;        // nodes (cells where it is listed; a cell counts once per node)
  std::int64_t soft_cells = 0;   // of those, nodes where it is soft
  double fraction_min = 1.0, fraction_max = 0.0;  // its basin fraction's range
  std::int64_t edge_cells = 0;   // nodes flagged kFamilyEdge: where it is born or dies
  std::int64_t label_changes = 0;  // matched neighbour pairs whose regimes differ
  std::uint64_t first_cell = 0;  // flat index of its first node (which fixes its id)
  int first_attractor = 0;       // that node's attractor index
  std::uint64_t last_cell = 0;   // flat index of its last node
};

class FamilyLabeller {
 public:
  // A cell whose nodes are final: flat index, one provisional label per node, its flags.
  using Emit = std::function<void(std::uint64_t cell, std::span<const std::int64_t> labels,
                                  std::span<const std::int8_t> flags)>;
  // shape: the grid's axis lengths, slowest first; threshold: the matching's, in motion scales.
  FamilyLabeller(std::vector<std::size_t> shape, double threshold, Emit emit);

  // The next cell in flat order (every cell of the grid, in order): its nodes, or done = false
  // for a cell not computed (it matches nothing and is nobody's edge).
  void add(std::uint64_t cell, std::vector<FamilyNode> nodes, bool done = true);
  // Emits the cells still held and resolves the labels: call once, after the last add.
  void finish();

  // After finish: a provisional label's family id (dense, 0-based).
  std::int32_t id(std::int64_t label) const;
  const std::vector<FamilyRecord>& families() const { return families_; }

 private:
  struct Cell {
    std::uint64_t index = 0;
    bool done = false;
    std::vector<FamilyNode> nodes;
    std::vector<std::int64_t> labels;
    std::vector<std::int8_t> flags;
  };
  struct Tally {  // a provisional label's share of its family's record
    FamilyRecord r;
    bool any = false;
  };
  std::int64_t find(std::int64_t label);
  void join(std::int64_t a, std::int64_t b);
  void match_neighbour(Cell& c, Cell& nb);
  void emit_front();

  std::vector<std::size_t> shape_;
  std::vector<std::uint64_t> stride_;
  double threshold_;
  Emit emit_;
  std::vector<Cell> window_;  // ring of the last stride_[0] + 1 cells
  std::uint64_t next_ = 0, emitted_ = 0;
  std::vector<std::int64_t> parent_;
  std::vector<Tally> tally_;
  std::vector<std::int64_t> changes_;  // per provisional label: label changes found at its nodes
  std::vector<std::int32_t> dense_;    // per provisional label, after finish
  std::vector<FamilyRecord> families_;
};

}  // namespace vibromap
