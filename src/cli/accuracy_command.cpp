// `vibromap accuracy`: the arguments; the study and its CSV are campaigns/accuracy/accuracy_run.hpp,
// the report and the progress lines io/accuracy_output.hpp.

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/accuracy/accuracy_run.hpp"
#include "vibromap/io/accuracy_output.hpp"
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

int accuracy_command(const AccuracyArgs& args, std::ostream& out) {
  const Scene scene = load_scene(args.scene, args.sets);
  AccuracyStudy study(scene, args.csv, args.overwrite);
  if (scene.sweep && !args.quiet) {
    std::cerr << "vibromap: note: " << scene.path << ": [sweep] is ignored; the study solves the scene's base point\n";
  }
  AccuracyProgress progress;
  if (!args.quiet)
    progress = [](const AccuracyRow& r, std::size_t done, std::size_t total) {
      write_accuracy_progress(std::cerr, r, done, total);
    };
  const AccuracyReport report = study.run(progress);
  if (args.format == "json") {
    write_accuracy_json(out, report, scene);
  } else {
    write_accuracy_table(out, report, scene);
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
         "scripts; postprocess/vibromap-post plot_work_precision FILE.csv draws error against time.";
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
