#include "vibromap/core/grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "vibromap/core/text.hpp"

namespace vibromap {

std::string to_string(AxisScale s) { return s == AxisScale::log ? "log" : "lin"; }

AxisScale parse_axis_scale(std::string_view s) {
  if (s == "lin") return AxisScale::lin;
  if (s == "log") return AxisScale::log;
  throw std::invalid_argument("unknown axis scale '" + std::string(s) + "' (allowed: lin, log)");
}

std::vector<double> axis_points(double from, double to, int n, AxisScale scale) {
  std::vector<double> v(static_cast<std::size_t>(std::max(n, 0)));
  if (n <= 0) return v;
  v.front() = from;
  if (n == 1) return v;
  const double den = static_cast<double>(n - 1);
  for (int i = 1; i < n - 1; ++i) {
    const double f = static_cast<double>(i) / den;
    v[static_cast<std::size_t>(i)] =
        scale == AxisScale::log ? std::exp(std::log(from) + f * (std::log(to) - std::log(from))) : from + f * (to - from);
  }
  v.back() = to;
  return v;
}

std::string validate_axis(const Axis& axis) {
  if (axis.name.empty()) return "an axis has no name";
  if (axis.values.empty()) return "axis " + axis.name + " has no values";
  for (double v : axis.values) {
    if (!std::isfinite(v)) return "axis " + axis.name + " has a non-finite value";
    if (axis.scale == AxisScale::log && v <= 0.0) return "log axis " + axis.name + " needs values > 0";
    if (!axis.categories.empty() &&
        !(v >= 0.0 && v < static_cast<double>(axis.categories.size()) && v == std::trunc(v)))
      return "categorical axis " + axis.name + " has a value that indexes none of its categories";
  }
  std::vector<double> sorted = axis.values;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    return "axis " + axis.name + " repeats a value";
  return {};
}

Grid::Grid(std::vector<Axis> axes) : axes_(std::move(axes)) {
  for (const Axis& a : axes_) {
    if (std::string err = validate_axis(a); !err.empty()) throw std::invalid_argument(err);
    if (size_ > std::numeric_limits<std::size_t>::max() / a.values.size())
      throw std::invalid_argument("the grid has more cells than a flat index can count");
    size_ *= a.values.size();
  }
}

std::vector<std::size_t> Grid::shape() const {
  std::vector<std::size_t> s;
  for (const Axis& a : axes_) s.push_back(a.values.size());
  return s;
}

std::vector<std::size_t> Grid::unravel(std::size_t flat) const {
  std::vector<std::size_t> index(axes_.size());
  for (std::size_t d = axes_.size(); d-- > 0;) {
    const std::size_t n = axes_[d].values.size();
    index[d] = flat % n;
    flat /= n;
  }
  return index;
}

std::size_t Grid::ravel(const std::vector<std::size_t>& index) const {
  std::size_t flat = 0;
  for (std::size_t d = 0; d < axes_.size(); ++d) flat = flat * axes_[d].values.size() + index[d];
  return flat;
}

void Grid::coordinates(std::size_t flat, std::span<double> out) const {
  if (out.size() != axes_.size())
    throw std::invalid_argument(cat("Grid::coordinates: ", std::to_string(out.size()), " slots for ",
                                    std::to_string(axes_.size()), " axes"));
  for (std::size_t d = axes_.size(); d-- > 0;) {
    const std::vector<double>& v = axes_[d].values;
    out[d] = v[flat % v.size()];
    flat /= v.size();
  }
}

}  // namespace vibromap
