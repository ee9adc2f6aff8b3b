#include "vibromap/core/refine/refine.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "vibromap/core/refine/refine_stats.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap {

namespace {

void check_levels(int levels) {
  if (levels < 0 || levels > kMaxRefineLevels)
    throw std::invalid_argument(cat("refinement levels ", std::to_string(levels), " outside [0, ",
                                    std::to_string(kMaxRefineLevels), "]"));
}

std::vector<bool> split_of(const std::vector<Axis>& axes) {
  std::vector<bool> s;
  for (const Axis& a : axes) s.push_back(axis_is_refined(a));
  return s;
}

std::vector<std::size_t> shape_of(const std::vector<Axis>& axes) {
  std::vector<std::size_t> s;
  for (const Axis& a : axes) s.push_back(a.values.size());
  return s;
}

bool strictly_monotone(const std::vector<double>& v) {
  bool up = true, down = true;
  for (std::size_t i = 1; i < v.size(); ++i) {
    up = up && v[i] > v[i - 1];
    down = down && v[i] < v[i - 1];
  }
  return up || down;
}

// Odometer over per-axis option lists (last axis fastest): calls f(index) for each
// combination, in ascending flat order when each list is ascending.
template <class F>
void for_each_combination(std::size_t dims, const std::array<std::array<std::size_t, 3>, kMaxRefineAxes>& opt,
                          const std::array<std::size_t, kMaxRefineAxes>& count, F&& f) {
  std::array<std::size_t, kMaxRefineAxes> pos{};
  GridIndex idx{};
  for (std::size_t d = 0; d < dims; ++d) idx[d] = opt[d][0];
  while (true) {
    f(idx);
    std::size_t d = dims;
    while (d > 0) {
      --d;
      if (++pos[d] < count[d]) {
        idx[d] = opt[d][pos[d]];
        break;
      }
      pos[d] = 0;
      idx[d] = opt[d][0];
      if (d == 0) return;
    }
  }
}

}  // namespace

std::size_t refined_extent(std::size_t n, int levels) {
  check_levels(levels);
  if (n <= 1) return n;
  const std::size_t factor = std::size_t{1} << levels;
  if (n - 1 > (std::numeric_limits<std::size_t>::max() - 1) / factor)
    throw std::invalid_argument("a refined axis has more points than an index can count");
  return (n - 1) * factor + 1;
}

bool axis_is_refined(const Axis& a) { return a.categories.empty() && a.values.size() >= 2; }

Axis refine_axis(const Axis& a, int levels) {
  check_levels(levels);
  if (!axis_is_refined(a) || levels == 0) return a;
  if (!strictly_monotone(a.values))
    throw std::invalid_argument(cat("axis ", a.name, ": refinement needs strictly increasing or decreasing values"));
  Axis fine = a;
  const std::size_t m = std::size_t{1} << levels;
  fine.values.assign(refined_extent(a.values.size(), levels), 0.0);
  for (std::size_t i = 0; i + 1 < a.values.size(); ++i) {
    const double lo = a.values[i], hi = a.values[i + 1];
    fine.values[i * m] = lo;
    for (std::size_t r = 1; r < m; ++r) {
      const double f = static_cast<double>(r) / static_cast<double>(m);
      fine.values[i * m + r] = a.scale == AxisScale::log ? std::exp(std::log(lo) + f * (std::log(hi) - std::log(lo)))
                                                          : lo + f * (hi - lo);
    }
  }
  fine.values.back() = a.values.back();
  return fine;
}

RefineGrid::RefineGrid(std::vector<std::size_t> coarse_shape, std::vector<bool> split, int levels)
    : coarse_(std::move(coarse_shape)), split_(std::move(split)), levels_(levels) {
  check_levels(levels);
  if (coarse_.empty() || coarse_.size() > kMaxRefineAxes || split_.size() != coarse_.size())
    throw std::invalid_argument(cat("a refined grid needs 1 to ", std::to_string(kMaxRefineAxes),
                                    " axes, each with its split flag"));
  for (std::size_t d = 0; d < coarse_.size(); ++d) {
    if (coarse_[d] == 0) throw std::invalid_argument("a refined grid has an axis without points");
    split_[d] = split_[d] && coarse_[d] >= 2;
    refined_dims_ += split_[d] ? 1 : 0;
    fine_.push_back(split_[d] ? refined_extent(coarse_[d], levels) : coarse_[d]);
    if (fine_size_ > std::numeric_limits<std::size_t>::max() / fine_.back())
      throw std::invalid_argument("the refined grid has more points than a flat index can count");
    fine_size_ *= fine_.back();
  }
}

