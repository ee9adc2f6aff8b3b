#pragma once
// A grid over some of a scene's numeric keys: the Cartesian product of its axes, with a flat
// (row-major, first axis slowest) cell index.
//
// Contract: a Grid is built from axes whose values pass validate_axis; coordinates(i) for i
// in [0, size()) gives the cell's value on each axis. The Grid knows nothing of what an axis
// means: the scene reader (io) names the key, unit and meaning of each axis, and io's
// CellMaker turns a cell's coordinates into a parameter point.

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vibromap {

enum class AxisScale { lin, log };
std::string to_string(AxisScale s);             // "lin", "log"
AxisScale parse_axis_scale(std::string_view s);  // throws std::invalid_argument

struct Axis {
  std::string key;             // full scene key: "contact.E1", "forcing.omega" (empty when unknown, e.g. read from a map)
  std::string name;            // coordinate name in maps: the key within its section, "E1", "omega"
  std::string units;           // SI unit, "1" when dimensionless
  std::string long_name;       // the key's meaning, one line
  std::vector<double> values;  // the axis points, SI units
  AxisScale scale = AxisScale::lin;  // how the points were spaced (plots use it for their axes)
  // A categorical axis (a choice key such as contact.law): the names of all the key's
  // choices; values are then indices into them (maps: CF flag_values / flag_meanings).
  std::vector<std::string> categories = {};
};

// n points from `from` to `to` inclusive, evenly spaced (lin) or geometrically (log).
// n = 1 gives {from}. The ends are exact.
std::vector<double> axis_points(double from, double to, int n, AxisScale scale);

// Empty when the axis is usable, else what is wrong (no name, no values, non-finite or
// non-positive log values, repeated values, a categorical value that indexes no category).
std::string validate_axis(const Axis& axis);

class Grid {
 public:
  Grid() = default;
  // Throws std::invalid_argument for an axis validate_axis refuses, or when the number of
  // cells (the product of the axis lengths) does not fit a std::size_t.
  explicit Grid(std::vector<Axis> axes);

  const std::vector<Axis>& axes() const { return axes_; }
  std::size_t size() const { return size_; }
  std::vector<std::size_t> shape() const;
  std::vector<std::size_t> unravel(std::size_t flat) const;        // per-axis indices
  std::size_t ravel(const std::vector<std::size_t>& index) const;  // inverse of unravel
  // The cell's value on each axis, out[d] for axis d (out.size() == axes().size(); throws
  // std::invalid_argument otherwise). Allocates nothing.
  void coordinates(std::size_t flat, std::span<double> out) const;

 private:
  std::vector<Axis> axes_;
  std::size_t size_ = 1;
};

}  // namespace vibromap
