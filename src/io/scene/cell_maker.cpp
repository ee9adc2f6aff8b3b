#include "vibromap/io/scene/cell_maker.hpp"

#include <algorithm>
#include <span>
#include <stdexcept>
#include <utility>

#include "vibromap/core/text.hpp"
#include "vibromap/io/scene/sweep_section.hpp"

namespace vibromap {

CellMaker::CellMaker(const Scene& base, const Grid& grid)
    : base_{base.params, base.options}, grid_(grid), initial_given_(base.initial_given) {
  const std::vector<Axis>& axes = grid_.axes();
  if (axes.size() > kMaxSweepAxes)
    throw std::invalid_argument(
        cat("CellMaker: ", std::to_string(axes.size()), " axes, at most ", std::to_string(kMaxSweepAxes)));
  std::vector<std::pair<Key, std::size_t>> order;  // (key, axis), sorted to table order
  for (std::size_t d = 0; d < axes.size(); ++d) {
    const std::optional<Key> k = axes[d].key.find('.') == std::string::npos ? std::nullopt : Key::find(axes[d].key);
    if (!k || !k->is_axis()) throw std::invalid_argument(cat("CellMaker: axis '", clip(axes[d].name), "' names no scene key"));
    order.emplace_back(*k, d);
    if (k->full_name() == "system.D") refill_rest_ = base.params.initial.has_value();
  }
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first.index() < b.first.index(); });
  for (const auto& [k, d] : order) {
    if (k.component() < 0) first_initial_ = steps_.size() + 1;
    steps_.push_back({d, k});
  }
  if (std::all_of(initial_given_.begin(), initial_given_.end(), [](bool g) { return g; })) refill_rest_ = false;
}

CellPoint CellMaker::operator()(std::size_t flat) const {
  std::array<double, kMaxSweepAxes> x{};
  grid_.coordinates(flat, std::span<double>(x.data(), grid_.axes().size()));
  CellPoint c = base_;
  for (std::size_t i = 0; i < first_initial_; ++i) steps_[i].key.set(c.params, c.options, x[steps_[i].axis]);
  if (refill_rest_) {  // the [initial] components the scene did not give follow the cell's rest state
    const Eigen::Vector4d rest(0.0, c.params.D, 0.0, 0.0);
    for (std::size_t k = 0; k < initial_given_.size(); ++k)
      if (!initial_given_[k]) (*c.params.initial)[static_cast<Eigen::Index>(k)] = rest[static_cast<Eigen::Index>(k)];
  }
  for (std::size_t i = first_initial_; i < steps_.size(); ++i) steps_[i].key.set(c.params, c.options, x[steps_[i].axis]);
  return c;
}

}  // namespace vibromap
