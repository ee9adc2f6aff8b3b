#include "vibromap/io/optimise_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

#include "vibromap/io/hdf5_file.hpp"
#include "attribute_seal.hpp"
#include "index_scale.hpp"
#include "regime_flags.hpp"
#include "vibromap/core/optimise/point_objective.hpp"

// The layout is documented in optimise_file.hpp.

namespace vibromap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out.append(out.empty() ? "" : " ").append(s);
  return out;
}

// "000", "001", ...: group names that sort in start order.
std::string padded(std::size_t i, int width) {
  std::array<char, 32> buf{};
  std::snprintf(buf.data(), buf.size(), "%0*zu", width, i);
  return std::string(buf.data());
}

void write_root(Hdf5File& f, const OptimiseReport& r, const OptimiseOptions& o, const std::string& scene_text) {
  f.set_attribute("title", "vibromap multistart optimisation");
  f.set_attribute("vibromap_version", VIBROMAP_VERSION);
  f.set_attribute("scene", scene_text);
  f.set_attribute("objective", to_string(o.objective));
  f.set_attribute("quantity", objective_quantity(o.objective));
  f.set_attribute("sense", objective_sense(o.objective) > 0 ? "minimise" : "maximise");
  f.set_attribute("impact", o.impact);
  f.set_attribute("regime", o.regime ? o.regime->label() : std::string("any"));
  f.set_attribute("stability", to_string(o.stability));
  f.set_attribute("hertz_valid", o.hertz_valid ? 1 : 0);
  f.set_attribute("min_soft_fraction", o.min_soft_fraction);
  f.set_attribute("soft_check_initial_conditions", o.soft_check_initial_conditions);
  f.set_attribute("variables", joined(r.variables));
  if (!o.laws.empty()) {
    std::vector<std::string> laws;
    for (const ContactLawKind k : o.laws) laws.push_back(to_string(k));
    f.set_attribute("laws", joined(laws));  // the contact law free: each start group says its own
  }
  std::vector<std::string> scales;
  for (const FreeVariable& v : o.variables) scales.push_back(to_string(v.scale));
  f.set_attribute("scales", joined(scales));
  f.set_attribute("measures", joined(r.measures));
  f.set_attribute("seeds_from", r.seeds_from);
  f.set_attribute("ranks", r.ranks);
  f.set_attribute("starts", static_cast<std::int64_t>(r.starts.size()));
  f.set_attribute("evaluations", r.evaluations());
  f.set_attribute("wall_s", r.wall_s);
  f.set_attribute("sweep_wall_s", r.sweep_wall_s);
  f.set_attribute("optimise_wall_s", r.optimise_wall_s);
  f.set_attribute("verify_wall_s", r.verify_wall_s);
  f.set_attribute("trajectory", r.trajectory_file);
}

// One dimension scale per axis of every dataset (netCDF-4, xarray): /variable is the free
// parameters' (the root attribute `variables` names them), shared by the groups below.
Dataset write_seeds(Hdf5File& f, const OptimiseReport& r, const OptimiseOptions& o) {
  Dataset variable = detail::write_index_scale(f, "variable", o.variables.size(),
                                               "free parameter, in the order of the root attribute 'variables'");
  const Dataset bound = detail::write_flag_scale(f, "bound", {"min", "max"}, "lower and upper bound");
  const Dataset seed = detail::write_index_scale(f, "seed", r.seeds.size(), "seed, in start order");
  std::vector<double> bounds;
  for (const FreeVariable& v : o.variables) bounds.insert(bounds.end(), {v.min, v.max});
  Dataset bd = f.write_dataset("bounds", bounds, {o.variables.size(), 2});
  bd.attach_dimension_scale(variable, 0);
  bd.attach_dimension_scale(bound, 1);
  std::vector<double> x, objective;
  std::vector<std::int64_t> cell;
  for (const Seed& s : r.seeds) {
    x.insert(x.end(), s.x.begin(), s.x.end());
    cell.push_back(s.cell);
    objective.push_back(s.cell >= 0 ? objective_sense(o.objective) * s.value : kNaN);
  }
  Dataset sd = f.write_dataset("seeds", x, {r.seeds.size(), o.variables.size()});
  sd.attach_dimension_scale(seed, 0);
  sd.attach_dimension_scale(variable, 1);
  f.write_dataset("seed_cell", cell).attach_dimension_scale(seed, 0);
  f.write_dataset("seed_objective", objective).attach_dimension_scale(seed, 0);
  return variable;
}

