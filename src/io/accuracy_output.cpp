// The accuracy study's output: see include/vibromap/io/accuracy_output.hpp.

#include "vibromap/io/accuracy_output.hpp"

#include <array>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/report.hpp"

namespace vibromap {

namespace {

// ---- text helpers ---------------------------------------------------------------------

// "nan" for any NaN (printf writes "-nan" for some).
std::string num(double x, const char* spec) { return std::isnan(x) ? "nan" : printf_number(x, spec); }

// "shooting (4)" (Newton iterations) or "integrate".
std::string steady_text(const AccuracyRow& r) {
  std::string s = to_string(r.steady_used);
  if (r.steady_used != SteadyMethod::integrate) {
    s += " (";
    s += std::to_string(r.newton_iterations);
    s += ")";
  }
  return s;
}

// ---- the table ------------------------------------------------------------------------

constexpr std::array kColumns = {
    Column{"method", 15, true},        Column{"setting", 13, true},      Column{"status", 7, true},
    Column{"regime", 12, true},         Column{"steady", 14, true},       Column{"wall s", 9, false},
    Column{"rhs evals", 11, false},    Column{"periods", 7, false},      Column{"err T_con", 9, false},
    Column{"err F_max", 9, false},     Column{"err k_con", 9, false},
};

std::vector<std::string> table_cells(const AccuracyRow& r) {
  return {r.label,
          r.setting,
          to_string(r.status),
          r.regime,
          steady_text(r),
          num(r.wall_s, "%.3g"),
          std::to_string(r.rhs_evals),
          std::to_string(r.periods),
          num(r.rel_err_T_con, "%.2e"),
          num(r.rel_err_F_max, "%.2e"),
          num(r.rel_err_k_con, "%.2e")};
}

void write_table_line(std::ostream& out, const std::vector<std::string>& cells, const std::string& note) {
  std::string line = table_line(kColumns, cells);
  if (!note.empty()) {
    line += "  ";
    line += note;
  }
  out << line << "\n";
}

// ---- JSON ---------------------------------------------------------------------

void write_row_json(JsonWriter& w, const AccuracyRow& r) {
  w.begin_object()
      .field("method", r.label)
      .field("setting", r.setting)
      .field("integrator", to_string(r.method))
      .field("steady", to_string(r.steady))
      .field("rtol", r.rtol)
      .field("atol", r.atol)
      .field("rk4_steps", r.rk4_steps)
      .field("status", to_string(r.status))
      .field("regime", r.regime)
      .field("regime_matches", r.regime_matches)
      .field("steady_used", to_string(r.steady_used))
      .field("newton_iterations", r.newton_iterations)
      .field("wall_s", r.wall_s)
      .field("rhs_evals", r.rhs_evals)
      .field("steps", r.steps)
      .field("periods", r.periods)
      .field("T_con", r.T_con)
      .field("F_max", r.F_max)
      .field("k_con", r.k_con)
      .field("rel_err_T_con", r.rel_err_T_con)
      .field("rel_err_F_max", r.rel_err_F_max)
      .field("rel_err_k_con", r.rel_err_k_con)
      .field("note", r.note)
      .end_object();
}

}  // namespace

void write_accuracy_table(std::ostream& out, const AccuracyReport& report, const Scene& scene) {
  const AccuracyRow& ref = report.reference;
  out << "vibromap " << VIBROMAP_VERSION << "  accuracy study of scene " << scene.path << "\n"
      << "reference: dopri5, " << ref.setting << ", atol " << num(ref.atol, "%.3g") << ", steady state by "
      << to_string(ref.steady) << ": " << to_string(ref.status) << " " << ref.regime << ", T_con "
      << num(ref.T_con, "%.10g") << " s, F_max " << num(ref.F_max, "%.10g") << " N, k_con "
      << num(ref.k_con, "%.10g") << "\n"
      << "errors: |x - x_ref| / |x_ref|; wall s: solve time of one point on one core\n\n";
  out << table_head(kColumns) << "  note\n";
  write_table_line(out, table_cells(ref), ref.note);
  for (const AccuracyRow& r : report.rows) write_table_line(out, table_cells(r), r.note);
  if (!report.unsolved.empty()) out << "\n" << report.unsolved << "\n";
}

void write_accuracy_json(std::ostream& out, const AccuracyReport& report, const Scene& scene) {
  JsonWriter w(out);
  w.begin_object().field("scene", scene.path).key("reference");
  write_row_json(w, report.reference);
  w.key("rows").begin_array();
  for (const AccuracyRow& r : report.rows) write_row_json(w, r);
  w.end_array().field("unsolved", report.unsolved).end_object();
  out << "\n";
}

void write_accuracy_progress(std::ostream& out, const AccuracyRow& r, std::size_t done, std::size_t total) {
  out << "vibromap: accuracy " << done << "/" << total << ": " << r.label << " " << r.setting << ": "
      << to_string(r.status) << " " << r.regime << " in " << num(r.wall_s, "%.3g") << " s\n";
}

}  // namespace vibromap