RefineGrid::RefineGrid(const std::vector<Axis>& coarse_axes, int levels)
    : RefineGrid(shape_of(coarse_axes), split_of(coarse_axes), levels) {}

std::size_t RefineGrid::ravel(const GridIndex& i) const {
  std::size_t flat = 0;
  for (std::size_t d = 0; d < dims(); ++d) flat = flat * fine_[d] + i[d];
  return flat;
}

GridIndex RefineGrid::unravel(std::size_t flat) const {
  GridIndex i{};
  for (std::size_t d = dims(); d-- > 0;) {
    i[d] = flat % fine_[d];
    flat /= fine_[d];
  }
  return i;
}

int RefineGrid::point_level(const GridIndex& i) const {
  for (int l = 0; l < levels_; ++l) {
    bool on = true;
    for (std::size_t d = 0; d < dims() && on; ++d) on = !split_[d] || i[d] % spacing(l) == 0;
    if (on) return l;
  }
  return levels_;
}

std::size_t RefineGrid::coarse_to_fine(std::size_t coarse_flat) const {
  GridIndex i{};
  for (std::size_t d = dims(); d-- > 0;) {
    i[d] = coarse_flat % coarse_[d] * (split_[d] ? spacing(0) : 1);
    coarse_flat /= coarse_[d];
  }
  return ravel(i);
}

std::size_t RefineGrid::cells(int level, std::size_t d) const {
  return split_[d] ? (coarse_[d] - 1) << (level - 1) : coarse_[d];
}

std::size_t RefineGrid::block_count(int level) const {
  if (level < 1 || level > levels_ || refined_dims_ == 0) return 0;
  std::size_t n = 1;
  for (std::size_t d = 0; d < dims(); ++d) n *= cells(level, d);
  return n;
}

std::size_t RefineGrid::block_id(const RefineBlock& b) const {
  const std::size_t s = spacing(b.level - 1);
  std::size_t id = 0;
  for (std::size_t d = 0; d < dims(); ++d) id = id * cells(b.level, d) + (split_[d] ? b.lo[d] / s : b.lo[d]);
  return id;
}

RefineBlock RefineGrid::block(int level, std::size_t id) const {
  RefineBlock b{level, {}};
  const std::size_t s = spacing(level - 1);
  for (std::size_t d = dims(); d-- > 0;) {
    const std::size_t n = cells(level, d);
    b.lo[d] = id % n * (split_[d] ? s : 1);
    id /= n;
  }
  return b;
}

bool RefineGrid::contains(const RefineBlock& b, const GridIndex& p) const {
  const std::size_t s = spacing(b.level - 1);
  for (std::size_t d = 0; d < dims(); ++d) {
    if (split_[d] ? (p[d] < b.lo[d] || p[d] > b.lo[d] + s) : p[d] != b.lo[d]) return false;
  }
  return true;
}

void RefineGrid::corners(const RefineBlock& b, std::vector<std::size_t>& out) const {
  out.clear();
  const std::size_t s = spacing(b.level - 1);
  std::array<std::array<std::size_t, 3>, kMaxRefineAxes> opt{};
  std::array<std::size_t, kMaxRefineAxes> count{};
  for (std::size_t d = 0; d < dims(); ++d) {
    opt[d] = {b.lo[d], b.lo[d] + s, 0};
    count[d] = split_[d] ? 2 : 1;
  }
  for_each_combination(dims(), opt, count, [&](const GridIndex& i) { out.push_back(ravel(i)); });
}

