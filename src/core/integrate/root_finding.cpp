#include "vibromap/core/integrate/root_finding.hpp"

#include <cmath>

namespace vibromap {

RootResult illinois(const std::function<double(double)>& g, double a, double b, double ga, double gb, double tol,
                    int max_iterations) {
  int side = 0;  // which end was kept last time: -1 left, +1 right
  int it = 0;
  while (b - a > tol && it < max_iterations) {
    double x = b - gb * (b - a) / (gb - ga);
    // Keep the secant point strictly inside; fall back to bisection when it is not.
    if (!(x > a && x < b)) x = 0.5 * (a + b);
    const double gx = g(x);
    ++it;
    if (gx > 0.0) {
      b = x;
      gb = gx;
      if (side == 1) ga *= 0.5;  // Illinois: halve the stale end's value
      side = 1;
    } else {
      a = x;
      ga = gx;
      if (side == -1) gb *= 0.5;
      side = -1;
    }
    if (gx == 0.0) {  // exactly on the boundary: the crossing is just past x
      return {x, it};
    }
  }
  return {b, it};
}

}  // namespace vibromap
