// Families of attractors across a census map: see families.hpp.

#include "vibromap/core/analysis/census/families.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

namespace vibromap {
namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();

// The largest distance from a point of a to the nearest point of b.
double directed_hausdorff(const std::vector<Eigen::Vector4d>& a, const std::vector<Eigen::Vector4d>& b) {
  double worst = 0.0;
  for (const Eigen::Vector4d& x : a) {
    double nearest = kNever;
    for (const Eigen::Vector4d& y : b) nearest = std::min(nearest, (x - y).norm());
    worst = std::max(worst, nearest);
  }
  return worst;
}

bool regime_less(const Regime& a, const Regime& b) {
  return std::tuple(static_cast<int>(a.kind), a.n, a.k) < std::tuple(static_cast<int>(b.kind), b.n, b.k);
}

void add_regime(std::vector<Regime>& list, const Regime& r) {
  const auto at = std::lower_bound(list.begin(), list.end(), r, regime_less);
  if (at == list.end() || !(*at == r)) list.insert(at, r);
}

// Adds b's figures to a (two provisional labels of one family).
void merge(FamilyRecord& a, const FamilyRecord& b) {
  for (const Regime& r : b.regimes) add_regime(a.regimes, r);
  a.cells += b.cells;
  a.soft_cells += b.soft_cells;
  a.fraction_min = std::min(a.fraction_min, b.fraction_min);
  a.fraction_max = std::max(a.fraction_max, b.fraction_max);
  a.edge_cells += b.edge_cells;
  a.label_changes += b.label_changes;
  if (b.first_cell < a.first_cell || (b.first_cell == a.first_cell && b.first_attractor < a.first_attractor)) {
    a.first_cell = b.first_cell;
    a.first_attractor = b.first_attractor;
  }
  a.last_cell = std::max(a.last_cell, b.last_cell);
}

}  // namespace

double family_distance(const FamilyNode& a, const FamilyNode& b) {
  if (a.periodic != b.periodic) return kNever;
  if (!a.periodic) return a.regime.kind == b.regime.kind ? 0.0 : kNever;
  if (a.points.empty() || b.points.empty()) return kNever;
  const double d = std::max(directed_hausdorff(a.points, b.points), directed_hausdorff(b.points, a.points));
  return std::isfinite(d) ? d : kNever;  // a NaN state matches nothing
}

std::vector<std::pair<int, int>> match_families(std::span<const FamilyNode> a, std::span<const FamilyNode> b,
                                                double threshold) {
  struct Pair {
    double d;
    int i, j;
  };
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      if (const double d = family_distance(a[i], b[j]); d < threshold)
        pairs.push_back({d, static_cast<int>(i), static_cast<int>(j)});
  std::sort(pairs.begin(), pairs.end(),
            [](const Pair& x, const Pair& y) { return std::tie(x.d, x.i, x.j) < std::tie(y.d, y.i, y.j); });
  std::vector<bool> used_a(a.size(), false), used_b(b.size(), false);
  std::vector<std::pair<int, int>> matched;
  for (const Pair& p : pairs) {
    if (used_a[static_cast<std::size_t>(p.i)] || used_b[static_cast<std::size_t>(p.j)]) continue;
    used_a[static_cast<std::size_t>(p.i)] = used_b[static_cast<std::size_t>(p.j)] = true;
    matched.emplace_back(p.i, p.j);
  }
  return matched;
}

FamilyLabeller::FamilyLabeller(std::vector<std::size_t> shape, double threshold, Emit emit)
    : shape_(std::move(shape)), stride_(shape_.size(), 1), threshold_(threshold), emit_(std::move(emit)) {
  for (std::size_t d = shape_.size(); d-- > 1;) stride_[d - 1] = stride_[d] * shape_[d];
  window_.resize(static_cast<std::size_t>((stride_.empty() ? 1 : stride_[0]) + 1));
}

std::int64_t FamilyLabeller::find(std::int64_t label) {
  while (parent_[static_cast<std::size_t>(label)] != label) {
    auto& p = parent_[static_cast<std::size_t>(label)];
    p = parent_[static_cast<std::size_t>(p)];  // path halving
    label = p;
  }
  return label;
}

// The smaller label stays the root: a family's root is the label of its first node.
void FamilyLabeller::join(std::int64_t a, std::int64_t b) {
  a = find(a);
  b = find(b);
  if (a == b) return;
  parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
}

