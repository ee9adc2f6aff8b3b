#include "vibromap/core/model/system.hpp"

#include <algorithm>
#include <numbers>

namespace vibromap {

Model::Model(const Parameters& p)
    : p_(p),
      contact_(p.E1, p.E2, p.nu1, p.nu2, p.R1, p.R2, p.q, p.damping_factor()),
      k1_(p.spring1.stiffness(p.m1)),
      k2_(p.spring2.stiffness(p.m2)),
      c1_(p.damper1.coefficient(p.m1, k1_)),
      c2_(p.damper2.coefficient(p.m2, k2_)),
      T_(p.period()),
      F_amp_(force_amplitude(p)),
      inv_m1_(1.0 / p.m1),
      inv_m2_(1.0 / p.m2),
      v_floor_(1e-6 * p.omega * motion_length(p)) {}

double Model::energy(const State& u) const {
  const Eigen::Vector4d x = to_physical(u);
  const double spring2 = u[1] + p_.D;  // x1 - x2 + D
  return 0.5 * p_.m1 * x[2] * x[2] + 0.5 * p_.m2 * x[3] * x[3] + 0.5 * k1_ * x[0] * x[0] +
         0.5 * k2_ * spring2 * spring2 + contact_.energy(u[1]);
}

}  // namespace vibromap
