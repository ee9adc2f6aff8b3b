#pragma once
// The motion regimes of docs/model.md; every solved point gets exactly one.

#include <string>
#include <string_view>

namespace vibromap {

enum class RegimeKind {
  periodic,           // (n,k): repeats after n forcing periods with k impacts in nT
  chatter,            // many impacts per forcing period (AnalysisOptions::chatter_impacts or more)
  no_contact,         // periodic without any impact
  permanent_contact,  // the bodies never separate in the steady motion
  quasi_periodic,     // no period up to n_max, largest Lyapunov exponent ~ 0 (when computed)
  chaotic,            // no period up to n_max, largest Lyapunov exponent > 0 (when computed)
  non_periodic,       // no period up to n_max and no longer converging; Lyapunov exponent not asked for
  unresolved,         // the budget (periods or steps) ran out while the motion was still settling
  failed,             // numerical failure (non-finite state, step-size underflow)
};

std::string to_string(RegimeKind k);          // "periodic", "chatter", "no-contact", ...
RegimeKind parse_regime_kind(std::string_view s);  // inverse of to_string; throws std::invalid_argument

struct Regime {
  RegimeKind kind = RegimeKind::unresolved;
  int n = 0;  // period in forcing periods (0 when not periodic)
  int k = 0;  // impacts in nT (0 when not periodic)
  // "(n,k)" for periodic motion, else to_string(kind).
  std::string label() const;
  friend bool operator==(const Regime&, const Regime&) = default;
};

// Parses "(n,k)" or a kind name; throws std::invalid_argument.
Regime parse_regime(std::string_view s);

// The one definition of a soft motion, used by run, maps, the census, the optimiser and the
// pictures alike: periodic with impacts (RegimeKind::periodic, k > 0), stable (every Floquet
// multiplier inside the unit circle: stable == 1; unknown stability is not soft), Hertz-valid
// (z_max/R* <= analysis.hertz_limit, where the force law the motion was computed with holds)
// and k_con <= soft_kcon (analysis.soft_kcon, 10 by default; k_con = T / T_con of the longest
// impact). A soft answer computed beyond the Hertz limit is no answer, so it is never soft.
bool is_soft(const Regime& regime, int stable, bool hertz_valid, double k_con, double soft_kcon);

}  // namespace vibromap
