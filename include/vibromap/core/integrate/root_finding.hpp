#pragma once
// Bracketed scalar root finding on a continuous extension.
//
// The Illinois variant of regula falsi (Dowell & Jarratt, BIT 11 (1971) 168-174), the method
// SUNDIALS uses for its root finding: superlinear convergence, and the bracket [a, b] is kept,
// so the root returned lies in the interval where the sign change was seen.

#include <functional>

namespace vibromap {

struct RootResult {
  double x;         // the point where g changes sign: g(x) has the sign of g(b)
  int iterations;   // function evaluations spent
};

// Finds x in (a, b] with g(a) <= 0 < g(b) narrowed to |b - a| <= tol. ga and gb are g(a), g(b).
// Returns the right end of the final bracket, so the returned point is past the crossing
// (g(x) > 0), which is what an event that switches the right-hand side needs.
RootResult illinois(const std::function<double(double)>& g, double a, double b, double ga, double gb, double tol,
                    int max_iterations = 100);

}  // namespace vibromap
