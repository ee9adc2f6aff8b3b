#pragma once
// A plane of initial states for a basin picture (`vibromap basins`): two of the state
// variables (x1, x2, v1, v2) on an evenly spaced grid, the other two fixed.
//
// Contract: axes[0] holds the first plane variable's values (N0 of them), axes[1] the second's
// (N1); pixel p = j N0 + i (row-major, the first variable fastest) is the state `fixed` with
// variable vars[0] set to axes[0][i] and vars[1] to axes[1][j]. Units: m for x1, x2 and m/s
// for v1, v2 (the model's physical state, docs/model.md). A pixel whose bodies overlap (x1 - x2 > 0) is not an
// initial state the census draws either; `vibromap basins` labels it kOverlapLabel.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace vibromap {

// The state variables by index into (x1, x2, v1, v2).
inline constexpr std::array<std::string_view, 4> kStateNames = {"x1", "x2", "v1", "v2"};
// The index of "x1", "x2", "v1" or "v2"; -1 for any other name.
int state_index(std::string_view name);
std::string state_units(int index);  // "m" or "m/s"

// Label of a pixel whose bodies overlap at the start (x1 - x2 > 0): not followed.
constexpr int kOverlapLabel = -3;

struct BasinsPlane {
  std::array<int, 2> vars{0, 2};              // plane variables, indices into (x1, x2, v1, v2)
  std::array<std::vector<double>, 2> axes;    // their values, m or m/s
  Eigen::Vector4d fixed = Eigen::Vector4d::Zero();  // the state of every pixel before the plane variables are set

  std::uint64_t pixels() const { return static_cast<std::uint64_t>(axes[0].size()) * axes[1].size(); }
  Eigen::Vector4d state(std::uint64_t pixel) const;
  bool overlapping(std::uint64_t pixel) const;  // x1 - x2 > 0
  // "x1,v1"
  std::string name() const;
};

}  // namespace vibromap
