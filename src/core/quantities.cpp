#include "vibromap/core/quantities.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace vibromap {

namespace {

// Where a quantity lives in CellResult: a float one in a double member (`real`), an integer
// one behind an int64 getter/setter pair made from its member by int_row.
struct QuantityInfo {
  Quantity q;
  std::string_view name, units, description;
  double CellResult::*real = nullptr;
  std::int64_t (*get_int)(const CellResult&) = nullptr;
  void (*set_int)(CellResult&, std::int64_t) = nullptr;
  std::int64_t max = 0;  // integer quantities: the largest valid value
  Bounds range{};        // real quantities: the values it takes where defined (integer ones: [0, max])
};

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr Bounds kPositive{0.0, kInf, true, false};
constexpr Bounds kNonNegative{0.0, kInf, false, false};
constexpr Bounds kFinite{-kInf, kInf, false, false};

template <auto Member>
std::int64_t get_member(const CellResult& c) {
  return c.*Member;
}

template <auto Member>
void set_member(CellResult& c, std::int64_t v) {
  c.*Member = static_cast<std::remove_reference_t<decltype(c.*Member)>>(v);
}

constexpr QuantityInfo real_row(Quantity q, std::string_view name, std::string_view units,
                                std::string_view description, double CellResult::*member, Bounds range) {
  return {q, name, units, description, member, nullptr, nullptr, 0, range};
}

template <auto Member>
constexpr QuantityInfo int_row(Quantity q, std::string_view name, std::string_view description,
                               std::int64_t max = std::numeric_limits<std::int64_t>::max()) {
  return {q, name, "1", description, nullptr, &get_member<Member>, &set_member<Member>, max};
}

// The two rows of one phase of a cell's solve (PhaseTimes, point_solver.hpp): its seconds and
// its right-hand side evaluations.
#define VIBROMAP_PHASE_ROWS(phase, what)                                                              \
  real_row(Quantity::t_##phase, "t_" #phase, "s",                                                    \
           "solve time " what " (a timing: differs run to run; 0 where the phase did not run)",      \
           &CellResult::t_##phase, kNonNegative),                                                     \
      int_row<&CellResult::rhs_##phase>(Quantity::rhs_##phase, "rhs_" #phase,                         \
                                        "right-hand side evaluations " what " (0 where the phase did not run)")

// Rows in enum order (checked below). The descriptions are the maps' long_name attributes.
constexpr std::array kQuantities = {
    real_row(Quantity::T_con, "T_con", "s", "duration of the longest impact", &CellResult::T_con, kPositive),
    real_row(Quantity::k_con, "k_con", "1", "softness T / T_con of the longest impact", &CellResult::k_con, kPositive),
    real_row(Quantity::F_max, "F_max", "N", "largest peak contact force", &CellResult::F_max, kNonNegative),
    real_row(Quantity::z_max, "z_max", "m", "largest peak penetration", &CellResult::z_max, kNonNegative),
    real_row(Quantity::z_ratio, "z_ratio", "1", "largest peak penetration over the reduced radius R*",
             &CellResult::z_ratio, kNonNegative),
    real_row(Quantity::v_in, "v_in", "m/s", "entry velocity of the longest impact", &CellResult::v_in, kFinite),
    real_row(Quantity::impulse, "impulse", "N s", "impulse of the longest impact", &CellResult::impulse, kNonNegative),
    int_row<&CellResult::hertz_valid>(Quantity::hertz_valid, "hertz_valid",
                                      "1 where z_ratio is within the Hertz validity limit, else 0", 1),
    int_row<&CellResult::periods>(Quantity::periods, "periods", "forcing periods integrated"),
    int_row<&CellResult::rhs_evals>(Quantity::rhs_evals, "rhs_evals", "right-hand side evaluations"),
    real_row(Quantity::max_multiplier, "max_multiplier", "1",
             "largest modulus of the Floquet multipliers of the periodic orbit (NaN where not computed)",
             &CellResult::max_multiplier, kNonNegative),
    real_row(Quantity::lyapunov, "lyapunov", "1/s", "largest Lyapunov exponent (NaN where not computed)",
             &CellResult::lyapunov, kFinite),
    real_row(Quantity::e_effective, "e_effective", "1",
             "effective restitution |v_out / v_in| of the relative velocity in the longest impact",
             &CellResult::e_effective, kNonNegative),
    real_row(Quantity::energy_dissipated, "energy_dissipated", "J",
             "energy the contact dissipates in the longest impact (0 for elastic Hertz)",
             &CellResult::energy_dissipated, kFinite),
    int_row<&CellResult::clipped_impacts>(Quantity::clipped_impacts, "clipped_impacts",
                                          "impacts of the steady cycle where the damped force was clipped at 0"),
    // A cell's solve by phase: the long_names end in what a reader must know (the tests read them).
    VIBROMAP_PHASE_ROWS(transient, "in the transients before shooting"),
    VIBROMAP_PHASE_ROWS(newton, "in shooting (Newton, its checks, the cycle measured)"),
    VIBROMAP_PHASE_ROWS(integrate, "following the motion by brute force"),
    VIBROMAP_PHASE_ROWS(floquet, "for the Floquet multipliers of brute force's orbit"),
    VIBROMAP_PHASE_ROWS(classify, "classifying the motion and measuring its impacts"),
};

// Row i describes Quantity(i) and has exactly one way in, so info() can index the table.
constexpr bool rows_in_enum_order() {
  for (std::size_t i = 0; i < kQuantities.size(); ++i) {
    const QuantityInfo& row = kQuantities[i];
    if (static_cast<std::size_t>(row.q) != i) return false;
    if ((row.real != nullptr) == (row.get_int != nullptr) || (row.get_int != nullptr) != (row.set_int != nullptr))
      return false;
  }
  return true;
}
static_assert(rows_in_enum_order(), "kQuantities: one row per Quantity, in enum order, float or integer");
#undef VIBROMAP_PHASE_ROWS

const QuantityInfo& info(Quantity q) {
  const auto i = static_cast<std::size_t>(q);
  if (i >= kQuantities.size()) throw std::invalid_argument("quantity without a row in kQuantities");
  return kQuantities[i];
}

const QuantityInfo& integer_info(Quantity q) {
  const QuantityInfo& row = info(q);
  if (row.get_int == nullptr) throw std::logic_error("quantity '" + std::string(row.name) + "' is not an integer");
  return row;
}
}  // namespace