// Matches cell c's nodes with those of its earlier neighbour nb: labels taken or joined, label
// changes counted, and the nodes of either left without a partner flagged as an edge.
void FamilyLabeller::match_neighbour(Cell& c, Cell& nb) {
  const auto pairs = match_families(c.nodes, nb.nodes, threshold_);
  std::vector<bool> matched_c(c.nodes.size(), false), matched_nb(nb.nodes.size(), false);
  for (const auto& [i, j] : pairs) {
    const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
    matched_c[ui] = matched_nb[uj] = true;
    if (c.labels[ui] < 0) {
      c.labels[ui] = find(nb.labels[uj]);
    } else {
      join(c.labels[ui], nb.labels[uj]);
    }
    if (!(c.nodes[ui].regime == nb.nodes[uj].regime)) {
      c.flags[ui] |= kFamilyLabelChange;
      nb.flags[uj] |= kFamilyLabelChange;
      ++tally_[static_cast<std::size_t>(nb.labels[uj])].r.label_changes;
    }
  }
  for (std::size_t i = 0; i < c.nodes.size(); ++i)
    if (!matched_c[i]) c.flags[i] |= kFamilyEdge;
  for (std::size_t j = 0; j < nb.nodes.size(); ++j)
    if (!matched_nb[j]) nb.flags[j] |= kFamilyEdge;
}

void FamilyLabeller::add(std::uint64_t cell, std::vector<FamilyNode> nodes, bool done) {
  if (cell != next_) throw std::logic_error("FamilyLabeller::add: cells must come in flat order");
  Cell& c = window_[static_cast<std::size_t>(cell % window_.size())];
  c.index = cell;
  c.done = done;
  c.nodes = done ? std::move(nodes) : std::vector<FamilyNode>{};
  c.labels.assign(c.nodes.size(), -1);
  c.flags.assign(c.nodes.size(), 0);
  if (done) {
    std::uint64_t rest = cell;
    for (std::size_t d = 0; d < shape_.size(); ++d) {  // the multi-index, slowest axis first
      const std::uint64_t at = rest / stride_[d];
      rest %= stride_[d];
      if (at == 0) continue;
      Cell& nb = window_[static_cast<std::size_t>((cell - stride_[d]) % window_.size())];
      if (nb.done) match_neighbour(c, nb);
    }
    for (std::int64_t& label : c.labels) {
      if (label >= 0) continue;
      label = static_cast<std::int64_t>(parent_.size());
      parent_.push_back(label);
      tally_.emplace_back();
    }
  }
  ++next_;
  if (next_ >= window_.size()) emit_front();
}

// Emits the oldest cell held: every neighbour after it has been matched with it.
void FamilyLabeller::emit_front() {
  Cell& c = window_[static_cast<std::size_t>(emitted_ % window_.size())];
  for (std::size_t i = 0; i < c.nodes.size(); ++i) {
    Tally& t = tally_[static_cast<std::size_t>(c.labels[i])];
    FamilyRecord& r = t.r;
    const FamilyNode& n = c.nodes[i];
    if (!t.any) {
      r.first_cell = c.index;
      r.first_attractor = static_cast<int>(i);
      t.any = true;
    }
    r.last_cell = c.index;
    add_regime(r.regimes, n.regime);
    ++r.cells;
    r.soft_cells += n.soft ? 1 : 0;
    r.fraction_min = std::min(r.fraction_min, n.fraction);
    r.fraction_max = std::max(r.fraction_max, n.fraction);
    r.edge_cells += (c.flags[i] & kFamilyEdge) ? 1 : 0;
  }
  emit_(c.index, c.labels, c.flags);
  c.nodes.clear();
  ++emitted_;
}

void FamilyLabeller::finish() {
  while (emitted_ < next_) emit_front();
  dense_.assign(parent_.size(), -1);
  for (std::size_t label = 0; label < parent_.size(); ++label) {
    const auto root = static_cast<std::size_t>(find(static_cast<std::int64_t>(label)));
    if (root == label) {
      dense_[label] = static_cast<std::int32_t>(families_.size());
      families_.push_back(tally_[label].r);
    } else {
      dense_[label] = dense_[root];  // root < label: numbered already
      merge(families_[static_cast<std::size_t>(dense_[label])], tally_[label].r);
    }
  }
}

std::int32_t FamilyLabeller::id(std::int64_t label) const {
  return label < 0 ? -1 : dense_[static_cast<std::size_t>(label)];
}

}  // namespace vibromap
