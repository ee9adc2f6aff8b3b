#include "vibromap/io/census_output.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <ostream>
#include <string>

#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/report.hpp"

namespace vibromap {

namespace {

// The shock record of an attractor (critical_shock.hpp).
void write_shock(JsonWriter& w, const CriticalShock& c) {
  w.begin_object();
  w.field("status", to_string(c.status));
  w.field("size", c.size);
  w.key("dx");
  write_state_json(w, c.dx);
  w.key("x_star");
  write_state_json(w, c.x_star);
  w.field("strobe_index", c.strobe_index);
  w.field("to", c.to);
  w.field("to_regime", c.to_regime.label());
  w.field("verified", c.verified);
  w.field("random_size", c.random_size);
  w.field("follows", c.follows);
  w.field("unresolved", c.unresolved);
  w.field("wall_s", c.wall_s);
  w.end_object();
}

void write_attractor(JsonWriter& w, const Attractor& a) {
  w.begin_object();
  w.field("regime", a.regime.label());
  w.field("n", a.regime.n);
  w.field("k", a.regime.k);
  w.field("periodic", a.periodic);
  w.field("T_con", a.T_con);
  w.field("k_con", a.k_con);
  w.field("F_max", a.F_max);
  w.field("z_ratio", a.z_ratio);
  w.field("hertz_valid", a.hertz_valid);
  w.field("max_floquet", a.max_floquet);
  write_stable_json(w.key("stable"), a.stable);
  w.field("soft", a.soft);
  w.field("count", a.count);
  w.field("fraction", a.fraction);
  w.field("fraction_stderr", a.fraction_stderr);
  w.field("from_rest", a.from_rest);
  w.field("transient", a.transient);
  w.field("escape_rate", a.escape_rate);  // exits per period past the budget (NaN: none followed on)
  w.field("mean_lifetime_periods", a.escape_rate > 0.0 ? 1.0 / a.escape_rate : std::numeric_limits<double>::quiet_NaN());
  w.field("escape_exposure_periods", a.escape_exposure);
  w.field("escapes", a.escapes);
  w.key("strobe").begin_array();
  for (const Eigen::Vector4d& x : a.strobe) write_state_json(w, x);
  w.end_array();
  if (a.shock.status != ShockStatus::not_computed) {
    w.key("shock");
    write_shock(w, a.shock);
  }
  w.end_object();
}

// The shock column: size, and where it leads ("-> #1"; "-> (2,2)" for an attractor the census
// does not list).
std::string shock_cell(const CriticalShock& c) {
  if (c.status != ShockStatus::found) return to_string(c.status);
  const std::string to = c.to >= 0 ? cat("#", std::to_string(c.to)) : c.to_regime.label();
  return cat(printf_number(c.size, "%.4g"), " -> ", to);
}

std::string state_text(const Eigen::Vector4d& x) {
  return cat("(", printf_number(x[0], "%.6g"), ", ", printf_number(x[1], "%.6g"), ", ", printf_number(x[2], "%.6g"),
             ", ", printf_number(x[3], "%.6g"), ")");
}

// Below the table: each shock found, with its vector, the state it moves and the work.
void write_shock_lines(std::ostream& os, const CensusSummary& s) {
  os << "\nminimal critical shock (motion scales L, omega L; dx in m, m, m/s, m/s):\n";
  for (std::size_t i = 0; i < s.attractors.size(); ++i) {
    const CriticalShock& c = s.attractors[i].shock;
    os << "  #" << i << " " << s.attractors[i].regime.label() << ": ";
    if (c.status != ShockStatus::found) {
      os << to_string(c.status) << " (" << c.follows << " follows, " << printf_number(c.wall_s, "%.2f") << " s)\n";
      continue;
    }
    os << printf_number(c.size, "%.5g") << " (random directions alone " << printf_number(c.random_size, "%.5g")
       << ") at strobe state " << c.strobe_index << "\n"
       << "     x* = " << state_text(c.x_star) << "\n"
       << "     dx = " << state_text(c.dx) << "\n"
       << "     leads to " << (c.to >= 0 ? cat("#", std::to_string(c.to), " ") : std::string("an unlisted "))
       << c.to_regime.label() << (c.verified ? " (verified by a fresh follow)" : " (NOT verified by a fresh follow)")
       << "; " << c.follows << " follows (" << c.unresolved << " unresolved), " << printf_number(c.wall_s, "%.2f")
       << " s\n";
  }
}

bool any_shock(const CensusSummary& s) {
  return std::any_of(s.attractors.begin(), s.attractors.end(),
                     [](const Attractor& a) { return a.shock.status != ShockStatus::not_computed; });
}

}  // namespace

void write_census_json(std::ostream& os, const CensusSummary& s) {
  JsonWriter w(os);
  w.begin_object();
  w.field("status", to_string(s.status));
  w.field("message", s.message);
  w.field("K", s.K);
  w.field("T", s.T);
  w.field("soft_fraction", s.soft_fraction);
  w.field("basin_entropy", s.basin_entropy);
  w.field("unresolved", s.unresolved);
  w.field("unlisted", s.unlisted);
  w.field("decided_early", s.decided_early);
  w.field("periods", s.periods);
  w.field("budget_states", s.budget_states);
  w.field("budget_periods", s.budget_periods);
  w.field("transient_periods", s.transient_periods);
  w.field("transient_states", s.transient_states);
  w.field("wall_s", s.wall_s);
  w.field("initial_states_per_s", s.wall_s > 0.0 ? s.K / s.wall_s : 0.0);
  w.field("ranks", s.ranks);
  w.key("attractors").begin_array();
  for (const Attractor& a : s.attractors) write_attractor(w, a);
  w.end_array();
  if (!s.labels.empty()) {
    w.key("initial_conditions").begin_array();
    for (const Eigen::Vector4d& x : s.initial_conditions) write_state_json(w, x);
    w.end_array();
    w.key("labels").begin_array();
    for (int l : s.labels) w.value(l);
    w.end_array();
  }
  w.end_object();
  os << "\n";
}

void write_census_table(std::ostream& os, const CensusSummary& s, const Scene& scene) {
  os << "scene          " << scene.path << "\n"
     << "census         " << s.K << " initial states (the rest state and " << s.K - 1 << " drawn)\n"
     << "attractors     " << s.attractors.size() << "\n"
     << "soft fraction  " << printf_number(s.soft_fraction, "%.4f") << "  (stable, Hertz-valid, k_con <= soft_kcon)\n"
     << "basin entropy  " << printf_number(s.basin_entropy, "%.4f") << "  (-sum f ln f over the attractors, unresolved and unlisted)\n";
  if (s.unresolved > 0) os << "unresolved     " << s.unresolved << " initial states (budget ran out while settling)\n";
  if (s.unlisted > 0) os << "unlisted       " << s.unlisted << " initial states (attractors beyond max_attractors)\n";
  os << "work           " << s.periods << " forcing periods, " << s.decided_early << " states decided early, "
     << printf_number(s.wall_s, "%.3f") << " s (" << printf_number(s.wall_s > 0.0 ? s.K / s.wall_s : 0.0, "%.0f")
     << " initial states/s" << (s.ranks > 1 ? cat(", ", std::to_string(s.ranks), " MPI ranks") : std::string()) << ")\n";
  if (s.budget_states > 0)
    os << "budget         " << s.budget_states << " states undecided to the budget's end took " << s.budget_periods
       << " of the periods (brute force follows them as far)\n";
  if (s.transient_periods > 0)
    os << "transient      " << s.transient_periods << " periods past analysis.max_periods followed states on leaking "
       << "non-periodic sets; " << s.transient_states << " still on one at the end\n";
  os << "\n";
  const bool shocks = any_shock(s);
  os << "  #  regime          fraction  +-stderr   k_con       T_con (s)   F_max (N)   z/R*      max|mu|   rest  soft"
     << (shocks ? "  shock" : "") << "\n";
  int i = 0;
  for (const Attractor& a : s.attractors) {
    char line[256];
    std::snprintf(line, sizeof line, "%3d  %-14s  %8.4f  %8.4f  %10.4g  %10.4g  %10.4g  %8.2e  %7.4f   %-4s  %s", i++,
                  a.regime.label().c_str(), a.fraction, a.fraction_stderr, a.k_con, a.T_con, a.F_max, a.z_ratio,
                  a.max_floquet, a.from_rest ? "yes" : "", shocks ? (a.soft ? "yes " : "    ") : (a.soft ? "yes" : ""));
    os << line << (shocks ? cat("  ", shock_cell(a.shock)) : std::string()) << "\n";
  }
  if (shocks) write_shock_lines(os, s);
  const int recurrences = scene.census ? scene.census->recurrences : CensusOptions{}.recurrences;
  i = 0;
  for (const Attractor& a : s.attractors) {
    if (a.transient) {
      os << "\n  #" << i << " is transient chaos: a state stayed " << recurrences
         << " periods in a row on it, then left for another attractor.\n"
         << "     Its fraction is the share still on it when the follow past the budget stopped (census.cpp);"
         << " it falls as that grows.\n";
      if (a.escape_exposure > 0)
        os << "     Escape rate " << printf_number(a.escape_rate, "%.3g") << " per period (" << a.escapes << " exits in "
           << a.escape_exposure << " periods followed past the budget"
           << (a.escape_rate > 0.0 ? ", mean lifetime " + printf_number(1.0 / a.escape_rate, "%.0f") + " periods" : std::string())
           << ").\n";
    }
    ++i;
  }
}

void write_census_labels_table(std::ostream& os, const CensusSummary& summary) {
  os << "\n  #  x1 (m)        x2 (m)        v1 (m/s)      v2 (m/s)      attractor\n";
  for (std::size_t i = 0; i < summary.labels.size(); ++i) {
    const Eigen::Vector4d& x = summary.initial_conditions[i];
    char line[160];
    std::snprintf(line, sizeof line, "%3zu  %12.5e  %12.5e  %12.5e  %12.5e  %d\n", i, x[0], x[1], x[2], x[3],
                  summary.labels[i]);
    os << line;
  }
}

}  // namespace vibromap
