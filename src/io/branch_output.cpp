// A continuation's output: see include/vibromap/io/branch_output.hpp.

#include "vibromap/io/branch_output.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/report.hpp"

namespace vibromap {

namespace {

double largest(const std::vector<std::complex<double>>& mu) { return mu.empty() ? NAN : std::abs(mu.front()); }

double born_at_param(const std::vector<Branch>& branches, const Branch& s) {
  return branches[static_cast<std::size_t>(s.parent)].bifurcations[static_cast<std::size_t>(s.born_at)].at.param;
}

// ---- JSON ---------------------------------------------------------------------------------

void points_json(JsonWriter& w, const std::vector<MeasuredPoint>& points) {
  w.key("points").begin_array();
  for (const MeasuredPoint& m : points) {
    w.begin_object().field("param", m.point.param).field("stable", m.point.stable);
    write_multipliers_json(w, m.point.multipliers);
    w.field("T_con", m.orbit.T_con).field("k_con", m.orbit.k_con).field("F_max", m.orbit.F_max);
    w.field("impacts", static_cast<long>(m.orbit.impacts.size()));
    w.field("x1_max", m.point.x1_max).field("x2_max", m.point.x2_max).field("clearance_min", m.point.clearance_min);
    w.field("regime", m.orbit.regime.label());
    write_state_json(w.key("y"), m.point.y);
    write_strobe_x1_json(w, m.point.strobe).end_object();
  }
  w.end_array();
}

void bifurcations_json(JsonWriter& w, const std::vector<Bifurcation>& bifurcations) {
  w.key("bifurcations").begin_array();
  for (const Bifurcation& b : bifurcations) {
    w.begin_object().field("type", to_string(b.type)).field("param", b.at.param);
    write_multipliers_json(w, b.at.multipliers);
    write_state_json(w.key("y"), b.at.y);
    w.end_object();
  }
  w.end_array();
}

void curve_points_json(JsonWriter& w, const MeasuredCurve& mc) {
  const Curve& c = mc.curve;
  w.key("points").begin_array();
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    const CurvePoint& q = c.points[i];
    const PointSummary& m = mc.orbits[i];
    w.begin_object().field("param", q.param).field("param2", q.param2);
    w.field("T_con", m.T_con).field("k_con", m.k_con).field("z_ratio", m.z_ratio).field("F_max", m.F_max);
    w.field("impacts", static_cast<long>(m.impacts.size())).field("stable", q.stable);
    write_multipliers_json(w, q.multipliers);
    w.field("residual", q.residual).field("orbit_residual", q.orbit_residual);
    write_state_json(w.key("y"), q.y);
    w.end_object();
  }
  w.end_array();
}

void curves_json(JsonWriter& w, const CurvesReport& r) {
  w.key("curves").begin_array();
  for (const MeasuredCurve& mc : r.curves) {
    const Curve& c = mc.curve;
    w.begin_object().field("kind", c.spec.label).field("n", c.n).field("stop", c.stop).field("start", c.start);
    if (!c.grazing.empty()) w.field("grazing", c.grazing);
    w.key("codim2").begin_array();
    for (const Codim2Point& x : c.codim2)
      w.begin_object().field("param", x.param).field("param2", x.param2).field("kind", x.kind).end_object();
    w.end_array();
    curve_points_json(w, mc);
    w.end_object();
  }
  w.end_array();
  w.key("skipped").begin_array();
  for (const std::string& s : r.skipped) w.value(s);
  w.end_array();
}

// ---- tables -------------------------------------------------------------------------------

void bifurcations_table(std::ostream& out, const std::string& key, const std::vector<Bifurcation>& bifurcations) {
  for (const Bifurcation& b : bifurcations)
    out << "  " << std::setw(16) << to_string(b.type) << "  " << key << " = " << std::setprecision(10) << b.at.param
        << "  max|mu| " << std::setprecision(6) << largest(b.at.multipliers) << "\n";
}

// One line per branch: its period, first and last key value, points and why it stopped.
void branches_table(std::ostream& out, const std::vector<Branch>& branches, bool points_shown) {
  out << "\n  " << std::setw(6) << "branch" << "  " << std::setw(6) << "period" << "  " << std::setw(16) << "from"
      << "  " << std::setw(16) << "to" << "  " << std::setw(6) << "points" << "  stopped"
      << (points_shown ? "" : "   (every point: --points, or --format json)") << "\n";
  for (std::size_t i = 0; i < branches.size(); ++i) {
    const Branch& b = branches[i];
    const double first = b.points.empty() ? NAN : b.points.front().param;
    const double last = b.points.empty() ? NAN : b.points.back().param;
    out << "  " << std::setw(6) << i << "  " << std::setw(4) << b.n << " T  " << std::setprecision(10) << std::setw(16)
        << first << "  " << std::setw(16) << last << "  " << std::setw(6) << b.points.size() << "  " << b.stop << "\n";
  }
}

void points_table(std::ostream& out, const std::vector<Branch>& branches,
                  const std::vector<std::vector<MeasuredPoint>>& measured) {
  for (std::size_t i = 0; i < branches.size(); ++i) {
    out << "\n  branch " << i << " (period " << branches[i].n << " T)\n  " << std::setw(14) << "param" << "  stable  "
        << std::setw(9) << "max|mu|" << "  " << std::setw(8) << "regime" << "  " << std::setw(10) << "k_con" << "  "
        << std::setw(11) << "F_max (N)" << "\n";
    for (const MeasuredPoint& m : measured[i])
      out << "  " << std::setw(14) << std::setprecision(8) << m.point.param << "  " << std::setw(6)
          << (m.point.stable ? "yes" : "no") << "  " << std::setw(9) << std::setprecision(5)
          << largest(m.point.multipliers) << "  " << std::setw(8) << m.orbit.regime.label() << "  " << std::setw(10)
          << m.orbit.k_con << "  " << std::setw(11) << m.orbit.F_max << "\n";
  }
}

// The range of one coordinate of a curve's points.
std::string range_of(const Curve& c, bool second) {
  if (c.points.empty()) return "-";
  double lo = INFINITY, hi = -INFINITY;
  for (const CurvePoint& q : c.points) {
    const double x = second ? q.param2 : q.param;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  std::ostringstream os;
  os << std::setprecision(7) << lo << " .. " << hi;
  return os.str();
}

// One curve's paragraph: kind, points, the ranges of both keys, the worst residual, why it
// stopped, and its codimension-two points.
void curve_table(std::ostream& out, std::size_t i, const Curve& c, const std::string& key, const std::string& key2) {
  double worst = 0.0;
  for (const CurvePoint& q : c.points) worst = std::max(worst, q.residual);
  out << "  curve " << i << "  " << c.spec.label << " (period " << c.n << " T): " << c.points.size() << " points, "
      << key << " " << range_of(c, false) << ", " << key2 << " " << range_of(c, true) << ", worst residual "
      << std::setprecision(2) << worst << ", from the point located at " << key << " = " << std::setprecision(10)
      << c.points[static_cast<std::size_t>(c.start)].param << std::setprecision(6) << "\n    stop: " << c.stop << "\n";
  if (!c.grazing.empty()) out << "    grazing: " << c.grazing << "\n";
  for (const Codim2Point& x : c.codim2)
    out << "    codim-2: " << x.kind << " at " << key << " = " << std::setprecision(10) << x.param << ", " << key2
        << " = " << x.param2 << std::setprecision(6) << "\n";
}

}  // namespace

// The first branch and its bifurcations, the switched branches and theirs, a summary line per
// branch, and every point only when asked.
void write_branch_table(std::ostream& out, const ContinuationReport& report, const BranchTable& table) {
  const std::vector<Branch>& branches = report.branches;
  const std::string& key = table.key;
  const Branch& branch = branches.front();
  out << "branch         " << key << " from " << number(table.from, 12) << " to " << number(table.to, 12)
      << ", period " << report.n << " T (" << report.start_regime << " at the start)\n"
      << "points         " << branch.points.size() << "; " << branch.stop << "\n"
      << "bifurcations   " << branch.bifurcations.size() << "\n";
  if (!table.file.empty()) out << "file           " << table.file << "\n";
  bifurcations_table(out, key, branch.bifurcations);
  for (std::size_t i = 1; i < branches.size(); ++i) {
    const Branch& s = branches[i];
    out << "switched       branch " << i << ": period " << s.n << " T, born at the period doubling " << key << " = "
        << std::setprecision(10) << born_at_param(branches, s) << " of branch " << s.parent << "; " << s.points.size()
        << " points; " << s.stop << "\n";
    bifurcations_table(out, key, s.bifurcations);
  }
  branches_table(out, branches, table.points);
  if (table.points) points_table(out, branches, report.measured);
}

void write_branch_json(std::ostream& out, const std::string& key, const ContinuationReport& report,
                       const CurvesReport* curves) {
  const std::vector<Branch>& branches = report.branches;
  const Branch& branch = branches.front();
  JsonWriter w(out);
  w.begin_object().field("key", key).field("n", report.n).field("stop", branch.stop);
  points_json(w, report.measured.front());
  bifurcations_json(w, branch.bifurcations);
  w.key("branches").begin_array();
  for (std::size_t i = 1; i < branches.size(); ++i) {
    const Branch& s = branches[i];
    w.begin_object().field("n", s.n).field("parent", s.parent).field("born_at", s.born_at);
    w.field("born_at_param", born_at_param(branches, s));
    w.field("stop", s.stop);
    points_json(w, report.measured[i]);
    bifurcations_json(w, s.bifurcations);
    w.end_object();
  }
  w.end_array();
  if (curves) curves_json(w, *curves);
  w.end_object();
  out << "\n";
}

void write_curves_table(std::ostream& out, const std::string& key, const std::string& key2, const CurvesReport& r) {
  out << "\ncurves         " << r.curves.size() << " in (" << key << ", " << key2 << "), started at " << key2 << " = "
      << number(r.q0, 12) << " (" << std::setprecision(3) << std::fixed << r.wall_s << " s in all)\n"
      << std::defaultfloat;
  for (std::size_t i = 0; i < r.curves.size(); ++i) curve_table(out, i, r.curves[i].curve, key, key2);
  for (const std::string& s : r.skipped) out << "  not followed: " << s << "\n";
}

}  // namespace vibromap