const std::vector<Quantity>& all_quantities() {
  static const std::vector<Quantity> all = [] {
    std::vector<Quantity> v;
    for (const auto& i : kQuantities) v.push_back(i.q);
    return v;
  }();
  return all;
}

std::string to_string(Quantity q) { return std::string(info(q).name); }
std::string_view quantity_units(Quantity q) { return info(q).units; }
std::string_view quantity_description(Quantity q) { return info(q).description; }
bool quantity_is_integer(Quantity q) { return info(q).get_int != nullptr; }
std::int64_t quantity_max(Quantity q) { return integer_info(q).max; }

Bounds quantity_range(Quantity q) {
  const QuantityInfo& row = info(q);
  return row.real != nullptr ? row.range : Bounds::between(0.0, static_cast<double>(row.max));
}

Quantity parse_quantity(std::string_view s) {
  for (const auto& i : kQuantities)
    if (i.name == s) return i.q;
  throw std::invalid_argument("unknown quantity '" + std::string(s) + "'");
}

double CellResult::value(Quantity q) const {
  const QuantityInfo& row = info(q);
  return row.real != nullptr ? this->*row.real : static_cast<double>(row.get_int(*this));
}

void set_quantity(CellResult& c, Quantity q, double v) {
  const QuantityInfo& row = info(q);
  if (row.real != nullptr) {
    c.*row.real = v;
    return;
  }
  // Checked first: converting a NaN or an out-of-range double to an integer is undefined.
  if (!(v > -1.0 && v < static_cast<double>(row.max) + 1.0))
    throw std::invalid_argument("quantity '" + std::string(row.name) + "' out of range");
  row.set_int(c, static_cast<std::int64_t>(v));
}

std::int64_t quantity_int(const CellResult& c, Quantity q) { return integer_info(q).get_int(c); }
void set_quantity_int(CellResult& c, Quantity q, std::int64_t v) { integer_info(q).set_int(c, v); }