void write_start_attributes(Group& g, const StartRecord& s, double sense) {
  const LocalResult& r = s.result;
  g.set_attribute("index", s.spec.index);
  g.set_attribute("seed", s.spec.seed);
  g.set_attribute("algorithm", to_string(s.spec.algorithm));
  if (s.spec.law) g.set_attribute("law", to_string(*s.spec.law));
  g.set_attribute("stop", r.stop);
  g.set_attribute("nlopt_code", r.nlopt_code);
  g.set_attribute("rank", s.rank);
  g.set_attribute("calls", r.calls);
  g.set_attribute("cache_hits", r.cache_hits);
  g.set_attribute("wall_s", r.wall_s);
  g.set_attribute("best", r.best ? static_cast<std::int64_t>(*r.best) : std::int64_t{-1});
  g.set_attribute("best_objective", r.best ? sense * r.evaluations[*r.best].result.value : kNaN);
}

void write_start(Group& g, const StartRecord& s, const Dataset& variable, const std::vector<std::string>& measures,
                 double sense) {
  write_start_attributes(g, s, sense);
  const auto& ev = s.result.evaluations;
  std::vector<double> x, objective, value, violation, wall;
  std::vector<std::uint8_t> feasible;
  std::vector<std::int8_t> regime, stable;
  std::vector<int> n, k;
  std::vector<std::vector<double>> measure(measures.size());
  for (const EvaluationRecord& e : ev) {
    x.insert(x.end(), e.x.begin(), e.x.end());
    objective.push_back(sense * e.result.value);
    value.push_back(e.result.value);
    violation.push_back(e.result.violation);
    feasible.push_back(e.result.feasible ? 1 : 0);
    regime.push_back(regime_code(e.result.regime.kind));
    n.push_back(e.result.regime.n);
    k.push_back(e.result.regime.k);
    stable.push_back(static_cast<std::int8_t>(e.result.stable));
    for (std::size_t m = 0; m < measures.size(); ++m)
      measure[m].push_back(m < e.result.measures.size() ? e.result.measures[m] : kNaN);
    wall.push_back(e.wall_s);
  }
  const Dataset evaluation = detail::write_index_scale(g, "evaluation", ev.size(), "distinct evaluation, in order");
  const auto column = [&](const std::string& name, const auto& values) {
    Dataset d = g.write_dataset(name, values);
    d.attach_dimension_scale(evaluation, 0);
    return d;
  };
  Dataset xd = g.write_dataset("x", x, {ev.size(), variable.shape().at(0)});
  xd.attach_dimension_scale(evaluation, 0);
  xd.attach_dimension_scale(variable, 1);
  column("objective", objective);
  column("value", value);
  column("violation", violation);
  column("feasible", feasible);
  Dataset rd = column("regime", regime);
  detail::set_regime_flags(rd);
  column("n", n);
  column("k", k);
  column("stable", stable);
  for (std::size_t m = 0; m < measures.size(); ++m) column(measures[m], measure[m]);
  column("wall_s", wall).set_attribute("units", "s");
}

void write_solve(Group g, const PointSummary& s) {
  g.set_attribute("status", to_string(s.status));
  g.set_attribute("message", s.message);
  g.set_attribute("regime", s.regime.label());
  g.set_attribute("n", s.regime.n);
  g.set_attribute("k", s.regime.k);
  g.set_attribute("stable", s.stable);
  g.set_attribute("T", s.T);
  g.set_attribute("T_con", s.T_con);
  g.set_attribute("k_con", s.k_con);
  g.set_attribute("F_max", s.F_max);
  g.set_attribute("z_max", s.z_max);
  g.set_attribute("z_ratio", s.z_ratio);
  g.set_attribute("hertz_valid", s.hertz_valid ? 1 : 0);
  g.set_attribute("periods", s.periods);
  g.set_attribute("steady_residual", s.steady_residual);
  g.set_attribute("max_multiplier", max_multiplier(s));
  g.set_attribute("wall_s", s.wall_s);
  if (s.floquet.empty()) return;
  std::vector<double> mu;
  for (const auto& m : s.floquet) mu.insert(mu.end(), {m.real(), m.imag()});
  const Dataset multiplier = detail::write_index_scale(g, "multiplier", s.floquet.size(), "Floquet multiplier");
  const Dataset part = detail::write_flag_scale(g, "part", {"real", "imaginary"}, "part of the complex multiplier");
  Dataset fd = g.write_dataset("floquet", mu, {s.floquet.size(), 2});
  fd.attach_dimension_scale(multiplier, 0);
  fd.attach_dimension_scale(part, 1);
}

