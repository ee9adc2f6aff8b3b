// `vibromap accuracy`: the scene's point solved by every case of the default accuracy study
// (analysis/accuracy.hpp), printed as a table or JSON, and written as CSV for
// postprocess/plot_work_precision.py.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vibromap/core/analysis/accuracy.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::cli {
namespace {

// ---- text helpers ---------------------------------------------------------------------

std::string num(double x, const char* spec) {
  if (std::isnan(x)) return "nan";
  std::array<char, 64> buf{};
  std::snprintf(buf.data(), buf.size(), spec, x);
  return buf.data();
}

// The shortest text that reads back to the same double; "nan" and "inf" for the others.
std::string exact(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  return std::string(buf.data(), res.ptr);
}

std::string pad(std::string s, std::size_t width, bool left_align) {
  if (s.size() < width) s.insert(left_align ? s.size() : 0, width - s.size(), ' ');
  return s;
}

// A CSV field, quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

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

struct Column {
  const char* head;
  std::size_t width;
  bool left;
};

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
  std::string line;
  for (std::size_t c = 0; c < kColumns.size(); ++c) {
    line += "  ";
    line += pad(cells[c], kColumns[c].width, kColumns[c].left);
  }
  if (!note.empty()) {
    line += "  ";
    line += note;
  }
  out << line << "\n";
}

void write_table(std::ostream& out, const AccuracyReport& report, const Scene& scene) {
  const AccuracyRow& ref = report.reference;
  out << "vibromap " << VIBROMAP_VERSION << "  accuracy study of scene " << scene.path << "\n"
      << "reference: dopri5, " << ref.setting << ", atol " << num(ref.atol, "%.3g") << ", steady state by "
      << to_string(ref.steady) << ": " << to_string(ref.status) << " " << ref.regime << ", T_con "
      << num(ref.T_con, "%.10g") << " s, F_max " << num(ref.F_max, "%.10g") << " N, k_con "
      << num(ref.k_con, "%.10g") << "\n"
      << "errors: |x - x_ref| / |x_ref|; wall s: solve time of one point on one core\n\n";
  std::vector<std::string> heads;
  for (const Column& c : kColumns) heads.push_back(c.head);
  write_table_line(out, heads, "note");
  write_table_line(out, table_cells(ref), ref.note);
  for (const AccuracyRow& r : report.rows) write_table_line(out, table_cells(r), r.note);
}

// ---- JSON and CSV ---------------------------------------------------------------------

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

void write_json(std::ostream& out, const AccuracyReport& report, const Scene& scene) {
  JsonWriter w(out);
  w.begin_object().field("scene", scene.path).key("reference");
  write_row_json(w, report.reference);
  w.key("rows").begin_array();
  for (const AccuracyRow& r : report.rows) write_row_json(w, r);
  w.end_array().end_object();
  out << "\n";
}

constexpr const char* kCsvHeader =
    "method,setting,integrator,steady,rtol,atol,rk4_steps,status,regime,regime_matches,steady_used,"
    "newton_iterations,wall_s,rhs_evals,steps,periods,T_con,F_max,k_con,rel_err_T_con,rel_err_F_max,"
    "rel_err_k_con,note";

std::string csv_line(const AccuracyRow& r) {
  const std::vector<std::string> fields = {
      r.label, r.setting, to_string(r.method), to_string(r.steady), exact(r.rtol), exact(r.atol),
      std::to_string(r.rk4_steps), to_string(r.status), r.regime, r.regime_matches ? "1" : "0",
      to_string(r.steady_used), std::to_string(r.newton_iterations), exact(r.wall_s), std::to_string(r.rhs_evals),
      std::to_string(r.steps), std::to_string(r.periods), exact(r.T_con), exact(r.F_max), exact(r.k_con),
      exact(r.rel_err_T_con), exact(r.rel_err_F_max), exact(r.rel_err_k_con), r.note};
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) line += ',';
    line += csv_field(fields[i]);
  }
  return line;
}

// The CSV text: header, the reference row (method "reference"), then the cases.
std::string csv_text(const AccuracyReport& report) {
  std::string text = cat(kCsvHeader, "\n", csv_line(report.reference), "\n");
  for (const AccuracyRow& r : report.rows) text += csv_line(r) + "\n";
  return text;
}

// ---- the study ------------------------------------------------------------------------

// The cases' options must be valid (what solve_point would reject as invalid_input; the
// scene's parameters passed validate() when it was read), checked before hours of solving.
void check_cases(const Scene& scene, const std::vector<AccuracyCase>& cases) {
  for (const AccuracyCase& c : cases) {
    for (const std::string& err : {validate(c.options.integrator), validate(c.options.analysis)}) {
      if (err.empty()) continue;
      std::string msg = scene.path;
      msg += ": accuracy case ";
      msg += c.method_label;
      msg += " ";
      msg += setting_label(c.options.integrator);
      msg += ": ";
      msg += err;
      throw SceneError(msg);
    }
  }
}

void print_progress(const AccuracyRow& r, std::size_t done, std::size_t total) {
  std::cerr << "vibromap: accuracy " << done << "/" << total << ": " << r.label << " " << r.setting << ": "
            << to_string(r.status) << " " << r.regime << " in " << num(r.wall_s, "%.3g") << " s\n";
}

}  // namespace

int accuracy_command(const AccuracyArgs& args, std::ostream& out) {
  const Scene scene = load_scene(args.scene, args.sets);
  // The CSV's new file is made before the (long) study, so that a bad --csv is known at once;
  // it replaces the named file only when the study is done.
  std::optional<NewFile> csv;
  if (!args.csv.empty()) {
    check_output(args.csv, {.option = "--csv", .overwrite = args.overwrite});
    csv.emplace(args.csv);
  }
  const std::vector<AccuracyCase> cases = default_accuracy_cases(scene.options);
  const AccuracyCase reference = default_accuracy_reference(scene.options);
  check_cases(scene, cases);
  check_cases(scene, {reference});
  if (scene.sweep && !args.quiet) {
    std::cerr << "vibromap: note: " << scene.path << ": [sweep] is ignored; the study solves the scene's base point\n";
  }
  AccuracyProgress progress;
  if (!args.quiet) progress = print_progress;
  const AccuracyReport report = run_accuracy(scene.params, cases, reference, progress);
  if (args.format == "json") {
    write_json(out, report, scene);
  } else {
    write_table(out, report, scene);
  }
  out.flush();
  if (csv) {
    csv->write(csv_text(report));
    csv->commit();
  }
  return code(ExitCode::ok);
}

}  // namespace vibromap::cli
