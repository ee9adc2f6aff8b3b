#include "vibromap/io/summary_output.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/report.hpp"

namespace vibromap {
namespace {

void write_impact_json(JsonWriter& w, const Impact& im, double T) {
  w.begin_object()
      .field("t_in", im.t_in(T))
      .field("t_out", im.t_out(T))
      .field("T_con", im.T_con)
      .field("F_max", im.F_max)
      .field("z_max", im.z_max)
      .field("z_ratio", im.z_ratio)
      .field("v_in", im.v_in)
      .field("impulse", im.impulse)
      .field("v_out", im.v_out)
      .field("e_effective", im.e_effective)
      .field("energy_dissipated", im.energy_dissipated)
      .field("clipped", im.clipped)
      .end_object();
}

// One row of the summary: name, value, unit, note.
void row(std::ostream& os, const std::string& name, const std::string& value, const std::string& unit,
         const std::string& note = {}) {
  std::string line = "  " + pad_right(name, 17) + pad_right(value, 16) + pad_right(unit, 7) + note;
  line.erase(line.find_last_not_of(' ') + 1);
  os << line << "\n";
}

void write_header(std::ostream& os, const PointSummary& s, const Scene& scene) {
  const IntegratorOptions& io = scene.options.integrator;
  os << "vibromap " << VIBROMAP_VERSION << "  scene " << scene.path << "  (" << to_string(io.method);
  if (io.method == Method::rk4) {
    os << ", " << io.rk4_steps << " steps per period";
  } else {
    os << ", rtol " << printf_number(io.rtol) << ", atol " << printf_number(io.atol);
  }
  os << "; steady state by " << to_string(scene.options.analysis.steady) << ")\n\n";
  row(os, "status", to_string(s.status), "");
  if (!s.message.empty()) os << "  " << pad_right("message", 17) << s.message << "\n";
}

// "0.912345 - 0.0123i" (numbers as printf_number()).
std::string complex_text(std::complex<double> mu) {
  std::string out = printf_number(mu.real());
  out += mu.imag() < 0.0 ? " - " : " + ";
  out += printf_number(std::abs(mu.imag()));
  out += "i";
  return out;
}

// How the steady motion was found, its stability and, when asked for, the Lyapunov exponent.
void write_steady(std::ostream& os, const PointSummary& s) {
  std::string how = to_string(s.steady_method);
  if (s.newton_iterations > 0) {
    how += ", ";
    how += std::to_string(s.newton_iterations);
    how += " Newton iterations";
  }
  row(os, "steady state by", how, "");
  double largest = 0.0;
  for (const auto& mu : s.floquet) largest = std::max(largest, std::abs(mu));
  std::string note = "no Floquet multipliers computed";
  if (!s.floquet.empty()) {
    note = "largest |mu| = ";
    note += printf_number(largest);
  }
  row(os, "stability", stability_text(s.stable), "", note);
  if (std::isfinite(s.lyapunov)) row(os, "lyapunov", printf_number(s.lyapunov, "%.4g"), "1/s", "largest Lyapunov exponent");
}

void write_floquet(std::ostream& os, const PointSummary& s) {
  if (s.floquet.empty()) return;
  os << "\n  Floquet multipliers (eigenvalues of the monodromy matrix over " << std::max(s.regime.n, 1)
     << " T; stable when every |mu| < 1):\n";
  for (std::size_t i = 0; i < s.floquet.size(); ++i) {
    std::string name = "mu";
    name += std::to_string(i + 1);
    os << "  " << pad_left(name, 5) << "  " << pad_right(complex_text(s.floquet[i]), 28) << "|mu| = "
       << printf_number(std::abs(s.floquet[i])) << "\n";
  }
}

// Why the motion is soft (is_soft), or the first condition it fails.
std::string soft_note(const PointSummary& s, const AnalysisOptions& a) {
  if (s.soft) return "periodic with impacts, stable, Hertz-valid, k_con <= " + printf_number(a.soft_kcon);
  if (s.regime.kind != RegimeKind::periodic || s.regime.k == 0) return "not periodic with impacts";
  if (s.stable != 1) return s.stable == 0 ? "unstable" : "stability unknown";
  if (!s.hertz_valid) return "Hertz-invalid: z_ratio " + printf_number(s.z_ratio, "%.3g") + " > " + printf_number(a.hertz_limit);
  return "k_con " + printf_number(s.k_con, "%.4g") + " > " + printf_number(a.soft_kcon);
}

void write_fragile_row(std::ostream& os, const Fragility& f);

void write_results(std::ostream& os, const PointSummary& s, const Scene& scene) {
  const std::string nk = s.regime.n > 0 ? "repeats after " + std::to_string(s.regime.n) + " T with " +
                                              std::to_string(s.regime.k) + " impact(s)"
                                        : std::string();
  row(os, "regime", s.regime.label(), "", nk);
  row(os, "T", printf_number(s.T), "s", "forcing period 2 pi/omega");
  row(os, "T_con", printf_number(s.T_con), "s", "duration of the longest impact");
  row(os, "k_con", printf_number(s.k_con), "-", "T / T_con (~1000 rigid, ~1-10 soft)");
  row(os, "F_max", printf_number(s.F_max), "N", "largest peak contact force");
  row(os, "z_max", printf_number(s.z_max), "m", "largest peak penetration");
  const std::string limit = printf_number(scene.options.analysis.hertz_limit);
  row(os, "z_ratio", printf_number(s.z_ratio), "-",
      "z_max/R*: Hertz theory " + std::string(s.hertz_valid ? "valid" : "NOT valid") + " (limit " + limit + ")");
  row(os, "soft", s.soft ? "yes" : "no", "", soft_note(s, scene.options.analysis));
  write_fragile_row(os, s.fragility);
  row(os, "steady_residual", printf_number(s.steady_residual, "%.3g"), "-",
      s.steady_method != SteadyMethod::integrate ? "scaled Newton residual |P^n(y) - y|"
                                                : "scaled |y(jT) - y((j-n)T)| at the end");
  write_steady(os, s);
  row(os, "periods", std::to_string(s.periods), "", "forcing periods integrated");
  row(os, "steps", std::to_string(s.counters.steps), "",
      "accepted; " + std::to_string(s.counters.rejected) + " rejected, " + std::to_string(s.counters.rhs_evals) +
          " rhs evaluations, " + std::to_string(s.counters.events) + " events");
  row(os, "wall time", printf_number(s.wall_s, "%.3g"), "s");
}

// With a dissipative contact law (some impact lost energy): each impact's exit velocity,
// effective restitution, dissipated energy and whether the damped force was clipped at 0.
void write_dissipation(std::ostream& os, const PointSummary& s) {
  if (std::none_of(s.impacts.begin(), s.impacts.end(), [](const Impact& im) { return im.energy_dissipated != 0.0; }))
    return;
  static constexpr Column columns[] = {{"#", 3}, {"v_out (m/s)", 11}, {"e_effective", 11}, {"dissipated (J)", 14},
                                       {"clipped", 7}};
  os << "\n  dissipation per impact (e_effective = |v_out / v_in|):\n" << table_head(columns) << "\n";
  for (std::size_t i = 0; i < s.impacts.size(); ++i) {
    const Impact& im = s.impacts[i];
    const std::vector<std::string> cells = {std::to_string(i + 1), printf_number(im.v_out), printf_number(im.e_effective),
                                            printf_number(im.energy_dissipated), im.clipped ? "yes" : "no"};
    os << table_line(columns, cells) << "\n";
  }
}

void write_impacts(std::ostream& os, const PointSummary& s) {
  if (s.impacts.empty()) {
    os << "\n  no impacts in the steady cycle\n";
    return;
  }
  static constexpr Column columns[] = {{"#", 3},          {"t_in (s)", 16},  {"t_out (s)", 16},
                                       {"T_con (s)", 11},  {"F_max (N)", 11}, {"z_max (m)", 11},
                                       {"z_max/R*", 9},    {"v_in (m/s)", 11}, {"impulse (N s)", 13}};
  os << "\n  impacts of one steady cycle (" << s.impacts.size() << "; t since t = 0):\n" << table_head(columns) << "\n";
  for (std::size_t i = 0; i < s.impacts.size(); ++i) {
    const Impact& im = s.impacts[i];
    const std::vector<std::string> cells = {std::to_string(i + 1), printf_number(im.t_in(s.T), "%.10g"),
                                            printf_number(im.t_out(s.T), "%.10g"), printf_number(im.T_con), printf_number(im.F_max),
                                            printf_number(im.z_max), printf_number(im.z_ratio, "%.3g"),
                                            printf_number(im.v_in), printf_number(im.impulse)};
    os << table_line(columns, cells) << "\n";
  }
  write_dissipation(os, s);
}

// analysis.fragility: whether the answer is fragile, and where each perturbed state ended.
std::string end_text(const SteadyEnd& e) {
  return e.regime.label() + (e.same ? ", the same attractor" : ", another attractor");
}

void write_fragile_row(std::ostream& os, const Fragility& f) {
  if (f.size <= 0.0) return;
  row(os, "fragile", f.fragile ? "yes" : "no", "",
      std::to_string(f.perturbed.size()) + " perturbations of size " + printf_number(f.size, "%.3g") +
          " (motion scales) of the initial state: " + (f.fragile ? "some end elsewhere" : "all end on its attractor"));
}

void write_fragility(std::ostream& os, const Fragility& f) {
  if (f.size <= 0.0) return;
  static constexpr Column columns[] = {{"#", 3}, {"x1 (m)", 16}, {"x2 (m)", 16}, {"v1 (m/s)", 16}, {"v2 (m/s)", 16},
                                       {"reaches", 30}};
  os << "\n  perturbed initial states (" << f.perturbed.size() << ", " << f.periods
     << " forcing periods; the point's own answer is the initial state's):\n"
     << table_head(columns) << "\n";
  for (std::size_t i = 0; i < f.perturbed.size(); ++i) {
    const SteadyEnd& e = f.perturbed[i];
    const std::vector<std::string> cells = {std::to_string(i + 1), printf_number(e.x0[0], "%.10g"),
                                            printf_number(e.x0[1], "%.10g"), printf_number(e.x0[2], "%.10g"),
                                            printf_number(e.x0[3], "%.10g"), end_text(e)};
    os << table_line(columns, cells) << "\n";
  }
}

void write_end_json(JsonWriter& w, const SteadyEnd& e) {
  w.begin_object().field("regime", e.regime.label()).field("regime_kind", to_string(e.regime.kind));
  w.field("n", e.regime.n).field("k", e.regime.k).field("same", e.same);
  write_state_json(w.key("initial_state"), e.x0);
  w.key("strobe").begin_array();
  for (const Eigen::Vector4d& x : e.strobe) write_state_json(w, x);
  w.end_array().end_object();
}

// "fragility": {size, fragile, periods, own: end, perturbed: [end, ...]}; only when assessed.
void write_fragility_json(JsonWriter& w, const Fragility& f) {
  if (f.size <= 0.0) return;
  w.field("fragile", f.fragile).key("fragility").begin_object();
  w.field("size", f.size).field("periods", f.periods).field("rhs_evals", f.counters.rhs_evals);
  write_end_json(w.key("own"), f.own);
  w.key("perturbed").begin_array();
  for (const SteadyEnd& e : f.perturbed) write_end_json(w, e);
  w.end_array().end_object();
}

// floquet: [{re, im, abs}, ...]; stable: true, false or null (unknown); lyapunov: 1/s or null.
void write_stability_json(JsonWriter& w, const PointSummary& s) {
  w.key("floquet").begin_array();
  for (const auto& mu : s.floquet) {
    w.begin_object().field("re", mu.real()).field("im", mu.imag()).field("abs", std::abs(mu)).end_object();
  }
  w.end_array().key("stable");
  write_stable_json(w, s.stable);
  w.field("lyapunov", s.lyapunov);  // NaN (not computed) is written as null
}

}  // namespace

void write_summary_json(std::ostream& os, const PointSummary& s) {
  JsonWriter w(os);
  w.begin_object()
      .field("status", to_string(s.status))
      .field("message", s.message)
      .field("regime", s.regime.label())
      .field("regime_kind", to_string(s.regime.kind))
      .field("n", s.regime.n)
      .field("k", s.regime.k)
      .field("T", s.T)
      .field("T_con", s.T_con)
      .field("k_con", s.k_con)
      .field("F_max", s.F_max)
      .field("z_max", s.z_max)
      .field("z_ratio", s.z_ratio)
      .field("hertz_valid", s.hertz_valid)
      .field("soft", s.soft);
  w.key("impacts").begin_array();
  for (const Impact& im : s.impacts) write_impact_json(w, im, s.T);
  w.end_array()
      .field("periods", s.periods)
      .field("steps", s.counters.steps)
      .field("rejected", s.counters.rejected)
      .field("rhs_evals", s.counters.rhs_evals)
      .field("events", s.counters.events)
      .field("steady_residual", s.steady_residual)
      .field("steady_method", to_string(s.steady_method))
      .field("newton_iterations", s.newton_iterations);
  write_stability_json(w, s);
  w.field("wall_s", s.wall_s);
  write_state_json(w.key("final_state"), s.final_state);
  write_fragility_json(w, s.fragility);
  w.end_object();
}

void write_summary_table(std::ostream& os, const PointSummary& s, const Scene& scene) {
  write_header(os, s, scene);
  write_results(os, s, scene);
  write_floquet(os, s);
  write_impacts(os, s);
  write_fragility(os, s.fragility);
}

}  // namespace vibromap