void RefineGrid::new_points(const RefineBlock& b, std::vector<std::size_t>& out) const {
  out.clear();
  const std::size_t h = spacing(b.level);
  std::array<std::array<std::size_t, 3>, kMaxRefineAxes> opt{};
  std::array<std::size_t, kMaxRefineAxes> count{};
  for (std::size_t d = 0; d < dims(); ++d) {
    opt[d] = {b.lo[d], b.lo[d] + h, b.lo[d] + 2 * h};
    count[d] = split_[d] ? 3 : 1;
  }
  for_each_combination(dims(), opt, count, [&](const GridIndex& i) {
    bool corner = true;
    for (std::size_t d = 0; d < dims() && corner; ++d) corner = !split_[d] || i[d] != b.lo[d] + h;
    if (!corner) out.push_back(ravel(i));
  });
}

void RefineGrid::children(const RefineBlock& b, std::vector<RefineBlock>& out) const {
  out.clear();
  if (b.level >= levels_) return;
  const std::size_t h = spacing(b.level);
  std::array<std::array<std::size_t, 3>, kMaxRefineAxes> opt{};
  std::array<std::size_t, kMaxRefineAxes> count{};
  for (std::size_t d = 0; d < dims(); ++d) {
    opt[d] = {b.lo[d], b.lo[d] + h, 0};
    count[d] = split_[d] ? 2 : 1;
  }
  for_each_combination(dims(), opt, count, [&](const GridIndex& i) { out.push_back({b.level + 1, i}); });
}

RefineBlock RefineGrid::parent(const RefineBlock& b) const { return ancestor(b, b.level - 1); }

void RefineGrid::containing_blocks(int level, const GridIndex& p, std::vector<RefineBlock>& out) const {
  out.clear();
  const std::size_t s = spacing(level - 1);
  std::array<std::array<std::size_t, 3>, kMaxRefineAxes> opt{};
  std::array<std::size_t, kMaxRefineAxes> count{};
  for (std::size_t d = 0; d < dims(); ++d) {
    if (!split_[d]) {
      opt[d] = {p[d], 0, 0};
      count[d] = 1;
      continue;
    }
    const std::size_t q = p[d] / s, n = cells(level, d);
    std::size_t k = 0;
    if (p[d] % s == 0 && q >= 1) opt[d][k++] = (q - 1) * s;  // on a lattice plane: the cell below too
    if (q < n) opt[d][k++] = q * s;
    count[d] = k;
  }
  for_each_combination(dims(), opt, count, [&](const GridIndex& i) { out.push_back({level, i}); });
}

RefineBlock RefineGrid::ancestor(const RefineBlock& b, int level) const {
  RefineBlock a{level, b.lo};
  const std::size_t s = spacing(level - 1);
  for (std::size_t d = 0; d < dims(); ++d)
    if (split_[d]) a.lo[d] -= a.lo[d] % s;
  return a;
}

void RefineGrid::touching(const RefineBlock& b, std::vector<RefineBlock>& out) const {
  out.clear();
  const std::size_t s = spacing(b.level - 1);
  std::array<std::array<std::size_t, 3>, kMaxRefineAxes> opt{};
  std::array<std::size_t, kMaxRefineAxes> count{};
  for (std::size_t d = 0; d < dims(); ++d) {
    std::size_t k = 0;
    if (split_[d] && b.lo[d] >= s) opt[d][k++] = b.lo[d] - s;
    opt[d][k++] = b.lo[d];
    if (split_[d] && b.lo[d] / s + 1 < cells(b.level, d)) opt[d][k++] = b.lo[d] + s;
    count[d] = k;
  }
  for_each_combination(dims(), opt, count, [&](const GridIndex& i) { out.push_back({b.level, i}); });
}

std::size_t RefineGrid::nearest_corner(const RefineBlock& b, const GridIndex& p) const {
  const std::size_t s = spacing(b.level - 1);
  GridIndex c = b.lo;
  for (std::size_t d = 0; d < dims(); ++d)
    if (split_[d] && 2 * (p[d] - b.lo[d]) > s) c[d] += s;
  return ravel(c);
}

}  // namespace vibromap
