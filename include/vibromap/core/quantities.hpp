#pragma once
// What a sweep keeps of one solved cell, and the optional quantities a scene may ask a map to
// store.
//
// Always kept (issues #3, #4): status, regime with n and k, stability, wall time
// and the steady-state residual. Stored on request only: the Quantity values. A sweep whose
// scene has [census] also keeps the cell's census: every attractor listed, with
// its basin fraction, and the fractions that are soft, unresolved and unlisted; its ordinary
// fields then describe the attractor the rest state reaches.

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/model/keys.hpp"

namespace vibromap {

// Optional per-cell quantities a map may store ([sweep] store = [...]).
enum class Quantity {
  T_con,        // duration of the longest impact, s
  k_con,        // T / T_con, 1
  F_max,        // largest peak contact force, N
  z_max,        // largest peak penetration, m
  z_ratio,      // largest z_max / R*, 1
  v_in,         // entry velocity of the longest impact, m/s
  impulse,      // impulse of the longest impact, N s
  hertz_valid,  // 1 when z_ratio <= hertz_limit, else 0
  periods,      // forcing periods integrated
  rhs_evals,    // right-hand side evaluations
  max_multiplier,  // largest |Floquet multiplier| of the periodic orbit (NaN where none), 1
  lyapunov,     // largest Lyapunov exponent (NaN where not computed), 1/s
  e_effective,  // effective restitution |v_out / v_in| of the longest impact, 1
  energy_dissipated,  // energy the contact dissipates in the longest impact, J
  clipped_impacts,    // impacts of the steady cycle whose damped force was clipped at 0
  // The cell's solve by phase (PhaseTimes, point_solver.hpp): seconds and right-hand side
  // evaluations; 0 in a census map.
  t_transient, rhs_transient,  // the transients before shooting
  t_newton, rhs_newton,        // shooting: Newton, its checks, the cycle measured
  t_integrate, rhs_integrate,  // brute force: the motion followed until it repeats or the budget ends
  t_floquet, rhs_floquet,      // brute force's orbit: its Floquet multipliers
  t_classify, rhs_classify,    // the motion classified (chaos included) and its impacts measured
};
// One table in quantities.cpp (kQuantities) holds, per Quantity, its name, units, description
// (the map's long_name, ending in "(NaN where not computed)" exactly when a default CellResult
// holds NaN) and the CellResult member it lives in. Everything below reads it, and so do the
// map file, the sweep's wire codec, [sweep] store, `vibromap keys` and, through the map's
// attributes, the Python readers: adding a quantity touches 2 files, this one (an enum value at
// the end, a CellResult member) and quantities.cpp (a table row, its value in summarize()), then
// 2 generated ones (docs/developer.md, "How to add a map quantity").
const std::vector<Quantity>& all_quantities();  // in enum order
std::string to_string(Quantity q);              // the dataset name, e.g. "T_con"
Quantity parse_quantity(std::string_view s);    // throws std::invalid_argument
std::string_view quantity_units(Quantity q);    // "s", "1", "N", "m", "m/s", "N s", "1/s"
std::string_view quantity_description(Quantity q);  // one line, the map's long_name
bool quantity_is_integer(Quantity q);           // int64 in maps (hertz_valid, periods, ...); else float64
std::int64_t quantity_max(Quantity q);          // largest valid value of an integer quantity (least: 0)
// The values the quantity can take where it is defined: "> 0" for T_con and k_con, ">= 0" for
// z_ratio, "in [0, 1]" for hertz_valid, "finite" for lyapunov (Bounds, model/keys.hpp).
Bounds quantity_range(Quantity q);

// Codes of the regime dataset (CF flag_values); -1 marks a cell not computed yet.
constexpr std::int8_t kNotComputed = -1;
std::int8_t regime_code(RegimeKind k);  // periodic 0, chatter 1, ..., failed 8 (enum order)
std::int8_t status_code(SolveStatus s); // ok 0, budget 1, failed 2, invalid_input 3

struct CellResult {
  std::int8_t status = kNotComputed;
  std::int8_t regime = kNotComputed;
  std::int8_t hertz_valid = 0;
  std::int8_t stable = -1;  // 1 stable, 0 unstable, -1 unknown (not computed or not periodic)
  std::int8_t soft = kNotComputed;  // 1 soft (is_soft, regime.hpp), 0 not, -1 not computed
  std::int8_t fragile = kNotComputed;  // analysis.fragility: 1 a perturbation of the initial state ends on
                                       // another attractor, 0 none does, -1 not assessed (off, census, not done)
  std::int32_t n = 0, k = 0;
  std::int64_t periods = 0, rhs_evals = 0, clipped_impacts = 0;
  double wall_s = 0.0, steady_residual = 0.0;
  double T_con = 0.0, k_con = 0.0, F_max = 0.0, z_max = 0.0, z_ratio = 0.0, v_in = 0.0, impulse = 0.0;
  double e_effective = 0.0, energy_dissipated = 0.0;
  double t_transient = 0.0, t_newton = 0.0, t_integrate = 0.0, t_floquet = 0.0, t_classify = 0.0;
  std::int64_t rhs_transient = 0, rhs_newton = 0, rhs_integrate = 0, rhs_floquet = 0, rhs_classify = 0;
  double max_multiplier = std::numeric_limits<double>::quiet_NaN();
  double lyapunov = std::numeric_limits<double>::quiet_NaN();
  // The census (sweeps with [census]; empty and NaN otherwise).
  // Attractors listed, by basin fraction, as the census found them (a map keeps part of each:
  // map_file.hpp; a cell read from a map has the rest at their defaults).
  std::vector<Attractor> census;
  double soft_fraction = std::numeric_limits<double>::quiet_NaN();        // census: basin fraction of soft attractors
  double unresolved_fraction = std::numeric_limits<double>::quiet_NaN();  // census: initial states not decided
  double unlisted_fraction = std::numeric_limits<double>::quiet_NaN();    // census: beyond max_attractors
  double budget_fraction = std::numeric_limits<double>::quiet_NaN();      // census: followed to max_periods
  double basin_entropy = std::numeric_limits<double>::quiet_NaN();        // census: -sum f ln f of its outcomes, nats
  // Adaptive maps (sweep.refine > 0; set by the sweep on rank 0, not by the solver): how the
  // point got its values (1 solved, 0 inherited, 2 audited, -1 not decided) and the level at
  // which that was decided.
  std::int8_t computed = -1, level = -1;

  double value(Quantity q) const;  // the quantity as a double (integers exactly up to 2^53)
};

// Sets quantity q of c. An integer quantity takes v converted toward zero, and throws
// std::invalid_argument unless 0 <= that <= quantity_max(q). quantity_int/set_quantity_int
// carry all 64 bits of an integer quantity and throw std::logic_error for a float one.
void set_quantity(CellResult& c, Quantity q, double v);
std::int64_t quantity_int(const CellResult& c, Quantity q);
void set_quantity_int(CellResult& c, Quantity q, std::int64_t v);

CellResult summarize(const PointSummary& s);
// A census cell: the ordinary fields from the attractor rest reaches (status budget and regime
// unresolved when rest was not decided; steady_residual NaN), the census fields from s.
CellResult summarize(const CensusSummary& s);

}  // namespace vibromap