// The re-check census of a best point: its verdict as attributes, its attractors as columns.
void write_soft_check(Group g, const SoftCheck& c, const OptimiseOptions& o) {
  g.set_attribute("status", to_string(c.census.status));
  g.set_attribute("message", c.census.message);
  g.set_attribute("initial_conditions", c.census.K);
  g.set_attribute("seed", static_cast<std::int64_t>(c.seed));
  g.set_attribute("soft_fraction", c.fraction);
  g.set_attribute("soft_fraction_stderr", c.fraction_stderr);
  g.set_attribute("threshold", soft_check_threshold(c, o));
  g.set_attribute("passed", c.passed ? 1 : 0);
  g.set_attribute("orbit_attractor", c.orbit_attractor);
  g.set_attribute("orbit_fraction", c.orbit_fraction);
  g.set_attribute("unresolved", c.census.unresolved);
  g.set_attribute("unlisted", c.census.unlisted);
  g.set_attribute("wall_s", c.census.wall_s);
  std::vector<double> k_con, T_con, fraction, stderr_;
  std::vector<std::int8_t> regime, stable;
  std::vector<int> n, k;
  std::vector<std::uint8_t> soft;
  for (const Attractor& a : c.census.attractors) {
    regime.push_back(regime_code(a.regime.kind));
    n.push_back(a.regime.n);
    k.push_back(a.regime.k);
    k_con.push_back(a.k_con);
    T_con.push_back(a.T_con);
    fraction.push_back(a.fraction);
    stderr_.push_back(a.fraction_stderr);
    stable.push_back(static_cast<std::int8_t>(a.stable));
    soft.push_back(a.soft ? 1 : 0);
  }
  const Dataset attractor = detail::write_index_scale(g, "attractor", regime.size(), "attractor of the census");
  const auto column = [&](const std::string& name, const auto& values) {
    Dataset d = g.write_dataset(name, values);
    d.attach_dimension_scale(attractor, 0);
    return d;
  };
  Dataset rd = column("regime", regime);
  detail::set_regime_flags(rd);
  column("n", n);
  column("k", k);
  column("k_con", k_con);
  column("T_con", T_con).set_attribute("units", "s");
  column("fraction", fraction);
  column("fraction_stderr", stderr_);
  column("stable", stable);
  column("soft", soft);
}

// The parameters a best point's group names as attributes: the source paper's search box and the
// restitution always (so that files of any run compare), then every other free parameter.
std::vector<Key> point_attribute_keys(const OptimiseOptions& o) {
  std::vector<Key> keys;
  for (const std::string_view name : {"E1", "E2", "R1", "R2", "m2", "k2", "omega2", "restitution"})
    keys.push_back(Key::at(name));
  for (const FreeVariable& f : o.variables)
    if (std::find(keys.begin(), keys.end(), f.key) == keys.end()) keys.push_back(f.key);
  return keys;
}

void write_best(Group& g, const VerifiedPoint& v, const OptimiseOptions& o, const Dataset& variable) {
  const double sense = objective_sense(o.objective);
  g.set_attribute("start", v.start);
  g.set_attribute("evaluation", static_cast<std::int64_t>(v.evaluation));
  g.set_attribute("objective", sense * v.value);
  g.set_attribute("soft_fraction", v.soft_fraction);
  for (const Key k : point_attribute_keys(o)) g.set_attribute(k.info().name, k.value(v.params));
  g.set_attribute("law", to_string(v.params.law));
  g.write_dataset("x", v.x).attach_dimension_scale(variable, 0);
  write_solve(g.create_group("integrate"), v.integrate);
  write_solve(g.create_group("shooting"), v.shooting);
  if (v.soft_check) write_soft_check(g.create_group("soft_check"), *v.soft_check, o);
}

}  // namespace

void write_optimise_file(const std::string& path, const OptimiseReport& report, const OptimiseOptions& options,
                         const std::string& scene_text) {
  const double sense = objective_sense(options.objective);
  write_hdf5_atomically(path, [&](Hdf5File& f) {
    write_root(f, report, options, scene_text);
    const Dataset variable = write_seeds(f, report, options);
    Group starts = f.create_group("starts");
    for (std::size_t i = 0; i < report.starts.size(); ++i) {
      Group g = starts.create_group(padded(i, 3));
      write_start(g, report.starts[i], variable, report.measures, sense);
    }
    Group best = f.create_group("best");
    for (std::size_t i = 0; i < report.best.size(); ++i) {
      Group g = best.create_group(padded(i, 2));
      write_best(g, report.best[i], options, variable);
    }
    detail::seal_attributes(f, kOptimiseFormat);  // last: the format version, then the seal over every attribute (attribute_seal.hpp)
  });
}

}  // namespace vibromap
