#pragma once
// Internal to solve_point (point_solver.cpp): the orbits Newton found from one transient.

#include <algorithm>
#include <complex>
#include <vector>

#include "vibromap/core/analysis/point/shooting.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap::detail {

// Orbits Newton found from the current transient (stable or not). None of them was the
// answer: each was unstable, or refused by the follow check (the first accepted is the answer).
class FoundOrbits {
 public:
  explicit FoundOrbits(const Model& model) : scale_(model) {}

  void add(int n, const State& y, const std::vector<std::complex<double>>& multipliers) {
    orbits_.push_back({n, y, multipliers});
  }

  // Two candidate periods often lead Newton to one orbit (n = 2 to the (1,1) orbit found for
  // n = 1). An iterate within kOffset motion scales of a found orbit of a period d dividing n,
  // a fixed point of P^n that is isolated (no multiplier's (n/d)-th power within kIsolation of
  // 1), would only converge to it again, and the same transient gives it the same verdict. On
  // the demo plane 691 of 2,634 Newton searches did.
  bool near(int n, const State& y) const {
    return std::any_of(orbits_.begin(), orbits_.end(), [&](const Orbit& o) {
      if (n % o.n != 0 || scale_.size(y - o.y) > kOffset) return false;
      return std::none_of(o.multipliers.begin(), o.multipliers.end(), [&](std::complex<double> mu) {
        return std::abs(std::pow(mu, n / o.n) - 1.0) < kIsolation;
      });
    });
  }

  // The same orbit, found again: period n and within `distance` (StateScale::distance).
  bool contains(int n, const State& y, double distance) const {
    return std::any_of(orbits_.begin(), orbits_.end(),
                       [&](const Orbit& o) { return o.n == n && scale_.distance(o.y, y) <= distance; });
  }

 private:
  static constexpr double kOffset = 1e-3;
  static constexpr double kIsolation = 0.1;
  struct Orbit {
    int n;
    State y;
    std::vector<std::complex<double>> multipliers;
  };
  StateScale scale_;
  std::vector<Orbit> orbits_;
};

}  // namespace vibromap::detail
