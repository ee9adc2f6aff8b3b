// An optimisation's output: see include/vibromap/io/optimise_output.hpp.

#include "vibromap/io/optimise_output.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <string_view>

#include "vibromap/core/optimise/point_objective.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/report.hpp"
#include "vibromap/io/scene/keys.hpp"

namespace vibromap {

namespace {

constexpr double kAgreeTol = 1e-6;  // relative k_con difference under which the two re-solves agree

// The parameters a best point shows: the source paper's search box always, then every other free
// parameter (the restitution is shown with the law).
std::vector<Key> shown_parameters(const OptimiseOptions& o) {
  std::vector<Key> keys;
  for (const std::string_view name : {"m2", "k2", "omega2", "E1", "E2", "R1", "R2"}) keys.push_back(Key::at(name));
  for (const FreeVariable& f : o.variables)
    if (std::find(keys.begin(), keys.end(), f.key) == keys.end() && f.name() != "restitution") keys.push_back(f.key);
  return keys;
}

// One algorithm's starts taken together (every algorithm runs from the same seeds).
struct AlgorithmSummary {
  Algorithm algorithm = Algorithm::bobyqa;
  int starts = 0;
  long evaluations = 0;
  double wall_s = 0.0;                                         // sum over its starts, s
  double best = std::numeric_limits<double>::quiet_NaN();      // best objective (quantity), NaN: none feasible
};

std::vector<AlgorithmSummary> by_algorithm(const OptimiseReport& r, const OptimiseOptions& o) {
  std::vector<AlgorithmSummary> out;
  for (const Algorithm a : o.algorithms) {
    AlgorithmSummary sum{a};
    double best_value = std::numeric_limits<double>::infinity();
    for (const StartRecord& s : r.starts) {
      if (s.spec.algorithm != a) continue;
      ++sum.starts;
      sum.evaluations += static_cast<long>(s.result.evaluations.size());
      sum.wall_s += s.result.wall_s;
      if (s.result.best) best_value = std::min(best_value, s.result.evaluations[*s.result.best].result.value);
    }
    if (std::isfinite(best_value)) sum.best = objective_sense(o.objective) * best_value;
    out.push_back(sum);
  }
  return out;
}

bool solves_agree(const VerifiedPoint& v) {
  return v.integrate.regime == v.shooting.regime && v.integrate.stable == v.shooting.stable &&
         std::abs(v.integrate.k_con - v.shooting.k_con) <= kAgreeTol * std::abs(v.integrate.k_con);
}

// A start's algorithm, and its law when the law is free.
std::string start_label(const StartSpec& s) {
  return s.law ? to_string(s.algorithm) + " " + to_string(*s.law) : to_string(s.algorithm);
}

// ---- JSON ---------------------------------------------------------------------------------

void write_solve_json(JsonWriter& w, const PointSummary& s) {
  w.begin_object().field("status", to_string(s.status)).field("regime", s.regime.label());
  write_stable_json(w.key("stable"), s.stable);
  w.field("k_con", s.k_con).field("T_con", s.T_con).field("F_max", s.F_max).field("z_ratio", s.z_ratio);
  w.field("max_multiplier", max_multiplier(s)).field("periods", s.periods).field("wall_s", s.wall_s).end_object();
}

void write_soft_check_json(JsonWriter& w, const VerifiedPoint& v, const OptimiseOptions& o) {
  w.field("soft_fraction", v.soft_fraction).key("soft_check");
  if (!v.soft_check) {
    w.null();
    return;
  }
  const SoftCheck& c = *v.soft_check;
  w.begin_object().field("status", to_string(c.census.status)).field("initial_conditions", c.census.K);
  w.field("seed", c.seed).field("soft_fraction", c.fraction).field("soft_fraction_stderr", c.fraction_stderr);
  w.field("threshold", soft_check_threshold(c, o)).field("passed", c.passed).key("orbit_attractor");
  if (c.orbit_attractor < 0) {
    w.null();
  } else {
    w.value(c.orbit_attractor);
  }
  w.field("orbit_fraction", c.orbit_fraction).field("wall_s", c.census.wall_s).key("attractors").begin_array();
  for (const Attractor& a : c.census.attractors) {
    w.begin_object().field("regime", a.regime.label()).field("k_con", a.k_con).field("fraction", a.fraction);
    w.field("fraction_stderr", a.fraction_stderr).field("hertz_valid", a.hertz_valid);
    write_stable_json(w.key("stable"), a.stable).field("soft", a.soft).end_object();
  }
  w.end_array().end_object();
}

void write_best_json(JsonWriter& w, const OptimiseReport& r, const VerifiedPoint& v, const OptimiseOptions& o) {
  const PointSummary& s = v.integrate;
  w.begin_object().key("params").begin_object();
  for (const Key k : shown_parameters(o)) w.field(k.info().name, k.value(v.params));
  w.end_object().field("k_con", s.k_con).field("T_con", s.T_con).field("F_max", s.F_max).field("regime", s.regime.label());
  write_stable_json(w.key("stable"), s.stable);
  w.field("z_ratio", s.z_ratio).field("hertz_valid", s.hertz_valid).field("soft", s.soft);
  w.field("objective_found", objective_sense(o.objective) * v.value).field("start", v.start);
  w.field("algorithm", to_string(r.starts.at(static_cast<std::size_t>(v.start)).spec.algorithm));
  w.field("law", to_string(v.params.law)).field("restitution", v.params.restitution);
  w.key("set").begin_array();
  for (const std::string& arg : optimised_overrides(v.params, o)) w.value(arg);
  w.end_array().key("integrate");
  write_solve_json(w, v.integrate);
  w.key("shooting");
  write_solve_json(w, v.shooting);
  w.field("agree", solves_agree(v));
  write_soft_check_json(w, v, o);
  w.end_object();
}

void write_starts_json(JsonWriter& w, const OptimiseReport& r, const OptimiseOptions& o) {
  w.key("starts").begin_array();
  for (const StartRecord& s : r.starts) {
    const LocalResult& lr = s.result;
    w.begin_object().field("start", s.spec.index).field("seed", s.spec.seed).field("algorithm", to_string(s.spec.algorithm));
    if (s.spec.law) w.field("law", to_string(*s.spec.law));
    w.field("evaluations", lr.evaluations.size()).field("cache_hits", lr.cache_hits).field("calls", lr.calls);
    w.key("best_objective");
    if (lr.best) {
      w.value(objective_sense(o.objective) * lr.evaluations[*lr.best].result.value);
    } else {
      w.null();
    }
    w.field("stop", lr.stop).field("nlopt_code", lr.nlopt_code).field("rank", s.rank).field("wall_s", lr.wall_s).end_object();
  }
  w.end_array();
}

void write_algorithms_json(JsonWriter& w, const OptimiseReport& r, const OptimiseOptions& o) {
  w.key("algorithms").begin_array();
  for (const AlgorithmSummary& a : by_algorithm(r, o)) {
    w.begin_object().field("algorithm", to_string(a.algorithm)).field("starts", a.starts);
    w.field("evaluations", a.evaluations).field("best_objective", a.best).field("wall_s", a.wall_s).end_object();
  }
  w.end_array();
}

// ---- the table ----------------------------------------------------------------------------

// A cell of the starts' tables: padded to `width`, then one space.
std::string cell(const std::string& s, std::size_t width) { return pad_right(s, width) + " "; }

// The run: output, objective and constraints, seeds, starts, times, trajectory.
void write_run_lines(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o, const std::string& output) {
  out << "output         " << output << "\n"
      << "objective      " << to_string(o.objective) << ", keeping " << (o.regime ? o.regime->label() : "any regime")
      << " (stability " << to_string(o.stability) << (o.hertz_valid ? ", Hertz theory valid" : "") << ")\n";
  if (o.min_soft_fraction > 0.0)
    out << "robust         soft attractors hold >= " << number(o.min_soft_fraction)
        << " of the basin (a census per feasible point; the best points re-checked)\n";
  out << "seeds          " << r.seeds.size() << " from " << r.seeds_from << "\n"
      << "starts         " << r.starts.size() << " on " << r.ranks << (r.ranks == 1 ? " rank, " : " ranks, ")
      << r.evaluations() << " evaluations\n"
      << "wall time      " << number(r.wall_s, 4) << " s (sweep " << number(r.sweep_wall_s, 4) << ", starts "
      << number(r.optimise_wall_s, 4) << ", re-solves " << number(r.verify_wall_s, 4) << ")\n";
  if (!r.trajectory_file.empty()) out << "trajectory     " << r.trajectory_file << "\n";
  out << "\n";
}

void write_starts_table(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o) {
  const std::string q = objective_quantity(o.objective);
  const int label = o.laws.empty() ? 20 : 40;
  out << cell("start", 6) << cell("seed", 5) << cell(o.laws.empty() ? "algorithm" : "algorithm law", label)
      << cell("evals", 6) << cell("hits", 6)
      << cell("best " + q, 12) << cell("stop", 18) << "wall s\n";
  for (const StartRecord& s : r.starts) {
    const LocalResult& lr = s.result;
    const std::string best = lr.best ? number(objective_sense(o.objective) * lr.evaluations[*lr.best].result.value) : "-";
    out << cell(std::to_string(s.spec.index), 6) << cell(std::to_string(s.spec.seed), 5)
        << cell(start_label(s.spec), label) << cell(std::to_string(lr.evaluations.size()), 6)
        << cell(std::to_string(lr.cache_hits), 6) << cell(best, 12) << cell(lr.stop, 18) << number(lr.wall_s, 3) << "\n";
  }
}

// With the law free: the best objective each law reached, from the same seeds and algorithms.
void write_laws_table(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o) {
  if (o.laws.empty()) return;
  out << "\nper contact law, from the same seeds and algorithms:\n"
      << cell("law", 22) << cell("starts", 7) << "best " << objective_quantity(o.objective) << "\n";
  for (const ContactLawKind law : o.laws) {
    int starts = 0;
    double best = std::numeric_limits<double>::infinity();
    for (const StartRecord& s : r.starts) {
      if (s.spec.law != law) continue;
      ++starts;
      if (s.result.best) best = std::min(best, s.result.evaluations[*s.result.best].result.value);
    }
    out << cell(to_string(law), 22) << cell(std::to_string(starts), 7)
        << (std::isfinite(best) ? number(objective_sense(o.objective) * best) : std::string("- (none feasible)")) << "\n";
  }
}

void write_algorithms_table(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o) {
  out << "\nper algorithm, from the same seeds:\n"
      << cell("algorithm", 20) << cell("starts", 7) << cell("best " + objective_quantity(o.objective), 12)
      << cell("evaluations", 12) << "wall s (sum of its starts)\n";
  for (const AlgorithmSummary& a : by_algorithm(r, o)) {
    out << cell(to_string(a.algorithm), 20) << cell(std::to_string(a.starts), 7)
        << cell(std::isnan(a.best) ? "-" : number(a.best), 12) << cell(std::to_string(a.evaluations), 12)
        << number(a.wall_s, 3) << "\n";
  }
}

// The soft attractors of a re-check census, and which of them the optimised orbit is.
void write_soft_attractors(std::ostream& out, const SoftCheck& c) {
  out << "soft attractors:";
  bool any = false;
  for (std::size_t i = 0; i < c.census.attractors.size(); ++i) {
    const Attractor& a = c.census.attractors[i];
    if (!a.soft) continue;
    out << (any ? ";" : "") << " " << a.regime.label() << " k_con " << number(a.k_con) << " fraction "
        << number(a.fraction, 4) << (static_cast<int>(i) == c.orbit_attractor ? " (the optimised orbit)" : "");
    any = true;
  }
  if (!any) out << " none";
  if (c.orbit_attractor < 0) {
    out << "; the optimised orbit is not among the census's attractors";
  } else if (!c.census.attractors[static_cast<std::size_t>(c.orbit_attractor)].soft) {
    out << "; the optimised orbit (fraction " << number(c.orbit_fraction, 4) << ") is not soft";
  }
  out << "\n    ";
}

// A best point's soft fraction: the optimiser's census, the re-check, its verdict, and the
// soft attractors (which the optimised orbit is among them, when it is).
void write_soft_check(std::ostream& out, const VerifiedPoint& v, const OptimiseOptions& o) {
  if (!v.soft_check) return;
  const SoftCheck& c = *v.soft_check;
  out << "soft fraction  " << number(v.soft_fraction, 4) << " (optimiser's census); re-check of "
      << c.census.K << " other initial states: " << number(c.fraction, 4) << " +- " << number(c.fraction_stderr, 2);
  if (c.census.status != SolveStatus::ok) {
    out << "  FAILS THE SOFT CHECK: the census failed (" << c.census.message << ")\n    ";
  } else if (c.passed) {
    out << "  passes (>= " << number(o.min_soft_fraction) << " - 3 stderr = " << number(soft_check_threshold(c, o), 4)
        << ")\n    ";
  } else {
    out << "  FAILS THE SOFT CHECK (< " << number(o.min_soft_fraction) << " - 3 stderr = "
        << number(soft_check_threshold(c, o), 4) << ")\n    ";
  }
  write_soft_attractors(out, c);
}

// Best point #i: both re-solves, Hertz validity, softness, the soft check, its parameters and
// the --set overrides that give it.
void write_best_point(std::ostream& out, std::size_t i, const VerifiedPoint& v, const OptimiseOptions& o) {
  const PointSummary& s = v.integrate;
  out << "#" << i << "  k_con " << number(s.k_con) << "  T_con " << number(s.T_con) << " s  F_max " << number(s.F_max)
      << " N  regime " << s.regime.label() << " " << stability_text(s.stable) << "  (shooting: k_con "
      << number(v.shooting.k_con) << ", " << v.shooting.regime.label() << " " << stability_text(v.shooting.stable)
      << (solves_agree(v) ? ", agrees" : ", DISAGREES") << ")  start " << v.start << "\n    ";
  if (!s.hertz_valid)
    out << "HERTZ-INVALID: z_max/R* = " << number(s.z_ratio, 3)
        << " beyond [analysis] hertz_limit: the force law does not hold there (optimise.hertz_valid = false)\n    ";
  out << "soft " << (s.soft ? "yes" : "no") << " (periodic with impacts, stable, Hertz-valid, k_con <= analysis.soft_kcon)\n    ";
  write_soft_check(out, v, o);
  for (const Key k : shown_parameters(o)) out << k.info().name << " " << number(k.value(v.params)) << "  ";
  out << "law " << to_string(v.params.law);
  if (v.params.law != ContactLawKind::hertz) out << " (restitution " << number(v.params.restitution) << ")";
  out << "\n    --set:";
  for (const std::string& arg : optimised_overrides(v.params, o)) out << " " << arg;
  out << "\n";
}

void write_best_table(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o) {
  out << "\nbest points, re-solved from scratch at rtol " << number(o.verify_rtol) << " (brute force from rest; shooting)"
      << (o.min_soft_fraction > 0.0 ? ", those that pass the soft check first" : "") << ":\n";
  for (std::size_t i = 0; i < r.best.size(); ++i) write_best_point(out, i, r.best[i], o);
  if (r.best.empty()) {
    out << "(no start found a feasible point)\n";
    if (o.min_soft_fraction > 0.0 && !o.hertz_valid)
      out << "(min_soft_fraction counts Hertz-valid attractors only: with hertz_valid = true the seeds and the "
             "search keep Hertz theory valid too)\n";
  }
  if (!r.best.empty() && r.best.front().soft_check && !r.best.front().soft_check->passed)
    out << "NO BEST POINT PASSES THE SOFT CHECK: none is shown to hold min_soft_fraction " << number(o.min_soft_fraction)
        << " of the basin\n";
}

}  // namespace

void write_optimise_json(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o,
                         const OptimiseRunInfo& run) {
  JsonWriter w(out);
  w.begin_object().field("output", run.output).field("seeds_from", r.seeds_from).field("trajectory", r.trajectory_file);
  w.field("objective", to_string(o.objective)).field("quantity", objective_quantity(o.objective));
  w.field("regime", o.regime ? o.regime->label() : std::string("any")).field("stability", to_string(o.stability));
  w.field("hertz_valid", o.hertz_valid).field("min_soft_fraction", o.min_soft_fraction);
  w.field("soft_check_initial_conditions", o.soft_check_initial_conditions);
  w.field("ranks", r.ranks).field("seeds", r.seeds.size()).field("evaluations", r.evaluations());
  w.field("starts_resumed", run.starts_resumed).field("sweep_cells_computed", run.sweep_cells_computed);
  w.field("wall_s", r.wall_s).field("sweep_wall_s", r.sweep_wall_s).field("optimise_wall_s", r.optimise_wall_s);
  w.field("verify_wall_s", r.verify_wall_s);
  write_starts_json(w, r, o);
  write_algorithms_json(w, r, o);
  w.key("best").begin_array();
  for (const VerifiedPoint& v : r.best) write_best_json(w, r, v, o);
  w.end_array().end_object();
  out << "\n";
}

void write_optimise_table(std::ostream& out, const OptimiseReport& r, const OptimiseOptions& o,
                          const OptimiseRunInfo& run) {
  write_run_lines(out, r, o, run.output);
  write_starts_table(out, r, o);
  write_algorithms_table(out, r, o);
  write_laws_table(out, r, o);
  write_best_table(out, r, o);
}

}  // namespace vibromap
