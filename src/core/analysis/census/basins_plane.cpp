#include "vibromap/core/analysis/census/basins_plane.hpp"

namespace vibromap {

int state_index(std::string_view name) {
  for (std::size_t i = 0; i < kStateNames.size(); ++i)
    if (kStateNames[i] == name) return static_cast<int>(i);
  return -1;
}

std::string state_units(int index) { return index < 2 ? "m" : "m/s"; }

Eigen::Vector4d BasinsPlane::state(std::uint64_t pixel) const {
  const std::uint64_t n0 = axes[0].size();
  Eigen::Vector4d x = fixed;
  x[vars[0]] = axes[0][static_cast<std::size_t>(pixel % n0)];
  x[vars[1]] = axes[1][static_cast<std::size_t>(pixel / n0)];
  return x;
}

bool BasinsPlane::overlapping(std::uint64_t pixel) const {
  const Eigen::Vector4d x = state(pixel);
  return x[0] - x[1] > 0.0;
}

std::string BasinsPlane::name() const {
  return std::string(kStateNames[static_cast<std::size_t>(vars[0])]) + "," +
         std::string(kStateNames[static_cast<std::size_t>(vars[1])]);
}

}  // namespace vibromap
