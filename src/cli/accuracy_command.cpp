// `vibromap accuracy`: the arguments, the progress lines and the report as a table or JSON; the
// study and its CSV are campaigns/accuracy/accuracy_run.hpp.

#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/accuracy/accuracy_run.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/report.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::cli {

// `vibromap accuracy SCENE [--set section.key=value]... [--csv FILE.csv] [--format table|json]`
struct AccuracyArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string csv;               // CSV file of the rows; empty: none
  bool overwrite = false;        // replace an existing CSV file
  std::string format = "table";  // stdout: "table" or "json"
  bool quiet = false;            // no progress lines on stderr
};

// Solves the scene's point with every case of the default accuracy study (accuracy.hpp) and
// prints error against cost; writes the CSV when asked. Throws SceneError on a bad scene,
// IoError when the CSV cannot be written (checked before the solves, too).
int accuracy_command(const AccuracyArgs& args, std::ostream& out);

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

void write_table(std::ostream& out, const AccuracyReport& report, const Scene& scene) {
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

namespace {

std::string accuracy_footer() {
  return "The study solves the scene's point (a [sweep] section is ignored) once per case below,\n"
         "one case at a time, and compares each with a reference solve of the same point:\n"
         "  reference        dopri5 at rtol 1e-13, steady state by brute-force integration: the most\n"
         "                   conservative combination (no closed form, no Newton)\n"
         "  rk4              the source paper's classical fixed-step RK4 (contact force always in the\n"
         "                   right-hand side), 2^11 ... 2^15 steps per forcing period; steady state by\n"
         "                   integration. Its order collapses at contact.\n"
         "  dopri5           adaptive Dormand-Prince 5(4) with located contact events, rtol 1e-6, 1e-8,\n"
         "                   1e-10, 1e-12; steady state by integration (hundreds of periods at xi = 0.01)\n"
         "  hybrid+shooting  closed-form free flight between impacts, dopri5 only in contact; steady\n"
         "                   state by Newton's method on the stroboscopic map (shooting, falling back to\n"
         "                   integration), rtol 1e-6, 1e-8, 1e-10, 1e-12\n"
         "atol scales with rtol (the scene's atol/rtol ratio is kept); steady_tol and newton_tol follow\n"
         "each tolerance (auto). The scene's other keys (budgets, n_max, max_step, ...) apply to every\n"
         "case; its method and tolerances are replaced by the cases'.\n\n"
         "Columns: the method and its setting, status, regime, the steady-state method that gave the\n"
         "answer (Newton iterations), wall s (the solve time of that one point on one core, so the\n"
         "run takes about the sum of the column), right-hand side evaluations, forcing periods\n"
         "integrated, and the relative errors |x - x_ref|/|x_ref| of T_con (duration of the longest\n"
         "impact), F_max (peak contact force) and k_con = T/T_con. nan: undefined (no impact, or a\n"
         "failed solve). A regime other than the reference's is noted. --csv writes the same rows for\n"
         "scripts; postprocess/vmpy plot_work_precision FILE.csv draws error against time.";
}

}  // namespace

Command declare_accuracy(CLI::App& app) {
  auto args = std::make_shared<AccuracyArgs>();
  CLI::App* acc = app.add_subcommand("accuracy", "Error against run time of rk4, dopri5 and hybrid+shooting on one point");
  add_scene_options(*acc, args->scene, args->sets, "Scene file (TOML)");
  add_output_option(*acc, "--csv", args->csv, "Also write the rows to FILE.csv (one line per case, reference first)", "FILE.csv");
  acc->add_flag("--overwrite", args->overwrite, "Replace an existing CSV file");
  add_format_option(*acc, args->format, "Output on stdout: a table for people or JSON for scripts");
  acc->add_flag("-q,--quiet", args->quiet, "No progress lines on stderr");
  return {.app = acc, .footer = accuracy_footer(), .topic = "the accuracy study", .campaign = {},
          .run = [args](std::ostream& out) { return accuracy_command(*args, out); }};
}

}  // namespace vibromap::cli