std::int8_t regime_code(RegimeKind k) { return static_cast<std::int8_t>(k); }
std::int8_t status_code(SolveStatus s) { return static_cast<std::int8_t>(s); }

CellResult summarize(const PointSummary& s) {
  CellResult c;
  c.status = status_code(s.status);
  c.regime = regime_code(s.regime.kind);
  c.n = s.regime.n;
  c.k = s.regime.k;
  c.hertz_valid = s.hertz_valid ? 1 : 0;
  c.stable = static_cast<std::int8_t>(s.stable);
  c.soft = s.soft ? 1 : 0;
  if (s.fragility.size > 0.0) c.fragile = s.fragility.fragile ? 1 : 0;
  if (!s.floquet.empty()) c.max_multiplier = std::abs(s.floquet.front());
  c.lyapunov = s.lyapunov;
  c.periods = s.periods;
  c.rhs_evals = s.counters.rhs_evals;
  c.wall_s = s.wall_s;
  c.t_transient = s.phases.transient.seconds;
  c.rhs_transient = s.phases.transient.rhs_evals;
  c.t_newton = s.phases.newton.seconds;
  c.rhs_newton = s.phases.newton.rhs_evals;
  c.t_integrate = s.phases.integrate.seconds;
  c.rhs_integrate = s.phases.integrate.rhs_evals;
  c.t_floquet = s.phases.floquet.seconds;
  c.rhs_floquet = s.phases.floquet.rhs_evals;
  c.t_classify = s.phases.classify.seconds;
  c.rhs_classify = s.phases.classify.rhs_evals;
  c.steady_residual = s.steady_residual;
  c.T_con = s.T_con;
  c.k_con = s.k_con;
  c.F_max = s.F_max;
  c.z_max = s.z_max;
  c.z_ratio = s.z_ratio;
  // The longest impact's entry velocity and impulse (the one that defines T_con).
  const auto longest = std::max_element(s.impacts.begin(), s.impacts.end(),
                                        [](const Impact& a, const Impact& b) { return a.T_con < b.T_con; });
  if (longest != s.impacts.end()) {
    c.v_in = longest->v_in;
    c.impulse = longest->impulse;
    c.e_effective = longest->e_effective;
    c.energy_dissipated = longest->energy_dissipated;
  }
  c.clipped_impacts = std::count_if(s.impacts.begin(), s.impacts.end(), [](const Impact& im) { return im.clipped; });
  return c;
}

CellResult summarize(const CensusSummary& s) {
  CellResult c;
  c.status = status_code(s.status);
  c.regime = regime_code(s.status == SolveStatus::ok ? RegimeKind::unresolved : RegimeKind::failed);
  c.periods = s.periods;
  c.rhs_evals = s.counters.rhs_evals;
  c.wall_s = s.wall_s;
  c.steady_residual = std::numeric_limits<double>::quiet_NaN();
  c.soft = 0;  // the motion from rest: its attractor's flag, when rest was decided
  if (s.status != SolveStatus::ok) return c;
  const double K = s.K > 0 ? static_cast<double>(s.K) : 1.0;
  c.soft_fraction = s.soft_fraction;
  c.unresolved_fraction = s.unresolved / K;
  c.unlisted_fraction = s.unlisted / K;
  c.budget_fraction = s.budget_states / K;
  c.basin_entropy = s.basin_entropy;
  c.census = s.attractors;
  bool rest_decided = false;
  for (const Attractor& a : s.attractors) {
    if (!a.from_rest) continue;
    rest_decided = true;
    c.regime = regime_code(a.regime.kind);
    c.n = a.regime.n;
    c.k = a.regime.k;
    c.stable = static_cast<std::int8_t>(a.stable);
    c.soft = a.soft ? 1 : 0;
    c.hertz_valid = a.hertz_valid ? 1 : 0;
    c.max_multiplier = a.max_floquet;
    c.T_con = a.T_con;
    c.k_con = a.k_con;
    c.F_max = a.F_max;
    c.z_max = a.z_max;
    c.z_ratio = a.z_ratio;
    c.v_in = a.v_in;
    c.impulse = a.impulse;
  }
  if (!rest_decided) c.status = status_code(SolveStatus::budget);  // rest's motion still settling at max_periods
  return c;
}

}  // namespace vibromap
