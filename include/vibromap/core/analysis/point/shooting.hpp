#pragma once
// Periodic orbits by shooting: Newton's method on G(y) = P^n(y) - y, P the stroboscopic
// (period-T) map, with the Jacobian M - I from the monodromy matrix M = dP^n/dy of the
// variational equations (VariationalIntegrator). At convergence the eigenvalues of M are the
// orbit's Floquet multipliers: the orbit is stable when all |mu| < 1.
//
// Newton steps are limited in length (a fraction of the motion's scale) so an iterate cannot
// jump across the state space; the residual is the steady-state detector's scaled max-norm.

#include <complex>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/integrate/integrator.hpp"

namespace vibromap {

struct ShootingOptions {
  int n = 1;                  // period of the orbit looked for, in forcing periods
  double tol = 1e-10;         // scaled residual ||P^n(y) - y|| to stop at
  int max_iterations = 30;    // Newton iterations
  double max_step = 2.0;      // longest Newton step, in units of the motion's scale
};

struct ShootingResult {
  bool converged = false;
  std::string message;            // why not, when not converged
  State y = State::Zero();        // a point of the orbit at a period start (internal coordinates)
  Eigen::Matrix4d monodromy = Eigen::Matrix4d::Identity();
  std::vector<std::complex<double>> multipliers;  // eigenvalues of the monodromy, largest |mu| first
  double residual = 0.0;          // scaled ||P^n(y) - y|| at the end
  int iterations = 0;
  bool known = false;             // stopped at an orbit already found (KnownOrbit)
  bool stable() const { return !multipliers.empty() && std::abs(multipliers.front()) < 1.0; }
};

// True for a state at an orbit already found: Newton stops at such an iterate
// (ShootingResult::known), which it would only converge to again.
using KnownOrbit = std::function<bool(const State&)>;

// Newton from y0. counters accumulates the integration work.
ShootingResult shoot(const Model& model, const IntegratorOptions& integration, const State& y0,
                     const ShootingOptions& options, IntegrationCounters& counters, const KnownOrbit& known = {});

// P^n(y) into `image` and its Jacobian dP^n/dy (the monodromy at a periodic orbit) into `jac`,
// integrated with the variational equations. counters accumulates the work.
IntegrationStatus period_map(const Model& model, const IntegratorOptions& integration, const State& y, int n,
                             State& image, Eigen::Matrix4d& jac, IntegrationCounters& counters);
// The eigenvalues of a monodromy matrix (Floquet multipliers), largest |mu| first.
std::vector<std::complex<double>> floquet_multipliers(const Eigen::Matrix4d& monodromy);

// The least d dividing n with ||P^d(y) - y|| <= tol (n when there is none): Newton for
// period n may converge to an orbit of a shorter period. counters accumulates the work.
int least_period(const Model& model, const IntegratorOptions& integration, const State& y, int n, double tol,
                 IntegrationCounters& counters);

// The scaled max-norm distance of two states used for steady states and shooting
// (positions over L + |x|, velocities over omega L + |v|, L = max(D, lambda F0 / k1)).
class StateScale {
 public:
  explicit StateScale(const Model& model);
  double distance(const State& a, const State& b) const;
  double length() const { return length_; }
  double speed() const { return speed_; }
  // The motion's unit of each coordinate: (L, L, omega L, omega L) as in distance().
  Eigen::Array4d unit() const { return {length_, length_, speed_, speed_}; }
  // The size of an offset d in those units: max |d_i| / unit_i.
  double size(const State& d) const { return (d.array() / unit()).abs().maxCoeff(); }

 private:
  double length_, speed_;
};

// A guess of the fixed point of a contracting map from its iterates x_0, x_1, ... (oldest
// first) by reduced rank extrapolation (RRE; Sidi, "Vector Extrapolation Methods", 2017,
// ch. 1): with differences u_j = x_{j+1} - x_j, find gamma minimising |sum gamma_j u_j| with
// sum gamma_j = 1 and return sum gamma_j x_j. Exact for a linear map when there are
// dim + 2 iterates; a transient that spirals in (complex Floquet multipliers) is seen from
// the side, and its centre is found where the last iterate alone is far off. Returns the
// last iterate when there are fewer than 3 or the least-squares problem is degenerate.
State extrapolate_fixed_point(const std::vector<State>& iterates, const StateScale& scale);

}  // namespace vibromap
