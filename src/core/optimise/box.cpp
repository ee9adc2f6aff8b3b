#include "vibromap/core/optimise/box.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vibromap {

Box::Box(std::vector<FreeVariable> variables) : variables_(std::move(variables)) {
  for (const FreeVariable& v : variables_)
    if (std::string e = validate(v); !e.empty()) throw std::invalid_argument(e);
}

std::vector<double> Box::to_scaled(std::span<const double> x) const {
  std::vector<double> u(variables_.size());
  for (std::size_t i = 0; i < u.size(); ++i) {
    const FreeVariable& v = variables_[i];
    const double t = v.scale == AxisScale::log ? (std::log(x[i]) - std::log(v.min)) / (std::log(v.max) - std::log(v.min))
                                               : (x[i] - v.min) / (v.max - v.min);
    u[i] = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
  }
  return u;
}

std::vector<double> Box::to_physical(std::span<const double> u) const {
  std::vector<double> x(variables_.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const FreeVariable& v = variables_[i];
    const double t = std::isnan(u[i]) ? 0.0 : std::clamp(u[i], 0.0, 1.0);
    double value = 0.0;
    if (t == 0.0) {
      value = v.min;
    } else if (t == 1.0) {
      value = v.max;
    } else if (v.scale == AxisScale::log) {
      value = std::exp(std::log(v.min) + t * (std::log(v.max) - std::log(v.min)));
    } else {
      value = v.min + t * (v.max - v.min);
    }
    x[i] = std::clamp(value, v.min, v.max);
  }
  return x;
}

bool Box::contains(std::span<const double> x, double slack) const {
  if (x.size() != variables_.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const FreeVariable& v = variables_[i];
    const double margin = slack * (v.max - v.min);
    if (!(x[i] >= v.min - margin && x[i] <= v.max + margin)) return false;
  }
  return true;
}

}  // namespace vibromap
