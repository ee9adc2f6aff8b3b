#pragma once
// A grid over some of the variable parameters (E1, E2, R1, R2, m2, k2, omega2): the
// Cartesian product of its axes, with a flat (row-major, first axis slowest) cell index.
//
// Contract: a Grid is built from validated axes (validate_axis); cell(i) for i in [0, size())
// gives the scene's base parameters with the swept ones replaced by the cell's values,
// through set_parameter (so k2 and omega2 keep their form, and xi2 stays a ratio).

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "vibromap/core/model/parameters.hpp"

namespace vibromap {

enum class AxisScale { lin, log };
std::string to_string(AxisScale s);             // "lin", "log"
AxisScale parse_axis_scale(std::string_view s);  // throws std::invalid_argument

struct Axis {
  std::string name;            // its coordinate name in maps: the key within its section (E1, omega2)
  std::vector<double> values;  // the axis points, SI units
  AxisScale scale = AxisScale::lin;  // how the points were spaced (plots use it for their axes)
  std::string key{};           // the full scene key ("contact.E1")
  std::string units{};         // SI unit ("Pa"; "1" when dimensionless)
  std::string long_name{};     // the key's meaning, one line (CF long_name)
};

// The parameters a [sweep] may have as axes, in the canonical order used when the scene does
// not give one.
const std::vector<std::string_view>& sweep_axis_names();
// SI unit of a swept parameter ("Pa", "m", "kg", "N/m", "rad/s").
std::string_view axis_units(std::string_view name);

// n points from `from` to `to` inclusive, evenly spaced (lin) or geometrically (log).
// n = 1 gives {from}. The ends are exact.
std::vector<double> axis_points(double from, double to, int n, AxisScale scale);

// Empty when the axis is usable, else what is wrong (unknown name, no values, non-finite
// or non-positive log values, duplicates).
std::string validate_axis(const Axis& axis);

class Grid {
 public:
  Grid() = default;
  explicit Grid(std::vector<Axis> axes);

  const std::vector<Axis>& axes() const { return axes_; }
  std::size_t size() const { return size_; }
  std::vector<std::size_t> shape() const;
  std::vector<std::size_t> unravel(std::size_t flat) const;        // per-axis indices
  std::size_t ravel(const std::vector<std::size_t>& index) const;  // inverse of unravel
  // The base parameters with the cell's axis values set.
  Parameters cell(const Parameters& base, std::size_t flat) const;

 private:
  std::vector<Axis> axes_;
  std::size_t size_ = 1;
};

}  // namespace vibromap
