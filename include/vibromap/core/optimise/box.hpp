#pragma once
// The box of the free parameters and the scaled variables the local optimisers work in.
//
// Each free parameter x_i in [min_i, max_i] (SI units) becomes u_i in [0, 1]:
//   lin: u = (x - min) / (max - min)
//   log: u = (ln x - ln min) / (ln max - ln min)
// so a step of 0.01 in u is 1 % of the box on every axis, whatever its unit or its decades
// (E in [2e4, 2.1e11] Pa: 0.01 in u is a factor 1.18 in E). The optimisers see only u in
// the unit cube; the objective sees only x.
//
// Contract: to_physical() maps u = 0 and u = 1 to min and max exactly, and every u (clamped
// into [0, 1] first) to a value inside [min, max]: bounds are never left by rounding.

#include <cstddef>
#include <span>
#include <vector>

#include "vibromap/core/optimise/optimise_options.hpp"

namespace vibromap {

class Box {
 public:
  Box() = default;
  // Throws std::invalid_argument when a variable is not valid (validate(FreeVariable)).
  explicit Box(std::vector<FreeVariable> variables);

  std::size_t size() const { return variables_.size(); }
  const std::vector<FreeVariable>& variables() const { return variables_; }

  // Physical values -> scaled ones, clamped into [0, 1].
  std::vector<double> to_scaled(std::span<const double> x) const;
  // Scaled values (clamped into [0, 1]) -> physical ones, inside [min, max].
  std::vector<double> to_physical(std::span<const double> u) const;
  // Every x_i within [min_i, max_i], allowing a relative slack of the box width.
  bool contains(std::span<const double> x, double slack = 1e-12) const;

 private:
  std::vector<FreeVariable> variables_;
};

}  // namespace vibromap
