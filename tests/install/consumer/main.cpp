// Solves the source paper's Table 1 point (jobs/paper/table1.toml) with the core API alone and
// prints its regime and k_con as `vibromap run` does: "regime (1,1) k_con 1111.22".
#include <cstdio>

#include "vibromap/core/analysis/point/point_solver.hpp"

int main() {
  using vibromap::Damper;
  using vibromap::Spring;
  vibromap::Parameters p;  // every value of jobs/paper/table1.toml, given explicitly
  p.m1 = 1000.0;
  p.m2 = 100.0;
  p.spring1 = {Spring::Form::frequency, 6.283};
  p.spring2 = {Spring::Form::frequency, 5.646};
  p.damper1 = {Damper::Form::ratio, 0.01};
  p.damper2 = {Damper::Form::ratio, 0.01};
  p.D = 0.05;
  p.E1 = 2.099e11;
  p.E2 = 2.099e11;
  p.R1 = 2.0;
  p.R2 = 2.0;
  p.nu1 = 0.3;
  p.nu2 = 0.3;
  p.q = 0.319;
  p.F0 = 500.0;
  p.omega = 7.23;
  p.lambda = 1.0;
  p.phi0 = 0.0;

  const vibromap::PointSummary s = vibromap::solve_point(p, vibromap::PointOptions{});
  if (s.status != vibromap::SolveStatus::ok) {
    std::fprintf(stderr, "consumer: %s: %s\n", vibromap::to_string(s.status).c_str(), s.message.c_str());
    return 1;
  }
  std::printf("regime %s k_con %g\n", s.regime.label().c_str(), s.k_con);
  return 0;
}
