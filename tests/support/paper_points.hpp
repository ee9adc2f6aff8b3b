#pragma once
// The source paper's Table 2 point (jobs/paper/table2.toml, docs/model.md): the softened
// system, m2 = 310 kg, omega2 = 3.606 rad/s, E1 = 1.4e10 Pa, E2 = 1e6 Pa, the rest Table 1's
// (the defaults). Shared by the tests that solve it.

#include "vibromap/core/model/parameters.hpp"

namespace vibromap::test {

inline Parameters table2() {
  Parameters p;
  p.m2 = 310.0;
  p.spring2 = {Spring::Form::frequency, 3.606};
  p.E1 = 1.4e10;
  p.E2 = 1.0e6;
  return p;
}

}  // namespace vibromap::test
