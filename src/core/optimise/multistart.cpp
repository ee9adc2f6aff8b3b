#include "vibromap/core/optimise/multistart.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "vibromap/core/analysis/point/shooting.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/core/optimise/point_objective.hpp"

namespace vibromap {
namespace {

constexpr double kSameOrbit = 1e-4;          // scaled distance under which a re-solved orbit is a census attractor

// The key a map axis stands for: its full key, or (a map that names only the coordinate) the
// key of that name.
std::optional<Key> axis_key(const Axis& a) { return Key::find(a.key.empty() ? a.name : a.key); }

// Every map axis is a free parameter, or the other form of a free spring or damper (k2 for a
// free omega2), so that a cell's point has a value of every free variable.
void check_axes(const Grid& grid, const OptimiseOptions& o) {
  for (const Axis& a : grid.axes()) {
    const std::optional<Key> k = axis_key(a);
    const auto frees = [&](const FreeVariable& v) { return k && (v.key == *k || v.name() == k->info().partner); };
    if (std::any_of(o.variables.begin(), o.variables.end(), frees)) continue;
    if (k && k->is_parameter())
      throw std::invalid_argument(cat("map axis ", a.name, " is not a free parameter of [optimise]: free it (",
                                      a.name, " = { min, max }) or seed from a map without it"));
    throw std::invalid_argument(cat("map axis ", clip(a.name), " is not a free parameter of [optimise], nor can it be one ",
                                    "(free parameters are the real keys of [system], [contact] and [forcing]): seed from ",
                                    "a map without it"));
  }
}

// The base parameters with cell `flat`'s axis values set (each axis names a free parameter or
// its partner, so k2 and omega2 keep their form); `x` holds one value per axis.
Parameters cell_parameters(const std::vector<Key>& keys, const Grid& grid, const Parameters& base, std::size_t flat,
                           std::vector<double>& x) {
  grid.coordinates(flat, x);
  Parameters p = base;
  for (std::size_t d = 0; d < x.size(); ++d) keys[d].set(p, x[d]);
  return p;
}

Quantity ranking_quantity(ObjectiveKind k) {
  switch (k) {
    case ObjectiveKind::min_k_con: return Quantity::k_con;
    case ObjectiveKind::max_T_con: return Quantity::T_con;
    case ObjectiveKind::min_F_max: return Quantity::F_max;
  }
  return Quantity::k_con;
}

bool is_stored(const std::vector<Quantity>& stored, Quantity q) {
  return std::find(stored.begin(), stored.end(), q) != stored.end();
}

// A map cell that keeps the regime with the stability rule.
bool cell_qualifies(const CellResult& c, const OptimiseOptions& o) {
  if (c.status != status_code(SolveStatus::ok) || !(c.T_con > 0.0)) return false;
  if (o.regime) {
    if (c.regime != regime_code(o.regime->kind)) return false;
    if (o.regime->kind == RegimeKind::periodic && (c.n != o.regime->n || c.k != o.regime->k)) return false;
  }
  if (o.stability == StabilityRule::required) return c.stable == 1;
  if (o.stability == StabilityRule::if_known) return c.stable != 0;
  return true;
}

}  // namespace

SeedSelector::SeedSelector(const Grid& grid, const std::vector<Quantity>& stored, const Parameters& base,
                           const OptimiseOptions& o)
    : grid_(grid), stored_(stored), base_(base), o_(o), box_(o.variables),
      quantity_(ranking_quantity(o.objective)), x_(grid.axes().size()) {
  if (!is_stored(stored, quantity_))
    throw std::invalid_argument(cat("the map does not store ", to_string(quantity_), ", which ranks the cells for ",
                                    to_string(o.objective), ": add it to [sweep] store"));
  if (o.hertz_valid && !is_stored(stored, Quantity::hertz_valid))
    throw std::invalid_argument("the map does not store hertz_valid, which hertz_valid = true needs (every map a "
                                "sweep writes stores it)");
  check_axes(grid, o);
  for (const Axis& a : grid.axes()) axis_keys_.push_back(*axis_key(a));
}

void SeedSelector::offer(std::uint64_t flat, const CellResult& c) {
  if (!cell_qualifies(c, o_)) return;
  if (o_.hertz_valid && c.hertz_valid != 1) return;
  const Parameters p = cell_parameters(axis_keys_, grid_, base_, static_cast<std::size_t>(flat), x_);
  Seed s{{}, static_cast<long>(flat), objective_sense(o_.objective) * c.value(quantity_)};
  for (const FreeVariable& v : o_.variables) s.x.push_back(v.key.value(p));
  if (!std::isfinite(s.value) || !box_.contains(s.x)) return;
  s.x = box_.to_physical(box_.to_scaled(s.x));  // a hair outside the box (rounding) comes inside
  best_.push_back(std::move(s));
  if (best_.size() > 4 * static_cast<std::size_t>(o_.seeds) + 64) trim();
}

// Keeps the best o.seeds candidates: by value, ties by cell index (the order cells were offered).
void SeedSelector::trim() {
  std::stable_sort(best_.begin(), best_.end(), [](const Seed& a, const Seed& b) { return a.value < b.value; });
  best_.resize(std::min(best_.size(), static_cast<std::size_t>(o_.seeds)));
}

std::vector<Seed> SeedSelector::seeds() {
  if (best_.empty())
    throw std::invalid_argument(cat("no cell of the map keeps the regime ", o_.regime ? o_.regime->label() : "(any)",
                                    " (stability ", to_string(o_.stability), o_.hertz_valid ? ", Hertz theory valid" : "",
                                    ") inside the box: nothing to seed from"));
  trim();
  return best_;
}

std::vector<Seed> select_seeds(const Grid& grid, const std::vector<CellResult>& cells,
                               const std::vector<std::uint8_t>& done, const std::vector<Quantity>& stored,
                               const Parameters& base, const OptimiseOptions& o) {
  SeedSelector selector(grid, stored, base, o);
  for (std::size_t i = 0; i < grid.size() && i < cells.size() && i < done.size(); ++i)
    if (done[i]) selector.offer(i, cells[i]);
  return selector.seeds();
}

Seed scene_seed(const Parameters& base, const OptimiseOptions& o) {
  const Box box(o.variables);
  Seed s;
  for (const FreeVariable& v : o.variables) s.x.push_back(v.key.value(base));
  s.x = box.to_physical(box.to_scaled(s.x));
  return s;
}

std::vector<StartSpec> plan_starts(std::size_t seeds, const std::vector<Algorithm>& algorithms,
                                   const std::vector<ContactLawKind>& laws) {
  std::vector<std::optional<ContactLawKind>> each_law(laws.begin(), laws.end());
  if (each_law.empty()) each_law.emplace_back();  // the scene's
  std::vector<StartSpec> plan;
  for (std::size_t s = 0; s < seeds; ++s)
    for (const auto& law : each_law)
      for (const Algorithm a : algorithms) plan.push_back({static_cast<int>(plan.size()), static_cast<int>(s), a, law});
  return plan;
}

Parameters start_parameters(const Parameters& base, const StartSpec& spec) {
  Parameters p = base;
  if (spec.law) p.law = *spec.law;
  return p;
}

std::vector<std::pair<std::size_t, std::size_t>> best_points(const std::vector<StartRecord>& starts, const Box& box,
                                                             int count, double merge) {
  std::vector<std::pair<std::size_t, std::size_t>> found;
  for (std::size_t i = 0; i < starts.size(); ++i)
    if (starts[i].result.best) found.emplace_back(i, *starts[i].result.best);
  const auto value = [&](const std::pair<std::size_t, std::size_t>& p) {
    return starts[p.first].result.evaluations[p.second].result.value;
  };
  std::stable_sort(found.begin(), found.end(), [&](const auto& a, const auto& b) { return value(a) < value(b); });
  std::vector<std::pair<std::size_t, std::size_t>> kept;
  std::vector<std::vector<double>> kept_u;
  for (const auto& p : found) {
    if (static_cast<int>(kept.size()) >= count) break;
    const std::vector<double> u = box.to_scaled(starts[p.first].result.evaluations[p.second].x);
    const auto close = [&](std::size_t k) {  // the same point: the same law, and every variable within merge
      if (starts[kept[k].first].spec.law != starts[p.first].spec.law) return false;
      for (std::size_t i = 0; i < u.size(); ++i)
        if (std::abs(u[i] - kept_u[k][i]) > merge) return false;
      return true;
    };
    bool seen = false;
    for (std::size_t k = 0; k < kept.size() && !seen; ++k) seen = close(k);
    if (seen) continue;
    kept.push_back(p);
    kept_u.push_back(u);
  }
  return kept;
}

VerifiedPoint verify_point(const Parameters& base, const PointOptions& options, const OptimiseOptions& o,
                           const StartRecord& start, std::size_t evaluation, int trajectory_periods,
                           const CensusOptions& census) {
  const EvaluationRecord& rec = start.result.evaluations.at(evaluation);
  VerifiedPoint v;
  v.start = start.spec.index;
  v.evaluation = evaluation;
  v.x = rec.x;
  v.params = PointObjective(start_parameters(base, start.spec), options, o).parameters_at(rec.x);
  v.value = rec.result.value;
  v.integrate = resolve_point(v.params, options, SteadyMethod::integrate, o.verify_rtol, trajectory_periods);
  v.shooting = resolve_point(v.params, options, SteadyMethod::shooting, o.verify_rtol);
  if (rec.result.measures.size() > kSoftFractionMeasure) v.soft_fraction = rec.result.measures[kSoftFractionMeasure];
  if (o.min_soft_fraction > 0.0) {
    const PointSummary& orbit = options.analysis.steady == SteadyMethod::shooting ? v.shooting : v.integrate;
    v.soft_check = check_soft_fraction(v.params, options, census, o, orbit);
  }
  return v;
}

CensusOptions soft_check_options(const CensusOptions& census, const OptimiseOptions& o) {
  CensusOptions c = census;
  c.initial_conditions = std::max(o.soft_check_initial_conditions, 4 * census.initial_conditions);
  c.seed = census.seed + 1;
  c.labels = false;
  return c;
}

SoftCheck check_soft_fraction(const Parameters& p, const PointOptions& options, const CensusOptions& census,
                              const OptimiseOptions& o, const PointSummary& orbit) {
  SoftCheck c;
  const CensusOptions check = soft_check_options(census, o);
  c.seed = check.seed;
  c.census = census_point(p, options, check);
  const double K = std::max(c.census.K, 1);
  c.fraction = c.census.soft_fraction;
  c.fraction_stderr = std::sqrt(c.fraction * (1.0 - c.fraction) / K);
  c.passed = c.census.status == SolveStatus::ok &&
             c.fraction >= soft_check_threshold(c, o) - kSoftFractionRounding;
  if (orbit.status != SolveStatus::ok) return c;
  const StateScale scale{Model(p)};
  for (std::size_t i = 0; i < c.census.attractors.size() && c.orbit_attractor < 0; ++i) {
    const Attractor& a = c.census.attractors[i];
    if (!a.periodic || !(a.regime == orbit.regime)) continue;
    for (const Eigen::Vector4d& y : a.strobe) {
      if (scale.distance(y, orbit.final_state) > kSameOrbit) continue;
      c.orbit_attractor = static_cast<int>(i);
      c.orbit_fraction = a.fraction;
      break;
    }
  }
  return c;
}

void prefer_passing(std::vector<VerifiedPoint>& best) {
  std::stable_partition(best.begin(), best.end(),
                        [](const VerifiedPoint& v) { return !v.soft_check || v.soft_check->passed; });
}

long OptimiseReport::evaluations() const {
  return std::accumulate(starts.begin(), starts.end(), 0L,
                         [](long n, const StartRecord& s) { return n + static_cast<long>(s.result.evaluations.size()); });
}

}  // namespace vibromap
