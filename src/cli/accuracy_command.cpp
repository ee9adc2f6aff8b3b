// `vibromap accuracy`: the arguments, the progress lines and the report as a table or JSON; the
// study and its CSV are campaigns/accuracy/accuracy_run.hpp.

#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vibromap/campaigns/accuracy/accuracy_run.hpp"
#include "vibromap/core/text.hpp"
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

std::string pad(std::string s, std::size_t width, bool left_align) {
  if (s.size() < width) s.insert(left_align ? s.size() : 0, width - s.size(), ' ');
  return s;
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

void write_json(std::ostream& out, const AccuracyReport& report, const Scene& scene) {
  JsonWriter w(out);
  w.begin_object().field("scene", scene.path).key("reference");
  write_row_json(w, report.reference);
  w.key("rows").begin_array();
  for (const AccuracyRow& r : report.rows) write_row_json(w, r);
  w.end_array().end_object();
  out << "\n";
}

// ---- progress ---------------------------------------------------------------------

void print_progress(const AccuracyRow& r, std::size_t done, std::size_t total) {
  std::cerr << "vibromap: accuracy " << done << "/" << total << ": " << r.label << " " << r.setting << ": "
            << to_string(r.status) << " " << r.regime << " in " << num(r.wall_s, "%.3g") << " s\n";
}

}  // namespace

int accuracy_command(const AccuracyArgs& args, std::ostream& out) {
  const Scene scene = load_scene(args.scene, args.sets);
  AccuracyStudy study(scene, args.csv, args.overwrite);
  if (scene.sweep && !args.quiet) {
    std::cerr << "vibromap: note: " << scene.path << ": [sweep] is ignored; the study solves the scene's base point\n";
  }
  AccuracyProgress progress;
  if (!args.quiet) progress = print_progress;
  const AccuracyReport report = study.run(progress);
  if (args.format == "json") {
    write_json(out, report, scene);
  } else {
    write_table(out, report, scene);
  }
  out.flush();
  study.write_csv(report);
  return code(ExitCode::ok);
}

}  // namespace vibromap::cli
